"""The guide's kernel (``guide_kernels``, given the crank's angles: each tile working out
the crank's cos and sin, the compiled path's, and the RTR guide's angle's, then the
rest) against the composed kernels (``compose.solve_lean``: the crank's cos and sin in
a pass of their own, the guide's in the RTR kernel's first stage): what a long sweep
keeps (Me, each dyad's closeness to a dead centre, the undefined rows) the same, bit
for bit, for the shaper, the slotted lever and a slotted lever whose slot is off the
pivot."""

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

ROWS = 2 * BLOCK_ROWS + 4097        # (a long sweep, not a whole number of tiles)


def example_sweep(name: str, count: int) -> dict:
    """The bundled example ``name`` over ``count`` positions of a turn."""
    d = copy.deepcopy(load_scene(ks.example(name)).raw)
    d["driver"].update(start=0.0, stop=360.0, count=count)
    return d


SCENES = {"shaper": lambda n: example_sweep("shaper", n),
          "slotted_lever": lambda n: example_sweep("slotted_lever", n),
          "offset_slot": offset_slot}


def kept_bytes(scene: dict, guided: bool) -> list[bytes]:
    """What ``scene``'s sweep keeps, as bytes: by ``guided_blocks`` (``guided``) or by the
    composed kernels."""
    from kinetostatics.solver.fast import solve as fast_solve
    from kinetostatics.solver.fast import use
    from kinetostatics.solver.fast.compose import Plan, solve_lean
    use("fast")
    try:
        sw = Sweep(scene)
        sc = sw.scene
        structure, geometry = fast_solve._assembled(sc, sw.structure)
        pos = sc.driver.positions
        if guided:
            kept = fast_solve.guided_blocks(loader.kernels(), sc, structure, geometry, pos)
        else:
            kept = solve_lean(Plan(loader.kernels(), sc, structure, structure.assembly,
                                   geometry=geometry), pos)
    finally:
        use(None)
    assert kept is not None                 # (the guide's kernels took it)
    return [kept.drive.value.tobytes(), kept.undefined.tobytes(),
            *(c.tobytes() for c in kept.closeness2)]


@pytest.mark.parametrize("name", list(SCENES))
def test_the_guide_pass_keeps_the_composed_kernels_numbers(name):
    scene = SCENES[name](ROWS)
    assert kept_bytes(scene, True) == kept_bytes(scene, False)
    # each entry point compiled once
    from kinetostatics.solver.fast import guide_kernels
    kernels = [guide_kernels.rtr_kept, *guide_kernels.AFTER_RTR_ON.values()]
    assert [len(k.signatures) for k in kernels if len(k.signatures) > 1] == []
