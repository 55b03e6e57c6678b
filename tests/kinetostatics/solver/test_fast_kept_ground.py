"""The fused kernel's entries by where a dyad's prismatic outer joints lie
(``fused_kernels.KEPT_ON``): a guide on the ground takes an entry whose ground's motion is
constants (``kernels.ground_param``, ``_vel_known``, ``_acc_known``), a guide on the
driver the general one. Their numbers are the composed kernels' bit for bit
(``test_fast_long.py``, a long sweep of each kind: TRR and TTR a ground guide as joint 1,
RRT, RTT and TRT as joint 2, TRT's joint 1 a guide on the crank; a ground's velocity of
1e-9 instead of 0 there failed its RRT and TRR cases, checked 2026-11-30)."""

from __future__ import annotations

import pytest

from kinetostatics.solver.fast import loader

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


def test_a_guide_on_the_ground_takes_its_own_entry(kernels) -> None:
    from kinetostatics.solver.fast.fused_kernels import KEPT, KEPT_ON
    from kinetostatics.solver.fast.layout import G1, G2
    # (no prismatic outer joint: one entry, whatever the known bodies)
    assert {g for k, g in KEPT_ON if k == "RRR"} == {0}
    assert KEPT["RRR"].entry(True, False) is KEPT["RRR"].entry(False, True)
    # the slider-crank: joint 2 a guide on the ground (k2d False)
    assert KEPT["RRT"].entry(True, False) is KEPT_ON["RRT", G2]
    assert KEPT["RRT"].entry(True, True) is KEPT_ON["RRT", 0]
    assert KEPT["TRR"].entry(False, True) is KEPT_ON["TRR", G1]
    assert KEPT["TRT"].entry(False, False) is KEPT_ON["TRT", G1 | G2]
    assert KEPT["TRT"].entry(True, False) is KEPT_ON["TRT", G2]
    # each entry a cache index of its own (test_fast_cache_names.py)
    names = [d.py_func.__name__ for d in KEPT_ON.values()]
    assert len(set(names)) == len(names) and "rrt_kept_g2" in names
