"""The bench's design rows: one per solve path."""

import pytest

from kinetostatics.bench.speed import bench_design, solve_paths


@pytest.mark.slow           # the fast row compiles the kernels on a fresh machine
def test_bench_design_row():
    rows = bench_design(population=8, generations=1, repeat=1)
    assert [r["path"] for r in rows] == solve_paths()       # numpy, and fast with numba
    for row in rows:
        assert row["size"] == "8 x 1 x 361"
        assert row["rows_per_second"] == 8 * 361 / row["seconds_best"] > 0
