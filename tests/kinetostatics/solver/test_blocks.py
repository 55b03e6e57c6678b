"""A sweep solved in blocks of rows gives exactly the one pass's numbers
(:mod:`kinetostatics.solver.blocks`).

Blocks are only used on long sweeps (``2 * BLOCK_ROWS`` rows and more); here the block
is made a few rows long, so that the scenes of tests/data, the bundled examples and
random mechanisms are cut into many blocks (the last one shorter), and every table is
compared bit for bit with the one pass.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver import blocks
from kinetostatics.solver import pipeline as pl
from tests.helpers import OWN_CASES, SCENES

# the numpy path's own workings (its blocks, its traps): whatever KINETOSTATICS_PATH says
pytestmark = pytest.mark.usefixtures("numpy_path")

FILES = (sorted(OWN_CASES.glob("*.toml")) + sorted(SCENES.glob("*.toml"))
         + [ks.example(n) for n in ks.examples()])
IDS = [p.stem for p in FILES]
TABLES = ("driver", "kinematics", "bodies", "reactions", "dyads", "frame", "reduced",
          "sliders")


def tables(sol) -> dict:
    out = {}
    for t in TABLES:
        try:
            out[t] = getattr(sol, t)
        except ValueError as exc:       # a table a scene does not have
            out[t] = repr(exc)
    out["summary"] = repr(sol.summary())
    return out


def sweeps(sc) -> tuple:
    """The scene's own sweep (None) and the same range at 61 rows in decreasing order."""
    pos = sc.driver.positions
    return None, (np.linspace(pos.max(), pos.min(), 61) if pos.size > 1 else None)


def assert_same(a: dict, b: dict) -> None:
    for k, x in a.items():
        y = b[k]
        if isinstance(x, str):
            assert x == y, k
        else:
            pd.testing.assert_frame_equal(x, y, check_exact=True, obj=k)


def one_pass(monkeypatch, scene, positions=None):
    with monkeypatch.context() as m:
        m.setattr(pl, "blockable", lambda sc, n, tops=False: False)
        return ks.solve(scene, positions)


def in_blocks(monkeypatch, scene, positions=None, rows: int = 7, expect: bool = True):
    """Solve with blocks of ``rows`` rows; ``expect``: the blocks must have been used."""
    used = []
    real = blocks.solve_blocks

    def spy(*a, **k):
        sol = real(*a, **k)
        used.append(True)
        return sol
    with monkeypatch.context() as m:
        m.setattr(blocks, "BLOCK_ROWS", rows)
        m.setattr(pl, "solve_blocks", spy)
        sol = ks.solve(scene, positions)
    assert bool(used) == expect
    return sol


@pytest.mark.parametrize("path", FILES, ids=IDS)
def test_blocks_give_the_one_pass_tables_bit_for_bit(path, monkeypatch) -> None:
    sc = load_scene(path)
    for positions in sweeps(sc):
        try:
            ref = one_pass(monkeypatch, sc, positions)
        except ks.WorkbenchError as exc:
            with pytest.raises(type(exc), match=None) as got:
                in_blocks(monkeypatch, sc, positions, expect=False)
            assert str(got.value) == str(exc)
            continue
        with monkeypatch.context() as m:
            m.setattr(blocks, "BLOCK_ROWS", 7)
            expect = blocks.blockable(sc, ref.positions.size, tops=True)
        sol = in_blocks(monkeypatch, sc, positions, expect=expect)
        assert_same(tables(ref), tables(sol))
        np.testing.assert_array_equal(ref.kin.between, sol.kin.between)
        np.testing.assert_array_equal(ref.kin.ends, sol.kin.ends)


def test_sweep_dependent_loads_and_friction_are_solved_in_one_pass() -> None:
    """A resist load's threshold is the whole sweep's top speed, joint friction iterates
    over the sweep: neither is streamed in blocks; the solve cuts the first into blocks
    (measuring the tops as it goes, loads.SweepTops), not the second."""
    for name in ("slider_crank", "shaper"):
        sc = load_scene(ks.example(name))
        assert not blocks.blockable(sc, 10 ** 6), name
        assert blocks.blockable(sc, 10 ** 6, tops=True), name
    assert blocks.blockable(load_scene(ks.example("four_bar")), 2 * blocks.BLOCK_ROWS)
    assert not blocks.blockable(load_scene(ks.example("four_bar")),
                                2 * blocks.BLOCK_ROWS - 1)


def test_a_block_refused_gives_the_one_pass_message(monkeypatch) -> None:
    """A dyad that cannot close in a later block (the four-bar's crank doubled: it
    assembles at 0 deg, not near 180 deg): the message is the one pass's, naming the
    rows of the whole sweep, not only the block's."""
    sc = load_scene(ks.example("four_bar"))
    d = {k: v for k, v in sc.raw.items() if k != "motion"}
    d["bodies"] = [dict(b) for b in d["bodies"]]
    for b in d["bodies"]:
        if b["name"] == "crank":
            b["points"] = {**b["points"], "B": [0.20, 0.0]}
    positions = np.linspace(0.0, 359.0, 200)
    with pytest.raises(ks.WorkbenchError) as alone:
        one_pass(monkeypatch, d, positions)
    assert "cannot be assembled" in str(alone.value)
    with pytest.raises(type(alone.value)) as got:
        in_blocks(monkeypatch, d, positions, expect=False)
    assert str(got.value) == str(alone.value)


