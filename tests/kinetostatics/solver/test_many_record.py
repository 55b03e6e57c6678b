"""What solve_many tells once per scene object (stack_record) and the Stacker built from
it: the labels group exactly the scenes of one signature, the numbers are each scene's
own, bit for bit, and a scene solved again (its record kept) gives the same numbers."""

from __future__ import annotations

import gc
import weakref
from dataclasses import replace

import numpy as np

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver import stack
from kinetostatics.solver.stack import Stacker, _numbers, signature, stack_record

from .test_many import assert_same, variants


def _bits(x) -> np.ndarray:
    return np.asarray(x, dtype=float).view(np.int64)


def test_labels_group_exactly_the_scenes_of_one_signature() -> None:
    scenes = [load_scene(d) for d in variants("four_bar", 6, 0.05)]
    scenes += [load_scene(d) for d in variants("slider_crank", 3, 0.05)]
    recs = [stack_record(s) for s in scenes]
    for a, ra in zip(scenes, recs, strict=True):
        for b, rb in zip(scenes, recs, strict=True):
            assert (ra[0] == rb[0]) == (signature(a) == signature(b))
    # told once per scene object: the same record, not worked out again
    assert all(stack_record(s) is r for s, r in zip(scenes, recs, strict=True))
    # each scene's numbers, packed, bit for bit
    for s, (_, nums, up, n, sweep, cell) in zip(scenes, recs, strict=True):
        np.testing.assert_array_equal(np.frombuffer(nums).view(np.int64), _bits(_numbers(s)))
        assert up
        assert n == s.driver.positions.size and sweep == s.driver.sweep
        assert cell == [None]       # (its assemblies: none chosen yet, kept_assemblies)


def test_a_scene_solved_alone_has_no_label() -> None:
    raw = load_scene(ks.example("four_bar")).raw
    joint = next(iter(raw["joints"]))
    friction = dict(raw, joints=[dict(joint, friction={"mu": 0.1, "radius": 0.01}),
                                 *raw["joints"][1:]])
    assert stack_record(load_scene(friction))[0] is None
    sc = load_scene(raw)
    empty = replace(sc, driver=replace(sc.driver, positions=np.zeros(0)))
    assert stack_record(empty)[0] is None


def test_a_record_goes_with_its_scene() -> None:
    """A record is kept while its scene lives: another object at the same address (the
    first one gone) gets its own."""
    sc = load_scene(ks.example("four_bar"))
    other = load_scene(ks.example("slider_crank"))
    gone = load_scene(ks.example("slider_crank"))
    ref = weakref.ref(gone)
    stale = stack_record(gone)
    del gone
    gc.collect()
    assert ref() is None
    stack._RECORDS.entries[id(sc)] = (ref, stale)        # (as if sc took the dead scene's place)
    assert stack_record(sc)[0] != stack_record(other)[0]
    assert stack_record(sc)[1] != stale[1]


def test_stacker_numbers_are_each_scenes_own() -> None:
    """A number the scenes share is the first scene's own object; one that varies is the
    array of every scene's, bit for bit (as read from each scene one by one)."""
    scenes = [load_scene(d) for d in variants("shaper", 7, 0.05, seed=3)]
    st = Stacker(scenes)
    s0 = scenes[0]

    def check(got, of) -> None:
        want = [of(s) for s in scenes]
        if isinstance(got, np.ndarray):
            np.testing.assert_array_equal(got.view(np.int64), _bits(want))
            assert len(set(_bits(want).tolist())) > 1
        else:
            assert got is of(s0)
            assert len(set(_bits(want).tolist())) == 1
    for p, (x, y) in st.ground.items():
        check(x, lambda s, p=p: s.ground[p][0])
        check(y, lambda s, p=p: s.ground[p][1])
    for name, (mass, inertia, cog, pts) in st.bodies.items():
        check(mass, lambda s, n=name: s.bodies[n].mass)
        check(inertia, lambda s, n=name: s.bodies[n].inertia)
        if cog is not None:
            check(cog[0], lambda s, n=name: s.bodies[n].cog[0])
        for p, (x, y) in pts.items():
            check(x, lambda s, n=name, p=p: s.bodies[n].points[p][0])
            check(y, lambda s, n=name, p=p: s.bodies[n].points[p][1])
    for k, (x, y) in st.near.items():
        check(x, lambda s, k=k: s.near[k][0])
        check(y, lambda s, k=k: s.near[k][1])
    check(st.size, lambda s: s.size)


def test_a_run_and_a_probe_take_each_scenes_numbers() -> None:
    """A run's stacked scene (each varying number repeated over its scene's rows) and a
    probe's (taken row by row) hold per row the numbers of the row's scene."""
    scenes = [load_scene(d) for d in variants("four_bar", 5, 0.05, seed=4)]
    st = Stacker(scenes)
    counts = np.array([3, 1, 4, 2, 5])
    run = st.runs(1, 4, counts[1:4], np.zeros(counts[1:4].sum()))
    owner = np.array([4, 0, 0, 2, 1, 4])
    probe = st.scene(owner, np.zeros(owner.size))
    rows = np.repeat(np.arange(1, 4), counts[1:4])
    for sc, who in ((run, rows), (probe, owner)):
        for name, b in sc.bodies.items():
            for p, (x, _) in b.points.items():
                want = [scenes[j].bodies[name].points[p][0] for j in who]
                np.testing.assert_array_equal(np.broadcast_to(x, who.shape), want)
            want = [scenes[j].bodies[name].mass for j in who]
            np.testing.assert_array_equal(np.broadcast_to(np.asarray(b.mass), who.shape),
                                          want)


def test_solved_again_from_kept_records_equal_solve(alone_calls) -> None:
    """solve_many twice over the same scene objects (their records kept) gives each the
    numbers solve gives it alone."""
    scenes = [load_scene(d) for d in variants("four_bar", 12, 0.08, seed=5)]
    first = ks.solve_many(scenes)
    again = ks.solve_many(scenes)
    for a, b, s in zip(first, again, scenes, strict=True):
        want = ks.solve(s)
        assert_same(a, want)
        assert_same(b, want)
    assert not alone_calls
