"""The pymunk cross-check: what is built, what is measured, and how well it agrees with
kinetostatics on every case and every dyad kind.

Runs are short (2000 steps per revolution, 90 readings per revolution); each tolerance
is about twice the error measured at that step (the measured value in the comment), so
a tenfold regression fails.
"""

import copy
import json
import math
import tomllib

import numpy as np
import pymunk
import pytest
from matplotlib.figure import Figure

import kinetostatics as ks
from kinetostatics import simulation as sim
from kinetostatics.cli import main
from kinetostatics.simulation import (
    SimulationError,
    build_space,
    crosscheck,
    plot_comparison,
    plot_study,
    run,
    study,
)
from tests.helpers import OWN_CASES, SCENES

STEPS = 2000          # steps per revolution (per sweep for the sliding driver)
SAMPLES = 90

# scene file -> (solver iterations, tolerance on max_error, pymunk's readings) at STEPS.
# Iterations: 30 unless the scene's chain converges slowly (bodies of very different
# mass or inertia, such as the shaper's heavy ram): the counts the automatic rule picks
# (the shaper's 60 with the ballast, which the run falls back on where the driver-last run
# diverges without it; 480 before). Measured (pymunk 7.3.1): max_error, then the largest
# derived (momentum balance) error.
CASES = {
    "four_bar": (30, 6e-5),                 # RRR; 3.13e-5, derived 3.22e-5
    "slider_crank": (30, 3e-5),             # RRT, resist load, no lock; 1.34e-5, 1.34e-5
    "slotted_lever": (60, 5e-5),            # RTR, guide on the lever; 2.25e-5, 3.69e-5
    "scotch_yoke": (30, 4e-6),              # TTR, two translating bodies; 1.95e-6, 4.42e-6
    "sliding_driver": (30, 1e-5),           # sliding driver (Fe), RRR; 4.46e-6, 8.77e-6
    "oscillating_cylinder": (30, 1.5e-5),   # RTR, guide on the rod; 7.19e-6, 1.52e-5
    "rtt_scotch_yoke": (30, 4e-6),          # RTT; 1.95e-6, 4.92e-6
    "trr_slider_crank": (30, 3e-5),         # TRR; 1.35e-5, 1.35e-5
    "trt_slotted_crank": (120, 3e-4),       # TRT, poor transmission; 1.52e-4, 1.52e-4
    "shaper": (60, 8e-5),                   # RTR + RRT, with the ballast; 3.74e-5, 3.74e-5
}


def scene_path(name):
    for base in (OWN_CASES, SCENES):
        if (base / f"{name}.toml").is_file():
            return base / f"{name}.toml"
    return ks.example(name)


def constant_speed(name):
    """The scene as a dict, its driver at constant speed (some test scenes accelerate)."""
    with open(scene_path(name), "rb") as fh:
        raw = tomllib.load(fh)
    raw["driver"]["acceleration"] = 0.0
    return raw


@pytest.fixture(scope="module")
def runs():
    return {name: crosscheck(constant_speed(name), steps_per_revolution=STEPS,
                             iterations=it, samples_per_revolution=SAMPLES)
            for name, (it, _) in CASES.items()}


def test_every_dyad_kind_is_crosschecked():
    kinds = set()
    for name in CASES:
        kinds |= {d.kind for d in ks.analyse(ks.load_scene(scene_path(name))).dyads}
    assert {"RRR", "RRT", "TRR", "RTR", "TRT", "RTT", "TTR"} <= kinds


@pytest.mark.parametrize("name", list(CASES))
def test_reactions_and_me_agree_with_kinetostatics(runs, name):
    it, tol = CASES[name]
    cc = runs[name]
    s = cc.summary()
    assert s["iterations"] == it
    assert s["dt"] == pytest.approx(cc.settings["dt"])
    assert s["steps_per_revolution"] == pytest.approx(STEPS)
    assert cc.max_error <= tol, (name, s["worst"], cc.max_error)
    # pymunk's own readings make the headline: every joint's |F| and the driver's |Me|
    sc = ks.load_scene(scene_path(name))
    q = "Me" if sc.driver.kind == "R" else "Fe"
    assert set(cc.errors) == {f"F[{j}]" for j in sc.joints} | {f"|{q}|"}
    assert s["max_error"] == max(s["errors"].values())
    # the signed values of the momentum balance are reported apart and agree too (at
    # most 2.5 times the readings' error, measured), their magnitudes the public
    # impulses to rounding (measured 5e-14 to 8e-11)
    assert q in cc.derived_errors and f"Fx[{next(iter(sc.joints))}]" in cc.derived_errors
    assert not set(cc.derived_errors) & set(cc.errors)
    assert max(cc.derived_errors.values()) <= 3 * tol
    assert cc.record.vector_check <= 1e-9
    # the joints stay together as a converged run's do: measured 0.11 to 0.31 a dt^2,
    # 1/16 of the bound at most
    assert cc.record.drift <= 0.1 * cc.settings["drift_bound"]
    assert s["rows_compared"] > 0.4 * s["rows"]


