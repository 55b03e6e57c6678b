"""The fused kernel's crank pass over a long sweep: the crank's cos and sin worked out in the
kernel, tile by tile (:func:`kinetostatics.solver.fast.fused_kernels.turn_rows`, the C
library's ``sincos``), where :func:`kinetostatics.solver.fast.solve.kernel_trig` finds them
numpy's: the same numbers, bit for bit, as the kernel given numpy's cos and sin per block
(:func:`kinetostatics.solver.fast.solve.crank_blocks`)."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from kinetostatics.model.scene import load_scene
from kinetostatics.solver.fast import loader
from kinetostatics.solver.fast import solve as fast_solve
from kinetostatics.solver.fast.short import OWNERS
from kinetostatics.solver.fast.solve import _assembled, fused_blocks, kernel_trig, trig_probes
from kinetostatics.solver.kinematics import with_positions
from kinetostatics.solver.pipeline import structure_of

from .test_fast_short import FUSED

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")

# more rows than one call of the kernel (OWNERS rows), and a last tile of a few rows
COUNT = 2 * OWNERS.size + 7


@pytest.fixture
def kernels():
    k = loader.kernels()
    if k is None:
        pytest.skip("no writable cache folder")
    return k


def test_the_kernels_cos_and_sin_are_numpys_where_they_are_used(kernels) -> None:
    from kinetostatics.solver.fast.fused_kernels import turn_rows
    x = trig_probes()
    cs, sn = np.empty_like(x), np.empty_like(x)
    turn_rows(x, cs, sn)
    with np.errstate(invalid="ignore"):
        same = (cs.tobytes() == np.cos(x).tobytes() and sn.tobytes() == np.sin(x).tobytes())
    assert kernel_trig() == same
    # (glibc's sincos against its cos and sin, which numpy calls: the same doubles on
    # every probe here, measured 2026-11-29, and on 1e7 angles within +-1e15)
    if not same:
        pytest.skip("numpy's cos and sin are not the C library's here: numpy's are used")


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
def test_the_kernels_crank_pass_is_numpys_bit_for_bit(kernels, monkeypatch, kind: str,
                                                      given: bool) -> None:
    if not kernel_trig():
        pytest.skip("numpy's cos and sin are not the C library's here: numpy's are used")
    sc, structure, geometry, pos = _long(kind, given)
    ours = fused_blocks(kernels, sc, sc, structure, geometry, pos)
    monkeypatch.setitem(fast_solve._TRIG, "same", False)        # numpy's, per block
    ref = fused_blocks(kernels, sc, sc, structure, geometry, pos)
    angles = sc.driver.angles
    assert ours.crank[0].tobytes() == np.cos(angles).tobytes()
    assert ours.crank[1].tobytes() == np.sin(angles).tobytes()
    assert ours.drive.value.tobytes() == ref.drive.value.tobytes()
    assert np.array_equal(ours.undefined, ref.undefined)
    assert ours.closeness2[0].tobytes() == ref.closeness2[0].tobytes()
