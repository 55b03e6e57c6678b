"""Cams (seed 002 ch. 1): laws, base circle, profile, forces and the [cam] scene.

Expected values come from closed forms typed from the seed, from finite differences of the
computed curves, or from equilibrium equations solved here with numpy.linalg, never from
the module's own formulas.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetostatics import cams
from kinetostatics.cams import CamError, CamLaw, OscillatingFollower, TranslatingFollower
from kinetostatics.model.errors import SceneError, WorkbenchError

LAWS = list(cams.LAWS)
strokes = st.floats(1e-3, 0.5)
spans = st.floats(math.radians(20.0), math.radians(200.0))


def seed_law() -> CamLaw:
    """Seed 002 s. 1.5: h = 10 mm, rise 90 (parabolic), dwell 60, return 120 (cosine), 90."""
    return CamLaw.cycle(0.010, "constant-acceleration", 90.0, "cosine-acceleration", 120.0,
                        top_dwell_deg=60.0, bottom_dwell_deg=90.0)


# ----------------------------------------------------------------------------- laws

@settings(max_examples=30, deadline=None)
@given(law=st.sampled_from(LAWS), h=strokes, span=spans)
def test_rise_boundary_conditions(law, h, span):
    s, ds, dds = cams.rise(law, np.array([0.0, span]), h, span)
    assert s[0] == pytest.approx(0.0, abs=1e-15 * h)
    assert s[1] == pytest.approx(h, rel=1e-13)
    if law != "zero-acceleration":          # the only law with velocity jumps (eq. 1.4)
        assert np.allclose(ds, 0.0, atol=1e-13 * h / span)


@settings(max_examples=30, deadline=None)
@given(law=st.sampled_from(LAWS), h=strokes, span=spans)
def test_law_derivatives_match_finite_differences(law, h, span):
    x = np.linspace(0.03, 0.97, 41) * span
    x = x[np.abs(x - 0.5 * span) > 0.02 * span]        # dds of the parabolic law jumps at 1/2
    d = 1e-5 * span
    s_p, ds_p, _ = cams.rise(law, x + d, h, span)
    s_m, ds_m, _ = cams.rise(law, x - d, h, span)
    _, ds, dds = cams.rise(law, x, h, span)
    scale_v, scale_a = h / span, h / span**2
    assert np.allclose((s_p - s_m) / (2 * d), ds, atol=1e-7 * scale_v)
    assert np.allclose((ds_p - ds_m) / (2 * d), dds, atol=1e-6 * scale_a)


@pytest.mark.parametrize("law, cv, ca, v_at, a_at", [
    ("constant-acceleration", 2.0, 4.0, 0.5, None),         # eqs 1.8-1.9
    ("cosine-acceleration", math.pi / 2, math.pi**2 / 2, 0.5, 0.0),   # eq. 1.14
    ("sine-acceleration", 2.0, 2.0 * math.pi, 0.5, 0.25),   # eq. 1.21: a_max at phi_u / 4
])
def test_peak_values_of_eqs_1_14_and_1_21(law, cv, ca, v_at, a_at):
    h, span = 0.012, math.radians(75.0)
    x = np.linspace(0.0, span, 200_001)
    _, ds, dds = cams.rise(law, x, h, span)
    assert ds.max() == pytest.approx(cv * h / span, rel=1e-12)
    assert np.abs(dds).max() == pytest.approx(ca * h / span**2, rel=1e-9)
    assert x[np.argmax(ds)] == pytest.approx(v_at * span, abs=2 * span / 200_000)
    if a_at is not None:
        assert x[np.argmax(dds)] == pytest.approx(a_at * span, abs=2 * span / 200_000)
    assert cams.law_peaks(law, h, span) == pytest.approx((cv * h / span, ca * h / span**2))


def test_return_laws_of_eqs_1_15_and_1_22():
    h, pc = 0.02, math.radians(110.0)
    x = np.linspace(0.0, pc, 97)
    s, ds, dds = cams.fall("cosine-acceleration", x, h, pc)                 # eq. 1.15
    assert np.allclose(s, h - h / 2 * (1 - np.cos(np.pi / pc * x)), atol=1e-15)
    assert np.allclose(ds, -np.pi * h / (2 * pc) * np.sin(np.pi / pc * x), atol=1e-15)
    assert np.allclose(dds, -np.pi**2 * h / (2 * pc**2) * np.cos(np.pi / pc * x), atol=1e-14)
    s, ds, dds = cams.fall("sine-acceleration", x, h, pc)                   # eq. 1.22
    assert np.allclose(s, h - h * (x / pc - np.sin(2 * np.pi / pc * x) / (2 * np.pi)), atol=1e-15)
    assert np.allclose(ds, -h / pc * (1 - np.cos(2 * np.pi / pc * x)), atol=1e-15)
    assert np.allclose(dds, -2 * np.pi * h / pc**2 * np.sin(2 * np.pi / pc * x), atol=1e-14)
    for law in LAWS:                       # a return is the rise run backwards
        s_c = cams.fall(law, x, h, pc)[0]
        s_u = cams.rise(law, pc - x, h, pc)[0]
        assert np.allclose(s_c, s_u, atol=1e-15)


def test_law_names_and_aliases():
    assert cams.law_name("cycloidal") == "sine-acceleration"
    assert cams.law_name("Harmonic") == "cosine-acceleration"
    with pytest.raises(CamError, match="did you mean 'sine-acceleration'"):
        cams.law_name("sine-aceleration")
    with pytest.raises(CamError, match="phase"):
        cams.rise("parabolic", [1.0], 0.01, 0.5)


def test_program_is_continuous_and_periodic():
    law = seed_law()
    joints = np.radians([90.0, 150.0, 270.0, 360.0])
    eps = 1e-9
    s_l = law(joints - eps)[0]
    s_r = law(joints + eps)[0]
    assert np.allclose(s_l, s_r, atol=1e-9)
    phi = np.linspace(-7.0, 7.0, 101)
    assert np.allclose(law(phi)[0], law(phi + 2 * np.pi)[0], atol=1e-15)
    s, ds, _ = law(np.radians([45.0, 120.0, 210.0, 300.0]))
    assert s == pytest.approx([0.005, 0.010, 0.005, 0.0], abs=1e-15)
    assert ds[1] == ds[3] == 0.0
    peaks = law.peaks()
    assert list(peaks["kind"]) == ["rise", "dwell", "return", "dwell"]
    assert peaks["ds_max"].iloc[2] == pytest.approx(np.pi * 0.010 / (2 * np.radians(120)))


@pytest.mark.parametrize("segments, message", [
    ([("rise", 90, "parabolic"), ("return", 90, "parabolic")], "add up to 180"),
    ([("return", 180, "parabolic"), ("rise", 180, "parabolic")], "cannot start on the base"),
    ([("rise", 180, "parabolic"), ("dwell", 180, None)], "ends at the top"),
    ([("rise", 180, None), ("return", 180, "parabolic")], "needs a motion law"),
    ([("rize", 180, "parabolic"), ("return", 180, "parabolic")], "did you mean 'rise'"),
])
def test_program_errors(segments, message):
    segs = tuple(cams.Segment(k, math.radians(a), law) for k, a, law in segments)
    with pytest.raises(CamError, match=message):
        CamLaw(0.01, segs)


# ----------------------------------------------------------------------------- geometry

def _numerical_tau(law, follower, phi, d=1e-6):
    """Transmission angle from the pitch curve alone: finite-difference tangent in the cam
    frame, turned back to the fixed frame, against the follower's direction of motion."""
    prof = cams.profile(law, follower, np.concatenate((phi - d, phi + d)))
    n = phi.size
    tx = (prof.x_pitch.to_numpy()[n:] - prof.x_pitch.to_numpy()[:n]) / (2 * d)
    ty = (prof.y_pitch.to_numpy()[n:] - prof.y_pitch.to_numpy()[:n]) / (2 * d)
    c, s = np.cos(phi), np.sin(phi)
    fx, fy = c * tx - s * ty, s * tx + c * ty               # R(phi) t: fixed frame
    if isinstance(follower, TranslatingFollower):
        ux, uy = np.zeros_like(phi), np.ones_like(phi)
    else:
        beta = law(phi)[0]
        th = np.pi + follower.beta0 + beta                  # rise_sense "same"
        ux, uy = -np.sin(th), np.cos(th)
    # tau = angle between the sliding direction and the follower's motion
    return np.arctan2(np.abs(fx * uy - fy * ux), np.abs(fx * ux + fy * uy))


