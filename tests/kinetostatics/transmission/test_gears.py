"""Gear pairs and trains with fixed axes (seed 002 s. 2.3.3, eqs 2.52-2.59)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from kinetostatics.model.errors import WorkbenchError
from kinetostatics.transmission.gears import (
    GearError,
    GearStage,
    equilibrating_moment,
    gear_pair,
    gear_ratio,
    gear_train,
    tooth_force,
    tooth_force_components,
)


def cross(ax, ay, bx, by):
    return ax * by - ay * bx


def check_equilibrium(g, rtol=1e-10):
    """Both gears in equilibrium: forces (bearing + tooth) and moments about each axis."""
    scale = np.max(np.abs(g.F)) + 1e-300
    mscale = np.max(np.abs(g.M2)) + np.max(np.abs(g.Me)) + 1e-300
    # gear 2: F12 + F02 = 0 and (P - O2) x F12 - M2 = 0 (the machine acts with -M2), eq. 2.52
    assert np.allclose(g.F12x + g.F02x, 0.0, atol=rtol * scale)
    assert np.allclose(g.F12y + g.F02y, 0.0, atol=rtol * scale)
    px, py = g.P[0] - g.O2[0], g.P[1] - g.O2[1]
    assert np.allclose(cross(px, py, g.F12x, g.F12y) - g.M2, 0.0, atol=rtol * mscale)
    # gear 1: F21 + F01 = 0 and (P - O1) x F21 + Me = 0, eq. 2.54
    assert np.allclose(g.F21x + g.F01x, 0.0, atol=rtol * scale)
    assert np.allclose(g.F21y + g.F01y, 0.0, atol=rtol * scale)
    qx, qy = g.P[0] - g.O1[0], g.P[1] - g.O1[1]
    assert np.allclose(cross(qx, qy, g.F21x, g.F21y) + g.Me, 0.0, atol=rtol * mscale)


def test_ratio_signs():
    assert gear_ratio(0.05, 0.2) == pytest.approx(-4.0)
    assert gear_ratio(0.05, 0.2, internal=True) == pytest.approx(4.0)
    assert np.allclose(gear_ratio(0.05, np.array([0.1, 0.2])), [-2.0, -4.0])


def test_tooth_force_eq_2_53():
    m2, r2, a = 150.0, 0.125, 20.0
    f = tooth_force(m2, r2, a)
    assert f == pytest.approx(m2 / (r2 * math.cos(math.radians(a))), rel=1e-14)
    assert tooth_force(-m2, r2, a) == pytest.approx(f)            # a magnitude
    ft, fr = tooth_force_components(m2, r2, a)
    assert ft == pytest.approx(f * math.cos(math.radians(a)), rel=1e-14)
    assert fr == pytest.approx(f * math.sin(math.radians(a)), rel=1e-14)
    assert math.hypot(ft, fr) == pytest.approx(f, rel=1e-14)


@pytest.mark.parametrize("internal,r1,r2", [(False, 0.04, 0.12), (True, 0.04, 0.12),
                                            (True, 0.12, 0.04), (False, 0.10, 0.03)])
@pytest.mark.parametrize("angle", [0.0, 37.0, -120.0])
def test_pair_equilibrium_and_geometry(internal, r1, r2, angle):
    M2 = np.array([-80.0, 0.0, 35.0, 240.0])
    g = gear_pair(M2, r1, r2, alpha_deg=20.0, internal=internal, centre_angle_deg=angle,
                  O1=(0.3, -0.1))
    check_equilibrium(g)
    # Me = M2 / i12 (eqs 2.55, 2.59), i12 signed
    assert np.allclose(g.Me, M2 / g.i12, rtol=1e-12, atol=1e-12)
    assert np.allclose(g.Me, equilibrating_moment(M2, r1, r2, internal), rtol=1e-12, atol=1e-12)
    # |F12| from eq. 2.53 / 2.57 and the components
    assert np.allclose(np.hypot(g.F12x, g.F12y), tooth_force(M2, r2, 20.0), rtol=1e-12)
    assert np.allclose(g.F, np.hypot(g.Ft, g.Fr), rtol=1e-12)
    # centre distance and pitch point on both pitch circles
    dist = math.dist(g.O1, g.O2)
    assert dist == pytest.approx(abs(r2 - r1) if internal else r1 + r2, rel=1e-12)
    assert math.dist(g.P, g.O1) == pytest.approx(r1, rel=1e-12)
    assert math.dist(g.P, g.O2) == pytest.approx(r2, rel=1e-12)
    # the line of action is tangent to both base circles: arm r_w cos(alpha) about each axis
    k = np.abs(M2) > 0
    for o, r in ((g.O1, r1), (g.O2, r2)):
        arm = np.abs(cross(g.P[0] - o[0], g.P[1] - o[1], g.F12x, g.F12y))[k] / g.F[k]
        assert np.allclose(arm, r * math.cos(math.radians(20.0)), rtol=1e-12)


def test_radial_component_presses_the_teeth_together():
    # external: the force on gear 2 pushes it away from gear 1 (+x here), whatever M2's sign
    for m2 in (-50.0, 50.0):
        g = gear_pair(m2, 0.05, 0.1, alpha_deg=20.0)
        assert g.F12x > 0.0
    # internal, ring = gear 2: the pinion pushes the ring's teeth outwards (away from O2)
    for m2 in (-50.0, 50.0):
        g = gear_pair(m2, 0.05, 0.1, alpha_deg=20.0, internal=True)
        ux, uy = g.P[0] - g.O2[0], g.P[1] - g.O2[1]
        assert ux * g.F12x + uy * g.F12y > 0.0


def test_vectorised_and_table():
    M2 = np.linspace(-100.0, 100.0, 7)
    g = gear_pair(M2, 0.05, 0.15)
    assert g.Me.shape == g.F12x.shape == g.F01y.shape == (7,)
    t = g.table()
    assert list(t.columns[:3]) == ["M2", "Me", "F"] and len(t) == 7
    assert np.allclose(t["Me"], M2 / -3.0)


@settings(max_examples=200, deadline=None)
@given(r1=st.floats(0.005, 2.0), r2=st.floats(0.005, 2.0), alpha=st.floats(0.0, 45.0),
       m2=st.floats(-1e5, 1e5), angle=st.floats(-180.0, 180.0), internal=st.booleans(),
       w1=st.floats(-500.0, 500.0))
def test_power_balance_and_equilibrium(r1, r2, alpha, m2, angle, internal, w1):
    """Without friction: Me w1 = M2 w2 with w2 = w1 / i12 (the input power goes out)."""
    assume(not internal or abs(r1 - r2) > 1e-3 * max(r1, r2))
    g = gear_pair(m2, r1, r2, alpha_deg=alpha, internal=internal, centre_angle_deg=angle)
    w2 = w1 / g.i12
    assert float(g.Me) * w1 == pytest.approx(m2 * w2, rel=1e-9, abs=1e-9 * abs(m2 * w1) + 1e-12)
    # velocity of the pitch point is the same on both gears (rolling pitch circles)
    assert abs(w1) * r1 == pytest.approx(abs(w2) * r2, rel=1e-12, abs=1e-12)
    check_equilibrium(g, rtol=1e-9)


def test_train_me_and_shaft_equilibrium():
    stages = [GearStage(0.02, 0.06), GearStage(0.025, 0.10, False, 90.0),
              GearStage(0.03, 0.09, True, 200.0)]
    M_out = np.array([50.0, -120.0, 300.0])
    t = gear_train(M_out, stages, alpha_deg=20.0, O1=(0.0, 0.0))
    i = (-3.0) * (-4.0) * 3.0
    assert t.i == pytest.approx(i, rel=1e-12)
    assert np.allclose(t.Me, M_out / i, rtol=1e-12)
    assert len(t.shafts) == 4 and len(t.bearings) == 4
    # every shaft in equilibrium: bearing + tooth forces = 0; moments: received = delivered
    for j, (bx, by) in enumerate(t.bearings):
        fx, fy = bx.copy(), by.copy()
        mom = np.zeros_like(M_out)
        if j > 0:
            p = t.pairs[j - 1]
            fx += p.F12x
            fy += p.F12y
            mom += cross(p.P[0] - t.shafts[j][0], p.P[1] - t.shafts[j][1], p.F12x, p.F12y)
        else:
            mom += t.Me
        if j < len(t.pairs):
            p = t.pairs[j]
            fx += p.F21x
            fy += p.F21y
            mom += cross(p.P[0] - t.shafts[j][0], p.P[1] - t.shafts[j][1], p.F21x, p.F21y)
        else:
            mom -= M_out
        assert np.allclose(fx, 0.0, atol=1e-9) and np.allclose(fy, 0.0, atol=1e-9)
        assert np.allclose(mom, 0.0, atol=1e-9)
    assert t.table()["stage"].tolist() == [1, 2, 3]


def test_idler_reverses_the_sense_only():
    direct = gear_train(60.0, [(0.03, 0.09)])
    idler = gear_train(60.0, [(0.03, 0.05), (0.05, 0.09)])
    assert idler.i == pytest.approx(-direct.i)
    assert float(idler.Me) == pytest.approx(-float(direct.Me))
    one = gear_pair(60.0, 0.03, 0.09)
    assert float(direct.Me) == pytest.approx(float(one.Me))


@pytest.mark.parametrize("call,words", [
    (lambda: gear_pair(10.0, -0.05, 0.1), "radii"),
    (lambda: gear_pair(10.0, 0.05, 0.0), "radii"),
    (lambda: gear_pair(10.0, 0.05, 0.1, alpha_deg=90.0), "pressure angle"),
    (lambda: gear_pair(10.0, 0.05, 0.05, internal=True), "internal"),
    (lambda: gear_pair(float("nan"), 0.05, 0.1), "M2"),
    (lambda: gear_train(10.0, []), "stage"),
])
def test_refusals_are_one_line(call, words):
    with pytest.raises(GearError) as exc:
        call()
    assert isinstance(exc.value, WorkbenchError)
    msg = str(exc.value)
    assert "\n" not in msg and words in msg
