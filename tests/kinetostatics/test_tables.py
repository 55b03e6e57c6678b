"""Result tables built column-wise: exact CSV text ('%.17g', the same bytes as pandas),
exact round trip, Parquet (what they cost: ``python -m kinetostatics bench --tables``)."""

import tomllib

import numpy as np
import pandas as pd
import pytest

import kinetostatics as ks
from kinetostatics.results import csvtext, output
from kinetostatics.results.longtable import LINE
from tests.helpers import OWN_CASES

CONTRACT = {
    "reactions": ["position", "joint", "on", "by", "Fx", "Fy", "F", "N", "M", "offset"],
    "driver": ["position", "Me", "singular", "undefined_load"],
    "kinematics": ["position", "body", "point", "x", "y", "vx", "vy", "ax", "ay"],
    "bodies": ["position", "body", "angle", "omega", "alpha"],
}
LABELS = {"joint", "on", "by", "body", "point"}


def load(name):
    with open(OWN_CASES / f"{name}.toml", "rb") as fh:
        return tomllib.load(fh)


def locking_slider_crank():
    """Friction that locks the slider-crank near its dead centres: NaN rows in driver
    and reactions, a self_locking column, and empty offset cells."""
    d = load("slider_crank")
    for j in d["joints"]:
        j["friction"] = {"mu": 1.3, "radius": 0.03} if j["kind"] == "R" else \
            {"mu": 1.3, "length": 0.08}
    return d


def python_text(values) -> list[str]:
    """Python's own text of each value (format(v, '.17g') is '%.17g' % v), NaN empty."""
    return ["" if v != v else format(v, ".17g") for v in np.asarray(values, dtype=float).tolist()]


def formatted(values) -> list[str]:
    chars, length = csvtext.format_floats(np.asarray(values, dtype=float))
    return [bytes(chars[i, :length[i] - 1]).decode() for i in range(length.size)]


def same_bits(a, b) -> bool:
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return a.shape == b.shape and bool(np.array_equal(np.isnan(a), np.isnan(b))) and \
        bool((a[~np.isnan(a)].view(np.int64) == b[~np.isnan(b)].view(np.int64)).all())


# ------------------------------------------------------------------ the float formatter
def test_floats_as_python_formats_them():
    """Every kind of double, as Python's '%.17g' writes it: wide exponents, random
    bit patterns (subnormals, NaN payloads, infinities), signed zeros, ties."""
    rng = np.random.default_rng(11)
    values = np.concatenate([
        rng.standard_normal(20_000),
        rng.standard_normal(20_000) * 10.0 ** rng.integers(-300, 300, 20_000),
        rng.integers(0, 2**63, 20_000, dtype=np.uint64).view(np.float64),
        np.round(rng.standard_normal(5_000), 3), np.linspace(0.0, 360.0, 5_001),
        # exact ties at the 17th digit: n + 0.25 or n + 0.75 with 16 integer digits
        rng.integers(10**15, 9 * 10**15, 5_000) + rng.choice([0.25, 0.75], 5_000),
        [0.0, -0.0, np.inf, -np.inf, np.nan, 1e16, 1e17, 1e-4, 1e-5, 1e22, 1e-300,
         5e-324, 1.7976931348623157e308, 0.1, 1 / 3, 99999999999999990.0],
    ])
    assert formatted(values) == python_text(values)


# ------------------------------------------------------------------ tables
@pytest.mark.parametrize("name", ks.examples())
def test_bundled_tables_written_as_pandas_writes_them(tmp_path, name):
    """Every bundled scene: each written CSV is byte for byte what pandas'
    to_csv(index=False, float_format='%.17g') writes for the same table, whether the
    long tables are streamed from the solver's arrays or written from the DataFrames."""
    sol = ks.solve(ks.example(name))
    streamed = sol.write(tmp_path / "streamed")       # long tables never built
    for path in streamed:
        if path.suffix == ".csv":
            table = getattr(sol, path.stem)
            expected = table.to_csv(index=False, float_format="%.17g").encode()
            assert path.read_bytes() == expected, path.name
    for path in sol.write(tmp_path / "built"):        # now from the built tables
        assert path.read_bytes() == (tmp_path / "streamed" / path.name).read_bytes()