def test_error_falls_as_dt_squared():
    raw = constant_speed("four_bar")
    e1 = crosscheck(raw, steps_per_revolution=1000, iterations=10,
                    samples_per_revolution=SAMPLES).max_error
    e2 = crosscheck(raw, steps_per_revolution=2000, iterations=10,
                    samples_per_revolution=SAMPLES).max_error
    assert math.log2(e1 / e2) == pytest.approx(2.0, abs=0.1)


def test_pymunk_default_joint_settings_are_far_worse():
    """pymunk's default error_bias (0.9^60 per second) leaves errors near 1e-3."""
    default = pymunk.PivotJoint(pymunk.Body(1, 1), pymunk.Body(1, 1), (0, 0)).error_bias
    cc = crosscheck(constant_speed("four_bar"), steps_per_revolution=4000, iterations=10,
                    samples_per_revolution=SAMPLES, error_bias=default)
    assert cc.max_error > 1e-3


# ----------------------------------------------------------------------------- model
@pytest.mark.parametrize("name", ["four_bar", "slider_crank", "scotch_yoke",
                                  "sliding_driver", "slotted_lever"])
def test_space_holds_only_what_the_physics_needs(name):
    sc = ks.load_scene(scene_path(name))
    m = build_space(constant_speed(name), dt=1e-4, iterations=10)
    space = m.space
    assert len(space.shapes) == 0
    assert space.sleep_time_threshold == math.inf
    assert space.gravity == sc.gravity
    dynamic = [b for b in space.bodies if b.body_type == pymunk.Body.DYNAMIC]
    assert len(dynamic) == len(sc.bodies)
    extra = [b for b in space.bodies if b.body_type != pymunk.Body.DYNAMIC]
    assert len(extra) == (1 if sc.driver.kind == "T" else 0)      # the actuator
    for name_, b in sc.bodies.items():
        body = m.bodies[name_]
        assert body.mass == b.mass
        assert tuple(body.center_of_gravity) == tuple(b.cog)
        assert body.moment == (math.inf if name_ in m.translating else b.inertia)
    for c in space.constraints:
        assert c.error_bias == 0.0
        assert c.max_bias == math.inf
        assert not c.collide_bodies
    kinds = [type(c).__name__ for c in space.constraints]
    n_r = sum(j.kind == "R" for j in sc.joints.values())
    n_t = sum(j.kind == "T" for j in sc.joints.values())
    assert kinds.count("PivotJoint") == n_r
    assert kinds.count("GrooveJoint") == n_t + (sc.driver.kind == "T")
    assert kinds.count("SimpleMotor") == (sc.driver.kind == "R")
    # a lock only between bodies that both turn
    locks = kinds.count("GearJoint")
    turning = {n for n in sc.bodies if n not in m.translating}
    assert locks == sum(j.kind == "T" and j.guide in turning and j.slider in turning
                        for j in sc.joints.values())


def test_translating_bodies_and_locks():
    m = build_space(ks.example("scotch_yoke"), dt=1e-4)
    assert m.translating == {"yoke", "block"}
    assert not any(isinstance(c, pymunk.GearJoint) for c in m.space.constraints)
    m = build_space(ks.example("slotted_lever"), dt=1e-4)
    assert m.translating == set()
    assert sum(isinstance(c, pymunk.GearJoint) for c in m.space.constraints) == 1


def test_bodies_start_on_the_exact_kinematic_state():
    dt = 1e-5
    m = build_space(ks.example("four_bar"), dt=dt)
    sol = sim.reference_solution(m.scene, [m.start])
    for name, b in m.scene.bodies.items():
        mm = sol.kin.bodies[name].take(slice(1, 2))
        body = m.bodies[name]
        gx, gy = (float(np.ravel(v)[0]) for v in mm.point(b.cog))
        cx, cy = body.local_to_world(b.cog)
        # half a step from the exact pose (x - a dt^2/2: measured 2.2e-9 to 4.7e-9 m)
        assert math.hypot(cx - gx, cy - gy) < 1e-8
        # and the angular velocity half a step on, omega + alpha dt / 2 (measured: equal)
        half_step = float(np.ravel(mm.omega)[0]) + float(np.ravel(mm.alpha)[0]) * dt / 2
        assert body.angular_velocity == pytest.approx(half_step, rel=1e-12, abs=1e-12)


def test_start_has_no_transient():
    cc = crosscheck(ks.example("four_bar"), steps_per_revolution=4000, iterations=10,
                    revolutions=2)
    w = cc.wide()
    first = w[w.time <= cc.settings["dt"] * 4000]
    err = np.max(np.abs(first["F[C] sim"] - first["F[C] ks"])) / first["F[C] ks"].max()
    assert err < 5 * cc.errors["F[C]"]


