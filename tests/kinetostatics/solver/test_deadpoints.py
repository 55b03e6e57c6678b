"""Dead points at a row and between rows, degenerate pivots, one transmission angle, and
no NaN left unchecked."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinetostatics as ks
from kinetostatics.model.errors import AssemblyError
from kinetostatics.results.summary import TIE
from kinetostatics.solver import arith as A
from kinetostatics.solver.pipeline import _check_finite
from tests.kinetostatics import scenes


def slotted_lever(crank: float, start: float = 0.0, count: int = 361) -> dict:
    """The bundled slotted lever; with crank = 0.30 (= O2 O4) the block passes through
    the lever's pivot O4 at 270 deg."""
    with open(ks.example("slotted_lever"), "rb") as fh:
        d = tomllib.load(fh)
    d["bodies"][0]["points"]["A"] = [crank, 0.0]
    d["driver"].update(start=start, stop=start + 360.0, count=count)
    return d


def change_point_four_bar(a: float, b: float, c: float, start: float, count: int) -> dict:
    """A four-bar with a + b = c + d (crank a < rocker c < coupler b, ground d = a + b - c):
    its change point (all four pivots on a line) is at crank angle 0 deg."""
    d = a + b - c
    return scenes.four_bar(a, b, c, d, cogs=([a / 2, 0.0], [b / 2, 0.01], [c / 2, 0.0]),
                           start=start, count=count,
                           loads=[{"body": "rocker", "moment": -5.0}],
                           near=[d, 10.0 * (a + b + c)])

def test_block_through_the_pivot_at_a_row_is_refused_naming_it() -> None:
    """Was: Me = -2e16 N m, reactions 4e33 N, singular false."""
    with pytest.raises(AssemblyError, match=r"O4.*coincide at driver position\(s\) 270 deg"):
        ks.solve(slotted_lever(0.30))


def test_block_through_the_pivot_between_rows_is_flagged() -> None:
    sol = ks.solve(slotted_lever(0.30, start=0.5))
    s = sol.summary()
    assert s["dead_points_between_rows"] == [[269.5, 270.5]]
    drv = sol.driver.set_index("position")
    assert drv.loc[269.5, "singular"] and drv.loc[270.5, "singular"]
    assert s["singular_rows"] == 2
    # the lever turns by 180 deg between those rows: that is the dead point
    lever = sol.bodies[sol.bodies.body == "lever"].set_index("position").angle
    assert abs(abs(lever[270.5] - lever[269.5]) - 180.0) < 5.0


def test_change_point_between_rows_is_flagged() -> None:
    """Was: omega of the rocker -53.5 -> +13.5 rad/s between adjacent rows, nothing
    flagged (sin tau = 4e-3 at both rows)."""
    sol = ks.solve(change_point_four_bar(0.1, 0.3, 0.2, 100.3, 361))
    s = sol.summary()
    assert s["dead_points_between_rows"] == [[359.3, 360.3]]
    rows = sol.driver.set_index("position").singular
    assert rows[359.3] and rows[360.3] and s["singular_rows"] == 2


def test_regular_mechanisms_have_no_dead_point() -> None:
    for name in ks.examples():
        s = ks.solve(ks.example(name)).summary()
        assert s["dead_points_between_rows"] == [] and s["singular_rows"] == 0, name


@settings(max_examples=30, deadline=None)
@given(st.floats(0.05, 0.2), st.floats(1.2, 3.0), st.floats(1.1, 2.0),
       st.floats(5.0, 355.0), st.integers(19, 721))
def test_rows_within_a_spacing_of_a_change_point_are_flagged(a, kb, kc, start, count):
    """Hypothesis: any change-point four-bar, any sweep: every row within one row's spacing
    of the change point (crank angle 0 mod 360) is flagged singular; rows far from it,
    where the dyad transmits well, are not."""
    c = a * kc
    b = c * kb
    try:
        sol = ks.solve(change_point_four_bar(a, b, c, start, count))
    except AssemblyError as exc:                        # a row on the change point itself
        pos = np.linspace(start, start + 360.0, count)
        assert np.min(np.abs((pos + 180.0) % 360.0 - 180.0)) < 1e-6, str(exc)
        return
    pos = np.asarray(sol.positions, dtype=float)
    spacing = 360.0 / (count - 1)
    dist = np.abs((pos + 180.0) % 360.0 - 180.0)
    flagged = sol.driver.singular.to_numpy()
    assert flagged[dist <= spacing * (1 - 1e-9)].all()
    tau = sol.dyads.transmission_angle.to_numpy()
    assert not flagged[(dist > 3 * spacing) & (tau > 5.0)].any()


