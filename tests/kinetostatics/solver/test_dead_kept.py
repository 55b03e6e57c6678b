"""The dead points of a scene's own sweep worked out at its first solve and kept in the
scene's record (pipeline.dead_points_kept): the same arrays at every later solve of the
scene object, the numbers of a fresh solve."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver import pipeline as pl
from tests.kinetostatics.solver.test_deadpoints import change_point_four_bar, slotted_lever

pytestmark = pytest.mark.usefixtures("numpy_path")


def _counted(monkeypatch) -> list:
    calls: list = []
    real = pl.dead_points_of_sweep

    def spy(*a, **k):
        calls.append(a[2].size)
        return real(*a, **k)
    monkeypatch.setattr(pl, "dead_points_of_sweep", spy)
    return calls


SCENES = {"shaper": lambda: load_scene(ks.example("shaper")).raw,
          "four_bar": lambda: load_scene(ks.example("four_bar")).raw,
          # (a dead point between rows 269.5 and 270.5 deg; a change point between 359.3
          # and 360.3 deg: test_deadpoints)
          "slotted_lever": lambda: slotted_lever(0.30, start=0.5),
          "change_point": lambda: change_point_four_bar(0.1, 0.3, 0.2, 100.3, 361)}


@pytest.mark.parametrize("name", list(SCENES))
def test_kept_dead_points_are_a_fresh_solves(name, monkeypatch) -> None:
    """Solved twice, the scene object screens its sweep once (the shaper probes a dip
    below the screen each time otherwise); the tables that read the dead points are a
    fresh scene's, and the kept arrays are read-only."""
    sc = load_scene(SCENES[name]())
    calls = _counted(monkeypatch)
    first, again = ks.solve(sc), ks.solve(sc)
    assert calls == [sc.driver.positions.size]
    with monkeypatch.context() as m:       # (a scene read from a dict again is the
        # same object: its record, the kept dead points, comes along)
        m.setattr(pl, "dead_points_kept", lambda scene, st, pos, m2:
                  pl.dead_points_of_sweep(scene, st, pos, m2()))
        fresh = ks.solve(copy.deepcopy(sc.raw))
    assert len(calls) == 2
    if name in ("slotted_lever", "change_point"):
        assert fresh.kin.between.size
    for sol in (first, again):
        for f in ("between", "ends", "unassembled"):
            np.testing.assert_array_equal(getattr(sol.kin, f), getattr(fresh.kin, f))
            assert not getattr(sol.kin, f).flags.writeable
        np.testing.assert_array_equal(sol.singular, fresh.singular)
        assert repr(sol.summary()) == repr(fresh.summary())


def test_positions_given_are_screened_each_time(monkeypatch) -> None:
    """A solve at positions given apart screens them each time, and what it finds is
    not taken for the scene's own sweep."""
    sc = load_scene(ks.example("shaper"))
    calls = _counted(monkeypatch)
    pos = np.linspace(10.0, 350.0, 77)
    a, b = ks.solve(sc, pos), ks.solve(sc, pos)
    own = ks.solve(sc)
    assert calls == [77, 77, sc.driver.positions.size]
    np.testing.assert_array_equal(a.kin.between, b.kin.between)
    assert own.kin.between is not a.kin.between
