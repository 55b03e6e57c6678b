"""kinetostatics.solve_many: each scene's Solution, in order, with exactly the numbers
solve gives it alone; scenes of one structure solved stacked."""

from __future__ import annotations

import copy
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import numpy as np
import pandas as pd
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import AssemblyError
from kinetostatics.model.scene import load_scene
from kinetostatics.results import solve_outcomes
from kinetostatics.solver import many

from .test_deadpoints import change_point_four_bar, slotted_lever

TABLES = ("driver", "reactions", "kinematics", "bodies", "dyads", "sliders", "frame")


def assert_same(got: ks.Solution, want: ks.Solution) -> None:
    """Every table bit for bit (check_exact, and the sign of each zero: a -0.0 is
    written "-0" in a CSV), the summary, the assemblies and the flags."""
    for t in TABLES:
        a, b = getattr(got, t), getattr(want, t)
        pd.testing.assert_frame_equal(a, b, check_exact=True)
        for c in a.columns:
            if a[c].dtype == np.float64:
                np.testing.assert_array_equal(np.signbit(a[c].to_numpy()),
                                              np.signbit(b[c].to_numpy()), err_msg=f"{t}.{c}")
    assert got.summary() == want.summary()
    assert got.structure.assembly == want.structure.assembly
    assert got.scene is not None and got.scene.title == want.scene.title
    np.testing.assert_array_equal(got.singular, want.singular)


def variants(name: str, count: int, spread: float, seed: int = 0) -> list[dict]:
    """``count`` scenes of a bundled example with every local point, ground point and mass
    scaled by a factor in 1 +- spread (those that assemble)."""
    base = load_scene(ks.example(name)).raw
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        d = copy.deepcopy(base)
        for b in d["bodies"]:
            b["points"] = {p: [x * rng.uniform(1 - spread, 1 + spread) for x in v]
                           for p, v in b["points"].items()}
            if "mass" in b:
                b["mass"] *= rng.uniform(1 - spread, 1 + spread)
        d["ground"] = {p: [x * rng.uniform(1 - spread, 1 + spread) for x in v]
                       for p, v in d["ground"].items()}
        try:
            ks.solve(d)
        except ks.WorkbenchError:
            continue
        out.append(d)
    return out


@pytest.mark.parametrize("name", ["four_bar", "scotch_yoke", "sliding_driver",
                                  "slotted_lever"])
def test_variants_stacked_equal_solve_alone(name, alone_calls) -> None:
    scenes = variants(name, 12, 0.05)
    sols = ks.solve_many(scenes)
    assert alone_calls == []            # all twelve in one stacked pass
    for s, d in zip(sols, scenes, strict=True):
        assert_same(s, ks.solve(d))


@pytest.mark.parametrize("name", ["slider_crank", "shaper"])
def test_resist_and_resisting_loads_stack(name, alone_calls, numpy_path) -> None:
    """A ``resist`` load (the slider-crank's piston) and a force ``when = "resisting"``
    (the shaper's cut) take their thresholds from each scene's own sweep: stacked, with
    every table, flag and summary of each scene's own solve. (The numpy path: the
    compiled one's, test_many_fast.py.)"""
    scenes = variants(name, 8, 0.05, seed=4)
    sols = ks.solve_many(scenes)
    assert alone_calls == []
    for s, d in zip(sols, scenes, strict=True):
        alone = ks.solve(d)
        assert_same(s, alone)
        np.testing.assert_array_equal(s.undefined_load, alone.undefined_load)


def test_a_sweeps_maximum_is_each_scenes_own() -> None:
    """loads._top over a run of stacked scenes: each scene's largest value over its own
    rows (at least the floor, which may differ per row), repeated over its rows."""
    from types import SimpleNamespace

    from kinetostatics.solver import loads
    x = np.array([1.0, 5.0, 2.0, 0.5, 0.25, 9.0, 3.0, 1.0])
    counts = np.array([3, 2, 3])
    run = SimpleNamespace(segments=counts)
    floor = np.repeat([0.0, 1.0, 4.0], counts)
    np.testing.assert_array_equal(loads._top(x, run, floor),
                                  np.repeat([5.0, 1.0, 9.0], counts))
    assert loads._top(x, SimpleNamespace(), 2.0) == 9.0     # one scene: the sweep's


