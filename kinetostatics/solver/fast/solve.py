"""A scene solved on the compiled path, or None for the numpy path (no numba here)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...model.scene import Scene
from ...results import Solution
from ..blocks import BLOCK_ROWS, LeanSolution
from ..deadpoints import dead_points_between_rows, dead_points_of_sweep, measure2
from ..kinematics import choose_assembly, with_positions
from .choice import wanted
from .compose import Plan, Refused, solve_full, solve_lean
from .geometry import not_covered


def solve_compiled(scene: Scene, structure, positions: np.ndarray, given: bool
                   ) -> Solution | None:
    """``scene`` at ``positions`` (``given``: not the scene's own) on the compiled path,
    or None: the path is off or not wanted for this many rows
    (:func:`~kinetostatics.solver.fast.choice.wanted`), the scene is not covered
    (:func:`~kinetostatics.solver.fast.geometry.not_covered`), or a kernel met a row the
    numpy path must judge (it refuses it with its message, or solves it)."""
    n = positions.size
    if not_covered(scene) is not None:
        return None
    kernels = wanted(n)
    if kernels is None:
        return None
    if len(structure.assembly) != len(structure.dyads):
        structure = replace(structure, assembly=choose_assembly(scene, structure))
    full = with_positions(scene, positions) if given else scene
    try:
        if n >= 2 * BLOCK_ROWS:
            sweep = solve_lean(Plan(kernels, full, structure, structure.assembly), positions)

            def again() -> Solution:
                return solve_full(Plan(kernels, full, structure, structure.assembly),
                                  positions)
            dead = dead_points_of_sweep(full, structure, positions,
                                        measure2(sweep.closeness2, n))
            sol = LeanSolution.of(full, sweep, positions, dead, again)
        else:
            sol = solve_full(Plan(kernels, full, structure, structure.assembly), positions)
            kin = sol.kin
            kin.between, kin.ends, kin.unassembled = dead_points_between_rows(
                full, structure, kin)
    except Refused:
        return None
    sol.path = "fast"
    return sol
