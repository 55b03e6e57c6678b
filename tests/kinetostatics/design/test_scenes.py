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
