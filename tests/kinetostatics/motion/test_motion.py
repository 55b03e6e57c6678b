"""Motion of the reduction element (seed 002 ch. 4) against closed-form solutions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetostatics import motion as mo
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.motion import MotionError

TWO_PI = 2 * math.pi


def const_inertia(i0):
    return lambda phi: (np.full(np.shape(phi), i0), np.zeros(np.shape(phi)))


def cos2_inertia(a, b):
    """I_r = a + b cos(2 phi), a slider-crank-like reduced inertia."""
    return lambda phi: (a + b * np.cos(2 * np.asarray(phi)), -2 * b * np.sin(2 * np.asarray(phi)))


def periodic_mean(f, n=4096):
    """Mean over a period of a smooth periodic function: the trapezoid rule is spectrally
    accurate (an independent quadrature for the references below)."""
    x = np.arange(n) * TWO_PI / n
    return float(np.mean(f(x)))


# ----------------------------------------------------------------------------- closed forms

@settings(max_examples=12, deadline=None)
@given(i0=st.floats(0.01, 10.0), m0=st.floats(-5.0, 20.0), w0=st.floats(5.0, 100.0))
def test_constant_inertia_and_moment(i0, m0, w0):
    """omega^2 = omega0^2 + 2 M phi / I, t = I (omega - omega0) / M = 2 phi / (omega + omega0),
    alpha = M / I."""
    span = 3 * TWO_PI
    if w0 * w0 + 2 * m0 * span / i0 < 1.0:
        return                                        # a stall: tested separately
    phi = np.linspace(0.0, span, 301)
    w_exact = np.sqrt(w0**2 + 2 * m0 * phi / i0)
    t_exact = 2 * phi / (w_exact + w0)
    sol = mo.simulate(const_inertia(i0), lambda p, w, t: m0, 0.0, w0, 3)
    w, t, alpha = sol.state(phi)
    assert np.allclose(w, w_exact, rtol=1e-10, atol=0)
    assert np.allclose(t, t_exact, rtol=1e-10, atol=1e-10 * t_exact[-1])
    assert np.allclose(alpha, m0 / i0, rtol=1e-9, atol=1e-9 * abs(w0**2))
    en = mo.solve_energy(const_inertia(i0), lambda p, w, t: m0, phi, w0)
    assert np.allclose(en.omega, w_exact, rtol=1e-12, atol=0)
    assert np.allclose(en.time, t_exact, rtol=1e-11, atol=1e-13 * t_exact[-1])


def test_varying_inertia_conserves_energy():
    """M = 0, I = a + b cos 2phi: I omega^2 stays I(0) omega0^2; the period is the integral
    of sqrt(I / (I0 omega0^2)) over a turn; omega is least at phi = 0 and largest at pi/2."""
    a, b, w0 = 1.0, 0.3, 10.0
    inertia = cos2_inertia(a, b)
    sol = mo.simulate(inertia, lambda p, w, t: 0.0, 0.0, w0, 4)
    phi = np.linspace(0.0, 4 * TWO_PI, 4001)
    w = sol.omega(phi)
    energy = (a + b * np.cos(2 * phi)) * w**2
    assert np.max(np.abs(energy / ((a + b) * w0**2) - 1)) < 1e-10
    period = TWO_PI * periodic_mean(lambda x: np.sqrt((a + b * np.cos(2 * x)) / (a + b))) / w0
    st_ = sol.cycle_stats()
    assert st_["period"] == pytest.approx(period, rel=1e-10)
    assert st_["omega_mean"] == pytest.approx(TWO_PI / period, rel=1e-10)
    assert st_["omega_max"] == pytest.approx(w0 * math.sqrt((a + b) / (a - b)), rel=1e-10)
    assert st_["omega_min"] == pytest.approx(w0, rel=1e-10)
    # alpha = -omega^2 I'/(2 I) = w0^2 (a + b) b sin(2 phi) / I^2: its largest magnitude
    x = np.linspace(0.0, np.pi, 2_000_001)
    alpha = w0**2 * (a + b) * b * np.sin(2 * x) / (a + b * np.cos(2 * x)) ** 2
    assert st_["alpha_max"] == pytest.approx(np.abs(alpha).max(), rel=1e-9)
    assert st_["delta"] == pytest.approx((st_["omega_max"] - w0) * period / TWO_PI, rel=1e-10)


@settings(max_examples=6, deadline=None)
@given(i0=st.floats(0.05, 2.0), ms=st.floats(5.0, 100.0), w_free=st.floats(10.0, 200.0),
       frac=st.floats(0.01, 0.9))
def test_linear_motor_exponential_approach(i0, ms, w_free, frac):
    """M = Ms (1 - omega / w0), I const: omega(t) = w0 - (w0 - omega0) exp(-t / T),
    T = I w0 / Ms, phi(t) = w0 t - (w0 - omega0) T (1 - exp(-t / T))."""
    w0 = frac * w_free
    sol = mo.simulate(const_inertia(i0), lambda p, w, t: ms * (1 - np.asarray(w) / w_free),
                      0.0, w0, 10)
    tc = i0 * w_free / ms
    times = np.linspace(0.0, sol.t[-1], 400)
    phi, w, eps = sol.at_time(times)
    decay = np.exp(-times / tc)
    w_exact = w_free - (w_free - w0) * decay
    assert np.allclose(w, w_exact, rtol=2e-9, atol=0)          # the promise is 1e-8
    assert np.allclose(phi, w_free * times - (w_free - w0) * tc * (1 - decay), rtol=0,
                       atol=1e-8)
    assert np.allclose(eps, ms / i0 * (1 - w_exact / w_free), rtol=0, atol=1e-9 * ms / i0)


def test_energy_balance_for_a_position_only_moment():
    """I = a + b cos 2phi, M = c + d sin(phi): I omega^2 - I0 omega0^2 = 2 (c phi + d (1 - cos
    phi)) (eq. 4.8), to 1e-10 with the accurate solvers."""
    a, b, c, d, w0 = 1.0, 0.3, 0.7, 2.0, 5.0
    inertia = cos2_inertia(a, b)

    def moment(p, w, t):
        return c + d * np.sin(p)

    phi = np.linspace(0.0, 3 * TWO_PI, 181)
    work = c * phi + d * (1 - np.cos(phi))
    i_r = a + b * np.cos(2 * phi)
    u0 = (a + b) * w0**2
    en = mo.solve_energy(inertia, moment, phi, w0)
    assert np.max(np.abs(i_r * en.omega**2 - u0 - 2 * work)) <= 1e-12 * u0
    sol = mo.simulate(inertia, moment, 0.0, w0, 3)
    w, t, _ = sol.state(phi)
    assert np.max(np.abs(i_r * w**2 - u0 - 2 * work)) <= 1e-10 * u0
    assert np.allclose(t, en.time, rtol=1e-10, atol=1e-10 * en.time.iloc[-1])


def test_delta_and_chi_closed_form():
    """I const, M = A sin(phi): omega^2 = omega0^2 + 2A/I (1 - cos phi), the largest speed at
    pi, the least at 0, alpha = A/I sin(phi), so max |alpha| = A/I (eqs 4.20-4.21)."""
    i0, amp, w0 = 0.8, 30.0, 12.0
    inertia = const_inertia(i0)

    def moment(p, w, t):
        return amp * np.sin(p)

    sol = mo.periodic_solution(inertia, moment, 0.0, w0)      # every speed is periodic here
    assert sol.omega0 == pytest.approx(w0, rel=1e-14)
    period = TWO_PI * periodic_mean(lambda x: 1 / np.sqrt(w0**2 + 2 * amp / i0 * (1 - np.cos(x))))
    mean = TWO_PI / period
    w_max = math.sqrt(w0**2 + 4 * amp / i0)
    st_ = sol.cycle_stats()
    assert st_["omega_max"] == pytest.approx(w_max, rel=1e-11)
    assert st_["omega_max_at"] == pytest.approx(math.pi, abs=1e-5)
    assert st_["delta"] == pytest.approx((w_max - w0) / mean, rel=1e-9)
    assert st_["chi"] == pytest.approx(amp / i0 / mean**2, rel=1e-9)
    assert st_["alpha_max_at"] in (pytest.approx(math.pi / 2, abs=1e-5),
                                   pytest.approx(3 * math.pi / 2, abs=1e-5))


# ----------------------------------------------------------------------------- recurrence

def test_recurrence_step_satisfies_eq_4_13():
    inertia = cos2_inertia(1.0, 0.3)

    def moment(p, w, t):
        return 5.0 - 0.1 * np.asarray(w) + np.sin(p)

    phi = np.linspace(0.2, 0.5, 4)
    rec = mo.solve_recurrence(inertia, moment, phi, 8.0, t0=1.0)
    w, t = rec.omega.to_numpy(), rec.time.to_numpy()
    i_r = 1.0 + 0.3 * np.cos(2 * phi)
    dphi = 0.1
    for i in range(3):
        m = float(moment(phi[i], w[i], t[i]))
        lhs = i_r[i] * (w[i + 1] - w[i]) / dphi * w[i] + (i_r[i + 1] - i_r[i]) / dphi * w[i]**2 / 2
        assert lhs == pytest.approx(m, rel=1e-12)                          # eq. 4.13
        assert t[i + 1] - t[i] == pytest.approx(2 * dphi / (w[i] + w[i + 1]))   # eq. 4.16


@pytest.mark.parametrize("position_only", [True, False])
def test_recurrence_is_first_order(position_only):
    inertia = cos2_inertia(2.0, 0.4)
    if position_only:
        def moment(p, w, t):
            return 30.0 * np.sin(p) + 5.0
    else:
        def moment(p, w, t):
            return 200.0 * (1 - np.asarray(w) / 40.0) - 100.0 * (1 + 0.8 * np.sin(p))
    table = mo.recurrence_convergence(inertia, moment, 0.0, 20.0, position_only=position_only,
                                      divisions=(36, 72, 144, 288, 576))
    assert list(table.columns) == ["step", "steps", "max_error", "max_rel_error", "wall_time"]
    assert table.attrs["order"] == pytest.approx(1.0, abs=0.05)
    ratios = table.max_error.to_numpy()[:-1] / table.max_error.to_numpy()[1:]
    assert np.all((ratios > 1.8) & (ratios < 2.2))           # halving the step halves the error
    assert (table.wall_time > 0).all() and table.attrs["reference_wall_time"] > 0


# ----------------------------------------------------------------------------- phases

def loaded_machine():
    """A motor M = 200 (1 - omega/40) against a load 100 (1 + 0.8 sin phi), I = 2 + 0.4 cos 2phi."""
    inertia = cos2_inertia(2.0, 0.4)

    def moment(p, w, t):
        return 200.0 * (1 - np.asarray(w) / 40.0) - 100.0 * (1 + 0.8 * np.sin(p))
    return inertia, moment


def test_periodic_steady_state_and_start_up():
    inertia, moment = loaded_machine()
    sol = mo.periodic_solution(inertia, moment, 0.3, 20.0)
    w0 = sol.omega0
    assert sol.omega(np.array([0.3 + TWO_PI]))[0] == pytest.approx(w0, rel=1e-10)
    # a start-up from a low speed reaches the same cycle
    run = mo.simulate(inertia, moment, 0.3, 5.0, 40)
    cyc = run.cycles()
    assert cyc.phase.iloc[0] == "start-up" and cyc.phase.iloc[-1] == "steady"
    assert (cyc.work.iloc[:3] > 0).all()                                   # eq. 4.17
    assert cyc.omega_end.iloc[-1] == pytest.approx(w0, rel=1e-7)
    summary = run.summary()
    assert set(summary) == {"omega_mean", "omega_max", "omega_min", "delta", "chi", "period",
                            "steady"}
    assert summary["steady"] is True
    assert summary["delta"] == pytest.approx(sol.cycle_stats()["delta"], rel=1e-6)
    start = math.degrees(0.3)
    table = run.table(np.linspace(start, start + 360.0, 5))
    assert list(table.columns) == ["cycle", "position", "time", "omega", "alpha"]
    assert len(table) == 40 * 5 and table.cycle.iloc[-1] == 40
    with pytest.raises(MotionError, match="within"):
        run.table([10.0])


def test_flywheel_for_target_delta():
    inertia, moment = loaded_machine()
    j = mo.flywheel_for_delta(inertia, moment, 0.02, 0.0, 20.0)

    def with_flywheel(p):
        i_r, di_r = inertia(p)
        return i_r + j, di_r

    delta = mo.periodic_solution(with_flywheel, moment, 0.0, 20.0).cycle_stats()["delta"]
    assert delta == pytest.approx(0.02, rel=1e-6)
    assert 5.0 < j < 100.0
    assert mo.flywheel_for_delta(inertia, moment, 0.9, 0.0, 20.0) == 0.0


def test_stall_and_stopping():
    """I = 0.5, M = -3: rest after phi = I omega0^2 / (2|M|) = 8.333 rad (cycle 2, 117.465 deg)
    and t = I omega0 / |M| = 5/3 s."""
    inertia = const_inertia(0.5)

    def brake(p, w, t):
        return -3.0

    phi_rest, t_rest = 0.5 * 100 / 6, 0.5 * 10 / 3
    sol = mo.stopping(inertia, brake, 0.0, 10.0)
    assert sol.rest[0] == pytest.approx(phi_rest, rel=1e-12)
    assert sol.rest[1] == pytest.approx(t_rest, rel=1e-9)
    pattern = r"stalls: omega falls to 0 in cycle 2 at driver angle 117\.46\d deg"
    with pytest.raises(MotionError, match=pattern):
        mo.simulate(inertia, brake, 0.0, 10.0, 3)
    with pytest.raises(MotionError, match=pattern):
        mo.solve_energy(inertia, brake, np.linspace(0.0, 3 * TWO_PI, 4), 10.0)
    with pytest.raises(MotionError, match="in cycle 2 at driver angle"):
        mo.solve_recurrence(inertia, brake, np.linspace(0.0, 3 * TWO_PI, 100), 10.0)
    run = mo.simulate(const_inertia(0.5), lambda p, w, t: -0.01, 0.0, 10.0, 3)
    assert (run.cycles().phase == "stopping").all()                           # eq. 4.18


def test_errors_are_workbench_errors():
    inertia, moment = loaded_machine()
    with pytest.raises(WorkbenchError, match="positive"):
        mo.simulate(lambda p: (np.zeros(np.shape(p)), np.zeros(np.shape(p))), moment, 0, 1.0)
    with pytest.raises(MotionError, match="omega0 must be positive"):
        mo.simulate(inertia, moment, 0.0, 0.0)
    with pytest.raises(MotionError, match="not a position-only moment"):
        mo.solve_energy(inertia, moment, [0.0, 1.0], 10.0)
    with pytest.raises(MotionError, match="no periodic steady state"):
        mo.periodic_solution(const_inertia(1.0), lambda p, w, t: 1.0 + np.sin(p), 0.0, 10.0)
    sol = mo.simulate(inertia, moment, 0.0, 20.0, 1)
    with pytest.raises(MotionError, match="time outside"):
        sol.at_time([sol.t[-1] + 1.0])


def test_golden_max_asks_only_what_it_announced_ahead():
    """Every point the search evaluates was announced to ``ahead`` first (the motion's
    reduced values are solved ahead in batches), and the answer is the same without."""
    announced, asked = set(), []

    def f(x: float) -> float:
        asked.append(x)
        return -math.cos(3.0 * x) * (x - 0.2) ** 2 - abs(x - 0.71)

    plain = mo.golden_max(f, 0.0, 1.3, xtol=1e-13)
    n = len(asked)
    asked.clear()
    assert mo.golden_max(f, 0.0, 1.3, xtol=1e-13, ahead=announced.update) == plain
    assert len(asked) == n > 20 and set(asked) <= announced


def test_golden_max_finds_a_corner_and_an_end():
    x, fx = mo.golden_max(lambda x: -abs(x - 0.3), 0.0, 1.0)
    assert x == pytest.approx(0.3, abs=1e-11) and fx == pytest.approx(0.0, abs=1e-11)
    x, fx = mo.golden_max(lambda x: x, 0.0, 2.0)
    assert x == 2.0 and fx == 2.0


def test_periodic_inertia_grid_matches_the_adaptive_integrator():
    """With I_r periodic, a fixed grid per cycle evaluates it once (one vectorised call per
    grid size) and gives the same motion."""
    calls = []
    base, moment = loaded_machine()

    def inertia(phi):
        calls.append(np.size(phi))
        return base(phi)

    grid = mo.simulate(inertia, moment, 0.0, 5.0, 12, periodic_inertia=True)
    n_calls = len(calls)
    assert n_calls <= 6                      # I_r(phi0) and a few grid sizes, whatever the steps
    adaptive = mo.simulate(base, moment, 0.0, 5.0, 12)
    phi = np.linspace(0.0, 12 * TWO_PI, 2001)
    assert np.allclose(grid.omega(phi), adaptive.omega(phi), rtol=1e-10, atol=0)
    j = mo.flywheel_for_delta(base, moment, 0.05, 0.0, 20.0, periodic_inertia=True)
    assert j == pytest.approx(mo.flywheel_for_delta(base, moment, 0.05, 0.0, 20.0), rel=1e-7)
    with pytest.raises(MotionError, match="in cycle 2 at driver angle 117"):
        mo.simulate(const_inertia(0.5), lambda p, w, t: -3.0, 0.0, 10.0, 3,
                    periodic_inertia=True)


def test_omega_at_one_angle_is_the_arrays_omega():
    """MotionSolution.omega_at (the golden-section searches' omega at one angle, without
    the arrays) gives omega(np.array([p]))'s number to the bit: at random angles, at every
    node, at the ends; an angle outside the span is refused as by omega, and so is a
    reduced inertia that is not positive."""
    base, moment = loaded_machine()
    sol = mo.simulate(base, moment, 0.0, 5.0, 3)
    rng = np.random.default_rng(7)
    pts = np.concatenate([rng.uniform(sol.phi[0], sol.phi[-1], 500), sol.phi])
    assert [sol.omega_at(p) for p in pts] == [float(sol.omega(np.array([p]))[0]) for p in pts]
    with pytest.raises(MotionError, match="outside"):
        sol.omega_at(sol.phi[-1] + 1.0)
    sol.inertia = lambda phi: (np.full(np.shape(phi), -1.0), np.zeros(np.shape(phi)))
    with pytest.raises(MotionError, match="positive"):
        sol.omega_at(1.0)
