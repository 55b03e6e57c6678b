"""Loads on the working stroke only: ``when = "resisting"`` (docs/scene-extensions.md).

A constant force that acts only while it opposes its point's motion (a shaper's
cutting force). Checked against the kinematics directly, by the work it absorbs over a
cycle (|F| times the stroke, a closed form), and by the independent checks of
``checks.py`` (virtual power, matrix solution), which apply the rule themselves.
"""

from __future__ import annotations

import copy
import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import WorkbenchError
from tests.kinetostatics import checks

with open(ks.example("shaper"), "rb") as fh:
    SHAPER = tomllib.load(fh)


def shaper(**driver) -> dict:
    d = copy.deepcopy(SHAPER)
    d["driver"].update(driver)
    return d


def cutting_load(sol) -> tuple[np.ndarray, np.ndarray]:
    """(Fx applied at the ram's T, ram velocity vx) per row."""
    ld = next(x for x in sol.loads if x.kind == "applied" and x.body == "ram")
    fx = np.broadcast_to(ld.fx, sol.positions.shape)
    k = sol.kinematics.query("body == 'ram' and point == 'T'")
    return fx, k.vx.to_numpy()


def test_force_acts_on_the_working_stroke_only():
    sol = ks.solve(SHAPER)
    fx, vx = cutting_load(sol)
    working = vx < 0.0                                  # F = +400 N resists motion to -x
    assert np.all(fx[working & ~sol.undefined_load] == 400.0)
    assert np.all(fx[~working] == 0.0)
    assert 0.5 < working.mean() < 0.7                   # the slow stroke is the longer one


def test_cycle_work_is_force_times_stroke():
    """Over a cycle at constant speed, inertia and gravity do no net work: the driver's
    work is the cutting work |F| s, s the ram's stroke (trapezoidal mean over a fine
    sweep; the force jumps at the two dead centres, an O(1/n) error)."""
    sol = ks.solve(shaper(count=20001))
    x = sol.kinematics.query("body == 'ram' and point == 'F'").x.to_numpy()
    stroke = x.max() - x.min()
    phi = np.deg2rad(sol.positions)
    work = np.trapezoid(sol.Me, phi)
    assert work == pytest.approx(400.0 * stroke, rel=2e-4)
    assert sol.summary()["Me_mean"] > 0.0


def test_independent_checks_hold():
    sol = ks.solve(SHAPER)
    assert checks.virtual_power(sol) < 1e-9
    assert checks.matrix_difference(sol) < 1e-9


def _around(position: float):
    """The shaper solved at 190 deg, ``position`` and 210 deg (the sweep sets the scale
    of 'standing still', as for ``resist``)."""
    d = copy.deepcopy(SHAPER)
    for k in ("start", "stop", "count"):
        d["driver"].pop(k, None)
    d["driver"]["positions"] = [190.0, position, 210.0]
    return ks.solve(d)


def _ram_vx(position: float) -> float:
    return float(_around(position).kinematics.query(
        "body == 'ram' and point == 'T'").vx.to_numpy()[1])


def test_a_standing_point_flags_the_row():
    """At the ram's dead centre (velocity zero, found by bisection near 199 deg) the
    force is off and the row is flagged ``undefined_load``; a degree away it is not."""
    lo, hi = 198.0, 200.0
    assert np.sign(_ram_vx(lo)) != np.sign(_ram_vx(hi))
    for _ in range(55):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.sign(_ram_vx(mid)) == np.sign(_ram_vx(lo)) else (lo, mid)
    s = _around(0.5 * (lo + hi))
    assert s.undefined_load.tolist() == [False, True, False]
    assert cutting_load(s)[0][1] == 0.0
    assert not _around(lo - 1.0).undefined_load.any()


@pytest.mark.parametrize(("edit", "words"), [
    ({"when": "sometimes"}, "not one of"),
    ({"when": "resisting", "force": None, "resist": 400.0}, "constant 'force'"),
    ({"when": "resisting", "moment": 5.0}, "no 'moment'"),
    ({"when": 3}, "when"),
])
def test_bad_when_is_one_line(edit, words):
    d = copy.deepcopy(SHAPER)
    ld = d["loads"][0]
    for k, v in edit.items():
        if v is None:
            ld.pop(k)
        else:
            ld[k] = v
    with pytest.raises(WorkbenchError) as exc:
        ks.solve(d)
    msg = str(exc.value)
    assert words in msg and "loads[0]" in msg and "\n" not in msg