@pytest.mark.parametrize("offset", [0.0, 0.004, -0.003])
def test_translating_transmission_angle(offset):
    law = seed_law()
    fol = TranslatingFollower(0.02, offset)
    phi = np.radians(np.linspace(1.0, 359.0, 59))
    phi = phi[np.abs(np.degrees(phi) % 90.0) > 1.0]
    tau = cams.transmission_angle(law, fol, phi)
    assert np.allclose(tau, _numerical_tau(law, fol, phi), atol=1e-7)
    s, ds, _ = law(phi)                                       # eq. 1.28 as printed
    s0 = math.sqrt(0.02**2 - offset**2)
    assert np.allclose(tau, np.arctan2(s + s0, np.abs(ds - offset)), atol=1e-14)


def test_oscillating_transmission_angle_is_eq_1_34():
    law = CamLaw.cycle(math.radians(18.0), "sine-acceleration", 100, "cosine-acceleration", 110,
                       top_dwell_deg=40.0)
    fol = OscillatingFollower(0.03, arm=0.05, pivot_distance=0.07)
    phi = np.radians(np.linspace(3.0, 357.0, 61))
    tau = cams.transmission_angle(law, fol, phi)
    assert np.allclose(tau, _numerical_tau(law, fol, phi), atol=1e-7)
    beta, dbeta, _ = law(phi)
    ac, cb, psi = 0.07, 0.05, fol.beta0 + beta
    tan_134 = ac * np.sin(psi) / (cb * dbeta - (cb - ac * np.cos(psi)))
    assert np.allclose(np.tan(tau), np.abs(tan_134), rtol=1e-12)
    # eq. 1.35: r0 from beta0
    assert math.sqrt(ac**2 + cb**2 - 2 * ac * cb * math.cos(fol.beta0)) == pytest.approx(0.03)


