"""Issue 30, "Done when": the same scene typed in SI, mm/g/rpm, in/t and cm gives equal
warnings (by field and rule) and equal SI numbers, for scenes of every kind, legitimate
ones near the rules' edges (silent) and real slips (each warned by its rule).

Every scene is written here in SI and rewritten into the other units by hand (the factors
written out in the rewriters, not read from the workbench), so a slip is the same physical
quantity in each twin: gravity of 9.81e-3 m/s^2 is the mm twin's ``gravity = [0, -9.81]``.
"""

from __future__ import annotations

import copy
import math
import tomllib
import warnings

import pytest

import balance
import kinetostatics as ks
from balance.errors import BalanceWarning
from kinetostatics.cams import load_cam_scene, solve_cam
from tests.kinetostatics import scenes
from tests.kinetostatics.model.test_slips_property import close, numbers, rotor_in, slips_of
from tests.kinetostatics.model.test_units_invariance import LENGTH, MASS, cam_in, mechanism_in

SYSTEMS = {
    "SI": {},
    "mm/g/rpm": {"length": "mm", "mass": "g", "speed": "rpm"},
    "in/t": {"length": "in", "mass": "t"},
    "cm": {"length": "cm"},
}


def example(name: str) -> dict:
    with open(ks.scene_path(name), "rb") as fh:
        return tomllib.load(fh)


def changed(name: str, change) -> dict:
    d = example(name)
    change(d)
    return d


def drv(**kw):
    return lambda d: d["driver"].update(kw)


def piston(mass: float):
    return lambda d: d["bodies"][2].update(mass=mass, inertia=0.0, cog=[0.0, 0.0])


def sweep(positions):
    def change(d):
        for k in ("start", "stop", "count"):
            d["driver"].pop(k, None)
        d["driver"]["positions"] = positions
    return change


def friction(radius: float):
    return lambda d: d["joints"][0].update(friction={"mu": 0.1, "radius": radius})


MECHANISMS = [
    # (name, SI scene, expected (field, rule) pairs)
    ("four_bar (RRR)", example("four_bar"), []),
    ("slider_crank (RRT)", example("slider_crank"), []),
    ("scotch_yoke (RTT)", example("scotch_yoke"), []),
    ("slotted_lever (RTR)", example("slotted_lever"), []),
    ("shaper (two dyads)", example("shaper"), []),
    ("sliding driver", example("sliding_driver"), []),
    ("point-mass piston 1.5 kg", changed("slider_crank", piston(1.5)), []),
    ("point-mass piston 1500 kg", changed("slider_crank", piston(1500.0)),
     [("body 'piston'.mass", "mass")]),
    ("sweep 40..46.3 deg", changed("four_bar", drv(start=40.0, stop=46.3, count=8)), []),
    ("sweep 2 deg", changed("four_bar", drv(start=10.0, stop=12.0, count=5)), []),
    ("positions in any order", changed("four_bar", sweep([90.0, 0.0, 180.0, 270.0])), []),
    ("positions 0..6 whole radians", changed("four_bar", sweep([0.0, 1.0, 2.0, 3.0, 4.0, 5.0,
                                                                6.0])),
     [("driver.positions", "positions")]),
    ("speed 2400 rad/s (rpm typed)", changed("four_bar", drv(speed=2400.0)),
     [("driver.speed", "speed")]),
    ("gravity 1000 x small", changed("four_bar", lambda d: d.update(gravity=[0.0, -9.81e-3])),
     [("gravity", "gravity")]),
    ("crank 1000 x heavy", changed("four_bar", lambda d: d["bodies"][0].update(mass=1200.0)),
     [("body 'crank'.mass", "mass")]),
    ("motion, omega0 300 (rpm typed)",
     changed("four_bar_motion", lambda d: d["motion"].update(omega0=300.0)),
     [("motion.omega0", "speed")]),
    ("motion", example("four_bar_motion"), []),
    ("eccentric pin radius 0.2 m", changed("four_bar", friction(0.2)), []),
    ("friction in every joint (RTT)", scenes.with_friction(example("scotch_yoke"), 0.05), []),
    ("pin radius 10 m (mm typed)", changed("four_bar", friction(10.0)),
     [("joint 'A'.friction.radius", "lengths")]),
]


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize(("name", "si", "want"), MECHANISMS, ids=[m[0] for m in MECHANISMS])
def test_mechanism_twins(name, si, want, system) -> None:
    typed = mechanism_in(si, SYSTEMS[system])
    assert slips_of(ks.load_scene, typed) == sorted(want)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ks.UnitWarning)
        a, b = ks.load_scene(copy.deepcopy(si)), ks.load_scene(typed)
    assert close(numbers(a), numbers(b))             # measured: within 3 ulp


