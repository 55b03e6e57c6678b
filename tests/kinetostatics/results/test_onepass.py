"""The ``reactions`` and ``kinematics`` tables of a long sweep solved lean, built in one
pass while the sweep is solved again block by block (issue 31, item 6): the same tables,
bit for bit, as from the full re-solve, without that re-solve being held."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import kinetostatics as ks
from kinetostatics.results import onepass
from kinetostatics.results.longtable import FloatBlock, LongTable
from kinetostatics.solver.blocks import BLOCK_ROWS, LeanSolved
from kinetostatics.solver.driver import BodyMotion

# the numpy path's own pass (the compiled path builds the tables from its own re-solve)
pytestmark = pytest.mark.usefixtures("numpy_path")

ROWS = 2 * BLOCK_ROWS + 5       # three blocks of rows, the last one short: solved lean
# revolute joints only; a sliding driver; two prismatic joints (offset = M / N); an RTR dyad
CASES = ("four_bar", "sliding_driver", "scotch_yoke", "slotted_lever")


def scene_text(name: str, rows: int = ROWS) -> str:
    text = Path(ks.example(name)).read_text()
    text, k = re.subn(r"(?m)^count\s*=\s*\d+", f"count = {rows}", text)
    assert k == 1
    return text


def bits(df: pd.DataFrame) -> dict:
    """Every column's name, dtype and bits (a categorical's categories and codes)."""
    out = {}
    for c in df.columns:
        s = df[c]
        if isinstance(s.dtype, pd.CategoricalDtype):
            out[c] = (str(s.dtype), list(s.cat.categories), s.cat.codes.to_numpy().tobytes())
        else:
            out[c] = (str(s.dtype), np.ascontiguousarray(s.to_numpy()).tobytes())
    return out


@pytest.mark.parametrize("order", [onepass.PASSED, onepass.PASSED[::-1]])
@pytest.mark.parametrize("case", CASES)
def test_one_pass_tables_equal_those_of_the_full_re_solve_bit_for_bit(case, order,
                                                                       monkeypatch):
    """Each table, built in one pass, equals the one built from the re-solved arrays:
    the same columns in the same order, dtypes and bits (NaN offsets and -0.0 included),
    whichever table is asked for first; after ``reactions`` the sweep is not solved again
    for ``kinematics`` (the pass kept the motion, and lets it go once the table is made),
    and the full re-solve is never made (nor held)."""
    text = scene_text(case)
    sol = ks.solve(text)
    lean = sol.__dict__["_deferred"]
    assert type(lean) is LeanSolved
    runs = []
    real = onepass.OnePass.run
    monkeypatch.setattr(onepass.OnePass, "run", lambda *a: runs.append(a[1]) or real(*a))
    first = getattr(sol, order[0])
    kept = sol.__dict__.get(onepass.KEPT)
    if order[0] == "reactions":         # the bodies' motion kept, not the table
        assert kept.motion is not None and "kinematics" not in kept.built
        # ... in the kinematics table's own room (the rows it later writes over)
        assert np.shares_memory(kept.motion.slab, kept.fills["kinematics"].block)
    else:                               # the kinematics pass keeps nothing for reactions
        assert kept is None
    passed = {order[0]: first, order[1]: getattr(sol, order[1])}
    assert runs == (["reactions"] if order[0] == "reactions" else list(order))
    assert onepass.KEPT not in sol.__dict__
    assert "kin" not in sol.__dict__ and lean.full is None      # never solved again in full
    full = ks.solve(text)
    full.kin                            # noqa: B018 (the full re-solve: the tables from it)
    assert "kin" in full.__dict__
    for name, table in passed.items():
        expected = getattr(full, name)
        assert bits(table) == bits(expected), name
        assert isinstance(table.index, pd.RangeIndex) and len(table) == len(expected)
    if case == "scotch_yoke":           # two prismatic joints: their offsets are numbers
        r = passed["reactions"]
        assert r.offset.notna().sum() >= ROWS and r.offset.isna().sum() >= ROWS


def test_one_pass_tables_hold_one_block_and_share_the_position_column():
    """The float columns are rows of one array (a column of one value on every row, as
    N, M and offset of a pin, a view of that one number), the position column is the one
    the other tables share, and a write to a table stays in it."""
    sol = ks.solve(scene_text("four_bar"))
    k, r = sol.kinematics, sol.reactions
    x, ay = k.x.to_numpy(), k.ay.to_numpy()
    # (rows 0 and 5 of one array, a view of a byte array: longtable.line_aligned)
    assert x.base is not None and x.base is ay.base
    assert ay.ctypes.data - x.ctypes.data == 5 * 8 * len(k)
    assert all(r[c].to_numpy().strides == (0,) for c in ("N", "M", "offset"))
    assert np.shares_memory(k.position.to_numpy(), r.position.to_numpy())
    y0, pos0 = k.y.to_numpy().copy(), r.position.to_numpy().copy()
    k.loc[0, "x"] = 12345.0
    k.loc[1, "position"] = -1.0
    assert k.loc[0, "x"] == 12345.0 and (k.y.to_numpy() == y0).all()
    assert (r.position.to_numpy() == pos0).all()


def test_the_compiled_path_and_a_held_solve_take_the_tables_from_their_arrays():
    """Only a lean numpy-path sweep is passed again; a solution whose arrays are whole
    builds its tables from them."""
    sol = ks.solve(scene_text("four_bar"))
    sol.kin                             # noqa: B018 (solved again in full first)
    assert onepass.lean_frame(sol, "kinematics") is None
    short = ks.solve(scene_text("four_bar", 361))
    assert onepass.lean_frame(short, "reactions") is None
    lean = ks.solve(scene_text("four_bar"))
    assert onepass.lean_frame(lean, "bodies") is None       # its angles need the sweep


def test_a_touched_trap_passes_again_with_every_check(monkeypatch):
    """Where the trapped pass meets a floating-point exception it is done again outside
    the trap, into the same columns: the same table."""
    text = scene_text("scotch_yoke")
    expected = bits(ks.solve(text).reactions)
    calls = []
    real = onepass.OnePass.run

    def touched(*args):
        calls.append(np.geterr())
        real(*args)
        if len(calls) == 1:
            np.float64(1.0) / np.float64(0.0)      # touches the trap of the first pass
    monkeypatch.setattr(onepass.OnePass, "run", touched)
    assert bits(ks.solve(text).reactions) == expected
    assert len(calls) == 2 and calls[0]["divide"] == "call" and calls[1]["divide"] != "call"


def test_float_block_takes_chunks_in_any_order():
    """Chunks written block after block or row block after row block give the same
    columns; a column of one value stays that value (8 bytes) until another comes, and
    then the rows written before get it."""
    n, k = 6, 3
    seen: list = []

    def chunk(i: int, part: slice) -> dict:
        rows = np.arange(part.start, part.stop, dtype=float)
        return {"a": rows + 10 * i, "one": 2.5, "late": 7.0 if i < 2 else rows - 1.0,
                "nan": np.nan}
    table = LongTable(np.arange(n, dtype=float), {"b": ["p", "q", "r"]},
                      ("a", "one", "late", "nan"), chunk)
    for order in ("blocks", "rows"):
        fill = FloatBlock(table)
        parts = [(i, slice(s, s + 2)) for i in range(k) for s in range(0, n, 2)]
        if order == "rows":
            parts.sort(key=lambda p: (p[1].start, p[0]))
        for i, part in parts:
            fill.put(i, slice(i * n + part.start, i * n + part.stop), chunk(i, part))
        seen.append(table.frame_of(fill))
    a, b = seen
    pd.testing.assert_frame_equal(a, b, check_exact=True)
    pd.testing.assert_frame_equal(a, table.frame(), check_exact=True)
    assert a.one.to_numpy().strides == (0,) and a.nan.isna().all()
    assert list(a.late) == [7.0] * 2 * n + list(np.arange(n) - 1.0)
    assert list(a.a) == [float(r + 10 * i) for i in range(k) for r in range(n)]


def motion(cos, omega, ox) -> BodyMotion:
    return BodyMotion(None, cos, 0.0, omega, 0.0, ox, 0.0, 0.0, 0.0, 0.0, 0.0)


def test_kept_motion_holds_each_array_once_and_gives_up_on_another_layout():
    """The bodies' motion kept block by block: the arrays of the blocks laid end to end
    (one array held by two fields, one row), a number kept as that number; a block of
    another layout (a number where an array was, another number, one array where there
    were two or two where there was one) leaves nothing kept."""
    a, b = np.arange(4.0), np.arange(4.0, 8.0)
    kept = onepass.KeptMotion(["link"], 8)
    kept.put({"link": motion(a, a, 1.5)}, slice(0, 4))
    kept.put({"link": motion(b, b, 1.5)}, slice(4, 8))
    m = kept.bodies()["link"]
    assert kept.whole and kept.slab.shape == (1, 8)
    assert m.cos is m.omega or np.shares_memory(m.cos, m.omega)
    assert list(m.cos) == list(range(8)) and m.ox == 1.5 and type(m.ox) is float
    for second in (motion(b, b, 2.5), motion(b, 1.0, 1.5), motion(b, b.copy(), 1.5),
                   motion(b, b, np.arange(4.0))):
        kept = onepass.KeptMotion(["link"], 8)
        kept.put({"link": motion(a, a, 1.5)}, slice(0, 4))
        kept.put({"link": second}, slice(4, 8))
        assert not kept.whole
    kept = onepass.KeptMotion(["link"], 8)
    kept.put({"link": motion(a, a.copy(), 1.5)}, slice(0, 4))
    kept.put({"link": motion(b, b, 1.5)}, slice(4, 8))
    assert not kept.whole


def test_nothing_kept_the_kinematics_table_is_passed_again(monkeypatch):
    """Where the bodies' motion could not be kept, the ``kinematics`` table is made by a
    pass of its own (the ``reactions`` table already made is not made again): the same
    table."""
    text = scene_text("scotch_yoke")
    expected = bits(ks.solve(text).kinematics)
    runs = []
    real = onepass.OnePass.run
    monkeypatch.setattr(onepass.OnePass, "run", lambda *a: runs.append(a[1:]) or real(*a))
    monkeypatch.setattr(onepass.KeptMotion, "put", lambda self, *a: setattr(self, "whole",
                                                                             False))
    sol = ks.solve(text)
    sol.reactions                       # noqa: B018
    assert onepass.KEPT not in sol.__dict__
    assert bits(sol.kinematics) == expected
    assert runs == [("reactions", True), ("kinematics", False)]


def test_what_a_pass_kept_goes_when_the_arrays_are_solved_whole():
    """The bodies' motion a ``reactions`` pass kept is let go when the sweep is solved
    again in full (its kinematics read), and the ``kinematics`` table then comes from the
    whole arrays: the same table; a pickled solution holds no pass."""
    import pickle
    text = scene_text("four_bar")
    expected = bits(ks.solve(text).kinematics)
    sol = ks.solve(text)
    sol.reactions                       # noqa: B018
    assert onepass.KEPT in sol.__dict__
    sol.kin                             # noqa: B018
    assert onepass.KEPT not in sol.__dict__
    assert bits(sol.kinematics) == expected
    other = ks.solve(text)
    other.reactions                     # noqa: B018
    assert onepass.KEPT not in pickle.loads(pickle.dumps(other)).__dict__
