"""Result tables built column-wise: exact CSV text ('%.17g', the same bytes as pandas),
exact round trip, Parquet (what they cost: ``python -m kinetostatics bench --tables``)."""

import tomllib

import numpy as np
import pandas as pd
import pytest

import kinetostatics as ks
from kinetostatics import csvtext, output
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
    from kinetostatics.bench_tables import measure_tables
    row = measure_tables(2_000, str(tmp_path))
    times = [k for k in row if k.endswith(("_s", "_MB", "_per_s", "_over_solve"))]
    assert {"solve_s", "long_tables_s", "long_tables_over_solve", "csv_s", "csv_MB",
            "parquet_s", "format_Mvalues_per_s", "python_format_Mvalues_per_s"} <= set(times)
    assert row["positions"] == 2_000
    assert all(np.isfinite(row[k]) and row[k] > 0 for k in times), row
    assert row["long_tables_s"] == pytest.approx(
        row["reactions_s"] + row["kinematics_s"] + row["bodies_s"])
    monkeypatch.setitem(__import__("sys").modules, "pyarrow.parquet", None)
    assert np.isnan(measure_tables(1_000, str(tmp_path))["parquet_s"])
    monkeypatch.undo()

    def broken(*args, **kwargs):
        raise ValueError("a bug in the writer")
    monkeypatch.setattr(output, "write_parquet", broken)
    with pytest.raises(ValueError, match="a bug in the writer"):
        measure_tables(1_000, str(tmp_path))
