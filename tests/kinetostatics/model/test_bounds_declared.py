"""Bounds read through the declarations (kinetostatics.model.fields): a balancing scene's
and a ``[motion]`` section's numbers out of their declared bounds are refused in one line
that quotes the value as typed, in the scene's unit (issue 30); the declared defaults are
the readers' defaults."""

from __future__ import annotations

import copy
import tomllib
import warnings

import pytest

import balance
import kinetostatics as ks
from balance.model import scene as bscene
from kinetostatics.model.fields import BALANCING, MECHANISM, section
from kinetostatics.motion import scene as mscene

ROTOR = ('[units]\nmass = "g"\nlength = "mm"\n[rotor]\n[[rotor.unbalance]]\nmass = {m}\n'
         'radius = 100.0\nangle = 0.0\n[[rotor.planes]]\nradius = {r}\n')
STATIC = ('[units]\nlength = "mm"\nmass = "g"\n[static_test]\ndisk_mass = 5000.0\n'
          'comparison_mass = 50.0\ncomparison_radius = {r}\nalpha = 10.0\n'
          'correction_radius = 80.0\n')
RES = ('[units]\nmass = "g"\n[[resonance_test]]\ntrial_mass = {m}\ntrial_radius = 0.1\n'
       'correction_radius = 0.1\nA1 = {a1}\nA2 = 2.0\nA3 = 3.0\n')

BALANCE_ERRORS = [
    (ROTOR.format(m=-350.0, r=80.0), r"rotor\.unbalance\[0\]\.mass must not be negative, "
                                     r"got -350 g$"),
    (ROTOR.format(m=350.0, r=-80.0), r"rotor\.planes\[0\]\.radius must be positive, got -80 mm$"),
    (STATIC.format(r=-100.0), r"static_test\.comparison_radius must be positive, got -100 mm$"),
    (RES.format(m=0.0, a1=1.0), r"resonance_test\[0\]\.trial_mass must be positive, got 0 g$"),
    (RES.format(m=10.0, a1=-1.0), r"resonance_test\[0\]\.A1 must not be negative, got -1$"),
    (ROTOR.format(m=1.0, r=80.0).replace("[rotor]\n", "[rotor]\nspeed_rpm = -3.0\n"),
     r"rotor\.speed_rpm must be positive, got -3 rpm$"),
]


FIELD = '[units]\nmass = "g"\nlength = "mm"\nangle = "rad"\n'
RUNS = ("[[influence]]\ninitial = [[4.0, 1.0]]\n{extra}runs = [{{ plane = 1, mass = {m}, "
        "angle = 0.0, readings = [[2.8, 2.0]] }}]\n")
BALANCE_ERRORS += [     # the field sections: masses and radii kept as typed, angles in rad
    (FIELD + RUNS.format(extra="", m=-350.0),
     r"influence\[0\]\.runs\[0\]\.mass must be positive, got -350 g$"),
    (FIELD + RUNS.format(extra="trial_radius = -100.0\n", m=350.0),
     r"influence\[0\]\.trial_radius must be positive, got -100 mm$"),
    (FIELD + RUNS.format(extra="phase_noise = -0.1\n", m=350.0),
     r"influence\[0\]\.phase_noise must not be negative, got -0\.1 rad$"),
    (FIELD + "[[split]]\nmass = -10.0\nangle = 0.1\npositions = 12\n",
     r"split\[0\]\.mass must not be negative, got -10 g$"),
    (FIELD + "[[combine]]\nweights = [{mass = -5.0, angle = 0.1}]\n",
     r"combine\[0\]\.weights\[0\]\.mass must not be negative, got -5 g$"),
    (FIELD + "[iso]\nrotor_mass = -5000.0\ngrade = 6.3\nspeed_rpm = 3000.0\n",
     r"iso\.rotor_mass must be positive, got -5000 g$"),
]


@pytest.mark.parametrize(("text", "match"), BALANCE_ERRORS)
def test_balancing_bounds_quote_the_typed_value(text, match) -> None:
    with pytest.raises(ks.SceneError, match=match):
        balance.solve(text)


def motion(**kw) -> dict:
    with open(ks.example("four_bar_motion"), "rb") as fh:
        d = tomllib.load(fh)
    d["units"] = {"speed": "rpm", "mass": "g"}
    for k, v in kw.items():
        (d["motion"]["motor"] if k == "no_load_speed" else d["motion"])[k] = v
    return d


@pytest.mark.parametrize(("kw", "match"), [
    ({"omega0": -3.0}, r"motion\.omega0 must be positive, got -3 rpm$"),
    ({"flywheel": -0.2}, r"motion\.flywheel must not be negative, got -0\.2 g m\^2$"),
    ({"no_load_speed": -100.0}, r"motion\.motor\.no_load_speed must be positive, got -100 rpm$"),
    ({"target_delta": 0.0}, r"motion\.target_delta must be positive, got 0$"),
])
def test_motion_bounds_quote_the_typed_value(kw, match) -> None:
    with pytest.raises(ks.SceneError, match=match):
        ks.simulate_motion(copy.deepcopy(motion(**kw)))


