"""Each scene's assemblies in a stack kept per scene object (``many.kept_assemblies``):
the assemblies and the scenes they settle as ``stack.assemblies`` chooses them for the
same stack, told again from the kept ones for the same scenes in any order or company."""

from __future__ import annotations

import numpy as np

from kinetostatics.solver import many
from kinetostatics.solver.many import kept_assemblies
from kinetostatics.solver.stack import Stacker, assemblies, stack_record
from kinetostatics.solver.structure import analyse

from .test_screen_probe import long_cranks


def chosen(scenes: list, kept: bool) -> tuple:
    structure = analyse(scenes[0], assemble=False)
    stacker = Stacker(scenes, [stack_record(s)[1] for s in scenes])
    firsts = np.array([s.driver.positions[0] for s in scenes])
    return (kept_assemblies if kept else assemblies)(stacker, structure, firsts)


def same(got: tuple, expected: tuple) -> None:
    for g, e in zip(got, expected, strict=True):
        assert g.dtype == e.dtype and g.shape == e.shape and g.flags.c_contiguous
        np.testing.assert_array_equal(g, e)


def test_kept_assemblies_are_the_stacks_own(monkeypatch) -> None:
    scenes = long_cranks(40, 3)
    expected = chosen(scenes, kept=False)
    # (measured: 3 of 40 cannot close at their first row; both assemblies among the rest)
    assert 0 < (~expected[1]).sum() < len(scenes)
    assert set(expected[0][0][expected[1]].tolist()) == {-1, 1}
    calls = []
    monkeypatch.setattr(many, "assemblies", lambda *a: calls.append(1) or assemblies(*a))
    same(chosen(scenes, kept=True), expected)
    same(chosen(scenes, kept=True), expected)       # (kept: not chosen again)
    assert len(calls) == 1
    # the same scenes in another order, with new ones among them
    mixed = long_cranks(10, 4) + scenes[::-1]
    same(chosen(mixed, kept=True), chosen(mixed, kept=False))
    assert len(calls) == 2
    same(chosen(scenes[5:], kept=True), tuple(x[..., 5:] for x in expected))
    assert len(calls) == 2