def test_csv_round_trips_bit_for_bit(tmp_path):
    """Read back with pandas, every float has its bits again (NaN rows of a locked
    mechanism and the empty offset cells as NaN), booleans are booleans, labels text."""
    sol = ks.solve(locking_slider_crank())
    assert sol.self_locking.any() and sol.reactions.offset.isna().any()
    sol.write(tmp_path)
    for name in ("reactions", "driver", "kinematics", "bodies", "dyads", "sliders", "frame"):
        table = getattr(sol, name)
        back = pd.read_csv(tmp_path / f"{name}.csv")
        assert list(back.columns) == list(table.columns), name
        for col in table.columns:
            a, b = table[col], back[col]
            if a.dtype.kind == "f":
                # whole numbers (positions 0, 1, ...) read back as integers: same values
                assert b.dtype.kind in "fi" and same_bits(a, b.astype(float)), (name, col)
            elif a.dtype.kind == "b":
                assert b.dtype.kind == "b" and (a.to_numpy() == b.to_numpy()).all(), (name, col)
            else:
                assert list(a.astype(str)) == list(b.astype(str)), (name, col)


def test_contract_columns_dtypes_and_blocks():
    """The contract's columns in order; floats float64, booleans bool, the name columns
    categorical; long tables in blocks of one joint (point, body) over the sweep."""
    sol = ks.solve(OWN_CASES / "slider_crank.toml")
    n = sol.positions.size
    for name, cols in CONTRACT.items():
        t = getattr(sol, name)
        assert list(t.columns[:len(cols)]) == cols, name
        for c in cols:
            kind = "category" if c in LABELS else "bool" if c in (
                "singular", "undefined_load") else "float64"
            assert str(t[c].dtype) == kind, (name, c)
    r = sol.reactions
    assert list(r.joint.cat.categories) == list(sol.scene.joints)
    assert (r.position.to_numpy().reshape(-1, n) == sol.positions).all()
    for i, joint in enumerate(sol.scene.joints):
        block = r.iloc[i * n:(i + 1) * n]
        assert (block.joint == joint).all()
        fx, fy = sol.reaction(joint)
        assert same_bits(block.Fx, fx) and same_bits(block.Fy, fy)
        assert same_bits(block.F, np.hypot(fx, fy))


def test_parquet_keeps_everything(tmp_path):
    pytest.importorskip("pyarrow")
    sol = ks.solve(locking_slider_crank())
    paths = sol.write(tmp_path, "parquet")
    assert {p.suffix for p in paths} == {".parquet", ".json"}
    for name in ("reactions", "driver", "kinematics", "bodies"):
        back = pd.read_parquet(tmp_path / f"{name}.parquet")
        table = getattr(sol, name)
        assert list(back.columns) == list(table.columns)
        assert (back.dtypes == table.dtypes).all(), name
        for col in table.columns:
            if table[col].dtype.kind == "f":
                assert same_bits(back[col], table[col]), (name, col)
            else:
                assert (back[col].astype(str) == table[col].astype(str)).all(), (name, col)


def test_written_tables_are_dropped(tmp_path):
    """Writing builds each table, writes it and lets it go (one long table in memory at a
    time); a table the caller already built stays."""
    sol = ks.solve(OWN_CASES / "four_bar.toml")
    kept = sol.bodies
    sol.write(tmp_path)
    assert "kinematics" not in sol.__dict__ and sol.__dict__["bodies"] is kept


