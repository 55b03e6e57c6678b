"""The field-balancing scene sections ([units], [[influence]] with trim runs, [iso],
[[split]], [[combine]]) through balance.solve, against hand-worked numbers."""

from __future__ import annotations

import cmath
import json
import math

import numpy as np
import pytest

import balance
from balance import example_path, examples
from kinetostatics.model.errors import WorkbenchError
from tests.balance._balance_cases import INFLUENCE_TWO_PLANE

FIELD_EXAMPLES = ("influence_two_plane", "influence_speeds", "trim_run", "iso_tolerance",
                  "split_combine")


def error_of(scene) -> str:
    with pytest.raises(WorkbenchError) as exc:
        balance.solve(scene)
    msg = str(exc.value)
    assert msg and "\n" not in msg and isinstance(exc.value, ValueError)
    return msg


def test_examples_are_bundled_and_json_ready() -> None:
    for name in FIELD_EXAMPLES:
        assert name in examples()
        out = balance.solve(example_path(name))
        json.dumps(out, allow_nan=False)               # no NaN anywhere


def test_published_case_from_the_scene() -> None:
    """B&K two-plane case: 1.979 g at 236.2 deg and 1.071 g at 121.8 deg; the split onto
    12 holes: positions 8 (210) and 9 (240) by the law of sines."""
    r = balance.solve(example_path("influence_two_plane"))["influence"][0]
    assert r["name"] == "fan, two planes"
    c1, c2 = r["corrections"]
    assert (round(c1["mass"], 3), round(c1["angle"], 1)) == (1.979, 236.2)
    assert (round(c2["mass"], 3), round(c2["angle"], 1)) == (1.071, 121.8)
    for c in (c1, c2):
        lo, hi = c["interval"]["mass"]
        assert lo < c["mass"] < hi
    p = c1["split"]["placements"]
    assert [q["position"] for q in p] == [8, 9]
    th = math.radians(c1["angle"])
    assert p[0]["mass"] == pytest.approx(c1["mass"] * math.sin(math.radians(240) - th)
                                         / math.sin(math.radians(30)), rel=1e-12)
    assert r["warnings"] == []
    assert [x["point"] for x in r["residual_vibration"]] == ["bearing A", "bearing B"]
    assert balance.solve(example_path("influence_two_plane"))["scene_units"]["mass"] == "g"


def test_two_speeds_recover_the_machine() -> None:
    """Readings made with a known linear machine (12 g at 20 deg, 8 g at 150 deg),
    rounded to 0.1 um and 0.1 deg: recovered to 0.015 g and 0.15 deg (measured 0.0043 g,
    0.059 deg)."""
    r = balance.solve(example_path("influence_speeds"))["influence"][0]
    for c, (m, a) in zip(r["corrections"], [(12.0, 20.0), (8.0, 150.0)], strict=True):
        assert c["mass"] == pytest.approx(m, abs=0.015)
        assert c["angle"] == pytest.approx(a, abs=0.15)
    assert len(r["coefficients"]) == 4 and len(r["coefficients"][0]) == 2


def test_trim_example_by_hand() -> None:
    """alpha' = (V1 - V0) / C from the scene's numbers; trim correction -V1 / alpha'."""
    V0, V1 = cmath.rect(20.0, math.radians(180.0)), cmath.rect(4.2, math.radians(226.1))
    C = cmath.rect(21.7, math.radians(290.0))
    a = (V1 - V0) / C
    W = -V1 / a
    r = balance.solve(example_path("trim_run"))["influence"][0]
    assert r["trim_runs"] == 1
    assert r["coefficients"][0][0]["amplitude"] == pytest.approx(abs(a), rel=1e-12)
    assert r["corrections"][0]["mass"] == pytest.approx(abs(W), rel=1e-12)
    assert r["corrections"][0]["angle"] == pytest.approx(math.degrees(cmath.phase(W)) % 360,
                                                         abs=1e-9)


def test_iso_example_by_hand() -> None:
    """U_per = 1000 G m / Omega in g mm; check of the measured residuals by the
    statics of a force and a moment (solved here as a 2x2 system)."""
    out = balance.solve(example_path("iso_tolerance"))
    s = out["iso"]
    U = 1000.0 * 6.3 * 10.0 / (3000.0 * 2.0 * math.pi / 60.0)
    assert s["U_per"] == pytest.approx(U, rel=1e-12)
    assert s["e_per"] == pytest.approx(U / 10.0 / 1000.0, rel=1e-12)     # mm
    assert [b["permissible"] for b in s["bearing_planes"]] == pytest.approx([0.6 * U, 0.4 * U])
    U1, U2 = cmath.rect(60.0, math.radians(30.0)), cmath.rect(45.0, math.radians(250.0))
    ua, ub = np.linalg.solve([[1.0, 1.0], [0.0, 600.0]], [U1 + U2, 100.0 * U1 + 500.0 * U2])
    assert s["check"]["bearing_residual"] == pytest.approx([abs(ua), abs(ub)], rel=1e-12)
    assert s["check"]["ok"] is True and s["check"]["exact"] is True