def cam(name: str, **change) -> dict:
    d = example(name)
    d["cam"].pop("speed_rpm", None)
    d["cam"]["speed"] = 31.0
    for k, v in change.items():
        (d["cam"]["follower"] if k == "stroke_angle" else d["cam"])[k] = v
    return d


CAMS = [
    ("translating roller", cam("translating_roller"), []),
    ("oscillating roller", cam("oscillating_roller"), []),
    ("oscillating 4.5 deg swing", cam("oscillating_roller", stroke_angle=4.5), []),
    ("cam at 3000 rad/s (rpm typed)", cam("translating_roller", speed=3000.0),
     [("cam.speed", "speed")]),
]


def read_and_solve(source: dict) -> tuple[list, dict]:
    """The unit slips warned on reading a cam scene, and the summary of the scene read:
    read once (reading an oscillating cam sizes its base radius, 0.25 s of CPU a read;
    each twin was read twice, once for its slips and once by ``solve_cam``)."""
    read = []
    slips = slips_of(lambda s: read.append(load_cam_scene(s)), source)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ks.UnitWarning)
        return slips, solve_cam(read[0]).summary


#: The SI twin's slips and summary of each cam, made once (every system is compared with
#: them).
_SI_TWINS: dict[str, tuple[list, dict]] = {}


def si_twin(name: str, si: dict) -> tuple[list, dict]:
    if name not in _SI_TWINS:
        _SI_TWINS[name] = read_and_solve(copy.deepcopy(si))
    return _SI_TWINS[name]


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize(("name", "si", "want"), CAMS, ids=[c[0] for c in CAMS])
def test_cam_twins(name, si, want, system) -> None:
    slips, b = read_and_solve(cam_in(si, SYSTEMS[system]))
    si_slips, a = si_twin(name, si)
    assert [r for _, r in slips] == [r for _, r in sorted(want)]
    assert slips == si_slips
    nums = [k for k, v in a.items() if isinstance(v, float) and not k.endswith("_at")]
    assert close([a[k] for k in nums], [b[k] for k in nums], 5e-15)    # measured 1.1e-15
    # where an extreme lies: a flat minimum's place moves by the root of the rounding of
    # its values (measured 7.7e-9 relative on the 4.5 deg swing in inches)
    at = [k for k in a if k.endswith("_at")]
    assert close([a[k] for k in at], [b[k] for k in at], 1e-7)


# ------------------------------------------------------------------ balancing, every section
def factors(units: dict) -> tuple[float, float]:
    return LENGTH[units.get("length", "m")], MASS[units.get("mass", "kg")]


def balancing_in(si: dict, units: dict) -> dict:
    """A balancing scene (SI, degrees) typed in ``units``, by hand: masses and lengths;
    readings, amplitudes and unbalances (``[units] unbalance``, not named) as they are."""
    L, M = factors(units)
    if "rotor" in si:
        return rotor_in(si, units)
    out = copy.deepcopy(si)
    out["units"] = dict(units)

    def scale(table: dict, keys: tuple, f: float) -> None:
        for k in keys:
            if isinstance(table.get(k), float):
                table[k] /= f
            elif isinstance(table.get(k), list):
                table[k] = [x / f for x in table[k]]
    st = out.get("static_test")
    if st:
        scale(st, ("disk_mass", "comparison_mass"), M)
        scale(st, ("comparison_radius", "correction_radius"), L)
    for t in out.get("resonance_test", []):
        scale(t, ("trial_mass",), M)
        scale(t, ("trial_radius", "correction_radius"), L)
    for t in out.get("influence", []):
        scale(t, ("trial_radius", "correction_radius"), L)
        for run in t.get("runs", []) + t.get("trim", []):
            scale(run, ("mass",), M)
    if "iso" in out:
        scale(out["iso"], ("rotor_mass",), M)
        scale(out["iso"], ("bearings", "cog", "planes"), L)
    for t in out.get("split", []):
        scale(t, ("mass",), M)
        scale(t, ("radius", "correction_radius"), L)
    for t in out.get("combine", []):
        for w in t["weights"]:
            scale(w, ("mass",), M)
    return out


