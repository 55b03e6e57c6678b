"""A long sweep of a crank and one dyad on the compiled path: Me, the flags and the
closeness to a dead centre from ``solve_many``'s fused kernel called block by block
(kinetostatics.solver.fast.solve.fused_blocks), the rest solved when a table asks: the
same numbers, bit for bit, as the composed kernels' lean and full solves, and within the
paths' tolerance of the numpy path's."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import AssemblyError
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.blocks import BLOCK_ROWS
from kinetostatics.solver.fast import loader, use
from kinetostatics.solver.fast import solve as fast_solve
from kinetostatics.solver.fast.compose import Plan, Refused, solve_lean
from kinetostatics.solver.fast.solve import _assembled, fused_blocks, guided_blocks
from kinetostatics.solver.pipeline import structure_of

from .test_fast_short import DATA, FUSED, full_solve

# a crank and one RTR dyad: the guide on the second body (the slotted lever) and on the
# first (the oscillating cylinder, with the crank's acceleration)
GUIDED = {"slotted lever": ks.example("slotted_lever"),
          "oscillating cylinder": DATA / "oscillating_cylinder.toml"}


def _rocker_ram() -> dict:
    """The shaper with its ram a rocker about a ground pivot G: a second dyad RRR whose
    known bodies are the lever and the ground."""
    d = copy.deepcopy(load_scene(ks.example("shaper")).raw)
    d["ground"]["G"] = [0.35, 0.75]
    ram = next(b for b in d["bodies"] if b["name"] == "ram")
    ram["points"] = {"F": [0.0, 0.0], "G": [0.35, 0.0], "T": [0.25, -0.05]}
    d["joints"] = [j for j in d["joints"] if j["name"] != "ram-guide"] + [
        {"name": "G", "kind": "R", "bodies": ["ground", "ram"]}]
    d["near"] = {"lever.E": [0.0, 0.60], "F": [0.1, 0.85]}
    return d


def _crank_link() -> dict:
    """The rocker-ram shaper with the ram's other end on the crank (joint H): a second
    dyad RRR whose known bodies are the lever and the crank."""
    d = _rocker_ram()
    del d["ground"]["G"]
    for b in d["bodies"]:
        if b["name"] == "crank":
            b["points"]["H"] = [0.10, 0.0]
        if b["name"] == "ram":
            b["points"] = {"F": [0.0, 0.0], "H": [0.3, 0.0], "T": [0.15, 0.02]}
    d["joints"] = [j for j in d["joints"] if j["name"] != "G"] + [
        {"name": "H", "kind": "R", "bodies": ["crank", "ram"]}]
    d["near"] = {"lever.E": [0.0, 0.60], "F": [-0.2, 0.4]}
    return d


# a crank, one RTR dyad and a second dyad (the shaper's structure): the bundled shaper
# (RRT on the lever and the ground, a force acting "when resisting"), and two of its
# variants (RRR on the lever and the ground; on the lever and the crank)
SIX_BARS = {"shaper": ks.example("shaper"), "shaper, a rocker ram": _rocker_ram(),
            "shaper, the ram on the crank": _crank_link()}
GUIDED.update(SIX_BARS)

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not loader.installed(), reason="numba not installed")]

# more rows than the short sweep's limit (and than one fused call's, OWNERS rows), not a
# whole number of tiles
COUNT = 2 * BLOCK_ROWS + 2 * 4096 + 1001
assert COUNT >= 2 * BLOCK_ROWS


def long_scene(kind: str) -> dict:
    d = copy.deepcopy(load_scene({**FUSED, **GUIDED}[kind]).raw)
    d["driver"] = {**d["driver"], "count": COUNT}
    return d


@pytest.mark.parametrize("kind", [*FUSED, *GUIDED])
def test_a_long_sweep_keeps_the_composed_kernels_numbers(fast, kind: str) -> None:
    sc = load_scene(long_scene(kind))
    structure, geometry = _assembled(sc, structure_of(sc))
    pos = sc.driver.positions
    if kind in GUIDED:
        assert fused_blocks(loader.kernels(), sc, sc, structure, geometry, pos) is None
        ours = guided_blocks(loader.kernels(), sc, structure, geometry, pos)
    else:
        ours = fused_blocks(loader.kernels(), sc, sc, structure, geometry, pos)
    assert ours is not None
    plan = Plan(loader.kernels(), sc, structure, structure.assembly, geometry=geometry)
    ref = solve_lean(plan, pos)
    assert np.array_equal(ours.drive.value, ref.drive.value)
    assert np.array_equal(ours.undefined, ref.undefined)
    assert len(ours.closeness2) == len(ref.closeness2) == len(structure.dyads)
    for i in range(len(structure.dyads)):
        assert np.array_equal(ours.closeness2[i], ref.closeness2[i])
        assert np.array_equal(ours.singular[i], ref.singular[i])


@pytest.mark.parametrize("kind", ["RRR", "RRT", "TTR", "slotted lever", *SIX_BARS])
def test_a_long_sweep_is_the_full_solves_bit_for_bit(fast, kind: str) -> None:
    d = long_scene(kind)
    sol = ks.solve(d)
    assert sol.path == "fast" and "kin" not in sol.__dict__      # (lean)
    driver = sol.driver.copy()
    ref = full_solve(d)
    assert driver.equals(ref.driver)
    assert sol.reactions.equals(ref.reactions)                    # (solved in full now)
    use("numpy")
    me = ks.solve(d).driver.iloc[:, 1].to_numpy()
    # the paths' agreement (measured here 2026-11-29: 1.5e-16 to 4.9e-16 of the column's
    # scale, the six-bars 8.6e-16 to 3.0e-15: two dyads' rounding, the rocker ram's
    # transmission angle; about four times that allowed)
    tol = 1.2e-14 if kind in SIX_BARS else 2e-15
    assert np.abs(driver.iloc[:, 1].to_numpy() - me).max() <= tol * np.abs(me).max()


@pytest.mark.parametrize("scene", [FUSED["RRR"], GUIDED["oscillating cylinder"]])
def test_given_positions_of_a_long_sweep(fast, scene) -> None:
    pos = np.concatenate([np.linspace(350.0, -340.0, COUNT), [355.5]])
    sol = ks.solve(scene, positions=pos)
    assert sol.path == "fast" and "kin" not in sol.__dict__
    assert sol.driver.equals(full_solve(scene, pos).driver)


def test_a_long_sweep_that_cannot_close_is_refused_as_on_numpy(fast, monkeypatch) -> None:
    d = long_scene("RRR")
    d["bodies"][0]["points"]["B"] = [0.16, 0.0]     # the crank too long: C lost past 154.85 deg
    refused = []
    blocks = fused_blocks

    def seen(*args):
        try:
            return blocks(*args)
        except Refused:
            refused.append(True)
            raise
    monkeypatch.setattr(fast_solve, "fused_blocks", seen)
    with pytest.raises(AssemblyError) as fast_error:
        ks.solve(d)
    assert refused                          # (the fused kernel met the rows, not a check)
    use("numpy")
    with pytest.raises(AssemblyError) as numpy_error:
        ks.solve(d)
    assert str(fast_error.value) == str(numpy_error.value)
    assert "cannot be assembled at driver position(s) 154.8" in str(fast_error.value)


@pytest.mark.parametrize("kind", [*FUSED])
def test_a_long_fused_sweep_never_makes_the_driver_angles(fast, kind: str) -> None:
    # the fused kernel takes each tile's radians (Driver.angles_into, one scratch array):
    # the driver's array of every row's angles is made only when read, the same doubles
    d = long_scene(kind)
    d["driver"]["count"] = COUNT + 2    # (a scene of its own: not one read and kept before)
    sc = load_scene(d)
    me = ks.solve(sc).driver.iloc[:, 1].to_numpy()
    assert "angles" not in sc.driver.__dict__
    scratch = np.empty(5000)
    tile = sc.driver.angles_into(slice(COUNT + 2 - 4097, None), scratch)
    assert "angles" not in sc.driver.__dict__ and not tile.flags.writeable
    assert np.shares_memory(tile, scratch)
    assert tile.tobytes() == np.radians(sc.driver.positions[-4097:]).tobytes()
    assert sc.driver.angles[-4097:].tobytes() == tile.tobytes()     # (made now)
    assert np.shares_memory(sc.driver.angles_into(slice(0, 9), scratch), sc.driver.angles)
    # the solve with the driver's angles made: the same Me
    assert ks.solve(sc).driver.iloc[:, 1].to_numpy().tobytes() == me.tobytes()
