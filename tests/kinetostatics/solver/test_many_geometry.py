"""The compiled fused kernel's geometry of a stack kept on its Stacker
(``fast.stacked.solve_group_kept``) and read again by the dead-point screen's bound
(``fast.screen.stack_tables``): the tables the screen makes itself, bit for bit, and
only for the structure and assemblies it was made with."""

from __future__ import annotations

import numpy as np
import pytest

from kinetostatics.bench.speed import example_variants
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.fast import loader
from kinetostatics.solver.fast.screen import stack_bound, stack_tables
from kinetostatics.solver.fast.stacked import solve_group_kept
from kinetostatics.solver.many import stacked_positions

from .test_screen_probe import stack

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


def _same(got: tuple, expected: tuple) -> None:
    (gd, gds), dyads = got
    (ed, eds), expected_dyads = expected
    assert gds == eds
    np.testing.assert_array_equal(np.asarray(gd).view(np.int64), np.asarray(ed).view(np.int64))
    assert len(dyads) == len(expected_dyads)
    for (g, gs), (e, es) in zip(dyads, expected_dyads, strict=True):
        assert gs == es and g.shape == e.shape
        np.testing.assert_array_equal(g.view(np.int64), e.view(np.int64))


@pytest.mark.parametrize("name", ["four_bar", "slider_crank"])
def test_kept_geometry_is_the_screens_own(fast, name) -> None:
    scenes = [load_scene(d) for d in example_variants(name, 12)]
    stacker, structure, ks = stack(scenes)
    expected = stack_tables(stacker, structure, ks)
    bound = stack_bound(stacker, structure, ks)
    assert not stacker.kept        # (the screen's own tables: nothing kept for them)
    counts = np.array([s.driver.positions.size for s in stacker.scenes])
    got = solve_group_kept(stacker, structure, ks, counts,
                           stacked_positions(stacker.scenes)[0])
    assert got is not None and "geometry" in stacker.kept
    _same(stack_tables(stacker, structure, ks), expected)
    again = stack_bound(stacker, structure, ks)
    if bound is None:
        assert again is None
    else:
        np.testing.assert_array_equal(again.view(np.int64), bound.view(np.int64))
    # other assemblies (a copy of them): the screen's own tables again
    other = ks.copy()
    _same(stack_tables(stacker, structure, other), expected)
