"""The summary's extremes: located at the first row that ties with them to rounding,
whichever way the rows are handed in (whole, or block by block as a streamed write)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from kinetostatics.results.summary import TIE, Extreme


def _extreme(kind: str, values, positions, cuts=()) -> Extreme:
    e = Extreme(kind)
    bounds = [0, *sorted(cuts), len(values)]
    for a, b in zip(bounds[:-1], bounds[1:], strict=True):
        e.add(np.asarray(values[a:b], dtype=float), np.asarray(positions[a:b], dtype=float))
    return e


def test_a_flat_minimum_is_located_at_its_first_row():
    # the slotted lever's RTR transmission angle: 90 deg at every row, one unit in the
    # last place below at some rows on the compiled path
    low = np.nextafter(90.0, 0.0)
    values = [90.0, 90.0, low, 90.0, low]
    positions = [0.0, 1.0, 2.0, 3.0, 4.0]
    for cuts in ((), (1,), (2,), (3,), (1, 3), (1, 2, 3, 4)):
        e = _extreme("min", values, positions, cuts)
        assert e.value == low and e.at == 0.0, cuts


def test_an_extreme_beyond_rounding_is_its_own_row():
    values = [1.0, 1.0 - 1e-12, 1.0, 1.0 + 1e-12]
    positions = [10.0, 20.0, 30.0, 40.0]
    assert _extreme("min", values, positions).at == 20.0
    assert _extreme("max", values, positions).at == 40.0
    assert _extreme("max", values, positions, (1, 2, 3)).at == 40.0


def test_a_nan_is_the_extreme_at_its_first_row():
    e = _extreme("max", [1.0, np.nan, 2.0, np.nan], [0.0, 1.0, 2.0, 3.0], (2,))
    assert np.isnan(e.value) and e.at == 1.0


def test_the_first_tie_may_lie_between_earlier_extremes():
    """Rows tying with the extreme only once a later block lowers it: the first of them
    (here the second row): neither the first row tying with the old extreme (the first)
    nor the old extreme's own (the third)."""
    t = TIE * 10.0
    values = [10.0 + 0.9 * t, 10.0 + 0.3 * t, 10.0, 10.0 - 0.5 * t]
    for cuts in ((), (3,), (1, 3), (2, 3)):
        e = _extreme("min", values, [0.0, 1.0, 2.0, 3.0], cuts)
        assert (e.value, e.at) == (10.0 - 0.5 * t, 1.0), cuts


@given(st.lists(st.integers(-4, 4), min_size=1, max_size=40), st.data())
def test_blocks_give_the_whole_rows_answer(steps, data):
    """Values steps of 0.4 of a tie apart (some rows tie, some do not), handed in block
    by block: the extreme and its row are those of the rows handed in whole, and the
    row is the first whose value ties with the extreme."""
    base = -7.25 if data.draw(st.booleans()) else 7.25
    values = [base + u * 0.4 * TIE * abs(base) for u in steps]
    positions = [float(i) for i in range(len(values))]
    cuts = sorted(data.draw(st.sets(st.integers(1, max(1, len(values) - 1)), max_size=4)))
    cuts = [c for c in cuts if c < len(values)]
    for kind in ("min", "max"):
        whole = _extreme(kind, values, positions)
        parts = _extreme(kind, values, positions, cuts)
        assert (parts.value, parts.at) == (whole.value, whole.at)
        best = min(values) if kind == "min" else max(values)
        assert whole.value == best
        first = next(i for i, v in enumerate(values)
                     if abs(v - best) <= TIE * abs(best))
        assert whole.at == first


def test_the_slotted_levers_transmission_angle():
    """Its RTR angle is 90 deg at every row (to one unit in the last place on the
    compiled path: ``KINETOSTATICS_PATH=fast`` runs this there): located at the first."""
    from kinetostatics.model.examples import scene_path
    from kinetostatics.model.scene import load_scene
    from kinetostatics.results import solve

    s = solve(load_scene(scene_path("slotted_lever"))).summary()
    assert s["transmission_angle_min"] == pytest.approx(90.0, abs=1e-12)
    assert s["transmission_angle_min_position"] == 0.0
