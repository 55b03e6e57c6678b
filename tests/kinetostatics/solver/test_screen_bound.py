"""The dead-point screen's proven bound (``solver/fast/screen_bound.py``): no slope of a
six-bar's or a four-bar's closeness to a dead centre above it, a dead point between rows
of a stack or of one sweep (the numpy path's screen too) still probed and found, and the
same verdicts with the bound as without it."""

from __future__ import annotations

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver import deadpoints
from kinetostatics.solver.fast import screen
from kinetostatics.solver.fast.geometry import driver_geometry, dyad_geometry
from kinetostatics.solver.fast.layout import D_LX, D_PX
from kinetostatics.solver.fast.screen import stack_probe
from kinetostatics.solver.fast.screen_bound import (
    cleared,
    known_bodies,
    lipschitz,
    sweep_clear,
)
from kinetostatics.solver.kinematics import choose_assembly
from kinetostatics.solver.pipeline import structure_of
from kinetostatics.solver.probes import probe_closeness
from tests.helpers import case_sources
from tests.kinetostatics import scenes

from .test_deadpoints import change_point_four_bar, slotted_lever
from .test_screen_chain import CASES, variants
from .test_screen_probe import stack

SIX_BARS = [c for c in CASES if c[0] in ("shaper", "slotted_lever")]


@pytest.mark.parametrize(("name", "kw"), SIX_BARS)
def test_no_slope_of_m2_exceeds_the_bound(fast, name, kw) -> None:
    """|m^2(x1) - m^2(x0)| / (x1 - x0) over dense probes (every 0.02 deg, both closing) is
    at most each scene's L (the mean value theorem: a slope above it breaks the proof).
    Measured 2026-11-30: at most 0.80 L (these cases, seeds 0-2 and 5)."""
    stacker, structure, k = stack(variants(name, 12, 5, **kw))
    at = stack_probe(stacker, structure, k)
    bound = at.clear.args[0]
    assert np.isfinite(bound).all()
    x = np.linspace(0.0, 360.0, 18001)
    worst = 0.0
    for e in range(len(stacker.scenes)):
        (m2,), gone = at(x, np.full(x.size, e, dtype=np.int64))
        ok = ~gone[1:] & ~gone[:-1] & ~np.isnan(m2[1:]) & ~np.isnan(m2[:-1])
        slope = np.abs(np.diff(m2))[ok] / np.radians(np.diff(x)[ok])
        if slope.size:
            worst = max(worst, slope.max() / bound[e * int(bound.size > 1)])
    assert 0.0 < worst <= 1.0


def test_a_dead_point_between_a_stacks_rows_is_probed_and_found(fast, monkeypatch) -> None:
    """Slotted levers in one stack, the last one's block through the lever's pivot at
    270 deg, between its rows 269.5 and 270.5 (m^2 there 1.4e-5, above the dead point's
    1e-6: the rows alone do not show it): that interval is probed, the others' cleared
    (no other scene's probed), and its dead point found as its own solve finds it."""
    scenes = [load_scene(slotted_lever(c, start=0.5)) for c in (0.10, 0.20, 0.30)]
    probed = []
    probe = deadpoints._probe

    def spy(at, lo, hi, owner):
        probed.extend(zip(owner.tolist(), lo.tolist(), hi.tolist(), strict=True))
        return probe(at, lo, hi, owner)
    monkeypatch.setattr(deadpoints, "_probe", spy)
    sols = ks.solve_many(scenes)
    # (measured: its intervals 268.5-269.5 and 269.5-270.5, both next to the dip)
    assert (2, 269.5, 270.5) in probed
    assert all(e == 2 and 268.0 <= lo < hi <= 272.0 for e, lo, hi in probed)
    assert sols[2].summary()["dead_points_between_rows"] == [[269.5, 270.5]]
    monkeypatch.setattr(deadpoints, "_probe", probe)
    for scene, sol in zip(scenes, sols, strict=True):
        assert sol.summary() == ks.solve(scene).summary()