def test_base_radius_cosine_rise_closed_form():
    """e = 0, cosine rise (the fastest phase): s0 = max(k sin x - h/2 (1 - cos x)) with
    k = pi h tan(tau) / (2 phi_u), i.e. sqrt(k^2 + h^2/4) - h/2 (eq. 1.29)."""
    h, tau = 0.01, math.radians(60.0)
    law = CamLaw.cycle(h, "cosine-acceleration", 80, "cosine-acceleration", 160,
                       top_dwell_deg=40.0)
    k = math.pi * h * math.tan(tau) / (2 * math.radians(80))
    assert cams.base_radius_translating(law, tau) == pytest.approx(
        math.sqrt(k * k + h * h / 4) - h / 2, rel=1e-12)


@pytest.mark.parametrize("offset", [0.005, -0.005, 0.0])
def test_base_radius_translating_gives_the_admissible_angle(offset):
    law = seed_law()
    tau_adm = math.radians(45.0)
    r0 = cams.base_radius_translating(law, tau_adm, offset)
    phi = np.radians(np.linspace(0.0, 360.0, 72_001))
    tau = cams.transmission_angle(law, TranslatingFollower(r0, offset), phi)
    assert tau.min() >= tau_adm - 1e-12
    assert tau.min() == pytest.approx(tau_adm, abs=1e-7)
    smaller = cams.transmission_angle(law, TranslatingFollower(0.999 * r0, offset), phi)
    assert smaller.min() < tau_adm