def test_a_block_of_another_layout_is_refused() -> None:
    """Gather: a later block whose attribute is a scalar where the first block had an
    array (or two arrays where it had one) raises Unblockable."""
    class Obj:
        __slots__ = ("a", "b", "pair")

        def __init__(self, a, b, pair):
            self.a, self.b, self.pair = a, b, pair
    arrays = blocks._Arrays(6)
    x = np.arange(3.0)
    first = Obj(x, 2.0, (x, 1.0))
    blocks.Gather(first, 3, arrays)
    arrays.allocate()
    g = blocks.Gather(first, 3, arrays)
    y = np.arange(3.0, 6.0)
    g.put(Obj(y, 2.0, (y, 1.0)), slice(3, 6), 3, {})
    out = g.build()
    np.testing.assert_array_equal(out.a, np.arange(6.0))
    assert out.pair[0] is out.a and out.b == 2.0       # one array held once
    with pytest.raises(blocks.Unblockable):
        g.put(Obj(2.0, 2.0, (y, 1.0)), slice(3, 6), 3, {})
    with pytest.raises(blocks.Unblockable):
        g.put(Obj(y, 2.0, (y.copy(), 1.0)), slice(3, 6), 3, {})
    with pytest.raises(blocks.Unblockable):
        g.put(Obj(y, y, (y, 1.0)), slice(3, 6), 3, {})


@settings(max_examples=12, deadline=None)
@given(rows=st.integers(1, 40), count=st.integers(2, 300), start=st.floats(0.0, 359.0))
def test_any_block_size_gives_the_same_numbers(rows, count, start) -> None:
    """Random block sizes and sweeps of the four-bar: every table is the one pass's,
    bit for bit."""
    sc = load_scene(ks.example("four_bar"))
    pos = np.unique((start + np.linspace(0.0, 360.0, count, endpoint=False)) % 360.0)
    ref = ks.solve(sc, pos)             # fewer than 2 * BLOCK_ROWS rows: one pass
    old = blocks.BLOCK_ROWS
    blocks.BLOCK_ROWS = rows
    try:
        sol = ks.solve(sc, pos)
    finally:
        blocks.BLOCK_ROWS = old
    assert_same(tables(ref), tables(sol))


def test_solve_many_in_blocks_gives_each_scene_its_solve(monkeypatch) -> None:
    """The stacked pass of solve_many cut into blocks: each scene's tables are its
    solve's, bit for bit."""
    from kinetostatics.bench.speed import four_bar_variants
    dicts = four_bar_variants(12, seed=3)
    alone = [tables(ks.solve(d)) for d in dicts]
    monkeypatch.setattr(blocks, "BLOCK_ROWS", 100)
    sols = ks.solve_many(dicts)
    for a, s in zip(alone, sols, strict=True):
        assert_same(a, tables(s))


def test_a_long_sweep_keeps_its_driver_table_and_solves_again_for_the_rest(
        monkeypatch) -> None:
    """A long sweep in blocks keeps Me, the flags and the dyads' closeness only: its
    driver table needs no second solve; the first other table solves the blocks again
    (once), with the same numbers as the one pass, bit for bit."""
    calls = []
    real = pl.solve_blocks

    def counted(*a, **k):
        calls.append(k.get("lean", False))
        return real(*a, **k)
    monkeypatch.setattr(pl, "solve_blocks", counted)
    monkeypatch.setattr(blocks, "BLOCK_ROWS", 7)
    # the slider-crank with the crank as long as the rod: dead centres at 90 and 270 deg,
    # between rows of this sweep (flagged singular from the dead points)
    sc = load_scene(ks.example("slider_crank"))
    d = {k: v for k, v in sc.raw.items() if k != "motion"}
    d["bodies"] = [dict(b, points=dict(b["points"])) for b in d["bodies"]]
    d["bodies"][0]["points"]["B"] = [0.35, 0.0]
    d["loads"] = []
    positions = np.linspace(0.0, 359.0, 97)
    sol = ks.solve(d, positions)
    assert isinstance(sol.__dict__["_deferred"], blocks.LeanSolved)
    assert "kin" not in sol.__dict__
    driver = sol.driver
    assert calls == [True]
    ref = one_pass(monkeypatch, d, positions)
    pd.testing.assert_frame_equal(driver, ref.driver, check_exact=True)
    np.testing.assert_array_equal(sol.singular, ref.singular)
    assert sol.singular.any() and len(sol.__dict__["_deferred"].dead[0])     # (dead points)
    assert_same(tables(ref), tables(sol))
    assert calls == [True, False]       # solved again once, in full
    np.testing.assert_array_equal(sol.kin.between, ref.kin.between)
    np.testing.assert_array_equal(sol.singular, sol.kin.singular)


def test_a_lean_solution_pickles_copies_and_replaces_whole(monkeypatch) -> None:
    """As any Solution: pickled (a process executor), copied, replaced."""
    import copy
    import dataclasses
    import pickle
    monkeypatch.setattr(blocks, "BLOCK_ROWS", 7)
    ref = tables(one_pass(monkeypatch, ks.example("four_bar")))

    def lean():
        sol = ks.solve(ks.example("four_bar"))
        assert "kin" not in sol.__dict__
        return sol
    back = pickle.loads(pickle.dumps(lean()))
    assert "_deferred" not in back.__dict__
    assert_same(ref, tables(back))
    assert_same(ref, tables(copy.copy(lean())))
    sol = lean()
    other = dataclasses.replace(sol, undefined_load=sol.undefined_load)
    assert_same(ref, tables(other))
