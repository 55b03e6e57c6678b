"""Efficiency (seed 002 s. 4.3): closed forms and work bookkeeping done by hand here."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetostatics.model.errors import WorkbenchError
from kinetostatics.transmission import efficiency as ef
from kinetostatics.transmission.efficiency import EfficiencyError

etas = st.lists(st.floats(0.05, 1.0), min_size=1, max_size=6)


def test_mean_efficiency_and_loss_coefficient():
    # L_m = L_ru + L_rp (eqs 4.22-4.23)
    assert ef.mean_efficiency(750.0, 1000.0) == 0.75
    assert ef.loss_coefficient(250.0, 1000.0) == 0.25
    assert ef.mean_efficiency(750.0, 1000.0) == 1 - ef.loss_coefficient(250.0, 1000.0)
    p = ef.mean_powers(2.0, 1000.0, 750.0, 250.0)                        # eqs 4.24-4.25
    assert p == {"motor": 500.0, "useful": 375.0, "passive": 125.0, "efficiency": 0.75}
    with pytest.raises(EfficiencyError, match="motor work must be positive"):
        ef.mean_efficiency(1.0, 0.0)


def test_cycle_efficiency_from_moments():
    """M_m = 10 + 2 sin(phi), M_ru = 8 + sin(2 phi) + 3 cos(3 phi) over a turn:
    L_m = 20 pi, L_ru = 16 pi, eta = 0.8."""
    for n in (361, 360):                       # Simpson's rule, then the trapezoid rule
        phi = np.linspace(0.0, 2 * np.pi, n)
        eta = ef.cycle_efficiency(phi, 10 + 2 * np.sin(phi),
                                  8 + np.sin(2 * phi) + 3 * np.cos(3 * phi))
        assert eta == pytest.approx(0.8, rel=1e-12)
    x = np.linspace(0.0, 2.0, 11)
    assert ef.cycle_work(x, x**3 - x) == pytest.approx(2.0**4 / 4 - 2.0, rel=1e-14)   # Simpson
    with pytest.raises(EfficiencyError, match="same length"):
        ef.cycle_work([0, 1, 2], [1, 2])


@settings(max_examples=50, deadline=None)
@given(etas=etas, work=st.floats(1.0, 1e6))
def test_series(etas, work):
    """Follow the work through the chain by hand (eq. 4.26); eta is the product (4.27)."""
    w = work
    outs = []
    for e in etas:
        w = e * w
        outs.append(w)
    assert np.allclose(ef.series_works(work, etas), outs, rtol=1e-13)
    eta = ef.series_efficiency(etas)
    assert eta == pytest.approx(outs[-1] / work, rel=1e-13)
    assert eta <= min(etas) * (1 + 1e-15)


@settings(max_examples=50, deadline=None)
@given(data=st.data(), n=st.integers(1, 6))
def test_parallel_forms_agree_and_are_bounded(data, n):
    es = data.draw(st.lists(st.floats(0.05, 1.0), min_size=n, max_size=n))
    # works are zero or of engineering size: a subnormal work (5e-324 J) would underflow
    # e * w to zero and test the floating point, not the formula
    work = st.one_of(st.just(0.0), st.floats(1e-6, 1e4))
    lm = data.draw(st.lists(work, min_size=n, max_size=n))
    if sum(lm) <= 0.0:
        lm[0] = 1.0
    useful = [e * w for e, w in zip(es, lm, strict=True)]                # eq. 4.28
    eta = ef.parallel_efficiency(es, motor_works=lm)                     # eq. 4.29
    assert eta == pytest.approx(sum(useful) / sum(lm), rel=1e-12)
    if sum(useful) > 0.0:
        assert ef.parallel_efficiency(es, useful_works=useful) == pytest.approx(eta, rel=1e-12)
    assert min(es) * (1 - 1e-12) <= eta <= max(es) * (1 + 1e-12)


def test_mixed_matches_the_work_flow():
    """Fig. 4.4: motor work through two mechanisms in series, then shared by three branches
    in parallel; eta = useful out / motor in (eqs 4.31-4.32)."""
    series, branches, shares = [0.95, 0.9], [0.8, 0.7, 0.6], [0.5, 0.3, 0.2]
    lm = 1000.0
    into = lm * 0.95 * 0.9
    useful = [e * s * into for e, s in zip(branches, shares, strict=True)]
    expected = sum(useful) / lm
    assert ef.mixed_efficiency(series, branches,
                               motor_works=[s * into for s in shares]) == pytest.approx(expected)
    assert ef.mixed_efficiency(series, branches, useful_works=useful) == pytest.approx(expected)


@settings(max_examples=100, deadline=None)
@given(pru=st.floats(0.0, 1e3), prp=st.floats(0.0, 1e3), pg=st.floats(-1e3, 1e3),
       pi=st.floats(-1e3, 1e3))
def test_instantaneous_efficiency_is_one_minus_losses(pru, prp, pg, pi):
    """With P_m from the energy balance P_m - P_ru - P_rp + P_G + P_i = 0 (eq. 4.34), both
    branches of eq. 4.35 give 1 - P_rp / (power put in)."""
    pm = pru + prp - pg - pi
    power_in = pm + max(pg + pi, 0.0)
    if pm <= 1e-9 or power_in <= 1e-9:
        return
    eta = float(ef.instantaneous_efficiency(pm, pru, pg, pi))
    assert eta == pytest.approx(1.0 - prp / power_in, rel=1e-9, abs=1e-9)


def test_instantaneous_efficiency_arrays_and_cam_ratio():
    eta = ef.instantaneous_efficiency([100.0, 0.0, 50.0], [80.0, 0.0, 40.0], [-10.0, 0.0, 5.0])
    assert eta[0] == pytest.approx(0.9) and math.isnan(eta[1]) and eta[2] == pytest.approx(40 / 55)
    # a translating cam follower with guide friction: eta = F v / (F12 sin tau v) =
    # 1 - mu (2a + b)/b cot(tau), from eq. 1.43
    tau, mu, a, b = np.radians([50.0, 70.0, 90.0]), 0.1, 0.02, 0.04
    f12 = 100.0 / (np.sin(tau) - mu * (2 * a + b) / b * np.cos(tau))
    ratio = ef.efficiency_ratio(100.0 * 0.3, f12 * np.sin(tau) * 0.3)
    assert np.allclose(ratio, 1 - mu * (2 * a + b) / b / np.tan(tau))


@pytest.mark.parametrize("call, message", [
    (lambda: ef.series_efficiency([0.9, 1.2]), r"\(0, 1\]"),
    (lambda: ef.series_efficiency([]), "non-empty"),
    (lambda: ef.parallel_efficiency([0.9, 0.8]), "exactly one"),
    (lambda: ef.parallel_efficiency([0.9, 0.8], motor_works=[1.0]), "one work per"),
    (lambda: ef.parallel_efficiency([0.9, 0.8], motor_works=[1.0, -1.0]), "non-negative"),
    (lambda: ef.mean_powers(0.0, 1.0, 1.0), "cycle time"),
])
def test_errors(call, message):
    with pytest.raises(WorkbenchError, match=message):
        call()


def test_efficiency_ratio_is_undefined_where_not_both_driving():
    """P_ideal / P_real is an efficiency only where both are driving powers."""
    eta = ef.efficiency_ratio([30.0, -5.0, 10.0, 0.0], [40.0, 20.0, -1.0, 5.0])
    assert eta[0] == 0.75 and eta[3] == 0.0
    assert np.isnan(eta[1]) and np.isnan(eta[2])