def test_seed_example_radius_is_admissible():
    """Seed s. 1.5 adopts r0 ~ 20 mm for e = 5 mm, tau_adm = 45 deg: admissible (the least
    radius is smaller), and the optimal offset gives a smaller cam still."""
    law = seed_law()
    tau_adm = math.radians(45.0)
    phi = np.radians(np.linspace(0.0, 360.0, 36_001))
    assert cams.transmission_angle(law, TranslatingFollower(0.020, 0.005), phi).min() > tau_adm
    r_e = cams.base_radius_translating(law, tau_adm, 0.005)
    assert r_e < 0.020
    e_opt, r_opt = cams.optimal_offset(law, tau_adm)
    assert r_opt < r_e
    for e in (e_opt - 1e-4, e_opt + 1e-4, 0.0, 0.005):
        assert cams.base_radius_translating(law, tau_adm, e) >= r_opt * (1 - 1e-9)
    assert cams.base_radius_translating(law, tau_adm, e_opt) == pytest.approx(r_opt, rel=1e-9)


def test_base_radius_oscillating():
    law = CamLaw.cycle(math.radians(20.0), "sine-acceleration", 100, "sine-acceleration", 100,
                       top_dwell_deg=40.0)
    tau_adm = math.radians(25.0)                     # the seed's value for oscillating followers
    r0 = cams.base_radius_oscillating(law, tau_adm, arm=0.06, pivot_distance=0.08)
    phi = np.radians(np.linspace(0.0, 360.0, 36_001))
    tau = cams.transmission_angle(law, OscillatingFollower(r0, 0.06, 0.08), phi)
    assert tau.min() == pytest.approx(tau_adm, abs=1e-6)
    assert tau.min() >= tau_adm - 1e-12
    tau_less = cams.transmission_angle(law, OscillatingFollower(0.995 * r0, 0.06, 0.08), phi)
    assert tau_less.min() < tau_adm


def test_base_radius_oscillating_sized_again_for_each_change():
    """The radius sized once per (law, tau_adm, L, d, sense) is kept: a second sizing that
    changes any one of them is sized anew (each radius meets eq. 1.36 at its own tau_adm)."""
    # (a rise unlike its return: the two senses need two radii, 22.5 and 22.3 mm)
    law = CamLaw.cycle(math.radians(20.0), "sine-acceleration", 100, "cosine-acceleration",
                       100, top_dwell_deg=40.0)
    other = CamLaw.cycle(math.radians(24.0), "sine-acceleration", 100, "cosine-acceleration",
                         100, top_dwell_deg=40.0)
    phi = np.radians(np.linspace(0.0, 360.0, 36_001))
    base = (law, math.radians(25.0), 0.06, 0.08, "same")
    radii = set()
    for args in (base, base, (other, *base[1:]), (law, math.radians(30.0), *base[2:]),
                 (*base[:2], 0.07, *base[3:]), (*base[:3], 0.09, "same"),
                 (*base[:4], "opposite")):
        lw, tau_adm, arm, dist, sense = args
        r0 = cams.base_radius_oscillating(lw, tau_adm, arm, dist, sense)
        fol = OscillatingFollower(r0, arm, dist, rise_sense=sense)
        tau = cams.transmission_angle(lw, fol, phi)
        assert tau.min() == pytest.approx(tau_adm, abs=1e-6), args       # as above
        radii.add(r0)
    assert len(radii) == 6                           # the second sizing of base: the same


@pytest.mark.parametrize("offset", [0.0, 0.005, -0.004])
def test_profile_matches_eq_1_37(offset):
    law = seed_law()
    fol = TranslatingFollower(0.02, offset)
    phi = np.radians(np.linspace(0.0, 359.0, 360))
    prof = cams.profile(law, fol, phi)
    r, theta = cams.polar_profile_translating(phi, law(phi)[0], 0.02, offset)
    x, y = prof.x_pitch.to_numpy(), prof.y_pitch.to_numpy()
    assert np.allclose(np.hypot(x, y), r, rtol=1e-13)
    # theta is measured from A B0 against the (counter-clockwise) rotation
    ang0 = math.atan2(math.sqrt(0.02**2 - offset**2), offset)
    diff = np.angle(np.exp(1j * (np.arctan2(y, x) - (ang0 - theta))))
    assert np.allclose(diff, 0.0, atol=1e-12)


