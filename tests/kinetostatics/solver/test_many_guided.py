"""solve_many of the six-bars (the shaper, the slotted lever) on the compiled path: a stack
of guided scenes in one call of the guide's kernel (``stacked.guided_kept``), each tile
one scene's rows with that scene's geometry, every table bit for bit its scene's solve."""

from __future__ import annotations

import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene

from .test_many import variants
from .test_many_fast import each_its_solve

numba = pytest.importorskip("numba")

# the compiled kernels: a fresh machine compiles them first (slow tier, as test_fast.py)
pytestmark = pytest.mark.slow

# rows of each scene: fewer than a tile of the guide's kernels (jitbase.TILE, 64), one
# tile, one row more, several tiles and a part; each scene's geometry then starts a tile
COUNTS = (361, 2, 64, 65, 17, 200, 3, 129)


@pytest.fixture
def guided_calls(monkeypatch):
    """What each call of ``stacked.guided_kept`` gave (None: not the guide's kernel)."""
    from kinetostatics.solver.fast import stacked

    calls = []
    kept = stacked.guided_kept

    def spy(*args, **kwargs):
        out = kept(*args, **kwargs)
        calls.append(out)
        return out
    monkeypatch.setattr(stacked, "guided_kept", spy)
    return calls


def _stack(name: str, seed: int, own_sweeps: bool) -> list:
    """Variants of ``name`` of :data:`COUNTS` rows, each its own sweep (``own_sweeps``:
    the crank's cos and sin over the run's rows) or, of 361 rows, the example's (one
    sweep's cos and sin, each scene's rows from 0)."""
    out = []
    for i, d in enumerate(variants(name, len(COUNTS), 0.05, seed=seed)):
        if own_sweeps:
            count = COUNTS[i]
            d["driver"].update(start=7.0 * i, stop=7.0 * i + 2.5 * count, count=count)
        out.append(load_scene(d))
    return out


@pytest.mark.parametrize("own_sweeps", [True, False])
@pytest.mark.parametrize("name", ["shaper", "slotted_lever"])
def test_a_stack_of_guided_scenes_is_each_scenes_solve(name, own_sweeps, alone_calls,
                                                       guided_calls, fast) -> None:
    """Six-bars of 2 to 361 rows stacked (or of one sweep): the guide's kernel refills a
    tile's geometry (the crank's, the RTR dyad's, the second dyad's, each body's loads)
    where its scene changes, and takes each row's cos and sin from its scene's; every
    table, flag and dead point is each scene's solve's on this path."""
    scenes = _stack(name, 3, own_sweeps)
    sols = ks.solve_many(scenes)
    assert alone_calls == []                        # all stacked
    assert guided_calls and all(k is not None for k in guided_calls)
    for s, alone in each_its_solve(sols, scenes):
        assert s.kin.between.tolist() == alone.kin.between.tolist()


def test_the_closeness_arrays_given_back_serve_the_next_stack(fast) -> None:
    """The two dyads' closeness arrays of a stack of shapers go back to the pool after its
    screen (``stacked.release``) and are taken by the next stack, m^2 written over the
    second (``deadpoints.measure2``, ``spent``): that stack's tables and dead points are
    still each scene's solve's, and both arrays come back again."""
    from kinetostatics.solver.fast import stacked

    first = _stack("shaper", 4, True)
    ks.solve_many(first)
    pooled = {id(b) for b in stacked.SCRATCH}
    assert len(pooled) >= 2
    scenes = _stack("shaper", 5, True)
    sols = ks.solve_many(scenes)
    assert {id(b) for b in stacked.SCRATCH} >= pooled
    for s, alone in each_its_solve(sols, scenes):
        assert s.kin.between.tolist() == alone.kin.between.tolist()
