"""The ``reactions`` and ``kinematics`` tables of a long sweep solved lean on the compiled
path, each built in one pass while the kernels solve the sweep again block by block
(issue 31, item 6): the same tables, bit for bit, as from the compiled path's full
re-solve, which is never made."""

from __future__ import annotations

import re

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.results import fastpass
from kinetostatics.solver.blocks import LeanSolved
from kinetostatics.solver.driver import BodyMotion
from kinetostatics.solver.fast import loader
from kinetostatics.solver.fast.compose import Refused
from kinetostatics.solver.fast.solve import SolvedAgain
from kinetostatics.solver.fast.table_pass import FusedTables

from .test_onepass import bits, scene_text

pytest.importorskip("numba")
pytestmark = pytest.mark.slow       # (the kernels compiled first on a fresh machine)

# every dyad kind the bundled examples hold and both drivers: revolute joints only, a
# sliding driver, prismatic joints (offset = M / N) inner and outer, an RTR dyad, six bars
CASES = ("four_bar", "sliding_driver", "slider_crank", "scotch_yoke", "slotted_lever",
         "shaper")
# those a fused table kernel solves again (a crank and one dyad, not RTR); the others the
# composed kernels (SolvedAgain)
FUSED = ("four_bar", "scotch_yoke")


def count_passes(monkeypatch) -> list[str]:
    """Each pass over the sweep, by the road it takes (``fused`` or ``composed``)."""
    passes: list[str] = []
    blocks, write = SolvedAgain.blocks, FusedTables.write
    monkeypatch.setattr(SolvedAgain, "blocks",
                        lambda *a: passes.append("composed") or blocks(*a))
    monkeypatch.setattr(FusedTables, "write",
                        lambda *a, **k: passes.append("fused") or write(*a, **k))
    return passes


@pytest.mark.parametrize("order", [("reactions", "kinematics"), ("kinematics", "reactions")])
@pytest.mark.parametrize("case", CASES)
def test_tables_equal_those_of_the_full_re_solve_bit_for_bit(fast, case, order, monkeypatch):
    """Each table, built in one pass, equals the one the full re-solve's arrays give:
    the same columns, dtypes and bits (NaN offsets and -0.0 included), in either order;
    after ``reactions`` the sweep is not solved again for ``kinematics`` (the pass wrote
    that table's columns too); the full re-solve is never made."""
    text = scene_text(case)
    sol = ks.solve(text)
    lean = sol.__dict__["_deferred"]
    assert sol.path == "fast" and type(lean) is LeanSolved
    passes = count_passes(monkeypatch)
    tables = {order[0]: getattr(sol, order[0])}
    kept = sol.__dict__.get(fastpass.KEPT)
    if order[0] == "reactions":         # the kinematics table's columns written ahead
        assert type(kept) is fastpass.PointRows and kept.out is kept.fill.block
    else:
        assert kept is None
    tables[order[1]] = getattr(sol, order[1])
    if order[0] == "reactions":         # ... and taken as they are
        assert np.shares_memory(tables["kinematics"].ay.to_numpy(), kept.out)
    road = "fused" if case in FUSED else "composed"
    assert passes == [road] * (1 if order[0] == "reactions" else 2)
    assert fastpass.KEPT not in sol.__dict__
    assert "kin" not in sol.__dict__ and lean.full is None
    full = ks.solve(text)
    assert full.kin is not None         # (the full re-solve: the tables from it)
    assert full.path == "fast" and "kin" in full.__dict__
    for name, table in tables.items():
        assert bits(table) == bits(getattr(full, name)), name


@pytest.mark.parametrize("case", CASES)
def test_the_bodies_table_in_one_pass_is_the_full_re_solves(fast, case, monkeypatch):
    """``bodies`` of a lean sweep: one composed pass (each body's omega and alpha
    written, its angle carried block to block by SweepAngles), no full re-solve; the
    table and ``angles`` the full re-solve's, bit for bit; the ``angle`` column the
    array ``angles`` views (held once)."""
    text = scene_text(case)
    sol = ks.solve(text)
    passes = count_passes(monkeypatch)
    table = sol.bodies
    assert passes == ["composed"]
    assert "kin" not in sol.__dict__ and sol.__dict__["_deferred"].full is None
    full = ks.solve(text)
    assert full.kin is not None and full.path == "fast"
    assert bits(table) == bits(full.bodies)
    assert sol.angles.keys() == full.angles.keys()
    for b, a in full.angles.items():
        assert sol.angles[b].tobytes() == a.tobytes(), b
    assert np.shares_memory(table.angle.to_numpy(), sol.angles[next(iter(sol.angles))])


