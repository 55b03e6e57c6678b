"""The fused kernel's crank pass over a long sweep: the crank's cos and sin worked out in the
kernel, tile by tile, into its scratch (``fused_kernels._tile_turn``; none kept over the
sweep): the same numbers as the kernel given the compiled path's
(:func:`kinetostatics.solver.fast.trig_kernels.turn_rows`; the road of a short sweep and
``solve_many``), bit for bit."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from kinetostatics.model.scene import load_scene
from kinetostatics.solver.deadpoints import SCREEN
from kinetostatics.solver.fast import loader
from kinetostatics.solver.fast import solve as fast_solve
from kinetostatics.solver.fast.short import NO_ANGLES, NO_ROWS, OWNERS, START
from kinetostatics.solver.fast.solve import _assembled, fused_blocks
from kinetostatics.solver.kinematics import with_positions
from kinetostatics.solver.pipeline import structure_of

from .test_fast_short import FUSED

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")

# more rows than one call of the kernel (OWNERS rows), and a last tile of a few rows
COUNT = 2 * OWNERS.size + 7


def _long(kind: str, given: bool):
    d = copy.deepcopy(load_scene(FUSED[kind]).raw)
    d["driver"] = {**d["driver"], "count": COUNT}
    sc = load_scene(d)
    structure, geometry = _assembled(sc, structure_of(sc))
    pos = sc.driver.positions
    if given:       # (positions given, not a sweep's)
        pos = np.linspace(350.0, -340.0, COUNT)
        sc = with_positions(sc, pos)
    # (read-only, as NO_ANGLES: the kernel's one signature)
    assert not sc.driver.angles.flags.writeable
    return sc, structure, geometry, pos


# Each kind is a fused kernel of its own, compiled on its first call (7-17 s of processor
# time on an empty or stale cache, measured 2026-11-30): the quick tier checks the four-bar's
# (a sweep and given positions), the slow tier every kind (whose kernels the slow tests of
# test_fast.py and test_fast_long.py compile anyway, with the same signature)
@pytest.mark.parametrize("kind,given", [
    pytest.param(k, False, marks=() if k == "RRR" else pytest.mark.slow) for k in FUSED]
    + [("RRR", True)])
def test_the_kernels_crank_pass_is_the_compiled_paths_bit_for_bit(kernels, kind: str,
                                                                   given: bool) -> None:
    from kinetostatics.solver.fast.trig_kernels import turned
    sc, structure, geometry, pos = _long(kind, given)
    ours = fused_blocks(kernels, sc, sc, structure, geometry, pos)
    angles = sc.driver.angles
    cs, sn = turned(angles)
    # the kernel given the cos and sin, per call of OWNERS rows
    kernel, fixed, _ = fast_solve._fused(kernels, sc, structure, geometry)
    n = pos.size
    drive, close, undefined = np.empty(n), np.empty(n), np.zeros(n, dtype=bool)
    singular = np.empty(n, dtype=bool)
    for lo in range(0, n, OWNERS.size):
        at = slice(lo, min(lo + OWNERS.size, n))
        bad, _ = kernel(0, at.stop - lo, OWNERS, cs[at], sn[at], START, NO_ANGLES, *fixed,
                        drive[at], close[at], singular[at], undefined[at], SCREEN**2, NO_ROWS)
        assert bad == 0
    assert ours.drive.value.tobytes() == drive.tobytes()
    assert np.array_equal(ours.undefined, undefined)
    assert ours.closeness2[0].tobytes() == close.tobytes()
    assert np.array_equal(ours.singular[0], singular)