def test_profile_matches_eq_1_38():
    law = CamLaw.cycle(math.radians(15.0), "cosine-acceleration", 120, "sine-acceleration", 100,
                       top_dwell_deg=30.0)
    r0, arm, dist = 0.035, 0.05, 0.07
    fol = OscillatingFollower(r0, arm, dist)
    phi = np.radians(np.linspace(0.0, 359.0, 360))
    prof = cams.profile(law, fol, phi)
    r, theta = cams.polar_profile_oscillating(phi, law(phi)[0], r0, arm, dist)
    x, y = prof.x_pitch.to_numpy(), prof.y_pitch.to_numpy()
    assert np.allclose(np.hypot(x, y), r, rtol=1e-13)
    ang0 = math.atan2(y[0], x[0])
    diff = np.angle(np.exp(1j * (np.arctan2(y, x) - (ang0 - theta))))
    assert np.allclose(diff, 0.0, atol=1e-12)


def test_roller_envelope_and_curvature():
    law = seed_law()
    rr = 0.004
    fol = TranslatingFollower(0.02, 0.005, rr)
    d = 1e-5
    phi = np.radians(np.linspace(2.0, 358.0, 179))
    corners = np.array([45.0, 90.0, 150.0, 270.0])           # the curvature jumps there
    phi = phi[np.min(np.abs(np.degrees(phi)[:, None] - corners), axis=1) > 1.0]
    p0, pp, pm = (cams.profile(law, fol, x) for x in (phi, phi + d, phi - d))
    px, py = p0.x_pitch.to_numpy(), p0.y_pitch.to_numpy()
    wx, wy = p0.x_profile.to_numpy(), p0.y_profile.to_numpy()
    assert np.allclose(np.hypot(wx - px, wy - py), rr, rtol=1e-12)
    tx = (pp.x_pitch.to_numpy() - pm.x_pitch.to_numpy()) / (2 * d)
    ty = (pp.y_pitch.to_numpy() - pm.y_pitch.to_numpy()) / (2 * d)
    ax = (pp.x_pitch.to_numpy() - 2 * px + pm.x_pitch.to_numpy()) / d**2
    ay = (pp.y_pitch.to_numpy() - 2 * py + pm.y_pitch.to_numpy()) / d**2
    # the offset is normal to the pitch curve and points towards the cam (inner envelope)
    assert np.allclose(((wx - px) * tx + (wy - py) * ty) / np.hypot(tx, ty), 0.0, atol=1e-9)
    assert np.all((wx - px) * px + (wy - py) * py < 0.0)
    kappa = -(tx * ay - ty * ax) / np.hypot(tx, ty) ** 3   # cw traversal: convex > 0
    assert np.allclose(p0.curvature.to_numpy(), kappa, rtol=1e-4, atol=1e-3)
    dwell = cams.profile(law, fol, np.radians([300.0]))
    assert dwell.curvature.iloc[0] == pytest.approx(1 / 0.02, rel=1e-12)


def test_clockwise_cam_is_the_mirror_image():
    law = seed_law()
    fol = TranslatingFollower(0.02, 0.005, 0.003)
    phi = np.radians(np.linspace(0.0, 360.0, 37))
    ccw = cams.profile(law, fol, phi, "ccw")
    cw = cams.profile(law, fol, phi, "cw")
    assert np.allclose(cw.x_profile, -ccw.x_profile) and np.allclose(cw.y_profile, ccw.y_profile)
    with pytest.raises(CamError, match="rotation"):
        cams.profile(law, fol, phi, "clockwise")


# ----------------------------------------------------------------------------- forces

@settings(max_examples=40, deadline=None)
@given(tau_deg=st.floats(30.0, 90.0), mu=st.floats(0.0, 0.3), a=st.floats(0.005, 0.05),
       b=st.floats(0.01, 0.08), load=st.floats(1.0, 1e4), direction=st.sampled_from([1, -1]))