def test_table_benchmark_reports_its_fields(tmp_path, monkeypatch):
    """``bench --tables`` measures (its numbers are machine time and no test judges
    them): one in-process run reports every field, positive and finite, and Parquet
    unmeasured (NaN) only where pyarrow is missing, with any other error raised."""
    from kinetostatics.bench.tables import first_floor, measure_tables, over_first_floor
    row = measure_tables(2_000, str(tmp_path))
    times = [k for k in row if k.endswith(("_s", "_MB", "_per_s", "_over_solve"))]
    assert {"solve_s", "long_tables_s", "long_tables_over_solve", "csv_s", "csv_MB",
            "parquet_s", "format_Mvalues_per_s", "python_format_Mvalues_per_s"} <= set(times)
    assert row["positions"] == 2_000
    assert all(np.isfinite(row[k]) and row[k] > 0 for k in times), row
    assert row["long_tables_s"] == pytest.approx(
        row["reactions_s"] + row["kinematics_s"] + row["bodies_s"])
    # each warm round's solve and three tables over its solve + floor: the median round
    assert row["warm_over_floor"] > 0 and row["warm_over_floor_cpu"] > 0
    assert row["warm_over_floor_best"] <= row["warm_over_floor"]
    assert row["warm_over_floor_cpu_best"] <= row["warm_over_floor_cpu"]
    first = row | {"first_floor_s": 0.5, "first_floor_cpu_s": 0.25}
    spent = sum(row[f"{k}_s"] for k in ("solve", "driver", "reactions", "kinematics"))
    assert over_first_floor(first)["over_first_floor"] == pytest.approx(
        spent / (row["solve_s"] + 0.5))
    # the floor's layout: the kinematics' float block (54 rows of 8 bytes a position) and
    # the position (9 blocks) written whole (each in an allocation a cache line longer:
    # longtable.line_aligned); the reactions' float block allocated whole, its written
    # rows alone held (N, M, offset of pins: one number each)
    layout = row.pop("layout")
    held = {e[0]: sum(b - a for a, b in zip(e[1::2], e[2::2], strict=True)) for e in layout}
    for whole in (54 * 8 * 2_000, 9 * 8 * 2_000):
        assert held[whole + LINE] == whole
    assert any(size > part > 0 for size, part in held.items())
    assert sum(sum(b - a for a, b in zip(e[1::2], e[2::2], strict=True))
               for e in layout) == round(row["tables_MB"] * 1e6)
    assert first_floor(2_000, layout)["first_floor_cpu_s"] > 0
    # 648 bytes a row: kinematics 9 points x 6 floats, their position and names; reactions
    # Fx, Fy, F of 4 pins and names (N, M and offset a view of one number); the driver
    assert row["tables_MB"] == pytest.approx(648 * 2_000 / 1e6, abs=1e-4)
    monkeypatch.setitem(__import__("sys").modules, "pyarrow.parquet", None)
    assert np.isnan(measure_tables(1_000, str(tmp_path))["parquet_s"])
    monkeypatch.undo()

    def broken(*args, **kwargs):
        raise ValueError("a bug in the writer")
    monkeypatch.setattr(output, "write_parquet", broken)
    with pytest.raises(ValueError, match="a bug in the writer"):
        measure_tables(1_000, str(tmp_path))


def test_held_bytes_count_shared_memory_once():
    """The write floor's byte count: a column shared by several tables (a view of one
    array) once, a column of one value 8 bytes, a categorical its codes."""
    from kinetostatics.bench.tables import held_bytes
    base = np.arange(100.0)
    one = pd.DataFrame({"a": base, "b": np.broadcast_to(np.float64(2.0), (100,))},
                       copy=False)
    two = pd.DataFrame({"a": base[:50], "c": pd.Categorical(["x", "y"] * 25)}, copy=False)
    assert np.shares_memory(one.a.to_numpy(), two.a.to_numpy())
    assert held_bytes([one, two]) == 800 + 8 + 50
    # a categorical's codes where the table holds them (not a copy: pandas 3's
    # ``Series.cat.codes`` is one), so codes two tables share count once
    codes = np.zeros(100, dtype=np.int8)
    cats = [pd.DataFrame({"c": pd.Categorical.from_codes(codes, categories=["x"])},
                         copy=False) for _ in range(2)]
    assert held_bytes(cats) == 100
    sol = ks.solve(OWN_CASES / "four_bar.toml")
    k, r = sol.kinematics, sol.reactions
    n = sol.positions.size
    points, pins = len(k) // n, len(r) // n
    assert points > pins and (r.N == 0).all()
    # kinematics: x..ay of each point, the position held once (the reactions' a view of
    # its first blocks), two int8 name columns; reactions: Fx, Fy, F of each pin, three
    # int8 columns, N and M the one 0.0 (a view of it, shared), offset NaN
    assert held_bytes([k, r]) == 8 * points * n * 7 + 2 * points * n + \
        8 * pins * n * 3 + 3 * pins * n + 2 * 8


