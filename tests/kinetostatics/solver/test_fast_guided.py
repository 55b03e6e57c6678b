"""The RTR guide's angle on the compiled path (``closure_kernels.rtr_guide_angle``, seed 000
ch. 6-7), worked out as its cos and sin (no asin, atan2, cos or sin): a slot through the
guide's pivot (c = 0, the shaper's and the slotted lever's) and a slot off the pivot
(c != 0) both agree with the numpy path, short and long sweeps."""

from __future__ import annotations

import copy

import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.blocks import BLOCK_ROWS
from kinetostatics.solver.fast import loader
from kinetostatics.solver.fast.layout import I_RTR
from kinetostatics.solver.fast.solve import _assembled
from kinetostatics.solver.pipeline import structure_of

from .test_fast import agree, both

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


def offset_slot(count: int, offset: float = 0.03) -> dict:
    """The slotted lever with its slot's line through a lever point ``offset`` off the
    pivot's line (c != 0: the guide's angle takes asin)."""
    d = copy.deepcopy(load_scene(ks.example("slotted_lever")).raw)
    lever = next(b for b in d["bodies"] if b["name"] == "lever")
    lever["points"]["L"] = [0.0, offset]
    slot = next(j for j in d["joints"] if j["name"] == "A-slot")
    slot["line_point"] = "L"
    d["driver"] = {**d["driver"], "count": count}
    return d


def rtr_offset(scene: dict) -> float:
    """c, the RTR dyad's line offset from the guide's pivot, as the kernels have it."""
    sc = load_scene(scene)
    _, geometry = _assembled(sc, structure_of(sc))
    return float(geometry.dyads[0][0][I_RTR, 0])


@pytest.mark.slow          # (the slotted lever's kernels compiled on a cold cache)
@pytest.mark.parametrize("count", [361, 2 * BLOCK_ROWS + 4097])
def test_a_slot_off_the_pivot_agrees_with_numpy(count: int) -> None:
    """A short sweep (its fused path: guided_blocks) and a long one (blocks of rows)."""
    d = offset_slot(count)
    assert rtr_offset(d) != 0.0
    assert rtr_offset(load_scene(ks.example("slotted_lever")).raw) == 0.0
    a, b = both(d)
    assert a.path == "numpy" and b.path == "fast"
    agree(a, b)