def test_follower_forces_solve_the_equilibrium(tau_deg, mu, a, b, load, direction):
    """Follower rod: contact force F12 at B (lateral F12 cos tau, axial F12 sin tau), load F
    along the axis, guide reactions N1 at height a and N2 at a + b (lateral, opposite),
    friction mu N against the motion (its moments neglected, as in eq. 1.40)."""
    tau = math.radians(tau_deg)
    k = mu * (2 * a + b) / b
    if math.sin(tau) - direction * k * math.cos(tau) < 0.05:
        return                                    # near self-locking: tested separately
    # unknowns F12, N1, N2; rows: lateral, axial, moments about B
    m = np.array([[math.cos(tau), -1.0, 1.0],
                  [math.sin(tau), -direction * mu, -direction * mu],
                  [0.0, a, -(a + b)]])
    f12, n1, n2 = np.linalg.solve(m, [0.0, load, 0.0])
    got = cams.translating_follower_forces(load, tau, mu, a, b, direction)
    assert np.allclose([float(g) for g in got], [f12, n1, n2], rtol=1e-10)


def test_follower_forces_limits_and_self_locking():
    f12, n1, n2 = cams.translating_follower_forces(100.0, math.pi / 2, 0.2, 0.02, 0.04)
    assert float(f12) == pytest.approx(100.0) and float(n1) == pytest.approx(0.0, abs=1e-12)
    tau_cr = float(cams.critical_transmission_angle(0.2, 0.02, 0.04))      # eq. 1.44
    assert math.tan(tau_cr) == pytest.approx(0.2 * (2 * 0.02 + 0.04) / 0.04)
    big = cams.translating_follower_forces(1.0, tau_cr + 1e-6, 0.2, 0.02, 0.04)[0]
    assert float(big) > 1e4
    with pytest.raises(CamError, match=r"self-locks at cam angle 12\.5 deg"):
        cams.translating_follower_forces([1.0], [tau_cr - 1e-3], 0.2, 0.02, 0.04,
                                         angles=[math.radians(12.5)])
    # falling, friction helps: no locking
    assert float(cams.translating_follower_forces(1.0, tau_cr - 1e-3, 0.2, 0.02, 0.04, -1)[0]) > 0
    # oscillating: F12 = M / (L sin tau - mu r) (eq. 1.47), sin tau_cr = mu r / L (eq. 1.48)
    f = cams.oscillating_follower_force(3.0, math.radians(60), 0.05, 0.1, 0.006)
    assert float(f) == pytest.approx(3.0 / (0.05 * math.sin(math.radians(60)) - 0.1 * 0.006))
    cr = cams.critical_transmission_angle_oscillating(0.1, 0.006, 0.05)
    assert math.sin(cr) == pytest.approx(0.1 * 0.006 / 0.05)
    with pytest.raises(CamError, match="eq. 1.48"):
        cams.oscillating_follower_force(3.0, cr * 0.9, 0.05, 0.1, 0.006)


# ----------------------------------------------------------------------------- scenes

def segments_toml(*segments: tuple) -> str:
    """``[[cam.segments]]`` tables, one per (kind, law, angle); a dwell has no law."""
    tables = []
    for kind, law, angle in segments:
        rows = [f'kind = "{kind}"', *([f'law = "{law}"'] if law else []), f"angle = {angle!r}"]
        tables.append("[[cam.segments]]\n" + "\n".join(rows) + "\n")
    return "\n".join(tables)


SEED_SCENE = """
title = "Seed 002 s. 1.5"
format = 1

[cam]
speed_rpm = 300.0
base_radius = 0.020
roller_radius = 0.004
count = 721

[cam.follower]
kind = "translating"
stroke = 0.010
offset = 0.005

""" + segments_toml(("rise", "constant-acceleration", 90.0), ("dwell", None, 60.0),
                    ("return", "harmonic", 120.0), ("dwell", None, 90.0)) + """
[cam.loads]
force = 20.0
mass = 0.2
gravity = 9.81
spring_rate = 2000.0
spring_preload = 10.0
friction = 0.15
guide_length = 0.030
guide_gap = 0.025
"""


