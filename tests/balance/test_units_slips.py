"""Issue 18, items 5 and 7: unit slips in balancing scenes give one warning each (a
BalanceWarning; a ``warning:`` line on the command line, exit code 0), never a silent
number; the estimate on the bound of its search is flagged; dof with A1 = 0; a mechanism
balancing whose closed form fails its own check is refused."""

from __future__ import annotations

import cmath
import math
import warnings

import pytest

import balance
from balance.errors import BalanceError, BalanceWarning
from tests.balance._balance_cases import INFLUENCE_TWO_PLANE
from tests.helpers import run_main

# a single-plane influence scene: a 100 g trial mass at 0 deg
INFLUENCE = """
[units]
mass = "g"
[[influence]]
initial = [[4.0, {p0}]]
runs = [{{ plane = 1, mass = {m}, angle = 0.0, readings = [[2.855, {p1}]] }}]
"""


def caught(scene) -> tuple[dict, list[str]]:
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        out = balance.solve(scene)
    return out, [str(w.message) for w in seen if issubclass(w.category, BalanceWarning)]


def hand_correction(p0: float, p1: float, m: float) -> tuple[float, float]:
    """W = -O m / (T - O), by hand (complex numbers, degrees)."""
    o = cmath.rect(4.0, math.radians(p0))
    t = cmath.rect(2.855, math.radians(p1))
    w = -o * m / (t - o)
    return abs(w), math.degrees(cmath.phase(w)) % 360.0


def test_the_issue_reproducers() -> None:
    out, msgs = caught(INFLUENCE.format(p0=250.0, p1=160.0, m=100.0))
    c = out["influence"][0]["corrections"][0]
    mass, angle = hand_correction(250.0, 160.0, 100.0)          # 81.39 g at 324.48 deg
    assert (c["mass"], c["angle"]) == (pytest.approx(mass, rel=1e-12),
                                       pytest.approx(angle, abs=1e-9))
    assert msgs == []
    # the phases typed in radians (160 deg as 2.7925): a warning naming them
    out, msgs = caught(INFLUENCE.format(p0=4.3633, p1=2.7925, m=100.0))
    assert len(msgs) == 1 and "influence[0]" in msgs[0] and "radians" in msgs[0]
    assert out["warnings"] == msgs                       # and in the result
    # the same phases with angle = "rad": the right answer, no warning
    rad = INFLUENCE.format(p0=math.radians(250.0), p1=math.radians(160.0), m=100.0)
    out, msgs = caught(rad.replace('mass = "g"', 'mass = "g"\nangle = "rad"'))
    c = out["influence"][0]["corrections"][0]
    assert msgs == [] and c["angle"] == pytest.approx(angle, abs=1e-9)
    # a 0.1 g trial weight (a small fan's) is legitimate: the physical mass is judged, and
    # 0.1 g is a real trial weight, whatever unit it was typed in
    out, msgs = caught(INFLUENCE.format(p0=250.0, p1=160.0, m=0.1))
    assert out["influence"][0]["corrections"][0]["mass"] == pytest.approx(mass / 1000.0)
    assert msgs == []
    # 5 g typed as kilograms: a 5 kg trial weight
    out, msgs = caught(INFLUENCE.format(p0=250.0, p1=160.0, m=5.0).replace(
        'mass = "g"', 'mass = "kg"'))
    assert len(msgs) == 1 and "runs.mass = [5] kg" in msgs[0] and "quiet" in msgs[0]
    quiet = INFLUENCE.format(p0=250.0, p1=160.0, m=5.0).replace('mass = "g"', 'mass = "kg"')
    assert caught('[checks]\nquiet = ["trial_mass"]\n' + quiet)[1] == []


def test_influence_trial_masses_1000_times_apart_warn_a_node_reading_not() -> None:
    text = INFLUENCE_TWO_PLANE.replace("[53.0, 78.0]", "[0.053, 78.0]").replace(
        "plane = 1, mass = 1.15", "plane = 1, mass = 0.00115")
    _, msgs = caught(text)
    assert len(msgs) == 1 and "trial masses" in msgs[0]      # 0.053 is a node: no warning


def rotor(angles, masses=(0.02, 0.015)) -> str:
    ub = "".join(f"\n[[rotor.unbalance]]\nmass = {m}\nradius = 0.1\nangle = {a}\nz = 0.1\n"
                 for m, a in zip(masses, angles, strict=True))
    return "[rotor]" + ub + "\n[[rotor.planes]]\nz = 0.0\nradius = 0.1\n"