def rotor(masses, angles) -> dict:
    return {"rotor": {"unbalance": [{"mass": m, "radius": 0.1, "angle": a, "z": 0.1 * (i + 1)}
                                    for i, (m, a) in enumerate(zip(masses, angles,
                                                                   strict=True))],
                      "planes": [{"z": 0.0, "radius": 0.1}, {"z": 0.5, "radius": 0.1}]}}


def influence(trial: float, phases=(250.0, 160.0), **extra) -> dict:
    sec = {"initial": [[4.0, phases[0]]],
           "runs": [{"plane": 1, "mass": trial, "angle": 0.0,
                     "readings": [[2.855, phases[1]]]}], **extra}
    return {"influence": [sec]}


STATIC = {"static_test": {"disk_mass": 5.0, "comparison_mass": 0.05, "comparison_radius": 0.1,
                          "alpha": 25.0, "correction_radius": 0.08}}
RESONANCE = {"resonance_test": [{"trial_mass": 0.02, "trial_radius": 0.1,
                                 "correction_radius": 0.12, "A1": 4.0, "A2": 5.1, "A3": 3.3}]}


def marks(angles) -> dict:
    """A resonance test with runs at ``angles`` (its amplitudes from one unbalance)."""
    u, trial = 0.002 * complex(math.cos(1.0), math.sin(1.0)), 0.02 * 0.1
    runs = [{"angle": a, "A": abs(u + trial * complex(math.cos(math.radians(a)),
                                                       math.sin(math.radians(a)))) * 1000}
            for a in angles]
    return {"resonance_test": [{"trial_mass": 0.02, "trial_radius": 0.1,
                                "correction_radius": 0.12, "A1": abs(u) * 1000, "runs": runs}]}


# a good correction (4.0 at 250 deg, trial 0.3 g: 0.0003 kg), then a trim run after it
GOOD = influence(0.0003)["influence"][0]
TRIM = {"influence": [{**GOOD, "trim": [{"plane": 1, "mass": 0.0003 * 1.01, "angle": 324.0,
                                         "readings": [[0.05, 80.0]]}]}]}

BALANCING = [
    ("rotor", rotor([0.02, 0.015, 0.01], [30.0, 150.0, 270.0]), []),
    ("rotor, a 0.15 g clip beside 200 g", rotor([0.2, 0.00015], [30.0, 150.0]), []),
    ("rotor, smallest mass 667 x off", rotor([0.03, 0.045, 20.0], [30.0, 150.0, 270.0]),
     [("rotor.unbalance.mass", "unbalance_mass")]),
    ("rotor, phases in radians", rotor([0.02, 0.015, 0.01], [0.5236, 2.618, 4.1]),
     [("rotor.unbalance.angle", "angles")]),
    ("static device", STATIC, []),
    ("static device, alpha 0.4363", {"static_test": {**STATIC["static_test"], "alpha": 0.4363}},
     []),
    ("resonance, three runs", RESONANCE, []),
    ("resonance, four marks", marks([0.0, 90.0, 180.0, 270.0]), []),
    ("resonance, marks in radians", marks([0.0, 1.5708, 3.1416, 4.7124]),
     [("resonance_test[0].runs.angle", "angles")]),
    ("influence, a 0.3 g fan trial", influence(0.0003), []),
    ("influence, 5 g typed as kg", influence(5.0), [("influence[0].runs.mass", "trial_mass")]),
    ("influence, phases in radians", influence(0.1, (4.3633, 2.7925)),
     [("influence[0].runs (phases and mass angles)", "angles")]),
    ("influence, a 0.1 um node reading",
     {"influence": [{**GOOD, "initial": [[4.0, 250.0], [1e-7, 10.0]],
                     "runs": [{**GOOD["runs"][0], "readings": [[2.855, 160.0], [2e-7, 30.0]]}]}]},
     []),
    ("trim run after a good correction", TRIM, []),
    ("iso, 500 kg rotor, 3 kg trial", {**influence(3.0), "iso": {
        "rotor_mass": 500.0, "grade": 6.3, "speed_rpm": 3000.0}}, []),
    ("iso, two bearings", {"iso": {"rotor_mass": 12.0, "grade": 2.5, "speed_rpm": 6000.0,
                                   "bearings": [0.0, 0.4], "cog": 0.18}}, []),
    ("split at 4.5 deg", {"split": [{"mass": 0.01, "angle": 4.5, "positions": 12}]}, []),
    ("split on radii", {"split": [{"mass": 0.01, "angle": 100.0, "positions": 8,
                                   "radius": 0.1, "correction_radius": 0.08}]}, []),
    ("combine", {"combine": [{"weights": [{"mass": 0.005, "angle": 10.0},
                                          {"mass": 0.003, "angle": 50.0}]}]}, []),
]