def test_seed_scene_solves_with_power_balance():
    res = cams.solve_cam(SEED_SCENE)
    sm = res.summary
    assert sm["base_radius"] == 0.020
    assert sm["working_base_radius"] == pytest.approx(0.016)
    phi = np.radians(np.linspace(0.0, 360.0, 720_001))
    tau = cams.transmission_angle(seed_law(), TranslatingFollower(0.02, 0.005), phi)
    assert sm["transmission_angle_min"] == pytest.approx(np.degrees(tau.min()), abs=1e-7)
    assert sm["transmission_angle_min"] <= np.degrees(tau.min())
    omega = 300.0 * 2 * math.pi / 60
    assert sm["velocity_max"] == pytest.approx(omega * 2 * 0.010 / (math.pi / 2))    # eq. 1.8
    assert sm["acceleration_max"] == pytest.approx(omega**2 * 4 * 0.010 / (math.pi / 2) ** 2)
    mot, frc = res.motion, res.forces
    assert len(mot) == len(frc) == len(res.geometry) == 721
    # axial load: force + preload + k s + m (a + g)
    load = 20.0 + 10.0 + 2000.0 * mot.s + 0.2 * (mot.a + 9.81)
    assert np.allclose(frc.load, load, rtol=1e-12)
    # power: the shaft's torque omega = (load + friction against the motion) v
    v = mot.v.to_numpy()
    assert np.allclose(frc.torque * omega, (load + np.sign(v) * frc.friction) * v,
                       atol=1e-9 * np.abs(frc.torque * omega).max())
    assert sm["separation_rows"] == 0 and not sm["undercut"]
    friction_work = np.trapezoid(frc.friction * np.abs(mot.ds), np.radians(mot.angle))
    assert sm["friction_work"] == pytest.approx(friction_work)
    # cycle mean torque: friction work per radian, the conservative loads cancelling over
    # the cycle up to the trapezoid rule's error, first order in the row spacing (the
    # constant-acceleration rise's jumps of m a): measured 4.36e-3 at 0.5 deg rows,
    # 1.08e-3 at 0.125 deg (4.05 times less)
    assert sm["torque_mean"] == pytest.approx(friction_work / (2 * math.pi), rel=5e-3)
    fine = cams.solve_cam(SEED_SCENE.replace("count = 721", "count = 2881"))
    fine_work = np.trapezoid(fine.forces.friction * np.abs(fine.motion.ds),
                             np.radians(fine.motion.angle))
    coarse_off = sm["torque_mean"] / (friction_work / (2 * math.pi)) - 1.0
    fine_off = fine.summary["torque_mean"] / (fine_work / (2 * math.pi)) - 1.0
    assert 3.5 < coarse_off / fine_off < 4.5
    assert 0.5 < sm["efficiency_rise"] < 1.0


def test_scene_from_transmission_angle_and_optimal_offset():
    text = SEED_SCENE.replace("base_radius = 0.020", "transmission_angle = 45.0")
    res = cams.solve_cam(text)
    law = seed_law()
    assert res.summary["base_radius"] == pytest.approx(
        cams.base_radius_translating(law, math.radians(45.0), 0.005), rel=1e-12)
    assert res.summary["transmission_angle_min"] == pytest.approx(45.0, abs=1e-6)
    res = cams.solve_cam(text.replace("offset = 0.005", 'offset = "optimal"'))
    assert res.summary["base_radius"] == pytest.approx(
        cams.optimal_offset(law, math.radians(45.0))[1], rel=1e-9)


def test_scene_without_friction_is_lossless():
    text = SEED_SCENE.replace("friction = 0.15\n", "")
    sm = cams.solve_cam(text).summary
    # the cam's work on the rise is the work against the load (measured: exactly 1.0)
    assert sm["efficiency_rise"] == pytest.approx(1.0, abs=1e-12)
    assert sm["friction_work"] == 0.0


def test_scene_detects_separation_and_self_locking():
    weak = SEED_SCENE.replace("spring_rate = 2000.0", "spring_rate = 0.0").replace(
        "spring_preload = 10.0", "spring_preload = -60.0")
    sm = cams.solve_cam(weak).summary
    assert sm["separation_rows"] > 0 and sm["preload_needed"] > 0.0
    locked = SEED_SCENE.replace("friction = 0.15", "friction = 0.5").replace(
        "base_radius = 0.020", "base_radius = 0.012").replace("offset = 0.005", "offset = -0.005")
    with pytest.raises(CamError, match="self-locks at cam angle"):
        cams.solve_cam(locked)


