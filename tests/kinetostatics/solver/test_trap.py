"""The finite check left to the floating-point trap (:mod:`kinetostatics.solver.trap`).

A tame scene is solved first with the trap standing for the finite checks; the tables
must be exactly those of the checked solve (every check made by looking at the numbers),
and a solve that meets a NaN or an infinity must end exactly as the checked one does
(the trap sends it back to the checked road).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.results import solve_many
from kinetostatics.solver import arith as A
from kinetostatics.solver import blocks, trap
from kinetostatics.solver import pipeline as pl
from kinetostatics.solver.stack import Stacker
from tests.kinetostatics.solver.test_blocks import FILES, IDS, assert_same, sweeps, tables


def checked(monkeypatch, scene, positions=None):
    """The solve with the trap never tried."""
    with monkeypatch.context() as m:
        m.setattr(pl, "tame", lambda sc, pos: False)
        return ks.solve(scene, positions)


def outcome(f):
    try:
        return tables(f())
    except ks.WorkbenchError as exc:
        return f"{type(exc).__name__}: {exc}"


@pytest.mark.parametrize("path", FILES, ids=IDS)
def test_trapped_solve_gives_the_checked_tables_bit_for_bit(path, monkeypatch) -> None:
    sc = load_scene(path)
    for positions in sweeps(sc):
        ref = outcome(lambda p=positions: checked(monkeypatch, sc, p))
        got = outcome(lambda p=positions: ks.solve(sc, p))
        if isinstance(ref, str):
            assert got == ref
        else:
            assert_same(ref, got)


def test_the_trapped_road_makes_no_finite_pass(monkeypatch) -> None:
    """A tame scene without friction is solved without the finite check's passes (the
    checked road's check, made to fail here, is not reached); an untamed one is checked."""
    def refuse(sol):
        raise AssertionError("the finite check was made")
    monkeypatch.setattr(pl, "_check_finite", refuse)
    ks.solve(ks.example("four_bar"))
    with pytest.raises(AssertionError, match="finite check"):
        checked(monkeypatch, ks.example("four_bar"))


def slider_at_dead_centre() -> dict:
    """The crank as long as the rod: at 90 deg the rod stands perpendicular to the line
    and the dyad is exactly singular (a division by zero)."""
    d = load_scene(ks.example("slider_crank")).raw
    d = {k: v for k, v in d.items() if k != "motion"}
    d["bodies"] = [dict(b, points=dict(b["points"])) for b in d["bodies"]]
    d["bodies"][0]["points"]["B"] = [0.35, 0.0]
    d["driver"] = {k: v for k, v in d["driver"].items() if k not in ("start", "stop", "count")}
    d["driver"]["positions"] = [0.0, 45.0, 90.0]
    d["loads"] = []
    return d


def test_a_touched_trap_sends_the_solve_back_to_the_checked_road(monkeypatch) -> None:
    d = slider_at_dead_centre()
    sc = load_scene(d)
    assert trap.tame(sc)
    assert pl._trapped(sc, pl.analyse(sc, assemble=False), sc.driver.positions, None) is None
    with pytest.raises(ks.AssemblyError) as got:
        ks.solve(d)
    with pytest.raises(ks.AssemblyError) as ref:
        checked(monkeypatch, d)
    assert str(got.value) == str(ref.value) and "90 deg" in str(got.value)


@pytest.mark.parametrize("rows", [None, 7], ids=["one pass", "blocks"])
def test_a_flag_raised_by_the_loads_sends_the_solve_back(rows, monkeypatch) -> None:
    """A floating-point exception met after the kinematics (here one made on purpose in
    the loads) sends the solve, in one pass or in blocks, to the checked road."""
    real = pl._solve_loads
    roads = []

    def flagged(sc, structure, kin):
        roads.append(trap.active())
        np.ones(1) / np.zeros(1)                # division by zero
        return real(sc, structure, kin)
    monkeypatch.setattr(pl, "_solve_loads", flagged)
    if rows:
        monkeypatch.setattr(blocks, "BLOCK_ROWS", rows)
    with warnings.catch_warnings():             # (the checked road warns of it)
        warnings.simplefilter("ignore", RuntimeWarning)
        sol = ks.solve(ks.example("four_bar"))
    assert roads[0] is True and roads[-1] is False
    monkeypatch.setattr(pl, "_solve_loads", real)
    assert_same(tables(sol), tables(checked(monkeypatch, ks.example("four_bar"))))


def test_trap_records_what_quiet_would_hide() -> None:
    one, zero = np.ones(3), np.zeros(3)
    with trap.trapped() as t:
        assert trap.active()
        with trap.quiet():
            x = zero / zero                     # invalid: NaN
        assert t.hit
        assert A.mul(x, 0.0) == 0.0             # not looked at: the trap saw it born
    assert not trap.active()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with trap.quiet():                      # a checked solve: ignored, no warning
            y = one / zero
    assert np.isinf(y).all()
    assert np.isnan(A.mul(x, 0.0)).all()        # outside the trap: looked at, kept NaN
    with trap.trapped() as t:
        _ = one * 2.0
    assert not t.hit


def test_tame() -> None:
    d = load_scene(ks.example("four_bar")).raw
    assert trap.tame(load_scene(d))
    # (the scene's reader refuses magnitudes above 1e12: the tiny ones are untamed here)
    for path, value in ((("bodies", 0, "mass"), 1e-60), (("bodies", 1, "inertia"), 1e-60),
                        (("driver", "speed"), -2e-51)):
        e = {k: v for k, v in d.items() if k != "motion"}
        e["bodies"] = [dict(b) for b in d["bodies"]]
        e["driver"] = dict(d["driver"])
        target = e
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value
        sc = load_scene(e)
        assert not trap.tame(sc), path
        if path[0] == "bodies":     # (a speed is shared by a stack: not a variant's)
            assert not Stacker([load_scene(d), sc]).tame(), path
        # solved checked: the same numbers as the trapped solve of the tame scenes
        sols = solve_many([d, e])
        assert_same(tables(sols[1]), tables(ks.solve(e)))
    sc = load_scene(d)
    assert trap.tame(sc, np.array([0.0, 1.0]))
    assert not trap.tame(sc, np.array([0.0, 1e51]))
    assert Stacker([sc, load_scene(d)]).tame()


def test_a_flag_in_a_stacked_run_sends_the_run_back(monkeypatch) -> None:
    """solve_many: a run whose trap is touched is solved again checked, with the same
    numbers as each scene alone."""
    from kinetostatics.solver import many
    real = many._solve_run
    roads = []

    def flagged(*args):
        roads.append(trap.active())
        np.ones(1) / np.zeros(1)                # division by zero
        return real(*args)
    monkeypatch.setattr(many, "_solve_run", flagged)
    base = load_scene(ks.example("four_bar")).raw
    scenes = []
    for f in (1.0, 1.01, 0.99):
        d = {k: v for k, v in base.items() if k != "motion"}
        d["bodies"] = [dict(b, mass=b["mass"] * f) for b in base["bodies"]]
        scenes.append(d)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        sols = solve_many(scenes)
        assert roads == [True, False]
        # the lean run solved again when its tables are read: the same two roads
        for d, sol in zip(scenes, sols, strict=True):
            assert_same(tables(sol), tables(ks.solve(d)))
    assert roads == [True, False, True, False]
