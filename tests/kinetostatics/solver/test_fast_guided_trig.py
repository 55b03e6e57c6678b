"""The guide's kernels' first pass with the cos and sin worked out in it
(``guide_kernels.rtr_guide_turned``: the crank's and the RTR guide's, the C library's,
used where ``solve.kernel_trig`` finds them numpy's) against the pass given numpy's
(``rtr_guide``, numpy's cos and sin around it): what a long sweep keeps (Me, each dyad's
closeness to a dead centre, the undefined rows) the same, bit for bit, for the shaper,
the slotted lever and a slotted lever whose slot is off the pivot (asin taken)."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.blocks import BLOCK_ROWS
from kinetostatics.solver.fast import loader
from kinetostatics.solver.pipeline import Sweep

from .test_fast_guided import offset_slot

# (slow: the guide's kernels compiled first on a fresh machine)
pytestmark = [pytest.mark.skipif(not loader.installed(), reason="numba not installed"),
              pytest.mark.slow]

ROWS = 2 * BLOCK_ROWS + 4097        # (blocks of GUIDED_ROWS and a short last one)


def example_sweep(name: str, count: int) -> dict:
    """The bundled example ``name`` over ``count`` positions of a turn."""
    d = copy.deepcopy(load_scene(ks.example(name)).raw)
    d["driver"].update(start=0.0, stop=360.0, count=count)
    return d


SCENES = {"shaper": lambda n: example_sweep("shaper", n),
          "slotted_lever": lambda n: example_sweep("slotted_lever", n),
          "offset_slot": offset_slot}


def kept_bytes(monkeypatch, scene: dict, trig: bool | None) -> list[bytes]:
    """What ``guided_blocks`` keeps of ``scene``'s sweep, as bytes, with the cos and sin
    in the guide's pass (``trig`` True), numpy's (False) or as the solve chooses (None:
    :func:`~kinetostatics.solver.fast.solve.kernel_trig`)."""
    from kinetostatics.solver.fast import solve as fast_solve
    from kinetostatics.solver.fast import use
    use("fast")
    if trig is not None:
        monkeypatch.setattr(fast_solve, "kernel_trig", lambda: trig)
    try:
        sw = Sweep(scene)
        sc = sw.scene
        structure, geometry = fast_solve._assembled(sc, sw.structure)
        kept = fast_solve.guided_blocks(loader.kernels(), sc, structure, geometry,
                                        sc.driver.positions)
    finally:
        use(None)
        monkeypatch.undo()
    assert kept is not None                 # (the guide's kernels took it)
    return [kept.drive.value.tobytes(), kept.undefined.tobytes(),
            *(c.tobytes() for c in kept.closeness2)]


@pytest.mark.parametrize("name", list(SCENES))
def test_the_guide_pass_turning_its_own_angles_keeps_the_numbers(monkeypatch, name):
    """The guide's pass as the solve chooses it (working out the cos and sin where the C
    library's are numpy's here, ``kernel_trig``: this machine's case, measured
    2026-11-30) gives what the pass given numpy's gives, bit for bit."""
    scene = SCENES[name](ROWS)
    assert kept_bytes(monkeypatch, scene, None) == kept_bytes(monkeypatch, scene, False)


def test_the_turned_pass_writes_numpy_cos_and_sin_of_the_crank():
    """``rtr_guide_turned``'s cos and sin of the crank's angles (a block from row ``a0``)
    are numpy's where ``kernel_trig`` holds, and its guide's angles' cos and sin are
    numpy's of the angles it writes."""
    from kinetostatics.solver.fast.compose import Plan
    from kinetostatics.solver.fast.solve import _assembled, _guided, kernel_trig
    loader.kernels()
    from kinetostatics.solver.fast.guide_kernels import rtr_guide_turned
    sw = Sweep(example_sweep("slotted_lever", 1001))
    sc = sw.scene
    structure, geometry = _assembled(sc, sw.structure)
    plan = Plan(loader.kernels(), sc, structure, structure.assembly, geometry=geometry)
    _, first, _ = _guided(plan)
    angles = sc.driver.angles
    a0, m = 300, 500
    th, ct, sg, cs, sn, reach, gap = np.full((7, m), np.nan)
    rtr_guide_turned(a0, m, angles, cs, sn, *first, th, ct, sg, reach, gap)
    turned = [cs, sn, ct, sg]
    numpys = [np.cos(angles[a0:a0 + m]), np.sin(angles[a0:a0 + m]), np.cos(th), np.sin(th)]
    assert np.isfinite(th).all() and np.isfinite(reach).all()
    same = [a.tobytes() == b.tobytes() for a, b in zip(turned, numpys, strict=True)]
    assert same == [kernel_trig()] * 4
