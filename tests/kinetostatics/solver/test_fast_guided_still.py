"""The six-bars' guided kernels (:func:`~kinetostatics.solver.fast.solve.guided_blocks`)
flag the rows where a ``when = "resisting"`` load stands still as the composed kernels
do: the one-scene road of ``tail_kernels.tile_swept`` (each load's forces over the tile
in a loop of their own, then its statistics and undefined rows) against ``swept_row``
row by row, the same rows, bit for bit."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.fast import loader
from kinetostatics.solver.fast.compose import Plan, solve_lean
from kinetostatics.solver.fast.solve import _assembled, guided_blocks
from kinetostatics.solver.pipeline import structure_of

from .test_fast_long import COUNT

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not loader.installed(), reason="numba not installed")]


def still_shaper(fy: float) -> dict:
    """The bundled shaper over ``COUNT`` positions with its ram's "resisting" force
    ``(400, fy)``: ``fy`` alone (across the ram's guide) never does work, every row
    stands still; ``(400, 0)``, the bundled one, moves but at the stroke's ends."""
    d = copy.deepcopy(load_scene(ks.example("shaper")).raw)
    d["driver"] = {**d["driver"], "count": COUNT}
    d["loads"][0]["force"] = [0.0 if fy else 400.0, fy]
    return d


@pytest.mark.parametrize("fy", [-400.0, 0.0], ids=["across the guide", "bundled"])
def test_still_rows_are_the_composed_kernels(fast, fy: float) -> None:
    sc = load_scene(still_shaper(fy))
    structure, geometry = _assembled(sc, structure_of(sc))
    pos = sc.driver.positions
    ours = guided_blocks(loader.kernels(), sc, structure, geometry, pos)
    ref = solve_lean(Plan(loader.kernels(), sc, structure, structure.assembly,
                          geometry=geometry), pos)
    assert ours is not None
    assert np.array_equal(ours.undefined, ref.undefined)
    assert np.array_equal(ours.drive.value, ref.drive.value)
    if fy:
        assert ours.undefined.all()         # (no work across the guide: every row still)