def test_both_assemblies_in_one_stack(alone_calls) -> None:
    """Open and crossed four-bars (the hint above or below) stacked together."""
    scenes = variants("four_bar", 6, 0.05, seed=1)
    for d in scenes[::2]:
        x, y = d["near"]["C"]
        d["near"]["C"] = [x, -y]
    sols = ks.solve_many(scenes)
    assert alone_calls == []
    assert {s.structure.assembly for s in sols} == {(1,), (-1,)}
    for s, d in zip(sols, scenes, strict=True):
        assert_same(s, ks.solve(d))


def test_dead_points_between_rows_per_scene(alone_calls) -> None:
    """Change points and a block through its pivot between rows, found per scene as
    solve finds them (the probes of all scenes in one solve); sweeps of other lengths."""
    scenes = [change_point_four_bar(0.1, 0.3, 0.2, 100.3, 361),
              change_point_four_bar(0.1, 0.3, 0.2, 100.0, 361),
              change_point_four_bar(0.11, 0.3, 0.2, 50.3, 181),
              change_point_four_bar(0.1, 0.31, 0.2, 0.3, 2)]
    sols = ks.solve_many(scenes)
    assert alone_calls == []
    assert sols[0].summary()["dead_points_between_rows"] == [[359.3, 360.3]]
    for s, d in zip(sols, scenes, strict=True):
        assert_same(s, ks.solve(d))
    levers = [slotted_lever(0.30, start=0.5), slotted_lever(0.25), slotted_lever(0.30, 0.5, 91)]
    for s, d in zip(ks.solve_many(levers), levers, strict=True):
        assert_same(s, ks.solve(d))
    assert alone_calls == []


def test_mixed_structures_in_order() -> None:
    names = ks.examples()
    order = names + names[::-1] + names
    sols = ks.solve_many([ks.example(n) for n in order])
    assert [s.scene.title for s in sols] == [load_scene(ks.example(n)).title for n in order]
    alone = {n: ks.solve(ks.example(n)) for n in names}
    for s, n in zip(sols, order, strict=True):
        assert_same(s, alone[n])


def test_with_an_executor() -> None:
    scenes = variants("four_bar", 9, 0.05, seed=2) + [ks.example("slider_crank")]
    scenes.insert(3, ks.example("shaper"))
    with ThreadPoolExecutor(2) as pool:
        sols = ks.solve_many(scenes, executor=pool, batch=3)
    for s, d in zip(sols, scenes, strict=True):
        assert_same(s, ks.solve(d))


def test_first_refused_scene_raises_as_solve_does() -> None:
    good = variants("four_bar", 3, 0.05, seed=3)
    bad = copy.deepcopy(good[0])
    bad["bodies"][2]["points"]["C"] = [0.01, 0.0]       # the rocker cannot reach
    with pytest.raises(AssemblyError) as alone:
        ks.solve(bad)
    with pytest.raises(AssemblyError) as together:
        ks.solve_many([good[0], bad, good[1], good[2]])
    assert str(together.value) == "scenes[1]: " + str(alone.value)
    assert ks.solve_many([]) == []


def test_a_link_without_length_in_a_stack_is_refused_as_solve_does() -> None:
    """A coupler whose joint points coincide is measured once per scene when the stack
    chooses its assemblies (not again row by row in the runs): refused as by solve."""
    good = variants("four_bar", 3, 0.05, seed=4)
    bad = copy.deepcopy(good[1])
    coupler = next(b for b in bad["bodies"] if b["name"] == "coupler")
    coupler["points"]["C"] = list(coupler["points"]["B"])
    with pytest.raises(AssemblyError) as alone:
        ks.solve(bad)
    assert "needs a length" in str(alone.value)
    with pytest.raises(AssemblyError) as together:
        ks.solve_many([good[0], bad, good[1], good[2]])
    assert str(together.value) == "scenes[1]: " + str(alone.value)