def test_rotor_slips_warn() -> None:
    assert caught(rotor([30.0, 150.0]))[1] == []
    msgs = caught(rotor([0.5236, 2.618]))[1]             # 30 and 150 deg in radians
    assert len(msgs) == 1 and "rotor.unbalance" in msgs[0] and "radians" in msgs[0]
    msgs = caught(rotor([30.0, 150.0], masses=(20.0, 0.015)))[1]     # 20 g typed in kg
    assert any("unbalance masses" in m and "times apart" in m for m in msgs)


RESONANCE = """
[[resonance_test]]
trial_mass = 0.01
trial_radius = 0.1
correction_radius = 0.1
A1 = {A1}
runs = [{{ angle = {a0}, A = 6.1 }}, {{ angle = {a1}, A = 5.2 }}, {{ angle = {a2}, A = 2.9 }}]
"""


def test_resonance_slips_warn() -> None:
    plain = caught(RESONANCE.format(A1=4.0, a0=0.0, a1=120.0, a2=240.0))[1]
    assert not any("quiet" in m for m in plain)     # no slip (the fit's own warnings aside)
    msgs = caught(RESONANCE.format(A1=4.0, a0=0.0, a1=2.0944, a2=4.1888))[1]
    assert any("resonance_test[0].runs" in m and "radians" in m for m in msgs)
    msgs = caught(RESONANCE.format(A1=4000.0, a0=0.0, a1=120.0, a2=240.0))[1]  # um among mm
    assert any("resonance_test[0].A (run 1)" in m and "times the median" in m for m in msgs)


def test_a_single_small_alpha_is_not_warned() -> None:
    text = ("[static_test]\ndisk_mass = 5.0\ncomparison_mass = 0.05\ncomparison_radius = 0.1\n"
            "alpha = {alpha}\ncorrection_radius = 0.08\n")
    assert caught(text.format(alpha=25.0))[1] == []
    # a single angle is never judged alone: 0.4363 deg may be read on a dial
    assert caught(text.format(alpha=0.4363))[1] == []


def test_a_correction_100_times_the_trial_mass_warns() -> None:
    # A1 = 400, the trial mass's own amplitude 1: U/T = 400, the correction 400 x 0.01 kg
    runs = ", ".join(f"{{ angle = {m}, A = {abs(400.0 + cmath.rect(1.0, math.radians(m)))}}}"
                     for m in (0.0, 120.0, 240.0))
    text = ("[[resonance_test]]\ntrial_mass = 0.01\ntrial_radius = 0.1\n"
            f"correction_radius = 0.1\nA1 = 400.0\nruns = [{runs}]\n")
    out, msgs = caught(text)
    assert out["resonance_test"][0]["correction_mass"] == pytest.approx(4.0, rel=1e-9)
    assert any("correction 4 kg is 400 times it" in m for m in msgs)