def near_dead_centres(name: str) -> list:
    """Six-bars near their dead centres, each a new Scene: the shaper's variants, long
    cranks among them (those that close over the whole turn); the slotted lever's, and
    its block passing at or near the lever's pivot (cranks 0.28-0.32 m, O2 O4 0.30 m)."""
    out = []
    for kw in ({}, {"crank": (0.25, 0.45)} if name == "shaper"
               else {"crank": (0.25, 0.35), "shift": 0.01}):
        for scene in variants(name, 30, 7, **kw):
            try:
                ks.solve(scene)
            except ks.WorkbenchError:       # (one that cannot close over the turn)
                continue
            out.append(load_scene(scene.raw))
    if name == "slotted_lever":
        out += [load_scene(slotted_lever(c, start=0.5))
                for c in (0.28, 0.29, 0.295, 0.299, 0.2999, 0.30, 0.3001, 0.301, 0.31, 0.32)]
    return out


@pytest.mark.filterwarnings("ignore::UserWarning")
@pytest.mark.parametrize("name", ["shaper", "slotted_lever"])
def test_the_screen_gives_the_same_verdicts_without_the_bound(fast, name, monkeypatch
                                                              ) -> None:
    """solve_many of six-bars near their dead centres with the bound and without it
    (every interval probed): the same dead points, flags and intervals that cannot be
    crossed; some intervals cleared, some probed. (Measured 2026-11-30: the slotted
    levers' stacks find 3 dead points between rows.)"""
    made = []
    real = cleared

    def spy(*args):
        made.append(real(*args))
        return made[-1]
    monkeypatch.setattr(screen, "cleared", spy)
    got = [s.summary() for s in ks.solve_many(near_dead_centres(name))]
    clear = np.concatenate(made)
    monkeypatch.setattr(screen, "lipschitz", lambda *args: None)
    made.clear()
    assert [s.summary() for s in ks.solve_many(near_dead_centres(name))] == got
    assert made == []
    # (measured: the shaper's 152 of 156 intervals cleared, the slotted lever's 164 of 292)
    assert clear.any() and not clear.all()
    if name == "slotted_lever":
        assert sum(len(s["dead_points_between_rows"]) for s in got) >= 1


def test_the_compiled_clear_is_numpys(fast) -> None:
    """``screen.cleared`` (the compiled pass ``probe_kernels.clear_rows``) gives
    ``screen_bound.cleared``'s verdicts: rows on both sides or one (-inf), NaN and +inf
    rows, bounds of 0, +inf and NaN, values about the threshold."""
    rng = np.random.default_rng(11)
    n = 4000
    bound = rng.choice([0.0, 0.5, 2.0, np.inf, np.nan], 50)
    lo = rng.uniform(-10.0, 370.0, n)
    hi = lo + rng.choice([0.0, 0.01, 1.0, 5.0], n)
    owner = rng.integers(0, 50, n)
    picks = [-np.inf, np.nan, np.inf, 0.0, 2e-6, 4e-6, 8e-6, 1e-3, 0.1]
    m_lo, m_hi = rng.choice(picks, n), rng.choice(picks, n)
    m_lo[::3] = rng.uniform(0.0, 0.05, m_lo[::3].size)
    m_hi[1::3] = rng.uniform(0.0, 0.05, m_hi[1::3].size)
    for stride in (1, 0):
        expected = cleared(bound, stride, lo, hi, owner, m_lo, m_hi)
        got = screen.cleared(bound, stride, lo, hi, owner, m_lo, m_hi)
        np.testing.assert_array_equal(got, expected)
        assert 0 < expected.sum() < n


# -- the numpy path's screen (deadpoints.SWEEP_BOUNDS: screen_bound.sweep_clear) and the
# RRR dyad's bound (the four-bar)

