"""Unit slips judged on the physical quantity (kinetostatics.model.slips): the legitimate
scenes that were warned are silent, the slips that passed are warned, each warning names
its field and rule, and the same scene typed in other units gives the same warnings and
the same SI numbers."""

from __future__ import annotations

import copy
import math
import tomllib
import warnings

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.slips import RULES


def four_bar() -> dict:
    with open(ks.example("four_bar"), "rb") as fh:
        return tomllib.load(fh)


def slips(d: dict, load=ks.load_scene) -> list[str]:
    """The UnitWarnings of reading ``d``, as 'field: rule' (the field before ' = ', the
    rule named in the quiet key)."""
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        load(d)
    out = []
    for w in seen:
        if issubclass(w.category, ks.UnitWarning):
            text = str(w.message)
            rule = text.split('quiet = ["')[1].split('"')[0]
            out.append(f"{text.split(' = ')[0]}: {rule}")
    return out


# ---- one independent conversion of the four-bar (factors by definition) -------------
SYSTEMS = {
    "SI": {"length": "m", "mass": "kg", "speed": "rad/s"},
    "mm/g/rpm": {"length": "mm", "mass": "g", "speed": "rpm"},
    "in/t": {"length": "in", "mass": "t"},
    "cm": {"length": "cm"},
}
LENGTH = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254}
MASS = {"kg": 1.0, "g": 1e-3, "t": 1e3}
SPEED = {"rad/s": 1.0, "rpm": math.pi / 30.0}


def typed_in(d: dict, units: dict) -> dict:
    """The four-bar scene ``d`` (SI) written in ``units``."""
    L, M = LENGTH[units["length"]], MASS[units.get("mass", "kg")]
    W = SPEED[units.get("speed", "rad/s")]
    out = copy.deepcopy(d)
    out["units"] = dict(units)

    def pt(p):
        return [c / L for c in p]

    out["gravity"] = pt(d["gravity"])
    out["ground"] = {k: pt(v) for k, v in d["ground"].items()}
    out["near"] = {k: pt(v) for k, v in d["near"].items()}
    for b in out["bodies"]:
        b["mass"] /= M
        b["inertia"] /= M * L * L
        b["cog"] = pt(b["cog"])
        b["points"] = {k: pt(v) for k, v in b["points"].items()}
    for ld in out["loads"]:
        ld["moment"] = ld.get("moment", 0.0) / L
    out["driver"]["speed"] = d["driver"]["speed"] / W
    return out


SLIPPED = {
    "speed 3000 rad/s": lambda d: d["driver"].update(speed=3000.0),
    "gravity 9.81e-3": lambda d: d.update(gravity=[0.0, -9.81e-3]),
    "mass 1200 kg": lambda d: d["bodies"][0].update(mass=1200.0),
    "none": lambda d: None,
}


@pytest.mark.parametrize("slip", SLIPPED)
@pytest.mark.parametrize("system", SYSTEMS)
def test_the_same_scene_in_other_units_gives_the_same_warnings_and_numbers(slip,
                                                                           system) -> None:
    si = four_bar()
    SLIPPED[slip](si)
    other = typed_in(si, SYSTEMS[system])
    assert slips(other) == slips(si)
    assert (slips(si) == []) == (slip == "none")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ks.UnitWarning)
        a, b = ks.solve(si), ks.solve(other)
    me_a, me_b = a.driver["Me"].to_numpy(), b.driver["Me"].to_numpy()
    assert np.max(np.abs(me_a - me_b)) <= 1e-12 * np.max(np.abs(me_a))   # measured 4e-15


def sweep(start: float, stop: float, count: int = 20, units: dict | None = None) -> dict:
    d = four_bar()
    d["driver"].update(start=start, stop=stop, count=count)
    if units:
        d["units"] = units
    return d


def scaled(k: float) -> dict:
    """The four-bar scaled by k (lengths), masses by k^3 and inertias by k^5."""
    d = four_bar()
    s = typed_in(d, {"length": "m"})
    for key in ("ground", "near"):
        s[key] = {n: [c * k for c in p] for n, p in d[key].items()}
    for b in s["bodies"]:
        b["mass"] *= k**3
        b["inertia"] *= k**5
        b["cog"] = [c * k for c in b["cog"]]
        b["points"] = {n: [c * k for c in p] for n, p in b["points"].items()}
    return s


LEGITIMATE = {
    "a 40..46.3 deg sweep": lambda: sweep(40.0, 46.3),
    "a 2 deg sweep": lambda: sweep(0.0, 2.0),
    "a 5 deg sweep": lambda: sweep(0.0, 5.0, 6),
    "a fractional 2.5 deg sweep": lambda: sweep(0.5, 3.0),
    "speed_rpm = 120000 on a 15 mm spindle": lambda: _rpm(scaled(0.05), 120000.0),
    "speed = 120000 under speed = rpm": lambda: _rpm(scaled(0.05), 120000.0, units=True),
    "900 rad/s on the four-bar": lambda: _speed(four_bar(), 900.0),
    "a sweep in radians said so": lambda: sweep(0.0, 2 * math.pi, units={"angle": "rad"}),
    "gravity on the moon": lambda: {**four_bar(), "gravity": [0.0, -1.62]},
}