def test_bodies_between_the_tables_keeps_what_the_reactions_pass_wrote(fast, monkeypatch):
    """``reactions``, ``bodies``, ``kinematics``: the kinematics table's columns the
    reactions pass wrote are kept past the bodies pass (no third pass)."""
    sol = ks.solve(scene_text("four_bar"))
    passes = count_passes(monkeypatch)
    assert len(sol.reactions) and len(sol.bodies)
    assert type(sol.__dict__.get(fastpass.KEPT)) is fastpass.PointRows
    assert len(sol.kinematics)
    assert passes == ["fused", "composed"]


def slider_crank_pushed() -> str:
    """The bundled slider-crank with its ``resist`` load made a constant force (an RRT
    dyad the fused table kernel takes; ``resist`` loads go the composed road)."""
    text, k = re.subn(r"(?m)^resist = 6000.0", "force = [-6000.0, 0.0]",
                      scene_text("slider_crank"))
    assert k == 1
    return text


@pytest.mark.parametrize("text", [scene_text("four_bar"), scene_text("scotch_yoke"),
                                  slider_crank_pushed()], ids=["RRR", "TTR", "RRT"])
def test_the_fused_road_gives_the_full_re_solves_tables(fast, text, monkeypatch):
    """A crank and one dyad: one pass of the fused table kernel for both tables (its
    reaction rows read off the composed path's own reading, revolute and prismatic
    joints, N and M of the slider included), the tables those of the full re-solve bit
    for bit; asked for alone, ``kinematics`` by a pass of its own (loads not solved)."""
    passes = count_passes(monkeypatch)
    sol = ks.solve(text)
    tables = {"reactions": sol.reactions, "kinematics": sol.kinematics}
    alone = ks.solve(text).kinematics
    assert passes == ["fused", "fused"]
    full = ks.solve(text)
    assert full.kin is not None         # (the full re-solve: the tables from it)
    for name, table in tables.items():
        assert bits(table) == bits(getattr(full, name)), name
    assert bits(alone) == bits(full.kinematics)


def test_the_pass_reads_the_cos_and_sin_it_works_out(fast, monkeypatch):
    """The lean solve keeps no cos and sin of the crank angle: the fused pass works them
    out per block (``table_pass.block_turn``) and its tables read them (other numbers
    there give other tables; the same numbers, the composed kernels' tables:
    test_fast_tables_turn.py)."""
    from kinetostatics.solver.fast import table_pass
    text = scene_text("four_bar")
    tables = bits(ks.solve(text).kinematics)
    turn = table_pass.block_turn()

    def reversed_turn():
        def run(angles, cs, sn):
            back = angles[::-1].copy()
            back.flags.writeable = False    # (read-only as the pass's angles: no second
            turn(back, cs, sn)              # compiled signature, test_fast.py counts them)
        return run
    monkeypatch.setattr(table_pass, "block_turn", reversed_turn)
    other = ks.solve(text)
    assert not hasattr(other.__dict__["_deferred"], "crank")
    assert bits(other.kinematics)["x"] != tables["x"]


def test_a_refused_block_takes_the_full_re_solve(fast, monkeypatch):
    """Where the kernels refuse a block of the pass (never expected), the table comes
    from the full re-solve: the same table."""
    text = scene_text("scotch_yoke")
    whole = ks.solve(text)
    assert whole.kin is not None                    # (the full re-solve)
    expected, bodies = bits(whole.reactions), bits(whole.bodies)

    def refused(self, block=0):
        raise Refused("a block")
        yield
    monkeypatch.setattr(SolvedAgain, "blocks", refused)
    monkeypatch.setattr(FusedTables, "write", lambda *a, **k: refused(None).send(None))
    sol = ks.solve(text)
    assert bits(sol.reactions) == expected
    assert "joint_reactions" in sol.__dict__       # (given by the full re-solve)
    sol = ks.solve(text)
    assert bits(sol.bodies) == bodies and "kin" in sol.__dict__


