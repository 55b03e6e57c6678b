"""The guide's kernel working out the cos and sin in each tile (``guide_kernels``,
given the crank's angles: the crank's and the RTR guide's, the C library's, used where
``solve.kernel_trig`` finds them numpy's) against the two passes given numpy's
(``rtr_guide``, numpy's cos and sin around it): what a long sweep keeps (Me, each dyad's
closeness to a dead centre, the undefined rows) the same, bit for bit, for the shaper,
the slotted lever and a slotted lever whose slot is off the pivot (asin taken)."""

from __future__ import annotations

import copy

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
    """The guide's kernel as the solve chooses it (working out the cos and sin in each
    tile where the C library's are numpy's here, ``kernel_trig``: this machine's case,
    measured 2026-11-30) gives what the two passes given numpy's give, bit for bit."""
    scene = SCENES[name](ROWS)
    assert kept_bytes(monkeypatch, scene, None) == kept_bytes(monkeypatch, scene, False)
    # the two roads give the kernel arrays of one type (the angles read-only, the rows
    # writable either way): each entry point compiled once
    from kinetostatics.solver.fast import guide_kernels
    kernels = [guide_kernels.rtr_kept, *guide_kernels.AFTER_RTR.values()]
    assert [len(k.signatures) for k in kernels if len(k.signatures) > 1] == []

