"""The benchmark's scenes are the hand-written baseline's mechanisms (the speed ratios of
``python -m kinetostatics bench`` compare like with like)."""

from __future__ import annotations

import numpy as np
import pytest

from kinetostatics.bench import (
    find_reference,
    fourbar_scene,
    load_reference,
    slider_crank_reference_scene,
)
from kinetostatics.results import solve


@pytest.fixture(scope="module")
def ref():
    return load_reference(find_reference())


def test_the_bundled_baseline_is_the_default() -> None:
    from kinetostatics.bench import reference
    assert load_reference() is reference and load_reference(find_reference()) is reference
    assert find_reference().is_file() and find_reference().parent.name == "bench"


def test_the_baselines_four_bar_against_the_half_angle_solution(ref) -> None:
    """The baseline's kinematics (circle intersection, loop projected on u and w) against
    the Freudenstein half-angle solution with Norton's formulas, written apart."""
    from kinetostatics.bench import fourbar_closed_form
    th = np.deg2rad(np.linspace(0.0, 360.0, 721))
    got, want = ref.fourbar_kin(th, 20.0), fourbar_closed_form(th, 20.0)
    for key in ("Cx", "Cy", "w3", "w4", "al3", "al4"):
        scale = np.abs(want[key]).max()
        # measured at most 1.1e-15 (al3)
        assert np.abs(got[key] - want[key]).max() <= 5e-15 * scale, key


@pytest.mark.parametrize("mechanism", ["fourbar", "slider"])
def test_the_baselines_me_closes_the_virtual_power(ref, mechanism) -> None:
    """Me w2 + P . vC = the rate of change of kinetic energy, sum m a . v + I alpha w,
    at every row (virtual power: it checks the forces without the solver)."""
    th = np.deg2rad(np.linspace(0.0, 360.0, 721))
    if mechanism == "fourbar":
        w2, p = 20.0, ref.FB
        r = ref.fourbar_dyad(th, w2)
        k = r["kin"]
        vc, ac = (k["vCx"], k["vCy"]), (k["aCx"], k["aCy"])
        cogs = [(p["m3"], p["I3"], 0.5, (k["vBx"] + vc[0], k["vBy"] + vc[1]),
                 (k["aBx"] + ac[0], k["aBy"] + ac[1]), k["w3"], k["al3"]),
                (p["m4"], p["I4"], 0.5, vc, ac, k["w4"], k["al4"])]
        load = p["P"][0] * vc[0] + p["P"][1] * vc[1]
    else:
        w2, p = ref.SC["w2"], ref.SC
        r = ref.slider_dyad(th, w2)
        k = r["kin"]
        cogs = [(p["m3"], p["I3"], 0.5, (k["vBx"] + k["vCx"], k["vBy"]),
                 (k["aBx"] + k["aCx"], k["aBy"]), k["w3"], k["al3"]),
                (p["m4"], 0.0, 1.0, (k["vCx"], 0.0), (k["aCx"], 0.0), 0.0, 0.0)]
        load = 0.0
    cogs.append((p["m2"], p["I2"], 0.5, (k["vBx"], k["vBy"]), (k["aBx"], k["aBy"]), w2, 0.0))
    kinetic = sum(m * f * f * (a[0] * v[0] + a[1] * v[1]) + inertia * al * w
                  for m, inertia, f, v, a, w, al in cogs)
    residual = r["Me"] * w2 + load - kinetic
    # measured 4.4e-16 (four-bar), 3.9e-16 (slider-crank)
    assert np.abs(residual).max() <= 2e-15 * np.abs(r["Me"] * w2).max()


