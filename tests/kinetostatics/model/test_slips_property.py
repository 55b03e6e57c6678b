"""Properties of the units stage and the slip rules (issue 30): a random scene typed in
SI, mm/g/rpm, in/t or cm (and with its angles in radians) reads back to the same SI
numbers within 1e-12 relative and gives the same warnings, field by field and rule by
rule; every bundled scene and every complete scene of the docs is silent.

The conversion here is the test's own, from the units' definitions (1 in = 0.0254 m,
1 rpm = pi/30 rad/s...), independent of :mod:`kinetostatics.model.units`.
"""

from __future__ import annotations

import math
import re
import tomllib
import warnings
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import balance
import kinetostatics as ks
from balance.errors import BalanceWarning
from kinetostatics.cams import load_cam_scene
from tests.kinetostatics.scenes import four_bar

ROOT = Path(__file__).resolve().parents[3]
LENGTH = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254}
MASS = {"kg": 1.0, "g": 1e-3, "t": 1e3}
SPEED = {"rad/s": 1.0, "rpm": math.pi / 30.0}
ANGLE = {"deg": 1.0, "rad": 180.0 / math.pi}       # one unit in degrees
SYSTEMS = {
    "SI": {},
    "mm/g/rpm": {"length": "mm", "mass": "g", "speed": "rpm"},
    "in/t": {"length": "in", "mass": "t"},
    "cm": {"length": "cm"},
    "mm/rad": {"length": "mm", "angle": "rad"},
}


def factors(units: dict) -> tuple[float, float, float, float]:
    return (LENGTH[units.get("length", "m")], MASS[units.get("mass", "kg")],
            SPEED[units.get("speed", "rad/s")], ANGLE[units.get("angle", "deg")])


def mechanism_in(si: dict, units: dict) -> dict:
    """The four-bar ``si`` (SI, degrees) typed in ``units``."""
    L, M, W, A = factors(units)

    def pts(table: dict) -> dict:
        return {k: [c / L for c in v] for k, v in table.items()}

    out = {**si, "units": dict(units), "ground": pts(si["ground"]), "near": pts(si["near"])}
    if "gravity" in si:
        out["gravity"] = [g / L for g in si["gravity"]]
    out["bodies"] = [{**b, "mass": b["mass"] / M, "inertia": b["inertia"] / (M * L * L),
                      "cog": [c / L for c in b["cog"]], "points": pts(b["points"])}
                     for b in si["bodies"]]
    d = si["driver"]
    out["driver"] = {**d, "speed": d["speed"] / W, "start": d["start"] / A,
                     "stop": d["stop"] / A}
    return out


def slips_of(load, source, category=ks.UnitWarning) -> list[tuple[str, str]]:
    """(field, rule) of each unit-slip warning of reading ``source``."""
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        load(source)
    out = []
    for w in seen:
        text = str(w.message)
        if issubclass(w.category, category) and 'quiet = ["' in text:
            out.append((text.split(" = ")[0], text.split('quiet = ["')[1].split('"')[0]))
    return sorted(out)


def numbers(sc) -> list[float]:
    """Every number of a read mechanism scene, in a fixed order."""
    out = [*sc.gravity, sc.driver.speed, sc.driver.acceleration, *sc.driver.positions]
    for p in (*sc.ground.values(), *sc.near.values()):
        out += p
    for b in sc.bodies.values():
        out += [b.mass, b.inertia, *b.cog]
        for p in b.points.values():
            out += p
    return out


def close(a: list[float], b: list[float], rel: float = 1e-12) -> bool:
    scale = max(abs(x) for x in a) or 1.0
    return len(a) == len(b) and all(abs(x - y) <= rel * max(abs(x), 1e-300) or
                                    abs(x - y) <= 1e-15 * scale for x, y in zip(a, b,
                                                                                 strict=True))


@st.composite
def mechanisms(draw) -> dict:
    """A four-bar of random size, masses, speed, gravity and sweep; some draws slipped
    (a speed in rpm typed as rad/s, gravity in mm/s^2 or 1000 x, a mass in g typed as
    kg, a sweep in radians typed as degrees)."""
    k = draw(st.sampled_from([0.01, 0.1, 1.0, 5.0]))
    a, b, c, d = (x * k for x in (0.1, 0.25, 0.2, 0.3))
    rho = draw(st.floats(50.0, 8000.0))             # kg/m^3 over the cube of the size
    masses = tuple(rho * (0.3 * k) ** 3 * f for f in (0.4, 1.0, 0.7))
    inertias = tuple(m * (s / 2) ** 2 / 3 for m, s in zip(masses, (a, b, c), strict=True))
    speed = draw(st.one_of(st.floats(0.5, 80.0 / k), st.floats(3000.0 / k, 1e5 / k)))
    gravity = draw(st.sampled_from([[0.0, -9.81], [0.0, 0.0], [0.0, -9.81e-3],
                                    [0.0, -9810.0], [0.0, -1.62]]))
    start = draw(st.floats(-180.0, 180.0))
    span = draw(st.sampled_from([360.0, 2.0, 6.2, 45.3, 180.0]))
    scene = four_bar(a, b, c, d, masses=masses, inertias=inertias, speed=speed,
                     start=start, stop=start + span, count=13, gravity=gravity)
    if draw(st.booleans()):
        scene["bodies"][1]["mass"] *= 1000.0        # grams typed as kilograms
    return scene


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(si=mechanisms(), system=st.sampled_from(sorted(SYSTEMS)))
def test_a_mechanism_in_other_units_reads_back_with_the_same_warnings(si, system) -> None:
    other = mechanism_in(si, SYSTEMS[system])
    assert slips_of(ks.load_scene, other) == slips_of(ks.load_scene, si)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ks.UnitWarning)
        a, b = ks.load_scene(si), ks.load_scene(other)
    assert close(numbers(a), numbers(b))            # measured: within 3 ulp