def test_positions_in_any_order_and_repeats_as_solve(alone_calls) -> None:
    """Stacked scenes whose positions come in any order give solve's rows, angles and
    summary (continuity and dead points along increasing position); a repeated position
    is refused as solve refuses it."""
    scenes = variants("four_bar", 3, 0.05, seed=3)
    rng = np.random.default_rng(7)
    for d in scenes:
        pos = np.linspace(0.0, 360.0, 13)[:-1]
        d["driver"] = {k: v for k, v in d["driver"].items()
                       if k not in ("start", "stop", "count")}
        d["driver"]["positions"] = [float(p) for p in rng.permutation(pos)]
    sols = ks.solve_many(scenes)
    assert alone_calls == []
    for got, d in zip(sols, scenes, strict=True):
        assert_same(got, ks.solve(d))
    bad = copy.deepcopy(scenes[0])
    bad["driver"]["positions"] = [0.0, 90.0, 0.0]
    with pytest.raises(ks.SceneError) as alone:
        ks.solve(bad)
    with pytest.raises(ks.SceneError) as batch:
        ks.solve_many([scenes[1], bad])
    assert str(batch.value) == "scenes[1]: " + str(alone.value)


def test_scene_objects_read_at_once_refuse_and_group_as_solve(alone_calls) -> None:
    """Scene objects of one structure are read at once (their records taken together,
    ``many._one_group``): one whose positions repeat is still refused as solve refuses
    it, led by its place; a scene of another structure among them, or one without
    positions, sends them all to be read one by one, each solved as solve solves it."""
    scenes = [load_scene(d) for d in variants("four_bar", 3, 0.05, seed=5)]
    drv = scenes[1].driver
    bad = replace(scenes[1], driver=replace(drv, positions=np.array([0.0, 90.0, 0.0])))
    with pytest.raises(ks.SceneError) as alone:
        ks.solve(bad)
    with pytest.raises(ks.SceneError) as batch:
        ks.solve_many([scenes[0], bad, scenes[2]])
    assert str(batch.value) == "scenes[1]: " + str(alone.value)
    other = load_scene(ks.example("slider_crank"))
    mixed = [scenes[0], other, scenes[1], scenes[2], other]
    for got, sc in zip(ks.solve_many(mixed), mixed, strict=True):
        assert_same(got, ks.solve(sc))
    assert alone_calls == []        # (each structure stacked: the four-bars, the two cranks)


def test_a_bad_value_names_its_scene_and_field() -> None:
    """A bad number in one dict of many: one line naming the scene's place and the field,
    of the class solve raises."""
    scenes = variants("four_bar", 3, 0.05, seed=4) * 4
    scenes = [copy.deepcopy(d) for d in scenes]
    scenes[7]["bodies"][1]["mass"] = -2.0
    scenes[9]["ground"]["D"] = [float("nan"), 0.0]
    with pytest.raises(ks.SceneError) as alone:
        ks.solve(scenes[7])
    with pytest.raises(ks.SceneError) as batch:
        ks.solve_many(scenes)
    msg = str(batch.value)
    assert msg == "scenes[7]: " + str(alone.value)
    assert "coupler" in msg and "mass" in msg and "\n" not in msg


def test_stacked_solutions_pickle_copy_and_replace(alone_calls) -> None:
    """A Solution cut lazily from a stack behaves as any Solution: pickled (a process
    executor), copied, replaced; its arrays are cut when first read."""
    import dataclasses
    import pickle

    scenes = variants("four_bar", 4, 0.05, seed=5)
    sols = ks.solve_many(scenes)
    assert alone_calls == [] and "kin" not in vars(sols[1])       # not cut yet
    back = pickle.loads(pickle.dumps(sols[1]))
    assert_same(back, ks.solve(scenes[1]))
    assert_same(copy.copy(sols[2]), ks.solve(scenes[2]))
    other = dataclasses.replace(sols[3], undefined_load=sols[3].undefined_load)
    assert_same(other, ks.solve(scenes[3]))
    assert isinstance(sols[0], ks.Solution) and not hasattr(sols[0], "no_such_name")


