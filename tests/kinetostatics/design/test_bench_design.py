"""The bench's design row."""

from kinetostatics.bench.speed import bench_design


def test_bench_design_row():
    (row,) = bench_design(population=8, generations=1, repeat=1)
    assert row["size"] == "8 x 1 x 361"
    assert row["rows_per_second"] == 8 * 361 / row["seconds_best"] > 0