def test_transmission_angle_has_one_definition() -> None:
    sol = ks.solve(ks.example("four_bar"))
    t = sol.dyads
    assert t.transmission_angle.between(0.0, 90.0).all()
    np.testing.assert_allclose(t.transmission_angle, np.minimum(t.tau, 180.0 - t.tau),
                               rtol=0, atol=1e-12)
    s = sol.summary()
    tau = t.transmission_angle.to_numpy()
    assert s["transmission_angle_min"] == tau.min()
    # located at the first row that ties with it to rounding: 0 deg (the row at 360 deg,
    # the same pose, one unit in the last place lower, ties with it)
    i = int(np.argmax(tau - tau.min() <= TIE * tau.min()))
    assert s["transmission_angle_min_position"] == float(t.position.iloc[i]) == 0.0
    assert round(s["transmission_angle_min"], 1) == 51.3     # the bundled four-bar


def test_zero_times_nan_stays_nan() -> None:
    bad = np.array([1.0, np.nan, 2.0])
    assert np.isnan(A.mul(0.0, bad)[1]) and np.isnan(A.mul(bad, 0.0)[1])
    assert A.mul(0.0, np.array([1.0, 2.0])) == 0.0      # finite: the pass is skipped


@pytest.mark.parametrize("field", ["sin", "omega", "alpha", "vx", "ay"])
def test_every_table_number_is_checked_finite(field) -> None:
    """A NaN anywhere behind a table (here planted in one body's motion) is refused,
    naming the driver position."""
    sol = ks.solve(ks.example("four_bar"))
    m = sol.kin.bodies["rocker"]
    value = np.array(np.broadcast_to(getattr(m, field), sol.positions.shape), dtype=float)
    value[7] = np.nan
    setattr(m, field, value)
    with pytest.raises(AssemblyError, match=r"at driver position 7 deg"):
        _check_finite(sol)


def test_coincident_pivots_at_the_first_row_are_named() -> None:
    """A crank as long as the ground link puts B on D at 0 deg: was "do not reach by inf m"."""
    with open(ks.example("four_bar"), "rb") as fh:
        d = tomllib.load(fh)
    d["bodies"][0]["points"]["B"] = [0.30, 0.0]
    with pytest.raises(AssemblyError, match=r"'B' and 'D' coincide at driver position\(s\) 0 deg"):
        ks.solve(d)


def _candidates_reference(m2: np.ndarray, starts: np.ndarray, counts: np.ndarray
                          ) -> np.ndarray:
    """The screen of :func:`~kinetostatics.solver.deadpoints._candidates` over every row
    (its first form): each row against its neighbours in the segment."""
    n = m2.size
    if n < 2:
        return np.zeros(0, dtype=int)
    left = np.concatenate([[np.inf], m2[:-1]])
    right = np.concatenate([m2[1:], [np.inf]])
    left[starts] = np.inf
    right[starts + counts - 1] = np.inf
    shrink = 1.0 - 1e-9
    dip = (((m2 < left * shrink) & (m2 <= right))
           | ((m2 <= left) & (m2 < right * shrink)))
    rows = np.flatnonzero(dip & (m2 < 0.25))
    out = np.unique(np.concatenate([rows - 1, rows]))
    out = out[(out >= 0) & (out < n - 1)]
    last = np.zeros(n, dtype=bool)
    last[starts + counts - 1] = True
    return out[~last[out]]


def test_candidate_intervals_as_every_row_compared() -> None:
    """The screen compares only the rows below it with their neighbours; it finds the
    intervals of comparing every row (segments of any length, empty ones, ties, values
    within rounding of each other, NaN and infinities, one segment or many)."""
    from kinetostatics.solver.deadpoints import SCREEN, _candidates

    assert SCREEN**2 == 0.25
    rng = np.random.default_rng(5)
    pool = np.array([0.0, 0.1, 0.1 * (1 - 1e-10), 0.1 * (1 - 2e-9), 0.2, 0.3, 0.6,
                     np.nan, np.inf])
    for _ in range(3000):
        counts = rng.integers(0, 8, rng.integers(1, 6))
        counts[-1] = max(counts[-1], 1)
        starts = np.cumsum(counts) - counts
        n = int(counts.sum())
        m2 = rng.choice(pool, n) if rng.random() < 0.6 else rng.random(n) * 0.6
        got = _candidates(m2, starts, counts)
        np.testing.assert_array_equal(got, _candidates_reference(m2, starts, counts))
        assert got.dtype == np.int64
        whole = (np.zeros(1, dtype=int), np.array([n]))
        np.testing.assert_array_equal(_candidates(m2), _candidates_reference(m2, *whole))