def test_oscillating_scene():
    text = """
    [cam]
    speed = 20.0
    transmission_angle = 25.0
    roller_radius = 0.005
    [cam.follower]
    kind = "oscillating"
    stroke_angle = 20.0
    arm = 0.06
    pivot_distance = 0.08
    """ + segments_toml(("rise", "cycloidal", 100.0), ("dwell", None, 40.0),
                        ("return", "cycloidal", 100.0), ("dwell", None, 120.0)) + """
    [cam.loads]
    moment = 2.0
    inertia = 1e-3
    spring_rate = 5.0
    spring_preload = 1.0
    friction = 0.1
    pin_radius = 0.006
    """
    res = cams.solve_cam(text)
    sm = res.summary
    assert sm["transmission_angle_min"] == pytest.approx(25.0, abs=1e-6)
    assert sm["omega2_max"] == pytest.approx(20.0 * 2 * math.radians(20) / math.radians(100))
    beta = np.radians(res.motion.beta.to_numpy())
    load = 2.0 + 1.0 + 5.0 * beta + 1e-3 * res.motion.eps2
    assert np.allclose(res.forces.load, load)
    # power about the pivot: torque = (M + sgn mu r F12) dbeta/dphi
    dbeta = res.motion.dbeta.to_numpy()
    assert np.allclose(res.forces.torque, (load + np.sign(dbeta) * res.forces.friction) * dbeta,
                       atol=1e-9 * np.abs(res.forces.torque).max())


@pytest.mark.parametrize("edit, error, message", [
    (("stroke = 0.010", "stroek = 0.010"), SceneError, "did you mean 'stroke'"),
    (("offset = 0.005", "arm = 0.005"), CamError, "oscillating follower"),
    (('law = "harmonic"', 'law = "harmonik"'), CamError, r"cam.segments\[3\].law.*harmonic"),
    (("angle = 120.0", "angle = 100.0"), CamError, "add up to 340"),
    (("speed_rpm = 300.0", ""), CamError, "speed"),
    (("guide_gap = 0.025", "guide_gap = 0.005"), CamError, "guide_gap"),
    (("base_radius = 0.020", "base_radius = 0.004"), CamError, "offset"),
    (("mass = 0.2", "mass = -0.2"), SceneError, "must not be negative"),
    (('kind = "translating"', 'kind = "sliding"'), CamError, "translating"),
])
def test_scene_errors_are_one_line(edit, error, message):
    text = SEED_SCENE.replace(*edit, 1)
    with pytest.raises(error, match=message) as info:
        cams.solve_cam(text)
    assert isinstance(info.value, WorkbenchError) and "\n" not in str(info.value)


def test_scene_from_dict_and_critical_angle_check():
    scene = cams.load_cam_scene({"cam": {
        "speed": 10.0, "transmission_angle": 20.0,
        "follower": {"kind": "translating", "stroke": 0.01},
        "segments": [{"kind": "rise", "law": "cycloidal", "angle": 180.0},
                     {"kind": "return", "law": "cycloidal", "angle": 180.0}]}})
    assert scene.follower.offset == 0.0
    with pytest.raises(CamError, match="critical angle"):
        cams.load_cam_scene({"cam": {
            "speed": 10.0, "transmission_angle": 20.0,
            "follower": {"kind": "translating", "stroke": 0.01},
            "segments": [{"kind": "rise", "law": "cycloidal", "angle": 180.0},
                         {"kind": "return", "law": "cycloidal", "angle": 180.0}],
            "loads": {"friction": 0.3, "guide_length": 0.02, "guide_gap": 0.02}}})


def test_cam_table_columns():
    law = seed_law()
    table = cams.cam_table(law, TranslatingFollower(0.02, 0.005, 0.003), count=13, speed=2.0)
    assert list(table.columns[:8]) == ["angle", "s", "ds", "dds", "v", "a", "tau",
                                       "pressure_angle"]
    assert np.allclose(table.tau + table.pressure_angle, 90.0)
    assert np.allclose(table.v, 2.0 * table.ds) and np.allclose(table.a, 4.0 * table.dds)
    assert not table.isna().any().any()