# ------------------------------------------------------------------ memory
def test_tables_share_columns_but_never_see_each_others_writes():
    """At 1e6 positions the tables are most of the memory: the long tables hold one
    ``position`` column, ``reactions`` shares Fx/Fy with the joint reactions, ``bodies``
    its angles with ``Solution.angles``, ``driver`` Me with the solve, and a column of one
    value (N, M, offset of pins) is that one number. A write to any table copies the
    column first: the other tables and the solution keep their numbers."""
    sol = ks.solve(OWN_CASES / "four_bar.toml")
    n = sol.positions.size
    r, k, b, d = sol.reactions, sol.kinematics, sol.bodies, sol.driver
    assert np.shares_memory(r.position.to_numpy(), k.position.to_numpy())
    assert np.shares_memory(b.angle.to_numpy(), sol.angles[next(iter(sol.scene.bodies))])
    assert r.N.to_numpy().strides == (0,)            # all pins: N = 0 held once
    joint = next(iter(sol.scene.joints))
    fx0 = sol.reaction(joint)[0].copy()
    angle0 = {name: a.copy() for name, a in sol.angles.items()}
    me0, pos0 = np.array(sol.Me), k.position.to_numpy().copy()
    for table, col in ((r, "position"), (r, "Fx"), (r, "N"), (r, "offset"), (b, "angle"),
                       (d, "Me"), (d, "position")):
        table.loc[0, col] = 12345.0                   # no read-only error
        assert table.loc[0, col] == 12345.0
    assert same_bits(k.position, pos0) and same_bits(b.position, np.tile(sol.positions, 3))
    assert same_bits(sol.reaction(joint)[0], fx0) and same_bits(sol.Me, me0)
    assert all(same_bits(sol.angles[name], a) for name, a in angle0.items())
    assert (ks.solve(OWN_CASES / "four_bar.toml").reactions.N == 0).all()   # the shared 0
    assert same_bits(r.N.to_numpy()[1:], np.zeros(4 * n - 1))


@pytest.mark.parametrize("share_rows", [0, 10**9], ids=["shared", "own"])
@pytest.mark.parametrize("case", ["four_bar", "slider_crank"])
def test_driver_table_either_way_is_the_same_and_keeps_writes_to_itself(monkeypatch, case,
                                                                        share_rows):
    """The driver table of a short sweep holds columns of its own (built from the block
    API), of a long one columns shared with the solve (its positions, Me/Fe): the same
    table either way (values, dtypes, labels, index, one block per column), and a write
    to it changes neither the solution, nor the long tables, nor a second look at it."""
    from kinetostatics.results import longtable
    expected = ks.solve(OWN_CASES / f"{case}.toml").driver.copy(deep=True)
    monkeypatch.setattr(longtable, "SHARE_ROWS", share_rows)
    sol = ks.solve(OWN_CASES / f"{case}.toml")
    d = sol.driver
    pd.testing.assert_frame_equal(d, expected, check_exact=True)
    assert list(d.columns) == CONTRACT["driver"][:1] + [sol.driver_quantity] + \
        CONTRACT["driver"][2:]
    assert isinstance(d.index, pd.RangeIndex) and d.index.equals(pd.RangeIndex(len(d)))
    assert [b.dtype for b in d._mgr.blocks] == list(d.dtypes)      # one block per column
    k = sol.kinematics
    shares = [np.shares_memory(d.position.to_numpy(), sol.positions),
              np.shares_memory(d[sol.driver_quantity].to_numpy(), sol.drive.value)]
    assert shares == ([False, False] if share_rows > len(d) else [True, True])
    me0, pos0, kpos0 = np.array(sol.Me), sol.positions.copy(), k.position.to_numpy().copy()
    sing0, undef0 = sol.singular.copy(), np.array(sol.undefined_load)
    q = sol.driver_quantity
    d.loc[0, q] = 12345.0
    d.loc[1, "position"] = -1.0
    d.loc[2, "singular"] = not sing0[2]
    d.loc[3, "undefined_load"] = not undef0[3]
    col = d["position"]                  # a column taken out and written to: a copy of it
    col.iloc[4] = 99.0
    assert d.loc[0, q] == 12345.0 and d.loc[1, "position"] == -1.0 and d.position[4] != 99.0
    assert sol.driver is d                                     # kept, with the writes
    assert same_bits(sol.Me, me0) and same_bits(sol.positions, pos0)
    assert same_bits(k.position, kpos0)
    with pytest.raises(ValueError, match="read-only"):    # the solver's array, kept safe
        sol.Me[0] = 1.0
    assert (sol.singular == sing0).all() and (np.asarray(sol.undefined_load) == undef0).all()
    d.columns.name = "renamed"                  # the labels are this table's own
    assert ks.solve(OWN_CASES / f"{case}.toml").driver.columns.name is None


