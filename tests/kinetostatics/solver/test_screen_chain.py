"""The compiled probe of the dead-point screen for any driver and chain of dyads
(``solver/fast/screen.py``'s ``chain_probe``: a stack's ``stack_probe``, a sweep's
``sweep_probe``; ``fast/probe_kernels.py``) against numpy's ``probe_closeness``: the same
probes that cannot close, the same closeness to a dead centre bit for bit but where an RTR
dyad's guide angle is the compiled path's (the shaper, the slotted lever: a few ulps
apart, measured), every round in one call the rounds one by one, and the same dead points
and flags on both paths near the six-bars' dead points."""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.model.examples import example
from kinetostatics.model.scene import load_scene
from kinetostatics.solver import deadpoints
from kinetostatics.solver.deadpoints import _end_probes, measure2
from kinetostatics.solver.fast import loader, use
from kinetostatics.solver.fast.geometry import driver_geometry, dyad_geometry
from kinetostatics.solver.fast.screen import chain_probe, stack_probe, sweep_probe
from kinetostatics.solver.fast.solve import kernel_trig
from kinetostatics.solver.memo import record_of
from kinetostatics.solver.probes import probe_closeness

from .test_many_rounds import assert_rounds_as_one_by_one
from .test_screen_probe import assert_numpys_closeness, long_cranks, stack

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")

# the largest relative difference of m^2 from numpy's measured where both close (60
# variants x 20 000 probes, seeds 1-6, 2026-11-30): the shaper 2.2e-12 with cranks of
# 0.25-0.45 m (the ram's RRT dyad near its dead centres, its lever's angle a few ulps
# from numpy's), 3.8e-14 as bundled; the slotted lever 1.3e-15 (at m^2 = 1); every
# other structure bit for bit
RTOL = {"shaper": 1e-11, "slotted_lever": 1e-14}


def variants(name: str, count: int, seed: int, shift: float = 0.03,
             crank: tuple | None = None) -> list:
    """``count`` variants of the bundled ``name``: every point moved by up to ``shift``
    (m) each way, every prismatic joint's line turned by up to 20 deg, the crank's far
    point ``crank`` (m) from its pivot when given (long cranks: the six-bars' dyads near
    their dead centres, or unable to close over part of the turn)."""
    rng = np.random.default_rng(seed)
    base = load_scene(example(name)).raw
    out: list = []
    while len(out) < count:
        d = copy.deepcopy(base)
        d["checks"] = {"quiet": ["angles"]}
        for b in d["bodies"]:
            b["points"] = {p: [x + rng.uniform(-shift, shift) for x in v]
                           for p, v in b["points"].items()}
        d["ground"] = {p: [x + rng.uniform(-shift, shift) for x in v]
                       for p, v in d["ground"].items()}
        for j in d["joints"]:
            if j["kind"] == "T":
                j["line_angle"] = j.get("line_angle", 0.0) + float(rng.uniform(-20.0, 20.0))
        if crank is not None:
            arm = next(b for b in d["bodies"] if b["name"] == d["driver"]["body"])
            for p in arm["points"]:
                if p != d["driver"]["joint"]:
                    arm["points"][p] = [float(rng.uniform(*crank)), 0.0]
        try:
            out.append(load_scene(d))
        except WorkbenchError:       # (one that cannot assemble: drawn again)
            continue
    return out


# (structure, its variants' keywords): the shaper's crank, RTR and RRT; the slotted
# lever's crank and RTR; the slider-crank's crank and RRT; the sliding driver and an RRR
# dyad; the Scotch yoke's crank and TTR
CASES = [("shaper", {}), ("shaper", {"crank": (0.25, 0.45)}), ("slotted_lever", {}),
         ("slotted_lever", {"crank": (0.25, 0.35), "shift": 0.01}), ("slider_crank", {}),
         ("slider_crank", {"crank": (0.05, 0.4), "shift": 0.05}), ("sliding_driver", {}),
         ("scotch_yoke", {})]


def probes_of(stacker, seed: int, count: int) -> tuple[np.ndarray, np.ndarray]:
    """``count`` random probes (scene, driver position) of the stack: a crank's angles over
    three turns, a slider's positions about its sweep."""
    rng = np.random.default_rng(seed)
    drv = stacker.base.driver
    who = rng.integers(0, len(stacker.scenes), count)
    if drv.kind == "R":
        return who, rng.uniform(-360.0, 720.0, count)
    lo, hi = float(drv.positions.min()), float(drv.positions.max())
    return who, rng.uniform(lo - 0.1 * (hi - lo), hi + 0.1 * (hi - lo), count)