def _rpm(d: dict, n: float, units: bool = False) -> dict:
    d["driver"].pop("speed")
    if units:
        d["units"] = {**d.get("units", {}), "speed": "rpm"}
        d["driver"]["speed"] = n
    else:
        d["driver"]["speed_rpm"] = n
    return d


def _speed(d: dict, w: float) -> dict:
    d["driver"]["speed"] = w
    return d


@pytest.mark.parametrize("case", LEGITIMATE)
def test_legitimate_scenes_are_not_warned(case) -> None:
    assert slips(LEGITIMATE[case]()) == []


def _t_scene() -> dict:
    d = four_bar()
    d["units"] = {"mass": "t"}                         # the masses left in kg
    return d


def _mm_gravity() -> dict:
    with open(ks.example("four_bar_mm"), "rb") as fh:
        d = tomllib.load(fh)
    d["gravity"] = [0.0, -9.81]                        # m/s^2 under length = "mm"
    return d


def _omega0() -> dict:
    with open(ks.example("four_bar_motion"), "rb") as fh:
        d = tomllib.load(fh)
    d["motion"]["omega0"] = 300.0                      # 300 rpm typed as rad/s
    return d


SLIPS = {
    "3000 rpm typed as rad/s": (lambda: _speed(four_bar(), 3000.0), "driver.speed: speed"),
    "speed = 2400 without rpm": (lambda: _speed(four_bar(), 2400.0), "driver.speed: speed"),
    "positions 0..6 as whole radians": (lambda: sweep(0.0, 6.0, 7),
                                        "driver.start..stop: positions"),
    "degrees under angle = rad": (lambda: sweep(0.0, 360.0, units={"angle": "rad"}),
                                  "driver.start..stop: positions"),
    "kilograms under mass = t": (_t_scene, "body 'crank'.mass: mass"),
    "m/s^2 under length = mm": (_mm_gravity, "gravity: gravity"),
    "omega0 300 rpm as rad/s": (_omega0, "motion.omega0: speed"),
}


@pytest.mark.parametrize("case", SLIPS)
def test_slips_are_warned_with_field_and_rule(case) -> None:
    make, expected = SLIPS[case]
    got = slips(make())
    assert expected in got, got


def test_a_warning_says_the_value_as_typed_and_how_to_silence_it() -> None:
    d = _speed(four_bar(), 3000.0)
    d["units"] = {"speed": "rpm"}
    d["driver"]["speed"] = 3000.0 * 30 / math.pi       # 3000 rad/s typed in rpm
    with pytest.warns(ks.UnitWarning) as seen:
        sc = ks.load_scene(d)
    text = str(seen[0].message)
    assert text.startswith("driver.speed = 28647.9 rpm:") and "rpm typed for rad/s" in text
    assert sc.warnings == (text,)
    d["checks"] = {"quiet": ["speed"]}
    assert slips(d) == []
    with pytest.raises(ks.SceneError, match="unknown rule 'sped'.*did you mean 'speed'"):
        ks.load_scene({**d, "checks": {"quiet": ["sped"]}})


@pytest.mark.parametrize("name", ks.examples() if hasattr(ks, "examples") else [])
def test_bundled_scenes_have_no_warning(name) -> None:
    path = ks.example(name)
    text = path.read_text()
    if "[cam]" in text:
        from kinetostatics.cams import load_cam_scene
        assert slips(path, load_cam_scene) == []
    elif "[driver]" in text:
        assert slips(path) == []


def test_every_rule_is_documented() -> None:
    from pathlib import Path
    doc = (Path(__file__).resolve().parents[3] / "docs" / "scene-format.md").read_text()
    for rule in RULES:
        assert f"`{rule}`" in doc, rule


@pytest.mark.slow     # the quick tier keeps test_one_positions_rule_for_mechanism_and_motion_scenes
def test_motion_positions_follow_the_mechanism_rule() -> None:
    """One positions rule for mechanism and [motion] scenes: any order (the same summary,
    rows in the list's order), a repeat refused with one line."""
    with open(ks.example("four_bar_motion"), "rb") as fh:
        d = tomllib.load(fh)
    for k in ("start", "stop", "count"):
        d["driver"].pop(k, None)
    d["driver"]["positions"] = [90.0, 0.0, 180.0, 270.0]
    mixed = ks.simulate_motion(d)
    d["driver"]["positions"] = [0.0, 90.0, 180.0, 270.0]
    plain = ks.simulate_motion(d)
    assert mixed.summary == plain.summary
    assert mixed.motion["position"].tolist()[:4] == [90.0, 0.0, 180.0, 270.0]
    assert mixed.motion["omega"].iloc[1] == plain.motion["omega"].iloc[0]
    d["driver"]["positions"] = [90.0, 0.0, 90.0]
    with pytest.raises(ks.SceneError, match="90 deg is listed more than once") as exc:
        ks.simulate_motion(d)
    assert "\n" not in str(exc.value)


