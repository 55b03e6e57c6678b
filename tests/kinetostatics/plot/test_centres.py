"""Instantaneous centres on every bundled mechanism (issue 33, item 3): each centre
checked independently of how it was found,

- by its velocities: at I_jk the velocity fields of elements j and k agree (a centre at
  infinity: j and k translate relative to each other, across its direction);
- by Kennedy's theorem: the three centres of any three elements lie on one line (a
  centre at infinity: the line of the other two runs along its direction);
- by its name: ``I`` and the two elements' numbers, one rule for all scenes (the
  element pivoted at a ground pivot ``Ok`` is element k; the shaper's crank at O2 is 2).
"""

from __future__ import annotations

from itertools import combinations

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics import plot as kp
from kinetostatics.model.scene import GROUND
from kinetostatics.plot.centres import element_numbers

SCENES = ks.examples()


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


@pytest.fixture(scope="module")
def solutions():
    return {name: ks.solve(ks.example(name)) for name in SCENES}


def _velocity(sol, body: str, i: int, x: float, y: float) -> np.ndarray:
    if body == GROUND:
        return np.zeros(2)
    return np.array(sol.kin.bodies[body].take(i).vel_at(x, y), dtype=float)


@pytest.mark.parametrize("name", SCENES)
def test_every_centre_by_velocities_kennedy_and_name(name, solutions):
    sol = solutions[name]
    numbers = element_numbers(sol.scene)
    n = sol.positions.size
    vmax = max(float(np.nanmax(np.hypot(sol.kinematics.vx, sol.kinematics.vy))), 1e-300)
    for i in (n // 7, n // 3, (3 * n) // 5):
        tab = kp.instant_centres(sol, row=i)
        k = len(numbers)
        assert len(tab) == k * (k - 1) // 2                       # seed 004 eq. 1
        for r in tab.itertuples():
            a, b = sorted((numbers[r.j], numbers[r.k]))
            assert r.name == f"I{a}{b}", (name, r.name, r.j, r.k)
            if r.at_infinity:       # relative translation, across the direction
                for x, y in ((0.0, 0.0), (1.0, 0.5)):
                    rel = _velocity(sol, r.j, i, x, y) - _velocity(sol, r.k, i, x, y)
                    assert abs(np.dot(rel, (r.dir_x, r.dir_y))) <= 1e-9 * vmax, (name, r.name)
            else:
                # measured: 2.2e-16 of the largest speed (all scenes, three rows)
                rel = _velocity(sol, r.j, i, r.x, r.y) - _velocity(sol, r.k, i, r.x, r.y)
                assert np.hypot(*rel) <= 1e-12 * vmax, (name, r.name, rel)
        at = {r.name: r for r in tab.itertuples()}
        xs = tab.x[~tab.at_infinity]
        size = float(max(np.ptp(xs), np.ptp(tab.y[~tab.at_infinity]), 1.0))
        for trio in combinations(sorted(numbers.values()), 3):
            p, q, s = (at[f"I{u}{v}"] for u, v in combinations(trio, 2))
            finite = [c for c in (p, q, s) if not c.at_infinity]
            if len(finite) == 3:
                u = np.subtract((q.x, q.y), (p.x, p.y))
                v = np.subtract((s.x, s.y), (p.x, p.y))
                span = max(np.hypot(*u), np.hypot(*v), size)
                # measured: 4e-16 of span^2 at most
                assert abs(_cross(u, v)) <= 1e-12 * span ** 2, (name, i, trio)
            elif len(finite) == 2:
                c = next(c for c in (p, q, s) if c.at_infinity)
                u = np.subtract((finite[1].x, finite[1].y), (finite[0].x, finite[0].y))
                if np.hypot(*u) > 1e-9 * size:
                    assert abs(_cross(u / np.hypot(*u), (c.dir_x, c.dir_y))) <= 1e-9, \
                        (name, i, trio)


@pytest.mark.parametrize("name", SCENES)
def test_elements_pivoted_at_ok_are_element_k(name, solutions):
    """One numbering rule: a body pivoted to the ground at ``Ok`` is element k, and its
    centre with the frame sits at that pivot."""
    sol = solutions[name]
    numbers = element_numbers(sol.scene)
    assert len(set(numbers.values())) == len(numbers)
    tab = kp.instant_centres(sol, row=5).set_index("name")
    for j in sol.scene.joints.values():
        if j.kind == "R" and GROUND in j.bodies:
            body = j.other(GROUND)
            if j.name.startswith("O") and j.name[1:].isdigit():
                assert numbers[body] == int(j.name[1:]), (name, j.name, body)
            a, b = sorted((numbers[GROUND], numbers[body]))
            x, y = sol.scene.ground[j.point_on(GROUND)]
            c = tab.loc[f"I{a}{b}"]
            assert np.hypot(c.x - x, c.y - y) <= 1e-12, (name, j.name)


def test_the_shapers_centres_carry_its_elements_numbers(solutions):
    sol = solutions["shaper"]
    tab = kp.instant_centres(sol, row=10).set_index("name")
    assert sol.scene.ground["O2"] == pytest.approx((tab.x["I12"], tab.y["I12"]), abs=1e-12)
    assert sol.scene.ground["O4"] == pytest.approx((tab.x["I14"], tab.y["I14"]), abs=1e-12)
    legend = kp.plot_instant_centres(sol, row=10).get_legend()
    texts = [t.get_text() for t in legend.get_texts()]
    assert "1 = ground, 2 = crank, 3 = block, 4 = lever, 5 = link, 6 = ram" in texts
    # the four-bar keeps the course's numbering: ground 0, crank 1 (F01, I13)
    assert element_numbers(solutions["four_bar"].scene) == {
        GROUND: 0, "crank": 1, "coupler": 2, "rocker": 3}