def test_a_length_whose_python_square_is_not_x_times_x(alone_calls) -> None:
    """0.250015019 ** 2 (a Python float: C pow) differs from 0.250015019 * 0.250015019 in
    the last bit, while a stack's arrays square: the closure squares by x * x, so the
    stacked coupler gives the numbers of its scene alone."""
    assert 0.250015019 ** 2 != 0.250015019 * 0.250015019
    base = load_scene(ks.example("four_bar")).raw
    odd = copy.deepcopy(base)
    odd["bodies"][1]["points"]["C"] = [0.250015019, 0.0]
    sols = ks.solve_many([base, odd])
    assert alone_calls == []
    assert_same(sols[1], ks.solve(odd))


def test_runs_of_whole_scenes_and_long_runs_in_blocks(alone_calls, monkeypatch) -> None:
    """The stack is solved in runs of whole scenes, each Solution cut from its run (runs
    of a few rows here, a run past two blocks solved in blocks and gathered); a run the
    solver refuses is solved scene by scene, the other runs stay stacked."""
    from kinetostatics.solver import blocks

    monkeypatch.setattr(many, "RUN_ROWS", 40)
    monkeypatch.setattr(many, "FAST_RUN_ROWS", 40)      # (the compiled path's runs)
    monkeypatch.setattr(blocks, "BLOCK_ROWS", 64)
    scenes = variants("four_bar", 9, 0.05, seed=6)
    for i, (d, count) in enumerate(zip(scenes, (30, 30, 200, 10, 361, 5, 13, 90, 2),
                                       strict=True)):
        d["title"] = f"v{i}"
        d["driver"].update(start=3.0 * i, stop=3.0 * i + 360.0, count=count)
    # first rows 0, 30, 60, 260, 270, 631, 636, 649, 739: runs of the rows 0-39, 40-79,
    # 240-279 (371 rows: in blocks), 600-639, 640-679 and 720-759
    assert many.run_bounds(*_rows(scenes), 40).tolist() == [0, 2, 3, 5, 7, 8, 9]
    sols = ks.solve_many(scenes)
    assert alone_calls == []
    for s, d in zip(sols, scenes, strict=True):
        assert_same(s, ks.solve(d))
    # scene 6: its first row closes, later rows do not (the rocker cannot reach)
    scenes[6]["bodies"][2]["points"]["C"] = [0.06, 0.0]
    with pytest.raises(AssemblyError) as alone:
        ks.solve(scenes[6])
    outcomes = solve_outcomes(scenes)
    assert alone_calls == ["v5", "v6"]        # its run only
    assert str(outcomes[6]) == str(alone.value)
    for i, (s, d) in enumerate(zip(outcomes, scenes, strict=True)):
        if i != 6:
            assert_same(s, ks.solve(d))


def test_runs_are_lean_and_solved_again_once_when_read(alone_calls, monkeypatch) -> None:
    """A run keeps only Me/Fe and the flags of its scenes: its kinematics and joint
    reactions are solved again (once for all its scenes) when one scene's are first
    read, with the same numbers; a run whose scenes' driver tables only are read is not
    solved again. (On the compiled path a crank and one dyad keep every run's arrays
    from one fused kernel call over the group: no run is solved until read.)"""
    monkeypatch.setattr(many, "RUN_ROWS", 543)
    monkeypatch.setattr(many, "FAST_RUN_ROWS", 543)
    solved = []
    run = many._solve_run
    wholes = []
    whole = many._whole_group

    def spy(stacker, structure, ks_, lo, hi, *rest):
        solved.append((lo, hi))
        return run(stacker, structure, ks_, lo, hi, *rest)

    def spy_whole(*args):
        out = whole(*args)
        wholes.append(out is not None)
        return out
    monkeypatch.setattr(many, "_solve_run", spy)
    monkeypatch.setattr(many, "_whole_group", spy_whole)
    scenes = variants("four_bar", 6, 0.05, seed=8)
    for d in scenes:
        d["driver"]["count"] = 181          # runs of scenes 0-2, 3-5
    sols = ks.solve_many(scenes)
    first = [] if wholes == [True] else [(0, 3), (3, 6)]
    assert solved == first and alone_calls == []
    assert all("kin" not in s.__dict__ for s in sols)
    alone = [ks.solve(d) for d in scenes]
    for i in (0, 1, 2):                       # the first run only, solved again once
        np.testing.assert_array_equal(sols[i].drive.value, alone[i].drive.value)
        assert_same(sols[i], alone[i])
    assert solved == [*first, (0, 3)]
    np.testing.assert_array_equal(sols[4].drive.value, alone[4].drive.value)
    pd.testing.assert_frame_equal(sols[4].driver, alone[4].driver, check_exact=True)
    assert "kin" not in sols[4].__dict__ and solved == [*first, (0, 3)]  # the driver: lean
    # kept whole (an answer key, an executor's task): each run solved once, every table
    # cut from it
    del solved[:]
    kept = solve_outcomes(scenes, lean=False)
    for s, a in zip(kept, alone, strict=True):
        assert_same(s, a)
    assert solved == [(0, 3), (3, 6)]