def test_the_readers_read_every_number_of_theirs_through_a_declaration() -> None:
    # each key a balancing table reads as a number has its declaration (else its bound
    # and its unit in messages would be written twice)
    tables = {("rotor",): ("speed_rpm",), ("rotor", "unbalance", "[]"): bscene.UNBALANCE_KEYS,
              ("rotor", "planes", "[]"): bscene.PLANE_KEYS,
              ("static_test",): bscene.STATIC_KEYS,
              ("resonance_test", "[]"): ("trial_mass", "trial_radius", "correction_radius",
                                         "A1", "A2", "A3", "dA", "confidence"),
              ("resonance_test", "[]", "runs", "[]"): bscene.RUN_KEYS,
              ("resonance_test", "[]", "noise"): bscene.NOISE_KEYS}
    for where, keys in tables.items():
        assert set(keys) <= set(section(BALANCING, *where)), where
    assert {"flywheel", "omega0", "target_delta"} <= set(mscene.MOTION)
    assert set(mscene.MOTOR) == {"stall_moment", "no_load_speed"}
    assert section(MECHANISM, "motion")["flywheel"].fallback == 0.0
    assert section(BALANCING, "rotor", "unbalance", "[]")["z"].fallback == 0.0


# ------------------------------------------------------------------ messages in the typed unit
CAMS = ks.example("four_bar").parent / "cams"


def mm_cam(name: str, **cam) -> dict:
    """A bundled cam typed in mm (and rad for angles when ``rad``), with ``cam`` changed."""
    with open(CAMS / f"{name}.toml", "rb") as fh:
        d = tomllib.load(fh)
    d["units"] = {"length": "mm"}
    c = d["cam"]
    for key in ("base_radius", "roller_radius"):
        if key in c:
            c[key] *= 1000.0
    for key in ("stroke", "offset", "arm", "pivot_distance"):
        if isinstance(c["follower"].get(key), float):
            c["follower"][key] *= 1000.0
    for key in ("guide_length", "guide_gap", "pin_radius"):
        if key in c.get("loads", {}):
            c["loads"][key] *= 1000.0
    for k, v in cam.items():
        (c["follower"] if k in ("offset", "arm", "pivot_distance") else c)[k] = v
    return d


@pytest.mark.parametrize(("scene", "match"), [
    (mm_cam("translating_roller", roller_radius=100.0),
     r"the roller radius 100 mm must lie in \[0, base radius \d+(\.\d+)? mm\)$"),
    (mm_cam("oscillating_roller", pivot_distance=30.0),
     r"no base radius keeps tau >= 45 deg with arm 60 mm and pivot distance 30 mm"),
    (mm_cam("oscillating_roller", transmission_angle=95.0),
     r"admissible transmission angle must lie in \(0, 90 deg\), got 95 deg$"),
])
def test_cam_follower_errors_quote_the_scene_units(scene, match) -> None:
    from kinetostatics.cams import load_cam_scene
    with pytest.raises(ks.WorkbenchError, match=match), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        load_cam_scene(scene)


def test_rotor_notes_and_errors_quote_the_scene_units() -> None:
    planes = ('[[rotor.planes]]\nz = 240.0\nradius = 80.0\n'
              '[[rotor.planes]]\nz = {z}\nradius = 80.0\n')
    text = ('[units]\nmass = "g"\nlength = "mm"\n[rotor]\n'
            '[[rotor.unbalance]]\nmass = 20.0\nradius = 100.0\nangle = 0.0\nz = 0.0\n'
            '[[rotor.unbalance]]\nmass = 20.0\nradius = 100.0\nangle = 180.0\nz = 500.0\n')
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        out = balance.solve(text + planes.format(z=260.0))
    notes = out["rotor"]["warnings"]
    assert any("planes are 20 mm apart" in n and "extent 500 mm" in n for n in notes), notes
    assert any("corrections total 1e+05 g mm" in n and "(4000 g mm)" in n for n in notes), notes
    assert len(seen) == len(notes)
    with pytest.raises(balance.BalanceError, match=r"coincide \(z = 240 and 240 mm\)"):
        balance.solve(text + planes.format(z=240.0))
    with pytest.raises(ks.SceneError, match=r"alpha must lie in \(0, 1\.5708 rad\], got 2 rad"):
        balance.solve('[units]\nangle = "rad"\n[static_test]\ndisk_mass = 5.0\n'
                      'comparison_mass = 0.05\ncomparison_radius = 0.1\nalpha = 2.0\n'
                      'correction_radius = 0.08\n')