def test_the_cli_prints_warning_lines_and_exits_0(tmp_path) -> None:
    path = tmp_path / "slip.toml"
    path.write_text(INFLUENCE.format(p0=4.3633, p1=2.7925, m=100.0))
    out = run_main("balance", "solve", str(path))
    assert out.returncode == 0, out.stderr
    lines = out.stderr.strip().splitlines()
    assert lines and all(ln.startswith("warning: ") for ln in lines)
    assert sum("radians" in ln for ln in lines) == 1
    bad = tmp_path / "bad.toml"
    bad.write_text('[units]\nmass = "lb"\n' + rotor([30.0, 150.0]))
    out = run_main("balance", "solve", str(bad))
    assert out.returncode == 2 and out.stderr.startswith("error: ")
    assert len(out.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("name", balance.examples())
def test_bundled_scenes_do_not_warn(name) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        balance.solve(balance.example_path(name))


# ---------------------------------------------------------------- item 7
def test_dof_with_a1_zero_is_trial_runs_minus_one() -> None:
    """docs/balancing.md: A1 = 0 read without noise pins the unbalance to 0; A is the one
    unknown left, so dof = trial runs - 1 (chi2 is the runs' scatter about their mean)."""
    three = ("[[resonance_test]]\ntrial_mass = 0.01\ntrial_radius = 0.1\n"
             "correction_radius = 0.1\nA1 = 0.0\nA2 = 5.0\nA3 = 5.2\n")
    est = caught(three)[0]["resonance_test"][0]["estimate"]
    assert est["dof"] == 1 and est["unbalance"] == 0.0
    # chi2 by hand: sigma_k = 0.01 A_k, a the weighted mean
    w = [1 / (0.01 * 5.0) ** 2, 1 / (0.01 * 5.2) ** 2]
    a = (w[0] * 5.0 + w[1] * 5.2) / sum(w)
    assert est["chi2"] == pytest.approx(w[0] * (5.0 - a) ** 2 + w[1] * (5.2 - a) ** 2,
                                        rel=1e-12)
    runs = RESONANCE.format(A1=0.0, a0=0.0, a1=120.0, a2=240.0)
    assert caught(runs)[0]["resonance_test"][0]["estimate"]["dof"] == 2
    # with absolute noise A1 = 0 is a noisy reading like any other: readings - 3
    noisy = runs + "noise = { relative = 0.01, absolute = 0.05 }\n"
    assert caught(noisy)[0]["resonance_test"][0]["estimate"]["dof"] == 1


def test_an_estimate_on_the_bound_of_its_search_is_flagged() -> None:
    """U/T = 1e5: the likelihood rises up to the search's edge at 1e4."""
    a = 1e-3
    runs = ", ".join(f"{{ angle = {m}, A = {abs(100.0 + cmath.rect(a, math.radians(m)))}}}"
                     for m in (0.0, 120.0, 240.0))
    text = ("[[resonance_test]]\ntrial_mass = 0.01\ntrial_radius = 0.1\n"
            f"correction_radius = 0.1\nA1 = 100.0\nruns = [{runs}]\n"
            "noise = { relative = 1e-9 }\n")
    res = caught(text)[0]["resonance_test"][0]
    assert res["estimate"]["at_bound"] is True
    assert any("bound of the searched range" in w for w in res["warnings"])
    ok = caught(RESONANCE.format(A1=4.0, a0=0.0, a1=120.0, a2=240.0))[0]["resonance_test"][0]
    assert "at_bound" not in ok["estimate"]
    assert not any("bound of the searched" in w for w in ok["warnings"])


def test_mechanism_balancing_refuses_a_failed_closed_form(monkeypatch) -> None:
    """balance.mechanism.solve checks its closed form; a failed check is an error now."""
    import balance.mechanism.solve as ms
    assert balance.solve("four_bar_balancing")["balancing"]["counterweights"]
    monkeypatch.setattr(ms, "_drift", lambda c: 1.0)      # the centre of mass still moves
    with pytest.raises(BalanceError, match="fails its own check"):
        balance.solve("four_bar_balancing")


@pytest.mark.slow
def test_a_slipped_scene_shows_its_warning_in_the_report_and_the_json(tmp_path) -> None:
    """Phases typed in radians: the report's Warnings section names the slip (never
    "None"), and so do the JSON and the solve's dict."""
    path = tmp_path / "slip.toml"
    path.write_text(INFLUENCE.format(p0=4.3633, p1=2.7925, m=100.0))
    report = tmp_path / "slip.html"
    out = run_main("balance", "solve", str(path), "--report", str(report))
    assert out.returncode == 0, out.stderr
    html = report.read_text()
    section = html[html.index("<h2>Warnings</h2>"):]
    section = section[:section.index("<h2>", 5)]
    assert "influence[0].runs" in section and "quiet" in section and "None" not in section
    js = run_main("balance", "solve", str(path), "--json")
    import json
    assert any("influence[0].runs" in w for w in json.loads(js.stdout)["warnings"])


CLIP_ROTOR = """
[units]
mass = "g"
length = "mm"
[rotor]
planes = [{{ z = 0.0, radius = 100.0 }}, {{ z = 300.0, radius = 100.0 }}]
[[rotor.unbalance]]
mass = {big}
radius = 100.0
angle = 30.0
z = 100.0
[[rotor.unbalance]]
mass = {small}
radius = 100.0
angle = 150.0
z = 200.0
"""

CLIP_RUNS = """
[units]
mass = "g"
vibration = "um"
[[influence]]
initial = [[170.0, 112.0], [53.0, 78.0]]
runs = [
  {{ masses = [[{big}, 0.0], [{small}, 90.0]], readings = [[235.0, 94.0], [58.0, 68.0]] }},
  {{ plane = 2, mass = {big}, angle = 0.0, readings = [[185.0, 115.0], [77.0, 104.0]] }},
]
"""


@pytest.mark.parametrize("scene", [CLIP_ROTOR, CLIP_RUNS], ids=["rotor", "trial run"])
def test_a_clip_beside_a_weight_is_silent_a_slip_is_not(scene) -> None:
    assert caught(scene.format(big=200.0, small=0.15))[1] == []     # a 0.15 g clip
    # the weight typed in grams under mass = "kg" is 200 kg (1 kg or more): a slip, one
    # warning
    kg = scene.replace('mass = "g"', 'mass = "kg"')
    msgs = caught(kg.format(big=200.0, small=0.15))[1]
    assert len(msgs) == 1 and "200" in msgs[0]
    # kilograms typed as grams: 0.2 mg beside 200 g (under a milligram): a slip
    msgs = caught(scene.format(big=200.0, small=0.0002))[1]
    assert len(msgs) == 1 and "times apart" in msgs[0]


def test_a_trim_run_after_a_good_correction_is_silent() -> None:
    """The correction left 0.05 um of 20 um (400 times less): the trim's reading is
    small beside the runs' and its mass near the trial's; neither is a slip."""
    text = """
[units]
mass = "g"
vibration = "um"
[[influence]]
initial = [[20.0, 180.0]]
runs = [{ plane = 1, mass = 20.0, angle = 0.0, readings = [[30.0, 120.0]] }]
[[influence.trim]]
plane = 1
mass = 21.7
angle = 290.0
readings = [[0.05, 226.1]]
"""
    out, msgs = caught(text)
    assert msgs == [] and out["warnings"] == []
    coeffs = text.replace(
        'runs = [{ plane = 1, mass = 20.0, angle = 0.0, readings = [[30.0, 120.0]] }]',
        "coefficients = [[[0.9, 70.0]]]")
    assert caught(coeffs)[1] == []


def mechanism_balancing(units: bool = False, **driver) -> dict:
    """The bundled four-bar balancing scene (SI), or typed in mm/g (``units``)."""
    import tomllib
    with open(balance.example_path("four_bar_balancing"), "rb") as fh:
        d = tomllib.load(fh)
    d["driver"].update(driver)
    if units:
        from tests.kinetostatics.model.test_units_invariance import mechanism_in
        d = mechanism_in(d, {"length": "mm", "mass": "g"})
        for cw in d["balancing"].get("counterweights", []):
            if "radius" in cw:
                cw["radius"] *= 1000.0
    return d


def test_a_slipped_mechanism_balancing_scene_carries_its_warning() -> None:
    """A mechanism's [balancing] read through balance: its mechanism's slip (3000 rpm typed
    as rad/s) is in the result's warnings (the report's and JSON's source), a [checks]
    quiet silences it, and the scene typed in mm/g is silent with the same numbers."""
    import kinetostatics as ks
    with pytest.warns(ks.UnitWarning) as seen:      # the mechanism reader's, warned once
        out = balance.solve(mechanism_balancing(speed=2400.0))
    assert len(out["warnings"]) == 1 and out["warnings"][0].startswith("driver.speed = 2400")
    assert [str(w.message) for w in seen] == out["warnings"]
    quiet = {**mechanism_balancing(speed=2400.0), "checks": {"quiet": ["speed"]}}
    assert caught(quiet)[0]["warnings"] == []
    si, mm = caught(mechanism_balancing())[0], caught(mechanism_balancing(units=True))[0]
    assert si["warnings"] == mm["warnings"] == []
    a, b = si["balancing"], mm["balancing"]
    for x, y in zip(a["counterweights"], b["counterweights"], strict=True):
        assert x["mass"] == pytest.approx(y["mass"], rel=1e-12)   # measured: 2e-16


def test_the_report_names_each_warning_s_section_once() -> None:
    from balance.report.text import result_warnings
    out = {"rotor": {"warnings": ["rotor: the correction planes are 20 mm apart"]},
           "influence": [{"warnings": ["the coefficients are ill-conditioned"]}]}
    assert list(result_warnings(out)) == [
        ("", "rotor: the correction planes are 20 mm apart"),
        ("influence[0]", "the coefficients are ill-conditioned")]