def field_of(rule_field: str) -> str:
    """A warning's field without its listed values (``influence[0].runs.mass``)."""
    return rule_field.split(" [")[0]


def balancing_slips(scene: dict) -> list[tuple[str, str]]:
    return sorted((field_of(f), r) for f, r in slips_of(balance.solve, scene, BalanceWarning))


def si_numbers(out: dict, units: dict) -> list[float]:
    """The results' numbers in SI: the field sections answer in the scene's masses and
    lengths (docs/balancing.md), converted back here by hand."""
    L, M = factors(units)
    nums: list[float] = []
    if "rotor" in out:
        nums += [x for c in out["rotor"]["corrections"] for x in (c["mass"], c["angle"])]
    if "static_test" in out:
        nums += list(out["static_test"].values())
    for r in out.get("resonance_test", []):
        nums += [r["correction_mass"], r["angle"]]
    for r in out.get("influence", []):
        nums += [x for c in r["corrections"] for x in (c["mass"] * M, c["angle"])]
    if "iso" in out:
        nums += [out["iso"]["rotor_mass"] * M, out["iso"]["U_per"], out["iso"]["e_per"] * L]
    for r in out.get("split", []):
        nums += [p["mass"] * M for p in r["placements"]] + [r["total_mass"] * M]
    for r in out.get("combine", []):
        nums += [r["mass"] * M, r["angle"]]
    return nums


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize(("name", "si", "want"), BALANCING, ids=[b[0] for b in BALANCING])
def test_balancing_twins(name, si, want, system) -> None:
    typed = balancing_in(si, SYSTEMS[system])
    assert balancing_slips(typed) == sorted(want)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BalanceWarning)
        a, b = balance.solve(copy.deepcopy(si)), balance.solve(typed)
    x, y = si_numbers(a, {}), si_numbers(b, SYSTEMS[system])
    assert x and close(x, y, 1e-11), (x, y)        # measured: 2e-15
    assert math.isfinite(sum(x))


# ------------------------------------------------------------------ one positions rule
@pytest.mark.parametrize("system", [{}, {"length": "mm", "angle": "rad"}])
def test_one_positions_rule_for_mechanism_and_motion_scenes(system) -> None:
    """Any order is read, a repeat is refused with the same one line (in the unit typed)
    by ``solve`` and by the motion of a ``[motion]`` scene."""
    si = changed("four_bar_motion", sweep([90.0, 0.0, 180.0, 270.0]))
    si["motion"]["cycles"] = 2
    del si["motion"]["target_delta"]       # (no flywheel sized: 1.2 s of CPU, not the point)
    ks.solve(mechanism_in(si, system))
    ks.simulate_motion(mechanism_in(si, system))
    twice = mechanism_in(changed("four_bar_motion", sweep([90.0, 0.0, 90.0, 270.0])), system)
    said = "1.5708 rad" if system else "90 deg"
    told = []
    for run in (ks.solve, ks.simulate_motion):
        with pytest.raises(ks.SceneError) as exc:
            run(copy.deepcopy(twice))
        told.append(str(exc.value))
    assert told[0] == told[1] and "\n" not in told[0]
    assert told[0].startswith(f"driver positions: {said} is listed more than once (rows 1, 3)")
    beyond = mechanism_in(changed("four_bar_motion", sweep([0.0, 10.0, 400.0])), system)
    with pytest.raises(ks.SceneError, match=r"within one turn from the smallest position "
                                            rf"\(0 {said.split()[1]}\)"):
        ks.simulate_motion(beyond)