def test_the_slider_crank_scene_is_the_baselines(ref) -> None:
    th = np.deg2rad(np.linspace(0.0, 360.0, 721))
    want = ref.slider_dyad(th, ref.SC["w2"])
    sol = solve(slider_crank_reference_scene(721, ref.SC))
    scale = np.abs(want["Me"]).max()
    assert np.abs(sol.Me - want["Me"]).max() <= 2e-15 * scale      # measured 4.8e-16
    fx, fy = sol.reaction("B")          # on the rod from the crank: the baseline's F23
    f = np.abs(want["FB"][0]).max()
    assert np.abs(fx - want["FB"][0]).max() <= 2e-15 * f            # measured 3.4e-16
    assert np.abs(fy - want["FB"][1]).max() <= 2e-15 * np.abs(want["FB"][1]).max()


def test_the_four_bar_scene_is_the_baselines(ref) -> None:
    th = np.deg2rad(np.linspace(0.0, 360.0, 721))
    want = ref.fourbar_dyad(th, 20.0)
    sol = solve(fourbar_scene(721))
    assert np.abs(sol.Me - want["Me"]).max() <= 5e-15 * np.abs(want["Me"]).max()


def test_the_slider_crank_scene_without_the_baseline_file() -> None:
    """The scene built from the baseline's numbers (here a copy of them, for a clone
    without ../shared): its piston follows the project's own closed form (seed 004) and
    its Me balances the inertia forces' power (virtual power)."""
    from kinetostatics.bench import slider_closed_form
    from tests.kinetostatics import checks
    p = {"r": 0.15, "l": 0.35, "m2": 2.0, "m3": 3.0, "m4": 1.5,
         "I2": 2.0 * 0.15**2 / 12, "I3": 3.0 * 0.35**2 / 12, "w2": 50.0 * np.pi}
    sol = solve(slider_crank_reference_scene(721, p))
    piston = sol.kinematics.query("body == 'piston' and point == 'C'")
    want = slider_closed_form(np.deg2rad(sol.positions), p["w2"])
    for col, key in (("x", "x"), ("vx", "v"), ("ax", "a")):
        scale = np.abs(want[key]).max()
        # measured 2.2e-16 (x), 2.8e-16 (v), 3.4e-16 (a)
        assert np.abs(piston[col].to_numpy() - want[key]).max() <= 2e-15 * scale
    assert checks.virtual_power(sol) <= 2e-15                        # measured 3.9e-16


def test_side_by_side_in_warm_batches(monkeypatch) -> None:
    """Each round times ``batch`` calls with the collector paused (timeit's way) and
    gives the time per call; the collector runs again after; a small size gets its
    warm row, a large one none (no time is asserted: speed lives in the bench)."""
    import gc

    from kinetostatics.bench import speed as B

    # (a full collection before each round costs about 0.8 s in the test suite's
    # process, which holds every module and fixture: counted here, not made)
    collected = []
    monkeypatch.setattr(gc, "collect", lambda *a: collected.append(1) or 0)

    calls = {"a": 0, "b": 0}
    seen = []

    def job(k):
        def f():
            calls[k] += 1
            seen.append(gc.isenabled())
            if count_frozen:
                # (get_freeze_count walks the frozen heap: the suite's worker holds
                # millions of objects, so counted in the first rounds alone: counted in
                # every warm batch below, this test took 84 s of CPU, 2026-11-30)
                frozen.append(gc.get_freeze_count())
        return f
    frozen: list[int] = []
    count_frozen = True
    times = B.side_by_side({"a": job("a"), "b": job("b")}, 2, batch=3)
    assert calls == {"a": 6, "b": 6} and [len(v) for v in times.values()] == [2, 2]
    assert len(collected) == 5                # once before freezing, before each job's round
    assert not any(seen) and gc.isenabled()
    # the heap frozen while the jobs run (the collections walk what they made), then not
    assert min(frozen) > 0 and gc.get_freeze_count() == 0
    count_frozen = False
    seen.clear()
    B.side_by_side({"a": job("a")}, 1)
    assert seen == [True]                   # one call a round: the collector left on
    rows = B._warm(2001, "x / y", {"reference": job("a"), "solve": job("b")}, 0.0)
    assert [r["measure"] for r in rows] == [f"x / y (warm, batches of {B.WARM_BATCH} calls)"]
    assert B._warm(200_001, "x / y", {"reference": job("a"), "solve": job("b")}, 0.0) == []