def test_motor_holds_the_speed_and_me_changes_sign():
    cc = crosscheck(ks.example("four_bar"), steps_per_revolution=2000, iterations=10,
                    samples_per_revolution=SAMPLES)
    me = cc.record.signed["driver"]
    assert me.min() < 0 < me.max()
    w = cc.record.velocity[:, 0, 2]              # the crank's angular velocity
    assert np.allclose(w, 30.0, rtol=1e-9)
    # positions are the simulated driver angles, uniformly spaced
    step = cc.settings["sample_every"] * 360.0 / cc.settings["steps_per_revolution"]
    assert np.allclose(np.diff(cc.record.position), step, rtol=1e-9)


def test_fast_path_matches_public_api():
    raw = constant_speed("slider_crank")
    a = crosscheck(raw, steps_per_revolution=1000, iterations=30, fast=True,
                   samples_per_revolution=SAMPLES)
    b = crosscheck(raw, steps_per_revolution=1000, iterations=30, fast=False,
                   samples_per_revolution=SAMPLES)
    assert a.record.fast and not b.record.fast
    for k in a.record.impulse:
        np.testing.assert_array_equal(a.record.impulse[k], b.record.impulse[k])


def test_resist_rows_at_dead_centres_are_left_out():
    cc = crosscheck(ks.example("slider_crank"), steps_per_revolution=2000, iterations=30,
                    samples_per_revolution=360)
    s = cc.summary()
    # 0 and 180 deg of the second turn: the piston stands still, the force flips
    assert s["rows_compared"] < 360
    assert any("left out" in n for n in s["notes"])


def test_auto_iterations_double_until_settled():
    cc = crosscheck(ks.example("four_bar"), steps_per_revolution=1000,
                    samples_per_revolution=SAMPLES)
    assert cc.settings["iterations"] == 30
    assert cc.settings["iterations_tried"] == [30, 60]


# ----------------------------------------------------------------------------- refusals
def test_accelerating_driver_is_refused():
    with pytest.raises(SimulationError, match="acceleration"):
        crosscheck(SCENES / "oscillating_cylinder.toml")


def test_massless_body_is_refused():
    raw = constant_speed("four_bar")
    raw["bodies"][1] = dict(raw["bodies"][1], mass=0.0)
    with pytest.raises(SimulationError, match="coupler"):
        crosscheck(raw)


@pytest.mark.parametrize("kw", [{"dt": -1.0}, {"dt": 1.0}, {"steps_per_revolution": 3},
                                {"revolutions": 1.0}])
def test_bad_settings_are_refused(kw):
    with pytest.raises(SimulationError):
        crosscheck(ks.example("four_bar"), iterations=10, **kw)


def test_run_checks_pinned_version(monkeypatch):
    m = build_space(ks.example("four_bar"), dt=1e-4, iterations=10)
    monkeypatch.setattr(pymunk, "version", "0.0.0")
    with pytest.raises(SimulationError, match="fast"):
        run(m, 10, 5, fast=True)
    rec = run(m, 10, 5)                      # falls back to the public API
    assert not rec.fast


# ----------------------------------------------------------------------------- CLI
def test_cli_json(capsys):
    assert main(["crosscheck", str(ks.example("four_bar")), "--json", "--steps", "1000",
                 "--iterations", "10", "--samples", "90"]) == 0
    d = json.loads(capsys.readouterr().out)
    for key in ("dt", "iterations", "seconds_per_revolution", "max_error", "errors"):
        assert key in d
    assert d["iterations"] == 10
    assert d["dt"] == pytest.approx(2 * math.pi / 30 / 1000)
    assert d["max_error"] == max(d["errors"].values())
    assert {"F[A]", "F[B]", "F[C]", "F[D]", "|Me|"} == set(d["errors"])
    assert "Me" in d["derived_errors"] and "Fx[A]" in d["derived_errors"]
    assert d["seconds_per_revolution"] > 0        # reported; how fast is the machine's affair