def test_every_key_of_every_scene_kind_is_documented() -> None:
    """docs/scene-format.md names every key the readers accept."""
    from pathlib import Path

    import balance.model.field_scene as field
    import balance.model.scene as bal
    import kinetostatics.cams.scene as cam
    import kinetostatics.model.scene as mech
    doc = (Path(__file__).resolve().parents[3] / "docs" / "scene-format.md").read_text()
    keys = {*mech.TOP_KEYS, *mech.DRIVER_KEYS, *mech.BODY_KEYS, *mech.JOINT_KEYS_R,
            *mech.JOINT_KEYS_T, *mech.LOAD_KEYS, *mech.MOTION_KEYS, *bal.ROTOR_KEYS,
            *bal.UNBALANCE_KEYS, *bal.PLANE_KEYS, *bal.STATIC_KEYS, *bal.RESONANCE_KEYS,
            *bal.RUN_KEYS, *bal.NOISE_KEYS, *field.INFLUENCE_KEYS, *field.RUN_KEYS,
            *field.SPLIT_KEYS, *field.SPLIT_SECTION_KEYS, *field.COMBINE_KEYS,
            *field.WEIGHT_KEYS, *field.ISO_KEYS, *cam.CAM_KEYS, *cam.SEGMENT_KEYS,
            *(k for ks_ in cam.FOLLOWER_KEYS.values() for k in ks_),
            *(k for ks_ in cam.LOAD_KEYS.values() for k in ks_), "checks", "quiet"}
    missing = sorted(k for k in keys if f"`{k}`" not in doc and f"{k} =" not in doc
                     and f"[{k}]" not in doc and f"[[{k}]]" not in doc)
    assert missing == []


def test_errors_quote_the_value_as_typed() -> None:
    """'got -350 g', '255 mm is listed more than once': the user's numbers, not SI."""
    with open(ks.example("four_bar_mm"), "rb") as fh:
        d = tomllib.load(fh)
    d["bodies"][0]["mass"] = -350.0
    with pytest.raises(ks.SceneError, match=r"'crank'\.mass must not be negative, got -350 g$"):
        ks.load_scene(d)
    with open(ks.example("sliding_driver"), "rb") as fh:
        d = tomllib.load(fh)
    for k in ("start", "stop", "count"):
        d["driver"].pop(k)
    d["units"] = {"length": "mm"}
    d = typed_lengths_mm(d)
    d["driver"]["positions"] = [200.0, 255.00000000000003, 300.0, 255.00000000000003]
    with pytest.raises(ks.SceneError, match=r"^driver positions: 255 mm is listed more"):
        ks.solve(d)
    with pytest.raises(ks.SceneError, match=r"^scenes\[0\]: driver positions: 255 mm is"):
        ks.solve_many([d])


def typed_lengths_mm(d: dict) -> dict:
    """The sliding-driver scene's lengths (and forces' moments) written in mm."""
    out = copy.deepcopy(d)

    def pt(p):
        return [c * 1000.0 for c in p]
    out["ground"] = {k: pt(v) for k, v in d.get("ground", {}).items()}
    if "gravity" in d:
        out["gravity"] = pt(d["gravity"])
    out["near"] = {k: pt(v) for k, v in d.get("near", {}).items()}
    for b in out["bodies"]:
        b["inertia"] = b.get("inertia", 0.0) * 1e6
        if "cog" in b:
            b["cog"] = pt(b["cog"])
        b["points"] = {k: pt(v) for k, v in b["points"].items()}
    for ld in out.get("loads", []):
        if "moment" in ld:
            ld["moment"] *= 1000.0
    return out


def test_an_assembly_error_is_said_in_the_scene_units() -> None:
    """A mm scene that does not assemble says its gap in mm (2.36 mm, not 0.00236 m),
    and its positions in the scene's angle unit."""
    with open(ks.example("four_bar_mm"), "rb") as fh:
        d = tomllib.load(fh)
    d["ground"]["D"] = [552.36, 0.0]        # crank 100 + coupler 250 + rocker 200 = 550
    with pytest.raises(ks.AssemblyError, match=r"at the first driver position 0 deg: the links "
                                            r"do not reach by 2\.36 mm;"):
        ks.solve(d)
    d["units"]["angle"] = "rad"
    d["ground"]["D"] = [450.0, 0.0]
    d["driver"].update(start=0.0, stop=2 * math.pi)
    with pytest.raises(ks.AssemblyError, match=r"at driver position\(s\) 1\.46608 rad \(by "
                                            r"0\.658 mm\)"):
        ks.solve(d)
