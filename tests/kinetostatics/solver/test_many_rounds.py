"""The dead-point screen's probes of a stack in one compiled call (``fast/screen.py``'s
``at.rounds``, ``screen_kernels.probe_rounds``, a crank and one RRR dyad; the other
structures' ``probe_kernels.rounds_of``: test_screen_chain) against the same probes
round by round (``deadpoints._probe`` with the rounds' ``at``: numpy's cos and sin, the
compiled probe per round): the same smallest closeness per interval bit for bit, the same
intervals where the dyad cannot close."""

from __future__ import annotations

import numpy as np
import pytest

from kinetostatics.solver.deadpoints import _probe
from kinetostatics.solver.fast import loader
from kinetostatics.solver.fast.screen import crank_rrr_probe
from kinetostatics.solver.fast.solve import kernel_trig

from .test_screen_probe import long_cranks, stack

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


class RoundByRound:
    """The probe ``at`` without its ``rounds``: each round probed apart."""

    def __init__(self, at) -> None:
        self.at = at

    def __call__(self, positions, owner):
        return self.at(positions, owner)


def assert_rounds_as_one_by_one(at, lo, hi, owner) -> tuple:
    """Check ``at.rounds`` (every round in one call) against the rounds probed one by one
    bit for bit, over the intervals (``lo``, ``hi``; the first five made empty); returns
    the latter."""
    lo[:5] = hi[:5]                 # (empty intervals too)
    expected = _probe(RoundByRound(at), lo, hi, owner)
    got = _probe(at, lo.copy(), hi.copy(), owner)
    for g, e in zip(got, expected, strict=True):
        assert g.dtype == e.dtype and g.shape == e.shape
        np.testing.assert_array_equal(g.view(np.uint8), e.view(np.uint8))
    return expected


@pytest.mark.parametrize("seed", [1, 2])
def test_rounds_in_one_call_are_the_rounds_one_by_one(fast, seed) -> None:
    stacker, structure, k = stack(long_cranks(120, seed))
    at = crank_rrr_probe(stacker, structure, k)
    if not kernel_trig():
        assert not hasattr(at, "rounds")
        pytest.skip("the C library's cos and sin are not numpy's here")
    rng = np.random.default_rng(seed)
    owner = rng.integers(0, len(stacker.scenes), 3000)
    lo = rng.uniform(-360.0, 720.0, 3000)
    hi = lo + rng.uniform(0.01, 30.0, 3000)
    expected = assert_rounds_as_one_by_one(at, lo, hi, owner)
    # (measured: 419 and 365 of 3000 intervals with a probe that cannot close, 321 and
    # 279 with no probe that closes; one below 1e-6 in each)
    assert 0 < expected[1].sum() < lo.size
    assert 0 < np.isfinite(expected[0]).sum() < lo.size