@pytest.mark.parametrize(("name", "kw"), CASES)
@pytest.mark.parametrize("seed", [1, 2])
def test_chain_probe_is_numpys(fast, name, kw, seed) -> None:
    stacker, structure, k = stack(variants(name, 40, seed, **kw))
    at = stack_probe(stacker, structure, k)
    assert at is not None
    who, where = probes_of(stacker, seed, 6000)
    probe = replace(structure, assembly=tuple(x[who] for x in k))
    closeness, expected_open = probe_closeness(stacker.scene(who, where), probe, measured=True)
    expected = measure2(closeness, who.size)
    (got,), got_open = at(where, who)
    np.testing.assert_array_equal(got_open, expected_open)
    np.testing.assert_array_equal(np.isnan(got), np.isnan(expected))
    closed = ~expected_open & ~np.isnan(expected)
    rtol = RTOL.get(name)
    if rtol is None:
        np.testing.assert_array_equal(got[closed].view(np.int64),
                                      expected[closed].view(np.int64))
    else:
        np.testing.assert_allclose(got[closed], expected[closed], rtol=rtol, atol=0.0)
    # (measured: the long cranks' probes near dead centres, m^2 down to 1.6e-4-5.6e-4
    # (shaper), 3e-6-1.3e-5 (slotted lever), 2e-5-1.3e-3 (slider-crank), and probes that
    # cannot close, 956-1664 (shaper) and 172-332 (slider-crank) of 6000)
    if "crank" in kw:
        assert expected[closed].min() < 1e-2
        assert name == "slotted_lever" or expected_open.any()


def test_a_crank_and_one_rrr_dyad_chained_is_numpys(fast) -> None:
    """The chain's probe of a four-bar (a sweep's: a stack's takes the RRR kernel,
    ``crank_rrr_probe``), numpy's bit for bit, long cranks that cannot close too."""
    stacker, structure, k = stack(long_cranks(60, 4))
    m = len(stacker.scenes)
    table = stacker.table(0, m, np.ones(m, dtype=np.int64), stacker.base.driver.positions,
                          trig=False)
    at = chain_probe(stacker.base.driver, driver_geometry(table),
                     [dyad_geometry(table, structure.dyads[0], k[0])], structure.dyads)
    who, where = probes_of(stacker, 4, 6000)
    expected_open = assert_numpys_closeness(at, stacker, structure, k, who, where)
    assert 0 < expected_open.sum() < who.size


@pytest.mark.parametrize(("name", "kw"), [CASES[i] for i in (1, 3, 5, 6)])
def test_chain_rounds_in_one_call_are_the_rounds_one_by_one(fast, name, kw) -> None:
    stacker, structure, k = stack(variants(name, 40, 3, **kw))
    at = stack_probe(stacker, structure, k)
    if stacker.base.driver.kind == "R" and not kernel_trig():
        assert not hasattr(at, "rounds")
        pytest.skip("the C library's cos and sin are not numpy's here")
    owner, lo = probes_of(stacker, 3, 600)
    hi = lo + np.random.default_rng(3).uniform(0.0, 0.05, lo.size) * np.ptp(lo)
    expected = assert_rounds_as_one_by_one(at, lo, hi, owner)
    assert np.isfinite(expected[0]).any()


def test_a_sweep_solved_compiled_is_probed_compiled(fast, monkeypatch) -> None:
    """The compiled path's sweep is probed by its compiled probe (numpy's never called),
    with its kernels' geometry; a scene at positions given apart, or solved on the numpy
    path, by numpy's."""
    calls = []
    numpy_probe = deadpoints.probe_closeness

    def spy(*args, **kwargs):
        calls.append(1)
        return numpy_probe(*args, **kwargs)
    monkeypatch.setattr(deadpoints, "probe_closeness", spy)
    # (a slotted lever whose block passes through the lever's pivot between rows: an
    # interval the numpy path's bound leaves probed, as the bundled six-bars' are not)
    scene = load_scene(slotted(0.30, 0.5, 361))
    sol = ks.solve(scene)
    assert sol.path == "fast" and calls == []
    kept = record_of(scene)["fast"]
    assert sweep_probe(scene, kept[1]) is not None
    assert sweep_probe(scene, replace(kept[1])) is None         # (another structure)
    ks.solve(scene, positions=np.linspace(0.5, 360.5, 361))
    assert calls                                                # (given positions)
    use("numpy")
    calls.clear()
    ks.solve(load_scene(slotted(0.30, 0.5, 361)))
    assert calls


