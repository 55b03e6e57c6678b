"""Two dyads' closeness to a dead centre (the six-bars' guided sweeps) taken in one
``np.minimum`` (:func:`~kinetostatics.solver.deadpoints.measure2`): the bits of the
running ``min(min(inf, a), b)`` it takes of other counts, NaN, signed zeros and
infinities too (no kernel compiled here: numpy's alone)."""

from __future__ import annotations

import numpy as np
import pytest

from kinetostatics.solver.deadpoints import measure2

SPECIAL = np.array([0.0, -0.0, 5e-324, 1.0, np.inf, -np.inf, np.nan, -np.nan, 1e300])


def pairs(n: int = 5_000) -> tuple[np.ndarray, np.ndarray]:
    """Every pair of the special values, then random magnitudes with signs."""
    rng = np.random.default_rng(7)
    a = np.concatenate([np.repeat(SPECIAL, SPECIAL.size), rng.standard_normal(n) * 1e3])
    b = np.concatenate([np.tile(SPECIAL, SPECIAL.size), rng.standard_normal(n) * 1e3])
    return a, b


def running_min(close: list, n: int) -> np.ndarray:
    """The smallest per row as a running ``np.minimum`` from inf (each array
    broadcast to ``n`` rows): the measure of any number of dyads, written out."""
    m2 = np.full(n, np.inf)
    for c in close:
        np.minimum(m2, np.broadcast_to(c, (n,)), out=m2)
    return m2


def test_two_dyads_give_measure2s_bits() -> None:
    a, b = pairs()
    n = a.size
    got = measure2([a, b], n)
    assert got.tobytes() == running_min([a, b], n).tobytes()
    assert got is not a and got is not b                 # (a new array: the inputs kept)


@pytest.mark.parametrize("count", [1, 3])
def test_other_counts_are_measure2s(count: int) -> None:
    a, b = pairs()
    close = [a, b, -a][:count]
    assert measure2(close, a.size).tobytes() == running_min(close, a.size).tobytes()


def test_a_scalar_closeness_is_broadcast_as_measure2_does() -> None:
    a, _ = pairs()
    close = [a, np.float64(0.5)]
    assert measure2(close, a.size).tobytes() == running_min(close, a.size).tobytes()


def test_spent_arrays_take_the_measure_over_the_second() -> None:
    """``spent``: the same bits, written over the second dyad's array (the first kept)."""
    a, b = pairs()
    n = a.size
    expected = running_min([a, b], n)
    first = a.copy()
    got = measure2([a, b], n, spent=True)
    assert got is b
    assert got.tobytes() == expected.tobytes()
    assert a.tobytes() == first.tobytes()