@st.composite
def rotors(draw) -> dict:
    """A two-plane rotor (SI, degrees): two to four unbalances of random mass, radius,
    angle and place; some draws slipped (one mass in g typed as kg, the angles in
    radians typed as degrees)."""
    n = draw(st.integers(2, 4))
    masses = [draw(st.floats(1e-3, 0.5)) for _ in range(n)]
    if draw(st.booleans()):
        masses[0] *= 1000.0
    angles = [draw(st.floats(0.0, 359.0)) for _ in range(n)]
    if draw(st.booleans()):
        angles = [math.radians(x) for x in angles]
    ub = [{"mass": m, "radius": draw(st.floats(0.01, 0.5)), "angle": ang,
           "z": draw(st.floats(0.0, 1.0))} for m, ang in zip(masses, angles, strict=True)]
    return {"rotor": {"unbalance": ub, "planes": [{"z": -0.1, "radius": 0.2},
                                                  {"z": 1.1, "radius": 0.25}]}}


def rotor_in(si: dict, units: dict) -> dict:
    L, M, _, A = factors(units)
    r = si["rotor"]
    return {"units": dict(units), "rotor": {
        "unbalance": [{"mass": u["mass"] / M, "radius": u["radius"] / L,
                       "angle": u["angle"] / A, "z": u["z"] / L} for u in r["unbalance"]],
        "planes": [{"z": p["z"] / L, "radius": p["radius"] / L} for p in r["planes"]]}}


def rotor_numbers(out: dict) -> list[float]:
    return [x for c in out["rotor"]["corrections"] for x in (c["mass"], c["angle"])]


@settings(max_examples=40, deadline=None)
@given(si=rotors(), system=st.sampled_from(sorted(SYSTEMS)))
def test_a_rotor_in_other_units_reads_back_with_the_same_warnings(si, system) -> None:
    other = rotor_in(si, SYSTEMS[system])
    assert (slips_of(balance.solve, other, BalanceWarning)
            == slips_of(balance.solve, si, BalanceWarning))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BalanceWarning)
        a, b = balance.solve(si), balance.solve(other)
    assert close(rotor_numbers(a), rotor_numbers(b), 1e-11)   # measured: 2e-15


def bundled() -> list[tuple[str, Path]]:
    out = [("kinetostatics", p) for p in sorted((ROOT / "kinetostatics/scenes").rglob("*.toml"))]
    return out + [("balance", p) for p in sorted((ROOT / "balance/scenes").glob("*.toml"))]


@pytest.mark.parametrize("path", [p for _, p in bundled()], ids=lambda p: p.stem)
def test_every_bundled_scene_is_silent(path) -> None:
    """No warning at all (not only no slip) from reading or solving a bundled scene."""
    text = path.read_text()
    read_with_warnings_as_errors(path, "cam" if "[cam]" in text else
                                 "mechanism" if "[driver]" in text else "balancing")


def read_with_warnings_as_errors(source, kind: str) -> None:
    """Read (a cam, a mechanism) or solve (a balancing scene) ``source``, any warning
    raised as an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        {"cam": load_cam_scene, "mechanism": ks.load_scene}.get(kind, balance.solve)(source)


def doc_scenes() -> list[tuple[str, str]]:
    """The complete scenes among the docs' TOML blocks (a fragment is left out)."""
    out = []
    for doc in sorted((ROOT / "docs").glob("*.md")):
        for i, m in enumerate(re.finditer(r"```toml\n(.*?)```", doc.read_text(), re.S)):
            raw = tomllib.loads(m.group(1))
            excerpt = "driver" in raw and "piston" in m.group(1)   # its bodies left out
            if excerpt:
                continue
            if ("cam" in raw and "segments" in raw["cam"]) or "driver" in raw or any(
                    k in raw for k in ("rotor", "influence", "static_test", "resonance_test",
                                       "split", "combine", "iso")):
                out.append((f"{doc.stem}[{i}]", m.group(1)))
    return out


@pytest.mark.parametrize("text", [t for _, t in doc_scenes()],
                         ids=[n for n, _ in doc_scenes()])
def test_every_complete_scene_of_the_docs_is_silent(text) -> None:
    raw = tomllib.loads(text)
    read_with_warnings_as_errors(text, "cam" if "cam" in raw else
                                 "mechanism" if "driver" in raw else "balancing")