def test_the_table_holds_one_block_of_columns(fast):
    """The float columns are the rows of one array (the table's own), the ``position``
    column shared with the other long tables; a pin's N, M and offset one number each."""
    sol = ks.solve(scene_text("four_bar"))
    r, k = sol.reactions, sol.kinematics
    def at(column) -> int:
        return column.to_numpy().__array_interface__["data"][0]
    assert at(r.F) - at(r.Fx) == 2 * 8 * len(r)         # rows 0 and 2 of one array
    assert at(k.ay) - at(k.x) == 5 * 8 * len(k)         # rows 0 and 5 of another
    assert np.shares_memory(r.position.to_numpy(), k.position.to_numpy())
    assert r.N.to_numpy().strides == (0,) and np.isnan(r.offset.to_numpy()).all()


# the four roads of arith.rotate: the origin, ly = 0, lx = 0 (each with a 1 that mul
# skips), any point; and -0.0, which x + 0.0 would turn into +0.0
LOCAL = [(0.0, 0.0), (-0.0, 0.0), (0.3, 0.0), (1.0, 0.0), (0.0, -0.2), (0.0, -1.0),
         (0.25, -0.4)]


@pytest.mark.parametrize("lx, ly", LOCAL)
def test_point_rows_is_the_numpy_paths_arithmetic(fast, lx, ly):
    """The kernel's six columns are BodyMotion.point, vel_arm and acc_arm, bit for bit,
    at a local point on each road of the arithmetic, on motions with signed zeros."""
    rng = np.random.default_rng(7)
    w = 301
    # (the values of rows padded, made C-contiguous as every caller hands it: a strided
    # view compiled point_rows a second time, 'A', and test_fast's one-signature check
    # failed when it ran after this test on the compiled group's worker)
    m = np.ascontiguousarray(rng.standard_normal((10, w + 8))[:, :w])
    theta = rng.uniform(-4, 4, w)
    m[0], m[1] = np.cos(theta), np.sin(theta)
    m[4:, :5] = -0.0                    # an origin, velocity and acceleration of -0.0
    m[:2, 5:9] = [[1.0, 0.0, -1.0, 0.0], [0.0, 1.0, 0.0, -1.0]]
    body = BodyMotion(None, *m)
    rx, ry = body.rotate(lx, ly)
    x, y = body.point((lx, ly))
    expected = [x, y, *body.vel_arm(rx, ry), *body.acc_arm(rx, ry)]
    out = np.full((6, w + 9), 7.0)
    loader.kernels().point_rows(m, w, lx, ly, out, 4)
    for c in range(6):
        want = np.broadcast_to(expected[c], (w,))
        assert out[c, 4:4 + w].tobytes() == np.ascontiguousarray(want).tobytes(), c
    assert (out[:, :4] == 7.0).all() and (out[:, 4 + w:] == 7.0).all()


@pytest.mark.parametrize("text", [scene_text("four_bar"), scene_text("scotch_yoke"),
                                  slider_crank_pushed()], ids=["RRR", "TTR", "RRT"])
