"""A sweep read from start, stop and count is known to increase, without a pass over its
rows, only where its step is wide enough (:func:`kinetostatics.model.scene.widely_spaced`);
elsewhere its rows are checked as typed positions are."""

from __future__ import annotations

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import SceneError
from kinetostatics.model.scene import load_scene, widely_spaced


def _grids():
    rng = np.random.default_rng(17)
    for _ in range(3000):
        start = float(rng.choice([0.0, -0.0, 1.0, -1e3, 359.5, 1e10, -7e15, 3e-300]))
        start *= float(rng.uniform(0.5, 2.0))
        count = int(rng.integers(2, 5000))
        # steps from a few ulps of the ends up to whole turns
        step = float(np.spacing(abs(start) + 1e-300)) * 10.0 ** rng.uniform(-1, 9)
        yield start, start + step * (count - 1) * float(rng.choice([1.0, -1.0])), count


def test_a_widely_spaced_grid_strictly_increases() -> None:
    told = 0
    for start, stop, count in _grids():
        grid = np.linspace(start, stop, count)
        if widely_spaced(grid):
            told += 1
            assert (grid[1:] > grid[:-1]).all(), (start, stop, count)
    assert told > 500           # (most grids told; measured here 1281 of 3000)


@pytest.mark.parametrize("start, stop, count", [(1e10, 1e10 + 1e-5, 1000),
                                                (1.0, 1.0 + 3e-15, 5), (5.0, 5.0, 3),
                                                (360.0, 0.0, 361)])
def test_a_grid_not_shown_to_increase_is_checked_row_by_row(start, stop, count) -> None:
    assert not widely_spaced(np.linspace(start, stop, count))


def test_a_read_sweep_is_told_increasing_and_one_of_repeats_refused() -> None:
    d = load_scene(ks.example("four_bar")).raw
    sc = load_scene({**d, "driver": {**d["driver"], "count": 2001}})
    assert sc.driver.increasing
    given = load_scene({**d, "driver": {k: v for k, v in d["driver"].items()
                                        if k not in ("start", "stop", "count")}
                        | {"positions": [0.0, 10.0, 20.0]}})
    assert not given.driver.increasing
    tiny = {**d, "driver": {**d["driver"], "start": 1e10, "stop": 1e10 + 1e-5,
                            "count": 1000}}
    assert not load_scene(tiny).driver.increasing
    with pytest.raises(SceneError, match="listed more than once"):
        ks.solve(tiny)
