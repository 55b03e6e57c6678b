"""The check of a sweep's ``resist`` statistics
(:func:`~kinetostatics.solver.fast.compose.check_stats`): one scene's, as Python floats,
refuses exactly where the stacks' numpy form does (NaN and infinities among them)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from kinetostatics.solver.fast.compose import Refused, check_stats, fresh_stats
from kinetostatics.solver.loads import RESIST_STILL

VALUES = [0.0, -0.0, 1e-12, 1e-9, 0.5, 1.0, 2.0, 1e9, np.inf, np.nan]


def numpy_form(top: float, least: float, floor: float) -> bool:
    """Refused, as the numpy form tells it (the stacks' road)."""
    return not (np.array([least]) > RESIST_STILL * np.maximum(np.array([top]), floor)).all()


def refused(top: float, least: float, floor: float) -> bool:
    swept = {"ram": (None, None, [floor])}
    stats = fresh_stats(swept, 1)
    stats["ram"][0, 0] = top, least
    try:
        check_stats(swept, stats)
    except Refused:
        return True
    return False


def test_fresh_stats_are_a_tile_of_zero_and_infinity() -> None:
    stats = fresh_stats({"ram": (None, None, [1.0, 2.0])}, 3)["ram"]
    assert stats.flags.c_contiguous and stats.dtype == np.float64
    assert np.array_equal(stats, np.tile([0.0, np.inf], (2, 3, 1)))


@pytest.mark.parametrize("floor", [0.0, 1e-3, 1.0, np.inf, np.nan])
def test_one_scene_refuses_as_the_numpy_form(floor: float) -> None:
    told = [(t, q) for t, q in itertools.product(VALUES, [v * RESIST_STILL for v in VALUES]
                                                 + VALUES)
            if refused(t, q, float(floor)) != numpy_form(t, q, float(floor))]
    assert told == []
    assert refused(1.0, 0.0, float(floor))          # (a still row among the moving)
