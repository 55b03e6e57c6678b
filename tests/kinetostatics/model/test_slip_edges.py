"""Scenes near the slip rules' edges (issue 30), every kind: the legitimate ones are
silent, the real slips of the issue's list warn with their rule, and nothing else goes
wrong (a slipped cam whose angles no longer add up to 360 is also refused)."""

from __future__ import annotations

import copy
import tomllib
import warnings
from pathlib import Path

import pytest

import balance
import kinetostatics as ks
from kinetostatics.cams import load_cam_scene
from tests.kinetostatics.scenes import four_bar

CAMS = Path(__file__).resolve().parents[3] / "kinetostatics" / "scenes" / "cams"


def ex(name: str) -> dict:
    with open(ks.example(name), "rb") as fh:
        return tomllib.load(fh)


def cam(**kw):
    d = tomllib.load(open(CAMS / "translating_roller.toml", "rb"))
    for k, v in kw.items():
        if k == "segments":
            d["cam"]["segments"] = v
        elif v is None:
            d["cam"].pop(k, None)
        else:
            d["cam"][k] = v
    return d


def osc(**kw):
    d = tomllib.load(open(CAMS / "oscillating_roller.toml", "rb"))
    for k, v in kw.items():
        d["cam"]["follower"][k] = v
    return d


def fb(**kw):
    d = four_bar(
        0.1,
        0.25,
        0.2,
        0.3,
        masses=(1.2, 2.0, 1.6),
        inertias=(0.004, 0.012, 0.0075),
        gravity=[0, -9.81],
        count=37,
    )
    for k, v in kw.items():
        if k.startswith("drv_"):
            d["driver"][k[4:]] = v
        else:
            d[k] = v
    return d


def mm(d):
    d = copy.deepcopy(d)
    d["units"] = {"length": "mm", "mass": "g"}
    d["ground"] = {k: [c * 1000 for c in v] for k, v in d["ground"].items()}
    d["near"] = {k: [c * 1000 for c in v] for k, v in d["near"].items()}
    for b in d["bodies"]:
        b["mass"] *= 1000
        b["inertia"] *= 1e9
        b["cog"] = [c * 1000 for c in b["cog"]]
        b["points"] = {k: [c * 1000 for c in v] for k, v in b["points"].items()}
    if "gravity" in d:
        d["gravity"] = [g * 1000 for g in d["gravity"]]
    return d


def piston(mass: float, inertia: float = 0.0) -> dict:
    """The bundled slider-crank with its piston a point mass (the course's mass
    concentration: inertia 0, its one joint point at its centre of mass)."""
    d = ex("slider_crank")
    d["bodies"][2].update(mass=mass, inertia=inertia, cog=[0.0, 0.0])
    return d


def rotor(masses, angles, units=None):
    ub = [
        {"mass": m, "radius": 0.1, "angle": a, "z": 0.1 * (i + 1)}
        for i, (m, a) in enumerate(zip(masses, angles, strict=True))
    ]
    d = {
        "rotor": {"unbalance": ub, "planes": [{"z": 0.0, "radius": 0.1}, {"z": 0.5, "radius": 0.1}]}
    }
    if units:
        d["units"] = units
    return d


def INF(m, ph=(250.0, 160.0), units='mass = "g"'):  # noqa: N802 (a scene text)
    return (
        f"[units]\n{units}\n[[influence]]\ninitial = [[4.0, {ph[0]}]]\nruns = [{{ plane = 1, "
        f"mass = {m}, angle = 0.0, readings = [[2.855, {ph[1]}]] }}]\n"
    )