def test_released_loads_come_back_bit_for_bit(monkeypatch):
    """The solve lets the loads go (no table of the contract needs them); asked for, they
    are computed again with exactly the numbers the solve used, as are the tables made
    from them."""
    scene = OWN_CASES / "slider_crank.toml"
    released = ks.solve(scene)
    assert released.__dict__["_loads"] is None
    monkeypatch.setattr(ks.Solution, "release_loads", lambda self: None)
    kept = ks.solve(scene)
    assert len(released.loads) == len(kept.loads)
    for a, b in zip(released.loads, kept.loads, strict=True):
        assert (a.body, a.kind, a.label) == (b.body, b.kind, b.label)
        for f in ("rx", "ry", "fx", "fy", "m"):
            assert same_bits(np.ravel(getattr(a, f)), np.ravel(getattr(b, f))), f
    for name in ("powers", "reduced", "frame"):
        pd.testing.assert_frame_equal(getattr(released, name), getattr(kept, name),
                                      check_exact=True)


def _long_sweep():
    """33 001 positions: three chunks of output.CHUNK positions per block of a long table
    (the last one short), solved in the solver's blocks (>= 2 x BLOCK_ROWS rows); the
    fixture's pandas bytes 7.7 s of CPU against 10.0-11.5 s at 40 001 (load 10,
    measured 2026-11-30)."""
    scene = ks.load_scene(ks.example("slider_crank"))
    return ks.solve(scene, np.linspace(0.0, 359.99, 33_001))


@pytest.fixture(scope="module")
def long_sweep_csv() -> dict[str, bytes]:
    """pandas' bytes of every table of the long sweep (8 s of CPU; made once for both
    writers' tests, tests/conftest.py: SHARED_ONCE), from a solve of its own: the tested
    solution has built no table when it writes."""
    sol = _long_sweep()
    return {name: getattr(sol, name).to_csv(index=False, float_format="%.17g").encode()
            for name in sol.FILES}


@pytest.mark.slow
@pytest.mark.parametrize("load", [0.0, 99.0])
def test_long_sweep_written_as_pandas_writes_it(tmp_path, monkeypatch, load, long_sweep_csv):
    """Many chunks per block, the position formatted once for every table, with the
    writer's threads (a core free) or without (a busy machine): still pandas' bytes."""
    monkeypatch.setattr(output.os, "getloadavg", lambda: (load, load, load))
    sol = _long_sweep()
    written = [path for path in sol.write(tmp_path) if path.suffix == ".csv"]
    assert {path.stem for path in written} == set(long_sweep_csv)
    for path in written:
        assert path.read_bytes() == long_sweep_csv[path.stem], path.name


def test_rows_text_keeps_a_label_with_a_nul():
    """The row text is each field's characters: a NUL in a label is kept (the zero bytes
    after a field's text are not characters)."""
    values = np.array([1.5, -0.0, np.nan])
    fields = [csvtext.format_column(np.array(["a\x00b", "c", "d"], dtype=object), ","),
              csvtext.format_floats(values, "\n")]
    assert csvtext.rows_text(fields) == b"a\x00b,1.5\nc,-0\nd,\n"


@pytest.mark.parametrize("share_rows", [0, 10**9], ids=["shared", "own"])
def test_a_deferred_solves_driver_table_keeps_writes_to_itself(monkeypatch, share_rows):
    """A deferred solve's driver table (a scene of solve_many): its ``singular`` the array
    ``singular()`` made for it, its ``undefined_load`` shared with the solve when long; a
    write to either changes neither the solution nor a second table."""
    from kinetostatics.results import longtable
    monkeypatch.setattr(longtable, "SHARE_ROWS", share_rows)
    scenes = [OWN_CASES / "four_bar.toml", OWN_CASES / "slider_crank.toml"] * 2
    sol = ks.solve_many(scenes)[2]
    assert "_deferred" in sol.__dict__ and "kin" not in sol.__dict__
    d = sol.driver
    sing0, undef0 = sol.singular.copy(), np.array(sol.undefined_load)
    assert not np.shares_memory(d.singular.to_numpy(), sol.singular)
    assert np.shares_memory(d.undefined_load.to_numpy(), sol.undefined_load) == \
        (share_rows == 0)
    d.loc[2, "singular"] = not sing0[2]
    d.loc[3, "undefined_load"] = not undef0[3]
    assert d.loc[2, "singular"] != sing0[2] and d.loc[3, "undefined_load"] != undef0[3]
    assert (sol.singular == sing0).all() and (np.asarray(sol.undefined_load) == undef0).all()
    del sol.__dict__["driver"]                  # (a second table of the same solution)
    again = sol.driver
    assert again.singular[2] == sing0[2] and again.undefined_load[3] == undef0[3]