def four_bars(count: int, seed: int) -> list:
    """Four-bars of random links (crank 0.05-0.3 m, the others 0.1-0.5 m), Grashof or
    not (some close over part of the turn alone), each one that assembles at its first
    row; and the change-point four-bar (a + b = c + d: a dead point at 0 deg)."""
    rng = np.random.default_rng(seed)
    out = [load_scene(change_point_four_bar(0.1, 0.3, 0.2, 0.0, 361))]
    while len(out) < count:
        a, (b, c, d) = rng.uniform(0.05, 0.3), rng.uniform(0.1, 0.5, 3)
        scene = load_scene(scenes.four_bar(a, b, c, d, start=float(rng.uniform(0, 360))))
        try:
            choose_assembly(scene, structure_of(scene))
        except ks.WorkbenchError:
            continue
        out.append(scene)
    return out


def slope_over_bound(scene) -> float:
    """The steepest |m^2(x1) - m^2(x0)| / (x1 - x0) over numpy's probes every 0.02 deg
    of the turn (both closing), over the scene's L (:func:`sweep_clear`)."""
    structure = structure_of(scene)
    bound = float(sweep_clear(scene, structure).args[0][0])
    x = np.linspace(0.0, 360.0, 18001)
    closeness2, gone = probe_closeness(scene, structure, x)
    m2 = deadpoints.measure2(closeness2, x.size)
    ok = ~gone[1:] & ~gone[:-1] & ~np.isnan(m2[1:]) & ~np.isnan(m2[:-1])
    slope = np.abs(np.diff(m2))[ok] / np.radians(np.diff(x)[ok])
    return float(slope.max() / bound) if slope.size else 0.0


def test_no_slope_of_a_four_bars_m2_exceeds_its_bound() -> None:
    """The RRR dyad's L (2 |G| |q| / (a b), 2 |G| |q| / size^2: screen_bound's notes)
    over dense numpy probes: no slope above it (the mean value theorem). Measured
    2026-11-30: at most 0.99979 L over these 40 (the pivots' distance term reaches its
    bound where R q is across G; the chord's slope falls short of it by some 2e-4),
    their median 0.69 L."""
    ratios = [slope_over_bound(s) for s in four_bars(40, 3)]
    assert 0.3 < max(ratios) <= 1.0


@pytest.mark.filterwarnings("ignore::UserWarning")
@pytest.mark.parametrize("name", ["shaper", "slotted_lever"])
def test_no_slope_of_a_six_bars_m2_exceeds_the_numpy_paths_bound(name) -> None:
    """The numpy path's L of one sweep (sweep_clear: the scene's own geometry tables)
    over numpy's dense probes, six-bars near their dead centres (every sixth). Measured
    2026-11-30: at most 0.099 L (the shapers), 0.72 L (the slotted levers)."""
    assert 0.05 < max(slope_over_bound(s) for s in near_dead_centres(name)[::6]) <= 1.0


def probed_intervals(monkeypatch) -> list:
    """The intervals probed from now on (lo, hi), spied on deadpoints._probe."""
    probed: list = []
    probe = deadpoints._probe

    def spy(at, lo, hi, owner):
        probed.extend(zip(lo.tolist(), hi.tolist(), strict=True))
        return probe(at, lo, hi, owner)
    monkeypatch.setattr(deadpoints, "_probe", spy)
    return probed


@pytest.mark.filterwarnings("ignore::UserWarning")
@pytest.mark.parametrize(("scene", "found"), [
    (change_point_four_bar(0.1, 0.3, 0.2, 100.3, 361), [[359.3, 360.3]]),
    (change_point_four_bar(0.1, 0.3, 0.2, 0.5, 2001), [[359.96, 360.14]]),
    (slotted_lever(0.30, start=0.5), [[269.5, 270.5]])])
