"""The records of many scenes at once (``stack.stack_records``, what solve_many reads of
each scene first): each scene's own record, the one :func:`stack_record` keeps."""

from __future__ import annotations

import copy

from kinetostatics.bench.speed import four_bar_variants
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.stack import stack_record, stack_records


def test_records_at_once_are_each_scenes_own() -> None:
    scenes = [load_scene(d) for d in four_bar_variants(6)]
    told = [stack_record(s) for s in scenes[:3]]        # (kept for half of them)
    got = stack_records(scenes)
    assert all(g is t for g, t in zip(got[:3], told, strict=True))
    assert got[3:] == [stack_record(s) for s in scenes[3:]]
    assert all(g is stack_record(s) for g, s in zip(got, scenes, strict=True))
    # a copy of a scene is another object: a record of its own, equal numbers
    again = [copy.copy(s) for s in scenes[:2]]
    fresh = stack_records(again)
    assert all(f is not t for f, t in zip(fresh, told[:2], strict=True))
    assert [f[1:] for f in fresh] == [t[1:] for t in told[:2]]
