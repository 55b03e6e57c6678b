"""The dead-point probe's closeness from the positions alone (``probe_closeness``) against
the kinematics solved with ``strict = False`` it replaces: the same numbers bit for bit,
and the same rows where a dyad cannot close, for every dyad kind of the bundled scenes,
at positions inside and beyond their sweeps (where some dyads do not close)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.continuity import open_rows
from kinetostatics.solver.deadpoints import kin_measure2
from kinetostatics.solver.kinematics import solve_kinematics
from kinetostatics.solver.probes import probe_closeness
from kinetostatics.solver.structure import analyse

NAMES = ["four_bar", "four_bar_mm", "scotch_yoke", "shaper", "slider_crank",
         "sliding_driver", "slotted_lever"]


def _bits(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64).view(np.int64)


@pytest.mark.parametrize("name", NAMES)
def test_probe_equals_the_kinematics_it_replaces(name):
    scene = load_scene(ks.example(name))
    structure = analyse(scene)
    pos = scene.driver.positions
    lo, hi = float(pos.min()), float(pos.max())
    span = hi - lo if hi > lo else 1.0
    rng = np.random.default_rng(7)
    # inside the sweep, a little beyond it, and far beyond it (some dyads cannot close)
    where = np.concatenate([rng.uniform(lo, hi, 400), rng.uniform(lo - span, hi + span, 400),
                            np.linspace(lo - 3 * span, hi + 3 * span, 201)])
    kin = solve_kinematics(scene, structure, positions=where, strict=False)
    closeness, gone = probe_closeness(scene, structure, where)
    assert len(closeness) == len(kin.dyads)
    for got, dm in zip(closeness, kin.dyads, strict=True):
        assert np.array_equal(_bits(got), _bits(np.broadcast_to(dm.closeness2, (where.size,))))
    assert np.array_equal(gone, open_rows(kin))
    assert np.array_equal(_bits(kin_measure2(kin)),
                          _bits(np.fmin.reduce([np.broadcast_to(c, (where.size,))
                                                for c in closeness])
                                if len(closeness) > 1 else closeness[0]))


def test_probe_picks_the_assembly_as_the_solve():
    """A structure without its assembly: chosen at the scene's first row, as there."""
    scene = load_scene(ks.example("four_bar"))
    structure = analyse(scene, assemble=False)
    where = np.linspace(0.0, 6.0, 50)
    kin = solve_kinematics(scene, structure, positions=where, strict=False)
    closeness, gone = probe_closeness(scene, replace(structure), where)
    assert np.array_equal(_bits(closeness[0]), _bits(kin.dyads[0].closeness2))
    assert np.array_equal(gone, open_rows(kin))


def test_probe_of_a_crank_pivoted_off_its_origin():
    """A crank whose pivot is not its frame's origin (its origin turns about the pivot,
    ``probes.driver_positions``): the probe still equals the kinematics, bit for bit."""
    raw = load_scene(ks.example("four_bar")).raw
    crank = raw["bodies"][0]
    assert crank["name"] == raw["driver"]["body"]
    shift = (0.013, -0.007)
    crank = dict(crank, cog=[c + s for c, s in zip(crank["cog"], shift, strict=True)],
                 points={p: [c + s for c, s in zip(xy, shift, strict=True)]
                         for p, xy in crank["points"].items()})
    scene = load_scene(dict(raw, bodies=[crank, *raw["bodies"][1:]]))
    structure = analyse(scene)
    where = np.linspace(-30.0, 400.0, 301)
    kin = solve_kinematics(scene, structure, positions=where, strict=False)
    closeness, gone = probe_closeness(scene, structure, where)
    assert np.array_equal(_bits(closeness[0]), _bits(kin.dyads[0].closeness2))
    assert np.array_equal(gone, open_rows(kin))