def _shaper_power(ref, th):
    """The shaper baseline's Me w2 + the load's and gravity's power and the rate of
    change of its kinetic energy, sum m a . v + I alpha w (the motion from shaper_kin)."""
    p, w2 = ref.SH, ref.SH["w2"]
    r = ref.shaper_dyad(th, w2)
    k = r["kin"]
    vf, af = (k["vFx"], 0.0), (k["aFx"], 0.0)
    ve, ae = (k["vEx"], k["vEy"]), (k["aEx"], k["aEy"])
    va, aa = (k["vAx"], k["vAy"]), (k["aAx"], k["aAy"])

    def half(a, b=(0.0, 0.0)):
        return 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])
    bodies = [(p["m2"], p["I2"], half(va), half(aa), w2, 0.0),
              (p["m3"], p["I3"], va, aa, k["w4"], k["al4"]),
              (p["m4"], p["I4"], half(ve), half(ae), k["w4"], k["al4"]),
              (p["m5"], p["I5"], half(ve, vf), half(ae, af), k["w5"], k["al5"]),
              (p["m6"], 0.0, vf, af, 0.0, 0.0)]
    kinetic = sum(m * (a[0] * v[0] + a[1] * v[1]) + inertia * al * w
                  for m, inertia, v, a, w, al in bodies)
    weight = sum(-p["g"] * m * v[1] for m, _, v, _, _, _ in bodies)
    load = np.where(vf[0] * p["P"] < 0.0, p["P"], 0.0) * vf[0]
    return r["Me"] * w2 + load + weight, kinetic


def test_the_shaper_baselines_me_closes_the_virtual_power(ref) -> None:
    th = np.deg2rad(np.linspace(0.0, 360.0, 721))
    given, kinetic = _shaper_power(ref, th)
    # measured 6.3e-16 of the largest power
    assert np.abs(given - kinetic).max() <= 2e-15 * np.abs(kinetic).max()


def test_the_shaper_baselines_motion_against_finite_differences(ref) -> None:
    """Each velocity the derivative of its position, each acceleration of its velocity
    (central differences in the crank angle, h = 1e-5 rad: error about h^2)."""
    h, w2 = 1e-5, ref.SH["w2"]
    th = np.deg2rad(np.linspace(0.0, 360.0, 181))
    lo, mid, hi = (ref.shaper_kin(th + d, w2) for d in (-h, 0.0, h))
    for x, v in (("Ax", "vAx"), ("Ex", "vEx"), ("Ey", "vEy"), ("Fx", "vFx"),
                 ("vEx", "aEx"), ("vEy", "aEy"), ("vFx", "aFx"), ("w4", "al4"),
                 ("w5", "al5")):
        rate = (hi[x] - lo[x]) / (2.0 * h) * w2
        # measured at most 2.9e-10 of the rate's scale (vEy)
        assert np.abs(rate - mid[v]).max() <= 1e-9 * np.abs(mid[v]).max(), v


def test_the_shaper_is_the_baselines(ref) -> None:
    """The bundled shaper solved (both paths agree with it: the paths' own tests) against
    the baseline: Me, the crank's force on the block at A, the lever's on the link at E."""
    import kinetostatics as ks
    sol = solve(ks.example("shaper"))
    th = np.deg2rad(sol.positions)
    want = ref.shaper_dyad(th, ref.SH["w2"])
    # measured 9.8e-16
    assert np.abs(sol.Me - want["Me"]).max() <= 5e-15 * np.abs(want["Me"]).max()
    for joint, on, key in (("A", "block", "FA"), ("E", "link", "FE")):
        rows = sol.reactions[(sol.reactions["joint"] == joint) & (sol.reactions["on"] == on)]
        for col, w in zip(("Fx", "Fy"), want[key], strict=True):
            # measured at most 3.0e-15 (E, Fy)
            assert np.abs(rows[col].to_numpy() - w).max() <= 1e-14 * np.abs(w).max(), (
                joint, col)
