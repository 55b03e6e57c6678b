"""Loading balancing scenes (scene-format.md section 2) and ``balance.solve``."""

from __future__ import annotations

import sys
import tomllib
import types

import pytest

import balance
from balance import BalanceWarning, load_scene
from kinetostatics.model.errors import SceneError, WorkbenchError
from tests.balance._balance_cases import SCENES

ALL_SECTIONS = SCENES["rotor_two_plane"] + SCENES["static_device"].split("\n", 2)[2] + \
    SCENES["resonance_example"].split("\n", 3)[3]


def test_all_sections_in_one_scene() -> None:
    out = balance.solve(ALL_SECTIONS)
    assert list(out) == ["rotor", "static_test", "resonance_test", "warnings", "result_units",
                         "scene_units"]
    assert out["warnings"] == []


def error_of(text_or_dict) -> str:
    with pytest.raises(WorkbenchError) as exc:
        balance.solve(text_or_dict)
    assert isinstance(exc.value, ValueError)
    msg = str(exc.value)
    assert msg and "\n" not in msg
    return msg


# one edit of the scenes, what the one-line error must say: unknown keys (the nearest
# suggested), then bad values
@pytest.mark.parametrize("old, new, words", [
    ("[rotor]", "[rotr]", "did you mean 'rotor'"),
    ("mass = 0.020", "mas = 0.020", "did you mean 'mass'"),
    ("radius = 0.12\n\n[[rotor.planes]]\nz = 0.30", "radus = 0.12\n\n[[rotor.planes]]\nz = 0.30",
     "did you mean 'radius'"),
    ("speed_rpm = 1500", "speed = 1500", "did you mean 'speed_rpm'"),
    ("alpha = 25.0", "alpa = 25.0", "did you mean 'alpha'"),
    ("trial_mass = 0.002", "trial_mas = 0.002", "did you mean 'trial_mass'"),
    ("A3 = 495.0", "A4 = 495.0", "did you mean"),
    ("mass = 0.020", "mass = -0.020", "rotor.unbalance[0].mass"),
    ("speed_rpm = 1500", "speed_rpm = 0", "speed_rpm"),
    ("disk_mass = 5.0", "disk_mass = 0.0", "disk_mass"),
    ("alpha = 25.0", "alpha = 95.0", "alpha"),
    ("alpha = 25.0", "alpha = 0.0", "alpha"),
    ("A1 = 546.5", "A1 = -546.5", "A1"),
    ("A2 = 1071.9", "A2 = 0.0", "A2"),
    ("trial_mass = 0.002", "trial_mass = 0.0", "trial_mass"),
    ("plane = 1", "plane = 3", "plane"),
    ("A2 = 1071.9", "A2 = 100.0", "A2^2 + A3^2 - 2 A1^2"),
    ("A3 = 495.0", "A3 = 10.0", "cos phi"),
    ("[[rotor.planes]]\nz = 0.30", "[[rotor.planes]]\nz = 0.0", "coincide"),
    ("A2 = 1071.9\n", "", "missing required key 'A2'"),
    ("mass = 0.020, ", "", "missing required key 'mass'"),
    ("[rotor]", "format = 2\n[rotor]", "format"),
    ("disk_mass = 5.0", "disk_mass = \"heavy\"", "must be a number"),
])
def test_a_bad_edit_gives_one_line(old, new, words) -> None:
    assert old in ALL_SECTIONS
    assert words in error_of(ALL_SECTIONS.replace(old, new, 1))


def test_plane_counts() -> None:
    raw = tomllib.loads(SCENES["rotor_two_plane"])
    raw["rotor"]["planes"] = raw["rotor"]["planes"] + [{"z": 0.5, "radius": 0.1}]
    assert "give one" in error_of(raw)
    raw["rotor"]["planes"] = []
    assert "give one" in error_of(raw)
    raw["rotor"]["planes"] = [{"z": 0.1, "radius": 0.1}]
    assert len(balance.solve(raw)["rotor"]["corrections"]) == 1


def test_tables_instead_of_arrays_of_tables() -> None:
    assert "[[resonance_test]]" in error_of("[resonance_test]\nA1 = 1.0\n")
    raw = tomllib.loads(SCENES["rotor_two_plane"])
    raw["rotor"]["unbalance"] = raw["rotor"]["unbalance"][0]
    assert "[[rotor.unbalance]]" in error_of(raw)