def _rows(scenes: list[dict]) -> tuple[np.ndarray, np.ndarray]:
    counts = np.array([d["driver"]["count"] for d in scenes])
    return np.cumsum(counts) - counts, counts


def test_dead_points_of_stacked_sweeps_in_any_order(alone_calls) -> None:
    """Dead points between rows and beyond the ends, per scene, where the stacked rows
    are not in increasing position (each scene's own order followed)."""
    rng = np.random.default_rng(11)
    scenes = [change_point_four_bar(0.1, 0.3, 0.2, 100.3, 361),
              change_point_four_bar(0.1, 0.3, 0.2, 0.0, 37),
              change_point_four_bar(0.11, 0.3, 0.2, 50.3, 181)]
    for d in scenes[:2]:
        drv = d["driver"]
        pos = np.linspace(drv["start"], drv["stop"], drv["count"])[:-1]
        d["driver"] = {k: v for k, v in drv.items() if k not in ("start", "stop", "count")}
        d["driver"]["positions"] = [float(p) for p in rng.permutation(pos)]
    sols = ks.solve_many(scenes)
    assert alone_calls == []
    assert sols[0].summary()["dead_points_between_rows"] == [[359.3, 360.3]]
    for s, d in zip(sols, scenes, strict=True):
        assert_same(s, ks.solve(d))


def test_signature_tells_numbers_by_their_bits(alone_calls) -> None:
    """The numbers a stack takes from its first scene (gravity, forces, moments, line
    angles, the driver's speed) must have the same bits in every scene: a -0.0 is not
    stacked with a 0.0 (their products differ in sign); the same numbers stack."""
    from kinetostatics.solver.stack import signature

    base = load_scene(ks.example("four_bar")).raw
    flipped = copy.deepcopy(base)
    flipped["gravity"] = [-0.0, base["gravity"][1]] if "gravity" in base else [-0.0, -9.81]
    plain = copy.deepcopy(base)
    plain["gravity"] = [0.0, flipped["gravity"][1]]
    a, b = load_scene(plain), load_scene(flipped)
    assert signature(a) != signature(b)
    assert signature(a) == signature(load_scene(copy.deepcopy(plain)))
    sols = ks.solve_many([plain, flipped, plain])
    for s, d in zip(sols, [plain, flipped, plain], strict=True):
        assert_same(s, ks.solve(d))
    assert alone_calls == [load_scene(flipped).title]     # a group of its own, of one


def test_increasing_told_per_scene_and_sweep() -> None:
    """Whether each scene's positions strictly increase (stack_record, told once per sweep
    key), as told scene by scene (empty and one-row sweeps, repeats, NaN)."""
    from types import SimpleNamespace

    from kinetostatics.solver.stack import _increases

    rng = np.random.default_rng(8)
    for _ in range(500):
        pos = [rng.choice([0.0, 1.0, 2.0, 3.0, np.nan], n) if rng.random() < 0.5
               else np.sort(rng.random(n)) for n in rng.integers(0, 6, rng.integers(1, 6))]
        # (a sweep read from start, stop and count: its key, the same bits for one key)
        keys = [(p.size, p.tobytes()) if rng.random() < 0.3 else None for p in pos]
        drivers = [SimpleNamespace(positions=p, sweep=k) for p, k in zip(pos, keys, strict=True)]
        want = [bool(np.all(p[1:] > p[:-1])) for p in pos]
        assert [_increases(d) for d in drivers] == want
        assert [_increases(d) for d in drivers] == want     # (told again: the same)