def test_cli_table_and_files(capsys, tmp_path):
    rows, png = tmp_path / "rows.csv", tmp_path / "cc.png"
    assert main(["crosscheck", "slider_crank", "--steps", "1000", "--iterations", "30",
                 "--samples", "90", "--rows", str(rows), "--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "max error" in out and "F[C-slide]" in out and "Me" in out
    assert rows.stat().st_size > 0 and png.stat().st_size > 0


def test_cli_speed_override(capsys):
    assert main(["crosscheck", "four_bar", "--speed", "150", "--steps", "1000",
                 "--iterations", "10", "--samples", "90", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["dt"] == pytest.approx(2 * math.pi / 150 / 1000)
    assert d["title"].endswith("at 150")


@pytest.mark.parametrize("argv,msg", [
    (["crosscheck", "no_such_scene"], "no such scene"),
    (["crosscheck", str(SCENES / "trt_slotted_crank.toml")], "acceleration"),
    (["crosscheck", "four_bar", "--study", "--study-steps", "a,b"], "study-steps"),
    (["crosscheck", "four_bar", "--speed", "0"], "speed"),
])
def test_cli_errors(capsys, argv, msg):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and msg in err
    assert len(err.strip().splitlines()) == 1


def test_cli_study(capsys):
    assert main(["crosscheck", "four_bar", "--study", "--study-steps", "500,1000",
                 "--study-iterations", "10", "--samples", "45", "--serial"]) == 0
    out = capsys.readouterr().out
    assert "observed order (10 iterations)" in out
    assert "cheapest run with error <= 1e-05" in out


# ----------------------------------------------------------------------------- study
def test_study_table_order_and_plots():
    st = study(ks.example("four_bar"), steps=(500, 1000, 2000), iterations=(10,),
               samples_per_revolution=45)
    t = st.table
    assert list(t.columns) == ["case", "dt", "steps_per_revolution", "iterations",
                               "ms_per_revolution", "max_error", "diverged", "drift",
                               "solver", "order", "timing_noise"]
    assert set(t.solver) == {"driver last"}
    assert len(t) == 3 and not t.diverged.any()
    assert t.steps_per_revolution.tolist() == [500, 1000, 2000]
    assert st.order_points[10] == (3, 3, 0)
    assert st.order[10] == pytest.approx(2.0, abs=0.1)
    assert t.max_error.is_monotonic_decreasing
    fig = plot_study(st)
    assert isinstance(fig, Figure)
    assert fig.axes[0].get_xscale() == "log" and fig.axes[0].get_yscale() == "log"
    assert fig.axes[0].get_xlabel() and fig.axes[0].get_ylabel()
    s = st.summary()
    assert s["best_1e-5"] is None or s["best_1e-5"]["max_error"] <= 1e-5


def test_plot_comparison_has_a_panel_per_quantity(runs):
    cc = runs["scotch_yoke"]
    fig = plot_comparison(cc)
    assert isinstance(fig, Figure)
    visible = [ax for ax in fig.axes if ax.get_visible()]
    # every joint's |F|, the couple of the prismatic joint kinetostatics finds non-zero
    # (yoke-guide) and the signed Me, which stands for |Me| too
    assert len(visible) == len(cc.errors) + 1
    assert "Me: error" in visible[-1].get_title()
    for ax in visible:
        assert "(" in ax.get_ylabel() and ax.get_xlabel()


def test_error_table_and_wide(runs):
    cc = runs["slider_crank"]
    t = cc.error_table()
    assert set(t[t.source == "pymunk"].quantity) == set(cc.errors)
    assert set(t[t.source == "momentum balance"].quantity) <= set(cc.derived_errors)
    assert (t.error <= t.max_abs_error / t.scale * (1 + 1e-12)).all()
    w = cc.wide()
    assert {"F[A] sim", "F[A] ks", "Me sim", "Me ks", "used"} <= set(w.columns)


def test_raw_scene_is_not_modified():
    raw = constant_speed("four_bar")
    before = copy.deepcopy(raw)
    crosscheck(raw, steps_per_revolution=500, iterations=10, samples_per_revolution=45)
    assert raw == before


def test_the_package_names_are_its_modules_all():
    """The package's lazy table is read from its modules' ``__all__``: the names are
    exactly their union (the command line's module apart), each from its module."""
    import importlib
    import pkgutil

    import kinetostatics.simulation as sim
    union = {}
    for info in pkgutil.iter_modules(sim.__path__):
        module = importlib.import_module(f"kinetostatics.simulation.{info.name}")
        assert isinstance(module.__all__, list), info.name
        assert all(hasattr(module, n) for n in module.__all__), info.name
        if info.name != "cli":
            assert not set(module.__all__) & set(union), info.name     # each name once
            union.update(dict.fromkeys(module.__all__, module))
    assert sim.__all__ == sorted(union)
    assert all(getattr(sim, n) is getattr(union[n], n) for n in union)


@pytest.mark.slow     # a new interpreter per name (1.2 s)
def test_public_names_load_lazily():
    import subprocess
    import sys
    code = ("import sys, kinetostatics.simulation as s, kinetostatics.simulation.cli; "
            "print('pymunk' in sys.modules); [getattr(s, n) for n in s.__all__]; "
            "print('pymunk' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["False", "True"]


def test_cli_parser_does_not_import_pymunk():
    import subprocess
    import sys
    code = ("import sys; from kinetostatics.cli import build_parser; build_parser(); "
            "print('pymunk' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "False"