def test_runs_in_a_scene() -> None:
    text = SCENES["resonance_example"].replace(
        "A2 = 1071.9\nA3 = 495.0",
        "runs = [{ angle = 0.0, A = 1071.9 }, { angle = 120.0, A = 700.0 }, "
        "{ angle = 240.0, A = 300.0 }]")
    # made-up readings: the estimate says they do not fit a linear machine, and that
    # the seed's result falls outside its interval (in the result and as warnings)
    with pytest.warns(BalanceWarning) as seen:
        out = balance.solve(text)["resonance_test"][0]
    assert [str(w.message) for w in seen] == out["warnings"]
    assert any("do not fit a linear machine" in w for w in out["warnings"])
    assert out["mirror_angle"] is None and 0.0 <= out["angle"] < 360.0
    both = SCENES["resonance_example"].replace("A3 = 495.0", "A3 = 495.0\nruns = []")
    assert "not both" in error_of(both)
    few = text.replace(", { angle = 240.0, A = 300.0 }", "")
    assert "at least three" in error_of(few)
    opposite = text.replace("angle = 120.0", "angle = 180.0").replace("angle = 240.0",
                                                                      "angle = 360.0")
    assert "equal or opposite" in error_of(opposite)
    badkey = text.replace("{ angle = 0.0, A", "{ angel = 0.0, A")
    assert "did you mean 'angle'" in error_of(badkey)


def test_dA_adds_an_uncertainty_entry() -> None:
    out = balance.solve(SCENES["resonance_example"] + "dA = 3.0\n")["resonance_test"][0]
    u = out["uncertainty"]
    assert u["dA"] == 3.0 and u["magnitude"][0] < out["correction_mass"] < u["magnitude"][1]


def test_title_and_format() -> None:
    sc = load_scene("title = 'x'\nformat = 1\n" + SCENES["static_device"].split("\n", 2)[2])
    assert sc.title == "x" and sc.sections == ("static_test",)
    with pytest.raises(SceneError):
        load_scene("title = 3\n[static_test]\n")


MECHANISM = """
title = "a mechanism"
gravity = [0.0, -9.81]
[ground]
A = [0.0, 0.0]
[driver]
body = "crank"
joint = "A"
speed = 10.0
start = 0.0
stop = 360.0
count = 5
[[bodies]]
name = "crank"
points = { A = [0.0, 0.0], B = [0.1, 0.0] }
[[joints]]
name = "A"
kind = "R"
bodies = ["ground", "crank"]
"""


def test_mechanism_scene_without_balancing_names_the_solvable_sections() -> None:
    msg = error_of(MECHANISM)
    for word in ("[rotor]", "[static_test]", "[[resonance_test]]", "[balancing]",
                 "kinetostatics.solve"):
        assert word in msg
    assert "no balancing section" in error_of("title = 'empty'\n")


BALANCED = MECHANISM + """
[balancing]
method = "full"
counterweights = [{ body = "crank", about = "A", radius = 0.06 }]
"""


def test_balancing_is_dispatched_to_balance_mechanism(monkeypatch) -> None:
    seen = {}

    def fake(raw: dict) -> dict:
        seen["raw"] = raw
        return {"counterweights": [], "shaking_force_before": 1.0, "shaking_force_after": 0.0}

    mod = types.ModuleType("balance.mechanism")
    mod.solve_mechanism_balancing = fake
    monkeypatch.setitem(sys.modules, "balance.mechanism", mod)
    out = balance.solve(BALANCED)
    assert seen["raw"]["balancing"]["method"] == "full"
    assert seen["raw"]["driver"]["body"] == "crank"
    assert {k: out[k] for k in ("balancing", "warnings")} == {"balancing": fake({}),
                                                              "warnings": []}


def test_bundled_mechanism_balancing_examples() -> None:
    """The bundled [balancing] scenes solve through balance.solve: the four-bar's full
    balancing leaves no shaking force, the slider-crank's first-harmonic one lowers it."""
    full = balance.solve(balance.example_path("four_bar_balancing"))["balancing"]
    assert full["method"] == "full" and len(full["counterweights"]) == 2
    assert full["shaking_force_after"] < 1e-12 * full["shaking_force_before"]
    first = balance.solve(balance.example_path("slider_crank_balancing"))["balancing"]
    assert first["method"] == "first-harmonic"
    assert first["checks"]["first_harmonic_after"] < 1e-12 * first["checks"][
        "first_harmonic_before"]
    assert first["shaking_force_after"] < first["shaking_force_before"]


def test_invalid_toml_and_missing_file() -> None:
    assert "TOML" in error_of("[rotor\nx = 1\n")
    assert "no such balancing scene file" in error_of("/no/such/scene.toml")


def test_public_api_names_resolve() -> None:
    """Every name in balance.__all__ resolves (the machine's names lazily), and an
    unknown attribute is an AttributeError."""
    for name in balance.__all__:
        assert getattr(balance, name) is not None, name
    from balance import machine
    assert balance.BalancingMachine is machine.BalancingMachine
    with pytest.raises(AttributeError):
        balance.__getattr__("no_such_method")