def test_the_fused_kernels_points_are_the_numpy_paths_arithmetic(fast, text):
    """The fused table kernel's columns of a point (written a column a loop by
    non-temporal stores) are the numpy path's arithmetic bit for bit, at a local point
    on each road of arith.rotate on every moving body, from the full re-solve's motion."""
    from kinetostatics.solver import arith as A
    sol = ks.solve(text)
    lean = sol.__dict__["_deferred"]
    fused = FusedTables(loader.kernels(), lean.known["scene"], lean.known["structure"])
    points = [(b, loc) for b in fused.slot for loc in LOCAL]
    n = lean.positions.size
    # the columns in a C-ordered block as the pass's own (a strided view is another
    # type to numba: a second compile of the kernel), three guard values after it
    buf = np.full(6 * len(points) * n + 3, 7.0)
    out = buf[:-3].reshape(6, len(points) * n)
    fused.write(points, out)
    full = ks.solve(text)
    for i, (b, loc) in enumerate(points):
        m = full.kin.bodies[b]
        rx, ry = m.rotate(*loc)
        expected = [A.add(m.ox, rx), A.add(m.oy, ry), *m.vel_arm(rx, ry), *m.acc_arm(rx, ry)]
        for c in range(6):
            want = np.ascontiguousarray(np.broadcast_to(expected[c], (n,)))
            assert out[c, i * n:(i + 1) * n].tobytes() == want.tobytes(), (b, loc, c)
    assert (buf[-3:] == 7.0).all()


def test_the_pass_solves_no_array_over_the_sweep(fast, monkeypatch):
    """The pass goes through the scratch buffer block by block: no full re-solve, and
    one call of the kinematics kernel per point and block."""
    text = scene_text("four_bar")
    sol = ks.solve(text)
    calls = []
    real = fastpass.compiled_frame
    monkeypatch.setattr(fastpass, "compiled_frame", lambda *a: calls.append(a[2]) or real(*a))
    sol.kinematics                      # noqa: B018
    sol.reactions                       # noqa: B018 (kinematics made: nothing kept)
    assert calls == ["kinematics", "reactions"] and fastpass.KEPT not in sol.__dict__
    assert sol.__dict__["_deferred"].full is None


def test_the_kernels_hypot_is_numpys_bit_for_bit(fast):
    """The fused table kernel's F: glibc's hypot inlined where it gives numpy's (checked
    once a process), else the C library's; either way numpy's ``hypot`` bit for bit, on
    pairs of every size (seeded apart from the process's own check), the four-bar's F
    of the reactions table among them."""
    from kinetostatics.solver.fast import table_pass
    from kinetostatics.solver.fast.table_kernels import hypot_rows
    rng = np.random.default_rng(2026)
    n = 200_000
    with np.errstate(all="ignore"):
        x = rng.standard_normal(n) * 2.0 ** rng.integers(-1074, 1024, n).astype(float)
        y = np.concatenate([rng.standard_normal(n // 2) * 2.0 ** rng.integers(
            -1074, 1024, n // 2).astype(float), x[:n // 2] * (1 + 1e-9 * rng.random(n // 2))])
        want = np.hypot(x, y)
    for own in (table_pass.own_hypot(), False):
        out = np.empty(n)
        hypot_rows(x, y, out, own)
        assert out.tobytes() == want.tobytes(), own
    r = ks.solve(scene_text("four_bar")).reactions
    assert r.F.to_numpy().tobytes() == np.hypot(r.Fx.to_numpy(), r.Fy.to_numpy()).tobytes()


def test_tables_with_the_c_librarys_hypot(fast, monkeypatch):
    """Where the inlined hypot is not numpy's, the C library's gives the same table."""
    from kinetostatics.solver.fast import table_pass
    text = scene_text("four_bar")
    expected = bits(ks.solve(text).reactions)
    monkeypatch.setitem(table_pass._HYPOT, "own", False)
    assert bits(ks.solve(text).reactions) == expected


def test_the_pass_makes_no_angles_over_the_sweep(fast):
    """The fused pass works out the crank's angles block by block
    (``table_pass.block_angles``): the driver's ``angles`` over the sweep (8 MB at 1e6
    rows, made for one read) stay unmade, and where they are made the pass reads them,
    the same tables bit for bit."""
    text = scene_text("four_bar")
    sol = ks.solve(text)
    driver = sol.__dict__["_deferred"].known["scene"].driver
    tables = [bits(sol.reactions), bits(sol.kinematics)]
    assert "angles" not in driver.__dict__
    other = ks.solve(text)
    made = other.__dict__["_deferred"].known["scene"].driver.angles
    assert made.size * 4 * 8 == len(tables[0]["Fx"][1])     # (four joints, 8 bytes a row)
    assert [bits(other.reactions), bits(other.kinematics)] == tables
