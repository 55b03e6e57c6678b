"""The compiled probe of a stack's dead-point screen (``solver/fast/screen.py``,
``crank_rrr_probe``: a crank and one RRR dyad) against numpy's ``probe_closeness``: the same
closeness to a dead centre bit for bit, and the same rows where the dyad cannot close."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.bench.speed import example_variants, four_bar_variants
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.fast import loader, use
from kinetostatics.solver.fast.screen import crank_rrr_probe, stack_probe
from kinetostatics.solver.probes import probe_closeness
from kinetostatics.solver.stack import Stacker, assemblies, stack_record
from kinetostatics.solver.structure import analyse

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


def stack(scenes: list) -> tuple:
    """The stacker, structure and assemblies of the scenes that assemble at their first
    row (as solve_many stacks them)."""
    structure = analyse(scenes[0], assemble=False)
    stacker = Stacker(scenes, [stack_record(s)[1] for s in scenes])
    ks_, ok = assemblies(stacker, structure)
    kept = [s for s, g in zip(scenes, ok, strict=True) if g]
    stacker = Stacker(kept, [stack_record(s)[1] for s in kept])
    return stacker, structure, assemblies(stacker, structure)[0]


def long_cranks(count: int, seed: int) -> list:
    """Four-bars whose crank is 0.05-0.3 m long (the bundled one's: 0.1 m), each read at
    its first row only: many cannot close over part of the turn (the probes' open rows)."""
    rng = np.random.default_rng(seed)
    out = []
    for d in four_bar_variants(count, spread=0.2, seed=seed):
        crank = next(b for b in d["bodies"] if b["name"] == "crank")
        crank["points"]["B"] = [float(rng.uniform(0.05, 0.3)), 0.0]
        out.append(load_scene(d))
    return out


def assert_numpys_closeness(at, stacker, structure, k, who, where) -> np.ndarray:
    """Check the probe ``at`` at ``where`` (scene ``who`` of the stack) against numpy's
    probe_closeness bit for bit: m^2 and the rows that cannot close (returned)."""
    probe = replace(structure, assembly=tuple(x[who] for x in k))
    (expected,), expected_open = probe_closeness(stacker.scene(who, where), probe,
                                                 measured=True)
    (got,), got_open = at(where, who)
    np.testing.assert_array_equal(got.view(np.int64), expected.view(np.int64))
    np.testing.assert_array_equal(got_open, expected_open)
    return expected_open


@pytest.mark.parametrize("seed", [1, 2])
def test_compiled_probe_is_numpys_bit_for_bit(fast, seed) -> None:
    stacker, structure, k = stack(long_cranks(120, seed))
    at = crank_rrr_probe(stacker, structure, k)
    assert at is not None
    rng = np.random.default_rng(seed)
    who = rng.integers(0, len(stacker.scenes), 8000)
    where = rng.uniform(-360.0, 720.0, 8000)
    expected_open = assert_numpys_closeness(at, stacker, structure, k, who, where)
    # (measured: 1024 and 826 of 8000 rows cannot close, none is NaN)
    assert 0 < expected_open.sum() < who.size
    # where every row closes, no gap is measured: none open either way
    closes = ~expected_open[:50]
    (got,), got_open = at(where[:50][closes], who[:50][closes])
    assert not got_open.any()


def test_compiled_probe_only_for_a_crank_and_one_rrr_dyad(fast) -> None:
    # (the variants made on the numpy path: each is checked by a solve, which on the
    # compiled path compiled the slider-crank's six kernels for nothing here, 11-15 s of
    # processor time on an empty cache, measured 2026-11-30)
    use("numpy")
    sliders = [load_scene(d) for d in example_variants("slider_crank", 3)]
    use("fast")
    assert crank_rrr_probe(*stack(sliders)) is None
    # (the stack's probe of any other structure: test_screen_chain)
    assert stack_probe(*stack(sliders)) is not None
    fours = [load_scene(d) for d in four_bar_variants(3)]
    at = stack_probe(*stack(fours))
    assert crank_rrr_probe(*stack(fours)) is not None and at is not None
    assert at.rounds.keywords["kernel"].__name__ == "probe_rounds"
    use("numpy")
    assert crank_rrr_probe(*stack(fours)) is None and stack_probe(*stack(sliders)) is None


def test_solve_many_screens_as_solve_with_the_compiled_probe(fast) -> None:
    """Four-bars near their change point (a dead point between rows, found by the probes)
    of several sizes and sweeps: solve_many's dead points are each scene's solve's."""
    from .test_deadpoints import change_point_four_bar

    scenes = [load_scene(change_point_four_bar(a, 0.3, 0.2, start, 91))
              for a in (0.1, 0.11, 0.12) for start in (0.5, 1.7, 3.1)]
    found = 0
    for sol, sc in zip(ks.solve_many(scenes), scenes, strict=True):
        one = ks.solve(sc)
        assert sol.path == one.path == "fast"
        for name in ("between", "ends", "unassembled"):
            np.testing.assert_array_equal(getattr(sol.kin, name), getattr(one.kin, name))
        found += len(one.kin.between)
    assert found >= len(scenes)
