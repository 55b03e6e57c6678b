"""A short sweep of a crank and one dyad on the compiled path: Me, the flags and the
closeness to a dead centre from ``solve_many``'s fused kernel, the rest solved when a
table asks (kinetostatics.solver.fast.short): the same numbers, bit for bit, as the
composed kernels' full solve, and within the paths' tolerance of the numpy path's."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.fast import loader, use
from kinetostatics.solver.fast.compose import Plan, solve_full
from kinetostatics.solver.fast.solve import _assembled
from kinetostatics.solver.kinematics import with_positions
from kinetostatics.solver.pipeline import structure_of

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not loader.installed(), reason="numba not installed")]

DATA = Path(__file__).resolve().parents[2] / "data" / "scenes"
# a crank and one dyad of each kind the fused kernels cover (RTR: the composed kernels)
FUSED = {
    "RRR": ks.example("four_bar"),
    "RRT": ks.example("slider_crank"),
    "TRR": DATA / "trr_slider_crank.toml",
    "TRT": DATA / "trt_slotted_crank.toml",
    "RTT": DATA / "rtt_scotch_yoke.toml",
    "TTR": ks.example("scotch_yoke"),
}


def full_solve(scene, positions=None):
    """The composed kernels' full solve of ``scene`` (at ``positions``), as a Solution."""
    sc = load_scene(scene)
    structure, geometry = _assembled(sc, structure_of(sc))
    pos = sc.driver.positions if positions is None else np.asarray(positions, dtype=float)
    full = sc if positions is None else with_positions(sc, pos)
    plan = Plan(loader.kernels(), full, structure, structure.assembly, geometry=geometry)
    return ks.Solution.of(solve_full(plan, pos))


# a crank and an RTR dyad (and a second dyad): Me from the guide's fused kernels
# (solve.guided_blocks), as a long sweep's
GUIDED_SHORT = {"slotted lever": ks.example("slotted_lever"), "shaper": ks.example("shaper")}


@pytest.mark.parametrize("kind", [*FUSED, *GUIDED_SHORT])
def test_a_short_sweep_is_the_full_solves_bit_for_bit(fast, kind: str) -> None:
    d = load_scene({**FUSED, **GUIDED_SHORT}[kind]).raw
    d["driver"] = {**d["driver"], "count": 2001}
    sol = ks.solve(d)
    assert sol.path == "fast" and "kin" not in sol.__dict__      # (lean: the fused kernel)
    driver = sol.driver.copy()
    ref = full_solve(d)
    assert driver.equals(ref.driver)
    assert sol.kinematics.equals(ref.kinematics)                  # (solved in full now)
    assert sol.reactions.equals(ref.reactions)
    assert np.array_equal(sol.Me, driver.iloc[:, 1].to_numpy())  # the lean Me kept


@pytest.mark.parametrize("kind", ["RRR", "RRT"])
def test_given_positions_take_the_fused_kernel_too(fast, kind: str) -> None:
    pos = np.concatenate([np.linspace(350.0, 10.0, 500), [355.5, 0.25]])
    sol = ks.solve(FUSED[kind], positions=pos)
    assert sol.path == "fast" and "kin" not in sol.__dict__
    ref = full_solve(FUSED[kind], pos)
    assert sol.driver.equals(ref.driver)
    use("numpy")
    ours = ks.solve(FUSED[kind], positions=pos)
    me = ours.driver.iloc[:, 1].to_numpy()
    # the paths' agreement (tests/kinetostatics/solver/test_fast.py: within 1e-13 of
    # the column's scale; measured here 2026-11-29: 2e-16)
    assert np.abs(sol.Me - me).max() <= 1e-13 * np.abs(me).max()
    assert sol.singular.tolist() == ours.singular.tolist()

