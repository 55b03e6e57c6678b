"""A design's Scene made from the bundled one is the Scene load_scene reads from the
design's dict, field by field."""

from __future__ import annotations

import dataclasses
import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.design.section import read_design
from kinetostatics.model.scene import load_scene


def _same(a, b) -> None:
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if f.name == "driver":
            for g in dataclasses.fields(x):
                assert np.array_equal(getattr(x, g.name), getattr(y, g.name)), g.name
        else:
            assert x == y, f.name
    assert a.size == b.size and a.raw == b.raw


def test_the_bundled_design_made_direct():
    spec = read_design("four_bar_design")
    X = spec.lower + np.random.default_rng(5).random((50, 4)) * (spec.upper - spec.lower)
    for x in X:
        design, made = spec.design_scene(x)
        assert made is not load_scene(design)
        _same(made, load_scene(design))


@pytest.mark.parametrize("variables", [
    {"bodies.coupler.mass": [1.0, 3.0], "bodies.rocker.inertia": [0.005, 0.01],
     "ground.A.1": [-0.02, 0.02], "bodies.coupler.cog.1": [0.0, 0.04]},
    {"driver.speed": [10.0, 40.0]},                 # (read again by load_scene)
])
def test_other_variables(variables):
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    raw["design"].update(variables=variables, follow={})
    spec = read_design(raw)
    X = spec.lower + np.random.default_rng(6).random((20, len(variables))) * (
        spec.upper - spec.lower)
    for x in X:
        design, made = spec.design_scene(x)
        _same(made, load_scene(design))


def test_units_read_again():
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    raw["units"] = {"mass": "g"}
    for b in raw["bodies"]:
        b["mass"] *= 1000.0
    spec = read_design(raw)
    design, made = spec.design_scene(spec.bundled * 1.1)
    _same(made, load_scene(design))
    assert made.bodies["crank"].mass == pytest.approx(1.2)


def test_a_scene_in_mm_gives_the_same_front():
    """Bounds as typed in the scene's units; objectives in SI, whatever the units."""
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    raw["design"]["constraints"] = ["transmission_min >= 45"]
    mm = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    mm["design"] = {**raw["design"], "variables": {
        k: [a * 1000, b * 1000] for k, (a, b) in raw["design"]["variables"].items()}}
    mm["units"] = {"length": "mm"}
    mm["gravity"] = [0.0, -9810.0]
    for b in mm["bodies"]:
        b["points"] = {k: [x * 1000, y * 1000] for k, (x, y) in b["points"].items()}
        b["cog"] = [c * 1000 for c in b["cog"]]
        b["inertia"] *= 1e6
    for table in ("ground", "near"):
        mm[table] = {k: [x * 1000, y * 1000] for k, (x, y) in mm[table].items()}
    a = ks.design(raw, population=8, generations=2)
    b = ks.design(mm, population=8, generations=2)
    assert b.summary["variables_units"] == "as typed in the scene (its [units]: {'length': 'mm'})"
    np.testing.assert_allclose(b.X, 1000 * a.X, rtol=1e-13)  # (measured: 2.2e-16)
    np.testing.assert_allclose(b.values, a.values, rtol=1e-12)  # (measured: 4.4e-16)