def test_a_sweeps_probe_is_made_once_per_kept_geometry(fast) -> None:
    """A scene solved again is probed by the probe made at its first solve (kept in its
    record beside the kernels' geometry), with the same numbers; a new kept geometry
    (the record's compiled entry made anew) gets a new probe."""
    scene = load_scene(example("shaper"))
    first = ks.solve(scene).driver
    kept = record_of(scene)["fast"]
    at = sweep_probe(scene, kept[1])
    assert at is not None and sweep_probe(scene, kept[1]) is at
    again = ks.solve(scene).driver
    assert sweep_probe(scene, kept[1]) is at
    for name in first.columns:
        np.testing.assert_array_equal(np.asarray(again[name]), np.asarray(first[name]))
    record_of(scene)["fast"] = (*kept[:2], copy.copy(kept[2]), *kept[3:])
    assert sweep_probe(scene, kept[1]) is not at


def test_a_chain_on_bodies_not_yet_solved_has_no_probe(fast) -> None:
    scene = load_scene(example("shaper"))
    ks.solve(scene)
    structure, geometry = record_of(scene)["fast"][1:]
    dyads = [g[:2] for g in geometry.dyads]
    # the ram's dyad first: its outer joint on the lever, not solved before it
    assert chain_probe(scene.driver, geometry.driver, dyads[::-1],
                       structure.dyads[::-1]) is None


def slotted(crank: float, start: float, count: int, name: str = "slotted_lever",
            turn: float = 360.0) -> dict:
    """The bundled six-bar ``name`` with a crank of ``crank`` m (0.30: the block passes
    through the lever's pivot at 270 deg) over ``turn`` deg from ``start``; the shaper's
    lever 0.2 m to E and its link 0.8 m (its ram follows the lever's whole turns)."""
    d = copy.deepcopy(load_scene(example(name)).raw)
    points = {b["name"]: b["points"] for b in d["bodies"]}
    points["crank"]["A"] = [crank, 0.0]
    if name == "shaper":
        points["lever"]["E"], points["link"]["F"] = [0.2, 0.0], [0.8, 0.0]
    d["driver"].update(start=start, stop=start + turn, count=count)
    return d


@pytest.mark.parametrize("name", ["slotted_lever", "shaper"])
def test_six_bars_near_their_dead_points_alike_on_both_paths(fast, name) -> None:
    """The six-bars' cranks about the pivots' distance (their blocks pass through or near
    the lever's pivot, between rows or just before the sweep's first row): the compiled
    probe's dead points, end rows, intervals that cannot be crossed and singular flags
    are the numpy path's (the probes' m^2 a few ulps apart at most)."""
    rng = np.random.default_rng(5)
    found = {"between": 0, "ends": 0, "unassembled": 0}
    for crank in (0.2999, 0.2999999, 0.30000001, 0.3001):
        for count, turn in ((91, 360.0), (361, 360.0), (2001, 360.0), (181, 180.0)):
            spacing = turn / (count - 1)
            # (a whole turn from anywhere; half a turn from just after the dead point)
            start = float(rng.uniform(0.0, spacing)) + (270.0 if turn < 360.0 else 0.0)
            d = slotted(crank, start, count, name, turn)
            use("fast")
            fast_sol = ks.solve(d)
            use("numpy")
            numpy_sol = ks.solve(d)
            assert fast_sol.path == "fast" and numpy_sol.path == "numpy"
            for what in found:
                a, b = getattr(fast_sol.kin, what), getattr(numpy_sol.kin, what)
                np.testing.assert_array_equal(a, b)
                found[what] += len(a)
            np.testing.assert_array_equal(fast_sol.driver.singular, numpy_sol.driver.singular)
    # (measured: a dead point between rows in each whole turn, 12, and an end row just
    # after it in each half turn, 4)
    assert found == {"between": 12, "ends": 4, "unassembled": 0}


def test_one_sweeps_end_probes_are_the_stacks() -> None:
    """A sweep's two end probes told in numbers (``_end_probes``, one segment) are those
    of the same rows as a segment of a stack (the arrays' way)."""
    rng = np.random.default_rng(7)
    for n in (1, 2, 3, 5, 40):
        for _ in range(50):
            m2 = rng.choice([0.0, 0.1, 0.2, 0.25, 0.3, np.nan, np.inf], n)
            pos = np.cumsum(rng.uniform(0.5, 2.0, n))
            one = _end_probes(m2, pos, np.array([0]), np.array([n]))
            # (the same rows as the first of two segments, the second empty)
            two = _end_probes(m2, pos, np.array([0, n]), np.array([n, 0]))
            for a, b in zip(one, two, strict=True):
                assert a.dtype == b.dtype
                np.testing.assert_array_equal(a, b)
