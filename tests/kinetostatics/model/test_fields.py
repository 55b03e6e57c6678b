"""The field declarations (kinetostatics.model.fields): the docs' tables are them, every
declared key is one the readers know, and the units stage reaches every declared field
with its quantity's factor (the factors by definition, not from the workbench)."""

from __future__ import annotations

import dataclasses
import math
import pickle
import re
from pathlib import Path

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.cams import scene as cam_scene
from kinetostatics.model import scene as mech_scene
from kinetostatics.model.fields import BALANCING, CAM, MECHANISM, ROLES, convert, markdown
from kinetostatics.model.units import Units

ROOT = Path(__file__).resolve().parents[3]
KINDS = {"mechanism": MECHANISM, "cam": CAM, "balancing": BALANCING}


@pytest.mark.parametrize("kind", KINDS)
def test_the_docs_tables_are_the_declarations(kind) -> None:
    doc = (ROOT / "docs" / "scene-format.md").read_text()
    found = re.search(rf"<!-- fields: {kind} -->\n(.*?)\n<!-- /fields -->", doc, re.S)
    assert found is not None, f"docs/scene-format.md has no table of the {kind} fields"
    assert found.group(1) == markdown(KINDS[kind])


def test_every_declared_key_is_one_the_readers_know() -> None:
    m = mech_scene
    known = {"bodies": m.BODY_KEYS, "joints": (*m.JOINT_KEYS_R, *m.JOINT_KEYS_T),
             "loads": m.LOAD_KEYS, "driver": m.DRIVER_KEYS, "motion": m.MOTION_KEYS,
             "friction": ("mu", "radius", "length"), "motor": ("stall_moment",
                                                               "no_load_speed")}
    for fd in MECHANISM:
        assert fd.path[0] in m.TOP_KEYS, fd.name
        keys = [k for k in fd.path if k not in ("[]", "*") and not k.startswith("#")]
        if len(keys) > 1 and keys[-2] in known:
            assert keys[-1] in known[keys[-2]], fd.name
    c = cam_scene
    cam_known = {"cam": c.CAM_KEYS, "segments": c.SEGMENT_KEYS,
                 "follower": {k for v in c.FOLLOWER_KEYS.values() for k in v},
                 "loads": {k for v in c.LOAD_KEYS.values() for k in v}}
    for fd in CAM:
        keys = [k for k in fd.path if k != "[]"]
        assert keys[-1] in cam_known[keys[-2]], fd.name


FACTOR = {"length": 1e-3, "mass": 1e-3, "force": 1e3, "angle": 1.0, "speed": math.pi / 30,
          "moment": 1.0, "inertia": 1e-9, "acceleration": 1e-3, "velocity": 1e-3,
          "stiffness": 1e6, None: 1.0}
"""One unit of ``UNITS`` in the contract's units (degrees for an angle), by definition."""
UNITS = Units(length="mm", mass="g", force="kN", angle="deg", speed="rpm")


def _build(path: tuple[str, ...]):
    """A mapping holding 7.0 (7.0 in both numbers of a pair) where ``path`` says."""
    if not path:
        return 7.0
    step, rest = path[0], path[1:]
    if step == "[]":
        return [_build(rest)]
    if step.startswith("#"):
        return [7.0, 7.0]
    if step == "*":
        return {"P": _build(rest)}
    return {step: _build(rest)}


def _read(node, path: tuple[str, ...]) -> float:
    for step in path:
        node = node[0] if step == "[]" else node["P"] if step == "*" else \
            node[int(step[1:])] if step.startswith("#") else node[step]
    return node


@pytest.mark.parametrize("fd", [*MECHANISM, *CAM, *BALANCING], ids=lambda f: f.name)
def test_the_units_stage_reaches_every_declared_field(fd) -> None:
    raw = _build(fd.path)
    quantity = ROLES[fd.quantity](raw) if fd.quantity in ROLES else fd.quantity or None
    if fd.kept:         # a field section's mass or radius: left as typed
        quantity = None
    out = convert(raw, UNITS, (fd,))
    assert _read(out, fd.path) == pytest.approx(7.0 * FACTOR[quantity], rel=1e-15)
    assert _read(raw, fd.path) == 7.0                   # the mapping read is not changed


@pytest.mark.parametrize("name", ["four_bar", "slider_crank", "four_bar_mm", "slotted_lever"])
def test_a_read_scene_holds_its_angles_in_radians(name) -> None:
    """Converted once, when read: a crank's positions (read-only, shared) and a prismatic
    line's angle, bit for bit numpy's and math's degrees-to-radians; the degrees stay as
    the tables' labels."""
    sc = ks.load_scene(name)
    drv = sc.driver
    assert np.array_equal(drv.angles, np.deg2rad(drv.positions))
    assert drv.angles is drv.angles and not drv.angles.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        drv.angles[0] = 0.0
    typed = {j["name"]: j.get("line_angle", 0.0) for j in sc.raw["joints"]}
    for j in sc.joints.values():
        assert j.beta == math.radians(typed[j.name] if j.kind == "T" else 0.0)
        assert "line_angle" not in vars(j)          # the degrees are not kept


def test_a_joint_given_degrees_or_read_for_them_warns_for_one_release() -> None:
    """``Joint.line_angle`` (deg), given or read, is deprecated: ``beta`` (rad) is what the
    joint holds; the old names still work and say so."""
    sc = ks.load_scene("slotted_lever")
    j = next(j for j in sc.joints.values() if j.kind == "T")
    with pytest.warns(DeprecationWarning, match="read Joint.beta"):
        assert j.line_angle == math.degrees(j.beta)
    with pytest.warns(DeprecationWarning, match="give beta"):
        old = mech_scene.Joint(j.name, "T", j.bodies, j.points, 30.0)
    assert old.beta == math.radians(30.0)
    with pytest.warns(DeprecationWarning, match="give beta"):
        assert mech_scene.Joint(j.name, "T", j.bodies, j.points, line_angle=-5.0).beta \
            == math.radians(-5.0)
    moved = dataclasses.replace(old, friction=None)     # beta kept, no warning
    assert moved.beta == old.beta and moved == old
    assert pickle.loads(pickle.dumps(sc)).joints[j.name].beta == j.beta


def test_a_driver_at_positions_in_si_holds_them_to_the_bit() -> None:
    """``Driver.at`` (the probes between rows, in rad or m) keeps the coordinates given,
    not their degrees read back (which lose a bit: 30 deg comes back 29.999999999999996)."""
    crank = ks.load_scene("four_bar").driver
    assert crank.coordinates is crank.angles
    x = np.array([0.1, 1.0, np.deg2rad(30.0)])
    moved = crank.at(x)
    assert np.array_equal(moved.angles, x) and moved.coordinates is moved.angles
    assert not moved.angles.flags.writeable and moved.sweep is None
    assert np.array_equal(moved.positions, np.rad2deg(x))
    assert not np.array_equal(np.deg2rad(np.rad2deg(x)), x)   # why the angles are kept
    slider = ks.load_scene("sliding_driver").driver
    assert slider.coordinates is slider.positions
    assert np.array_equal(slider.at([0.01, 0.02]).coordinates, [0.01, 0.02])