def test_iso_in_si_and_failing_check() -> None:
    s = balance.solve({"iso": {"grade": 2.5, "rotor_mass": 4.0, "speed_rpm": 6000.0,
                               "bearings": [0.0, 0.4], "cog": 0.2,
                               "residual": [20e-6, 5e-6]}})["iso"]
    U = 1e-6 * 1000.0 * 2.5 * 4.0 / (6000.0 * math.pi / 30.0)            # kg m
    assert s["U_per"] == pytest.approx(U, rel=1e-12) and s["unbalance_unit"] == "kg m"
    assert s["check"]["ok"] is False
    assert any("exceeds" in w for w in s["warnings"])


def test_split_and_combine_sections() -> None:
    out = balance.solve(example_path("split_combine"))
    sp, cb = out["split"][0], out["combine"][0]
    assert [p["position"] for p in sp["placements"]] == [3, 4]
    x = (3.0 * 120.0 + 4.0 * 100.0 * math.cos(math.radians(200.0))) / 120.0
    y = (2.0 * 120.0 + 4.0 * 100.0 * math.sin(math.radians(200.0))) / 120.0
    assert cb["mass"] == pytest.approx(math.hypot(x, y), rel=1e-12)


BASE = INFLUENCE_TWO_PLANE


@pytest.mark.parametrize("old, new, expected", [
    ("initial =", "inital =", "did you mean 'initial'"),
    ("runs =", "coefficients = [[[1.0, 0.0]]]\nruns =", "runs (trial runs) or coefficients"),
    ("plane = 2, mass", "plane = 2, mas", "did you mean 'mass'"),
    ("[58.0, 68.0]]", "[58.0, 68.0, 1.0]]", "[amplitude, phase_deg]"),
    ("[[influence]]", "[units]\nmass = \"lb\"\n[[influence]]", "unknown unit 'lb'"),
    ("[[influence]]", "[influence]", "write [[influence]]"),
    ("runs =", "noise = { relative = 0.0 }\nphase_noise = 0.0\nruns =", "all 0"),
    ("runs =", "split = 2\nruns =", "split.positions"),
    ("runs =", "points = [\"A\"]\nruns =", "1 names for 2 readings"),
])
def test_influence_scene_errors(old, new, expected) -> None:
    assert old in BASE
    assert expected in error_of(BASE.replace(old, new, 1))


def test_units_beside_seed_sections_apply_to_them() -> None:
    """[units] now applies to every section (issue 18): the static test in g and mm gives
    the SI result of the same test in kg and m; the influence section stays in g."""
    si = '[static_test]\ndisk_mass = 5.0\ncomparison_mass = 0.05\ncomparison_radius = 0.1\n' \
        'alpha = 25.0\ncorrection_radius = 0.08\n'
    text = BASE + '\n[units]\nmass = "g"\nlength = "mm"\n\n[static_test]\ndisk_mass = 5000.0\n' \
        'comparison_mass = 50.0\ncomparison_radius = 100.0\nalpha = 25.0\n' \
        'correction_radius = 80.0\n'
    out = balance.solve(text)
    ref = balance.solve(si)["static_test"]
    assert out["static_test"]["correction_mass"] == pytest.approx(ref["correction_mass"],
                                                                  rel=1e-14)
    assert out["scene_units"]["mass"] == "g" and out["scene_units"]["length"] == "mm"
    assert out["influence"][0]["corrections"]


@pytest.mark.parametrize("body, expected", [
    ("grade = 6.3\nrotor_mass = 10.0", "missing required key 'speed_rpm'"),
    ("grade = 6.3\nrotor_mass = 10.0\nspeed_rpm = 3000\nbearings = [0.0, 1.0]",
     "need cog"),
    ("grade = 6.3\nrotor_mass = 10.0\nspeed_rpm = 3000\nplanes = [0.1, 0.2]", "need bearings"),
    ("grade = 6.3\nrotor_mass = 10.0\nspeed_rpm = 3000\nresidual = [1.0, [2.0, 3.0]]",
     "every residual"),
    ("grade = 6.3\nrotor_mass = 10.0\nspeed_rpm = 3000\nresidual = [1.0, 2.0]",
     "2 values for one"),
    ("grade = 6.3\nrotor_mass = 10.0\nspeed_rpm = 3000\nnarrow = true", "narrow = true needs"),
])
def test_iso_scene_errors(body, expected) -> None:
    assert expected in error_of("[iso]\n" + body + "\n")


def test_iso_single_correction_plane_takes_the_whole_u_per() -> None:
    s = balance.solve({"iso": {"grade": 2.5, "rotor_mass": 30.0, "speed_rpm": 1800.0,
                               "bearings": [0.0, 0.8], "cog": 0.4, "planes": [0.35],
                               "residual": [300e-6]}})["iso"]
    U = 1000.0 * 2.5 * 30.0 / (1800.0 * math.pi / 30.0) * 1e-6
    assert s["check"]["permissible"] == pytest.approx([U], rel=1e-12)
    assert s["check"]["ratio"] == pytest.approx([300e-6 / U], rel=1e-12)
    assert s["check"]["ok"] is True
