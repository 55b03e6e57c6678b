"""solve_many on the compiled path: every scene's Solution bit for bit its solve on that
path, stacked (not solved one by one) whatever its loads."""

from __future__ import annotations

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver import many

from .test_many import assert_same, variants


def each_its_solve(sols: list, scenes: list) -> list[tuple]:
    """Each stacked Solution of ``sols`` with its scene's own solve, both on the compiled
    path and equal in every table and flag (:func:`assert_same`)."""
    pairs = [(s, ks.solve(sc)) for s, sc in zip(sols, scenes, strict=True)]
    for s, alone in pairs:
        assert s.path == alone.path == "fast"
        assert_same(s, alone)
    return pairs

numba = pytest.importorskip("numba")

# the compiled kernels: a fresh machine compiles them first (slow tier, as test_fast.py)
pytestmark = pytest.mark.slow


def unequal(name: str, count: int, seed: int) -> list:
    """``count`` read variants of a bundled example, each a few rows shorter than the
    one before (a tile of the fused kernels holds rows of two scenes, each with its
    geometry)."""
    out = []
    for i, d in enumerate(variants(name, count, 0.05, seed=seed)):
        d["driver"]["count"] = int(d["driver"]["count"]) - 5 * i
        out.append(load_scene(d))
    return out


def test_scenes_shorter_than_a_tile_share_it(alone_calls, fast) -> None:
    """Four-bars of 2 to 97 rows stacked: a tile of the fused kernel (16 rows) holds the
    rows of several scenes, each column its scene's geometry and cos and sin (a scene's
    geometry filled where the columns held another's); every table, flag and dead point
    is each scene's solve's on this path."""
    scenes = []
    for i, d in enumerate(variants("four_bar", 12, 0.05, seed=7)):
        count = (2, 5, 17, 31, 33, 3, 40, 97, 32, 9, 64, 7)[i]
        d["driver"].update(start=3.0 * i, stop=3.0 * i + 12.0 * count, count=count)
        scenes.append(load_scene(d))
    sols = ks.solve_many(scenes)
    assert alone_calls == []                # all twelve in one stacked pass
    each_its_solve(sols, scenes)


@pytest.mark.parametrize("name", ["slider_crank", "shaper"])
def test_resist_and_resisting_loads_stack(name, alone_calls, fast) -> None:
    """A ``resist`` load (the slider-crank's piston) and a force ``when = "resisting"``
    (the shaper's cut) stacked on the compiled path: each scene's still threshold is
    checked against its own sweep's top, and every table, flag and undefined row is its
    solve's on this path."""
    scenes = unequal(name, 8, seed=4)
    sols = ks.solve_many(scenes)
    assert alone_calls == []                # all eight in one stacked pass
    for s, alone in each_its_solve(sols, scenes):
        np.testing.assert_array_equal(s.undefined_load, alone.undefined_load)


def test_a_refused_run_is_solved_scene_by_scene(alone_calls, fast, monkeypatch
                                                ) -> None:
    """A run a kernel refuses (here: the check of a sweep's top made to fail) is solved
    scene by scene, each as its solve: not the run on the numpy path, whose numbers
    differ from the compiled path's in the last bits."""
    from kinetostatics.solver.fast import compose

    scenes = unequal("slider_crank", 5, seed=2)

    def refuse(self) -> None:
        if "segments" in self.scene.__dict__:       # (a stack: not a scene alone)
            raise compose.Refused("swept load")
    monkeypatch.setattr(compose.Plan, "check_swept", refuse)
    sols = ks.solve_many(scenes)
    assert sorted(alone_calls) == sorted(sc.title for sc in scenes)
    for s, sc in zip(sols, scenes, strict=True):
        assert s.path == "fast"
        assert_same(s, ks.solve(sc))
    assert all(type(r) is not many.CutSolved for r in many.solve_all(scenes))


def test_what_one_call_keeps_never_reaches_the_next(alone_calls, fast) -> None:
    """What solve_many keeps from call to call (the group's closeness array, a shared
    sweep's stacked positions, each row's scene) carries nothing of one call's rows into
    the next: groups of the same sweep, of another sweep of as many rows, of
    change-point four-bars (dead points between rows), one after another; each scene's
    Solution is its solve's, flags and dead points too."""
    from .test_deadpoints import change_point_four_bar

    def group(seed: int, start: float) -> list:
        out = []
        for d in variants("four_bar", 5, 0.05, seed=seed):
            d["driver"].update(start=start, stop=start + 360.0, count=181)
            out.append(load_scene(d))
        return out
    same = group(5, 0.0)
    other = group(6, 0.7)                   # (as many rows, other positions)
    # (one sweep shared by the five, their dead points found by probing its positions)
    dead = [load_scene(change_point_four_bar(a, 0.3, 0.2, 0.5, 181))
            for a in (0.1, 0.105, 0.11, 0.115, 0.12)]
    apart = [load_scene(change_point_four_bar(0.1, 0.3, 0.2, 0.5 * i, 181)) for i in range(4)]
    assert all(len(ks.solve(sc).kin.between) for sc in dead)
    for scenes in (same, other, dead, apart, same):
        sols = ks.solve_many(scenes)
        assert alone_calls == []
        for s, alone in each_its_solve(sols, scenes):
            np.testing.assert_array_equal(s.kin.between, alone.kin.between)


def test_the_kernel_tells_the_flags_and_the_rows_below_the_screen(fast, monkeypatch
                                                                  ) -> None:
    """solve_many's fused kernel writes each row's singular flag and the rows below the
    dead-point screen as it goes: numpy's ``~(c > SINGULAR_WARN**2)`` and
    ``flatnonzero(c < SCREEN**2)`` of the closeness it writes (measured 2026-11-30, 40
    four-bar variants: 224 rows of 14 440 below the screen, none singular), and each
    scene's Solution is its solve's."""
    from kinetostatics.solver.deadpoints import SCREEN
    from kinetostatics.solver.kinematics import SINGULAR_WARN
    scenes = [load_scene(d) for d in variants("four_bar", 40, 0.10, seed=3)]
    got: dict = {}
    real = many.solve_group_kept

    def spy(*args):
        out = real(*args)
        kept, below = out
        # (copies: the closeness array is given back for the next call once screened)
        got.update(close=kept.closeness2[0].copy(), singular=kept.singular[0].copy(),
                   below=None if below is None else below.copy())
        return out
    monkeypatch.setattr(many, "solve_group_kept", spy)
    sols = ks.solve_many(scenes)
    close = got["close"]
    assert got["below"] is not None and got["below"].size > 0
    np.testing.assert_array_equal(got["below"], np.flatnonzero(close < SCREEN**2))
    np.testing.assert_array_equal(got["singular"], ~(close > SINGULAR_WARN**2))
    each_its_solve(sols[:8], scenes[:8])
