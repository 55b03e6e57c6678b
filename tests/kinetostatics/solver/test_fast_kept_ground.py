"""The fused kernel's entries by where a dyad's outer joints lie (``fused_kernels.KEPT_ON``,
each outer joint's known body the driver or the ground): a guide on the ground takes an
entry whose ground's motion is constants (``kernels.ground_param``, ``_vel_known``,
``_acc_known``), a guide on the driver the general one; the driver's resultants take the
loads of the outer joints on it, a constant of the entry. Their numbers are the composed
kernels' bit for bit (``test_fast_long.py``, a long sweep of each kind: TRR and TTR a
ground guide as joint 1, RRT, RTT and TRT as joint 2, TRT's joint 1 a guide on the crank;
a ground's velocity of 1e-9 instead of 0 there failed its RRT and TRR cases, checked
2026-11-30; ``test_fast_short.py``: the driver's adds left out of the four-bar's entry,
``if not k1d``, failed its RRR case, checked 2026-11-30)."""

from __future__ import annotations

import pytest

from kinetostatics.solver.fast import loader

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


def test_a_guide_on_the_ground_takes_its_own_entry(kernels) -> None:
    from kinetostatics.solver.fast.fused_kernels import KEPT, KEPT_ON
    # an entry per kind and known bodies (each outer joint's the driver, else the ground):
    # which of the driver's resultants take the dyad's outer loads is the entry's constant
    assert KEPT["RRR"].entry(True, False) is KEPT_ON["RRR", True, False]
    assert KEPT["RRR"].entry(True, False) is not KEPT["RRR"].entry(False, True)
    # the slider-crank: joint 2 a guide on the ground (k2d False)
    assert KEPT["RRT"].entry(True, False) is KEPT_ON["RRT", True, False]
    assert KEPT["TRT"].entry(False, False) is KEPT_ON["TRT", False, False]
    # each entry a cache index of its own (test_fast_cache_names.py), named by its ground
    # bits (a prismatic outer joint whose known body is the ground: its guide's motion
    # constants) and its outer joints on the driver
    names = [d.py_func.__name__ for d in KEPT_ON.values()]
    assert len(set(names)) == len(names)
    assert {"rrt_kept_g2_d1", "rrt_kept_d1_d2", "trr_kept_g1_d2", "trt_kept_g1_g2",
            "trt_kept_g2_d1", "rrr_kept_d1", "rrr_kept_d2", "rrr_kept"} <= set(names)


def test_a_dyad_whose_first_outer_joint_is_on_the_ground_takes_its_entry(fast) -> None:
    # the four-bar with its inner joint's bodies the other way round: the dyad's first
    # body is the rocker (its outer joint on the ground), its second the coupler (on the
    # crank): the entry that adds the second outer joint's loads to the driver's, the
    # same numbers, bit for bit, as the composed kernels' full solve (that entry's adds
    # left out, ``if k2d and k1d``, failed this test, checked 2026-11-30)
    import kinetostatics as ks
    from kinetostatics.model.scene import load_scene
    from kinetostatics.solver.fast import fused_kernels
    from tests.kinetostatics.solver.test_fast_short import full_solve
    d = load_scene(ks.example("four_bar")).raw
    d["joints"] = [{**j, "bodies": j["bodies"][::-1]} if j["name"] == "C" else j
                   for j in d["joints"]]
    called = []
    entry = fused_kernels.Kept.entry

    def spy(self, k1d, k2d):
        called.append((self.kind, bool(k1d), bool(k2d)))
        return entry(self, k1d, k2d)
    fused_kernels.Kept.entry = spy
    try:
        sol = ks.solve(d)
        driver = sol.driver.copy()
    finally:
        fused_kernels.Kept.entry = entry
    assert called == [("RRR", False, True)]
    assert driver.equals(full_solve(d).driver)