CASES = [
    # (name, load, scene, expected rules ([] = silent))
    ("mm four-bar, gravity 9810 mm/s^2", ks.load_scene, mm(fb()), []),
    (
        "mm four-bar, gravity 9.81 (m/s^2 under mm)",
        ks.load_scene,
        {**mm(fb()), "gravity": [0.0, -9.81]},
        ["gravity"],
    ),
    ("four-bar 1000x gravity", ks.load_scene, fb(gravity=[0.0, -9810.0]), ["gravity"]),
    ("four-bar 2400 rad/s (speed without rpm)", ks.load_scene, fb(drv_speed=2400.0), ["speed"]),
    ("four-bar 300 rad/s (fast, real)", ks.load_scene, fb(drv_speed=300.0), []),
    (
        "1 mm MEMS at 20000 rad/s",
        ks.load_scene,
        four_bar(
            1e-3,
            2.5e-3,
            2e-3,
            3e-3,
            masses=(1e-6, 2e-6, 1.5e-6),
            inertias=(1e-13, 1e-12, 5e-13),
            speed=20000.0,
            count=13,
        ),
        [],
    ),
    (
        "sweep 0..6.2832 typed as degrees",
        ks.load_scene,
        fb(drv_start=0.0, drv_stop=6.2832),
        ["positions"],
    ),
    (
        "sweep 0..3.1416 (half a turn, fractional)",
        ks.load_scene,
        fb(drv_start=0.0, drv_stop=3.1416),
        ["positions"],
    ),
    ("sweep 10..12 deg", ks.load_scene, fb(drv_start=10.0, drv_stop=12.0), []),
    (
        "sweep 0..360 under angle = rad",
        ks.load_scene,
        {**fb(), "units": {"angle": "rad"}},
        ["positions"],
    ),
    (
        "sweep 0..6.28 under angle = rad",
        ks.load_scene,
        {**fb(drv_start=0.0, drv_stop=6.283185307179586), "units": {"angle": "rad"}},
        [],
    ),
    (
        "cog 50 mm typed in an m scene",
        ks.load_scene,
        (lambda d: (d["bodies"][0].update(cog=[50.0, 0.0]), d)[1])(fb()),
        ["lengths"],
    ),
    (
        "crank 1.2 kg typed under mass = t",
        ks.load_scene,
        {**fb(), "units": {"mass": "t"}},
        ["mass"],
    ),
    (
        "heavy real flywheel crank 30 kg",
        ks.load_scene,
        (lambda d: (d["bodies"][0].update(mass=30.0, inertia=0.15), d)[1])(fb()),
        [],
    ),
    ("point-mass piston 1.5 kg", ks.load_scene, piston(1.5), []),
    ("point-mass piston 1.5 kg in mm/g", ks.load_scene, mm(piston(1.5)), []),
    ("point-mass piston 40 kg (a heavy ram)", ks.load_scene, piston(40.0), []),
    ("near-point piston 3 kg, inertia 1e-6", ks.load_scene, piston(3.0, 1e-6), []),
    ("point-mass piston 1500: grams as kg", ks.load_scene, piston(1500.0), ["mass"]),
    (
        "point-mass piston under mass = t",
        ks.load_scene,
        {**piston(1.5), "units": {"mass": "t"}},
        ["mass"],
    ),
    (
        "speed_rpm 120000 on a 15 mm spindle",
        ks.load_scene,
        (lambda d: (d["driver"].pop("speed"), d["driver"].update(speed_rpm=120000.0), d)[2])(
            four_bar(
                0.005,
                0.0125,
                0.01,
                0.015,
                masses=(1e-3, 2e-3, 1.5e-3),
                inertias=(1e-9, 1e-8, 5e-9),
                count=13,
            )
        ),
        [],
    ),
    (
        "motion omega0 300 as rad/s",
        ks.load_scene,
        (lambda d: (d["motion"].update(omega0=300.0), d)[1])(ex("four_bar_motion")),
        ["speed"],
    ),
    (
        "motion omega0 31.4",
        ks.load_scene,
        (lambda d: (d["motion"].update(omega0=31.4), d)[1])(ex("four_bar_motion")),
        [],
    ),
    (
        "cam segments in radians",
        load_cam_scene,
        cam(
            segments=[
                {"kind": "rise", "law": "cosine-acceleration", "angle": 1.5708},
                {"kind": "dwell", "angle": 1.0472},
                {"kind": "return", "law": "cosine-acceleration", "angle": 2.0944},
                {"kind": "dwell", "angle": 2.0944},
            ]
        ),
        ["angles"],
    ),
    (
        "cam speed 3000 rad/s (rpm typed)",
        load_cam_scene,
        cam(speed_rpm=None, speed=3000.0),
        ["speed"],
    ),
    ("cam speed_rpm 3000 (real)", load_cam_scene, cam(speed_rpm=3000.0), []),
    ("oscillating 4.5 deg swing", load_cam_scene, osc(stroke_angle=4.5), []),
    (
        "rotor phases in radians",
        balance.solve,
        rotor([0.02, 0.015, 0.01], [0.5236, 2.618, 4.1]),
        ["angles"],
    ),
    (
        "rotor smallest mass in g (667x)",
        balance.solve,
        rotor([0.03, 0.045, 20.0], [30.0, 150.0, 270.0]),
        ["unbalance_mass"],
    ),
    (
        "rotor 0.15 g clip beside 200 g",
        balance.solve,
        rotor([200.0, 0.15], [30.0, 150.0], {"mass": "g"}),
        [],
    ),
    ("rotor typed in t", balance.solve, rotor([2e-5, 1.5e-5], [30.0, 150.0], {"mass": "t"}), []),
    ("influence 0.3 g fan trial", balance.solve, INF(0.3), []),
    ("influence 5 g typed as kg", balance.solve, INF(5.0, units='mass = "kg"'), ["trial_mass"]),
    ("influence phases radians", balance.solve, INF(100.0, (4.3633, 2.7925)), ["angles"]),
    (
        "static alpha 0.4363 (single)",
        balance.solve,
        "[static_test]\ndisk_mass = 5.0\ncomparison_mass = 0.05\ncomparison_radius = 0.1\n"
        "alpha = 0.4363\ncorrection_radius = 0.08\n",
        [],
    ),
    (
        "split at 4.5 deg",
        balance.solve,
        '[units]\nmass = "g"\n[[split]]\nmass = 10.0\nangle = 4.5\npositions = 12\n',
        [],
    ),
    (
        "iso 500 kg rotor, 3 kg trial",
        balance.solve,
        INF(3.0, units='mass = "kg"')
        + "[iso]\nrotor_mass = 500.0\ngrade = 6.3\nspeed_rpm = 3000.0\n",
        [],
    ),
]


@pytest.mark.parametrize(("name", "load", "scene", "want"), CASES, ids=[c[0] for c in CASES])
def test_scenes_near_the_rules_edges(name, load, scene, want) -> None:
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        try:
            load(copy.deepcopy(scene))
        except ks.WorkbenchError as exc:
            assert "radians" in name and "add up to" in str(exc), exc
    rules = sorted(
        {
            str(w.message).split('quiet = ["')[1].split('"')[0]
            for w in seen
            if 'quiet = ["' in str(w.message)
        }
    )
    assert rules == sorted(want), [str(w.message) for w in seen]