def test_a_dead_point_between_a_sweeps_rows_is_probed_and_found_on_numpy(
        numpy_path, monkeypatch, scene, found) -> None:
    """A four-bar's change point and a slotted lever's block through the lever's pivot
    between two rows (both rows' m^2 above the dead point's 1e-6): the numpy path's
    bound leaves that interval probed, and its dead point is found."""
    probed = probed_intervals(monkeypatch)
    scene = load_scene(scene)
    s = ks.solve(scene).summary()
    assert s["dead_points_between_rows"] == found
    assert tuple(found[0]) in [(round(lo, 6), round(hi, 6)) for lo, hi in probed]
    assert deadpoints.sweep_bound(scene, structure_of(scene)) is not None


def verdict_scenes() -> list:
    """The numpy path's hard cases: six-bars near their dead centres, four-bars near
    their change point (rows on it, about it, a spacing off) and of random links, the
    course's cases (tests/data/cases, ../shared/cases)."""
    out = near_dead_centres("shaper") + near_dead_centres("slotted_lever")
    out += [load_scene(change_point_four_bar(0.1, 0.3, 0.2, start, count))
            for start, count in ((0.0, 361), (0.5, 361), (100.3, 361), (0.5, 2001),
                                 (-0.03, 7), (180.0, 3601))]
    out += four_bars(20, 5)
    out += [load_scene(scene) for _, scene, _ in case_sources()]
    return out


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_the_numpy_screen_gives_the_same_verdicts_without_the_bound(numpy_path,
                                                                    monkeypatch) -> None:
    """Single solves on the numpy path with the bound and without it (every interval
    probed): the same summaries (dead points between rows, flagged rows, intervals that
    cannot be crossed); some intervals cleared, some probed. (Measured 2026-11-30:
    486 intervals probed without the bound, 160 with it; 7 dead points between rows.)"""
    def verdicts() -> list:
        out = []
        for scene in verdict_scenes():
            try:
                out.append(ks.solve(scene).summary())
            except ks.WorkbenchError as e:
                out.append(type(e).__name__)
        return out
    probed = probed_intervals(monkeypatch)
    got = verdicts()
    with_bound = len(probed)
    monkeypatch.setattr(deadpoints, "SWEEP_BOUNDS", [])
    probed.clear()
    assert verdicts() == got
    assert 0 < with_bound < len(probed)
    assert sum(len(s["dead_points_between_rows"]) for s in got if isinstance(s, dict)) >= 3


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_a_stacks_bound_is_each_scenes_own(fast) -> None:
    """The compiled stack's L of each scene (chain_probe's, a column per scene) is the
    numpy path's of that scene alone (sweep_clear)."""
    stacker, structure, k = stack(near_dead_centres("shaper")[:6])
    bound = stack_probe(stacker, structure, k).clear.args[0]
    assert bound.size == len(stacker.scenes) > 1
    own = [float(sweep_clear(s, structure_of(s)).args[0][0]) for s in stacker.scenes]
    np.testing.assert_array_equal(bound, own)
    assert len(set(own)) == len(own)


@pytest.mark.parametrize("name", ["shaper", "slotted_lever", "four_bar"])
def test_a_driver_table_of_many_columns_beside_dyads_of_one(name) -> None:
    """lipschitz with the driver's table a column per scene and the dyads' of one
    column (a stack whose driver's numbers alone differ): each column's L is the one of
    that column alone (one column of both: numpy's scalars)."""
    scene = load_scene(ks.example(name))
    structure = structure_of(scene)
    gd = driver_geometry(scene)[0]
    gy = np.stack([dyad_geometry(scene, d, 1.0)[0] for d in structure.dyads])
    known = np.array(known_bodies(scene.driver, structure.dyads))
    kinds = tuple(d.kind for d in structure.dyads)
    many = np.repeat(gd, 3, axis=1)
    many[D_PX] += [0.0, 0.05, -0.1]
    many[D_LX] *= [1.0, 1.2, 0.9]
    got = lipschitz(True, many, known, gy, kinds)
    alone = [lipschitz(True, many[:, [j]].copy(), known, gy, kinds)[0] for j in range(3)]
    np.testing.assert_array_equal(got, alone)
    assert len(set(alone)) == 3



def whole_turn(scene) -> bool:
    """Whether ``scene`` solves over its sweep (solve_many raises for one that does not)."""
    try:
        ks.solve(scene)
    except ks.WorkbenchError:
        return False
    return True


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_a_stack_of_four_bars_gives_the_same_verdicts_without_the_bound(fast,
                                                                        monkeypatch) -> None:
    """solve_many of four-bars (crank_rrr_probe's ``clear``: the RRR dyad's L, each
    scene's own) with the bound and without it: the same summaries, the change points
    between rows found; some intervals cleared, some probed."""
    near = [change_point_four_bar(0.1, 0.3, 0.2, start, 361)
            for start in (0.5, 100.3, 0.0, 180.25)]
    others = [s.raw for s in four_bars(40, 8)[1:] if whole_turn(s)]
    stacker, structure, k = stack([load_scene(d) for d in others])
    own = [float(sweep_clear(s, structure_of(s)).args[0][0]) for s in stacker.scenes]
    np.testing.assert_array_equal(stack_probe(stacker, structure, k).clear.args[0], own)

    def solved() -> list:
        return [s.summary() for s in ks.solve_many([load_scene(d) for d in near + others])]
    probed = probed_intervals(monkeypatch)
    got = solved()
    with_bound = len(probed)
    monkeypatch.setattr(screen, "lipschitz", lambda *args: np.full(1, np.inf))
    probed.clear()
    assert solved() == got
    # (measured 2026-11-30: 38 intervals probed without the bound, 12 with it; 18 of
    # the 39 random four-bars close over the whole turn)
    assert 0 < with_bound < len(probed), (with_bound, len(probed))
    assert [s["dead_points_between_rows"] for s in got[:2]] == [[[359.5, 360.5]],
                                                                 [[359.3, 360.3]]]


@pytest.mark.filterwarnings("ignore::UserWarning")
@pytest.mark.parametrize("name", ["shaper", "slotted_lever", "four_bar"])
def test_a_numpy_stack_gives_the_same_verdicts_without_the_bound(numpy_path, name,
                                                                 monkeypatch) -> None:
    """solve_many on the numpy path (its probe's ``clear``: screen.stack_clear, each
    scene's L from the stack's tables) with the bound and without it: the same
    summaries, dead points between rows found; fewer intervals probed with it."""
    from kinetostatics.bench.speed import example_variants
    from kinetostatics.solver import many
    if name == "four_bar":
        items = [load_scene(change_point_four_bar(0.1, 0.3, 0.2, start, 361))
                 for start in (0.5, 100.3, 0.0, 180.25)]
        items += [load_scene(s.raw) for s in four_bars(40, 8)[1:] if whole_turn(s)]
    elif name == "slotted_lever":   # (one stack: the last one's block through the pivot)
        items = [load_scene(slotted_lever(c, start=0.5)) for c in (0.10, 0.20, 0.30)]
    else:
        items = [load_scene(d) for d in example_variants(name, 40)]
    probed = probed_intervals(monkeypatch)
    got = [s.summary() for s in ks.solve_many(items)]
    with_bound = len(probed)
    monkeypatch.setattr(many, "stack_clear", lambda *args: None)
    probed.clear()
    assert [s.summary() for s in ks.solve_many(items)] == got
    # (measured 2026-12-01: probed with / without the bound, 40 shapers' 0 / 110, the
    # three slotted levers' 2 / 8, the four-bars' 12 / 38; with L = 0 the slotted
    # levers' and the four-bars' dead points are missed: checked)
    assert with_bound < len(probed), (with_bound, len(probed))
    if name != "shaper":
        assert sum(len(s["dead_points_between_rows"]) for s in got) >= 1
