"""Influence coefficients: intervals from amplitude and phase noise, conditioning
warnings and trim runs, each against an independent computation."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

from balance import BalanceError, NoiseModel, influence_balance, trim_balance
from balance.field.influence_stats import parse_noise


def pl(z) -> list[tuple[float, float]]:
    return [(abs(v), math.degrees(cmath.phase(v))) for v in np.atleast_1d(z)]


def plane_masses(t: np.ndarray) -> list:
    return [None if v == 0 else (abs(v), math.degrees(cmath.phase(v))) for v in t]


def noisy(V: np.ndarray, rel: float, phase_deg: float, rng) -> np.ndarray:
    a = np.abs(V) * (1.0 + rel * rng.standard_normal(V.shape))
    return a * np.exp(1j * (np.angle(V) + np.radians(phase_deg) * rng.standard_normal(V.shape)))


def inside_angle(x: float, iv: list[float]) -> bool:
    lo, hi = iv
    return (x - lo) % 360.0 <= (hi - lo) % 360.0 if iv != [0.0, 360.0] else True


ALPHA = np.array([[2.0 * cmath.exp(0.5j), 0.4 * cmath.exp(2j)],
                  [0.5 * cmath.exp(-1j), 1.5 * cmath.exp(1j)]])
U = np.array([1.0 * cmath.exp(0.3j), 0.7 * cmath.exp(2.5j)])
TRIALS = [np.array([0.5, 0]), np.array([0, 0.5j])]


@pytest.mark.slow
@pytest.mark.parametrize("rel, phase", [(0.01, 2.0), (0.03, 1.0)])
def test_interval_coverage_with_phase_noise(rel: float, phase: float) -> None:
    """Monte-Carlo on a linear two-plane machine: the 95 % intervals of the correction
    mass and angle cover the truth in 93-97 % of 2 x 400 intervals each.
    Measured (seed 11): (1 %, 2 deg) mass 0.954, angle 0.948; (3 %, 1 deg) mass 0.946,
    angle 0.940 (binomial sd of 800 draws: 0.8 %)."""
    rng = np.random.default_rng(11)
    model = NoiseModel(relative=rel, absolute=0.0, phase=phase)
    hits_m = hits_a = n = 0
    for _ in range(400):
        runs = [(plane_masses(t), pl(noisy(ALPHA @ (U + t), rel, phase, rng))) for t in TRIALS]
        r = influence_balance(pl(noisy(ALPHA @ U, rel, phase, rng)), runs, noise=model)
        for j, w in enumerate(-U):
            lo, hi = r.intervals[j]["mass"]
            hits_m += lo <= abs(w) <= hi
            hits_a += inside_angle(math.degrees(cmath.phase(w)) % 360.0,
                                   r.intervals[j]["angle"])
            n += 1
    assert 0.93 <= hits_m / n <= 0.97
    assert 0.93 <= hits_a / n <= 0.97


def correction_by_hand(amps: np.ndarray, phases: np.ndarray) -> np.ndarray:
    """Two planes, one trial run each (0.5 at 0 deg, 0.5 at 90 deg): alpha's columns
    (V_k - V0) / T_k, W = -alpha^-1 V0 by Cramer's rule."""
    V = amps * np.exp(1j * np.radians(phases))
    a = np.stack([(V[1] - V[0]) / 0.5, (V[2] - V[0]) / 0.5j], axis=1)
    det = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    return -np.array([a[1, 1] * V[0, 0] - a[0, 1] * V[0, 1],
                      a[0, 0] * V[0, 1] - a[1, 0] * V[0, 0]]) / det


@pytest.mark.parametrize("rel, phase", [(0.005, 0.0), (0.0, 0.5), (0.005, 0.5)])
def test_intervals_match_the_delta_method_for_small_noise(rel: float, phase: float) -> None:
    """For small noise the bootstrap's 95 % half widths equal the first-order
    (delta-method) 1.96 sigma from a finite-difference Jacobian of the hand solution.
    Measured ratios 0.998-1.024."""
    V0, runs = pl(ALPHA @ U), [(plane_masses(t), pl(ALPHA @ (U + t))) for t in TRIALS]
    r = influence_balance(V0, runs, noise=NoiseModel(rel, 0.0, phase))
    rows = [V0] + [v for _, v in runs]
    amps = np.array([[a for a, _ in row] for row in rows])
    phs = np.array([[p for _, p in row] for row in rows])
    W0 = correction_by_hand(amps, phs)
    assert np.allclose(W0, r.corrections, atol=1e-12)
    var_m, var_a = np.zeros(2), np.zeros(2)
    for idx in np.ndindex(amps.shape):
        for arr, sigma in ((amps, rel * amps[idx]), (phs, phase)):
            if sigma == 0.0:
                continue
            h = 1e-6 * (abs(arr[idx]) + 1.0)
            up, dn = arr.copy(), arr.copy()
            up[idx] += h
            dn[idx] -= h
            args_up = (up, phs) if arr is amps else (amps, up)
            args_dn = (dn, phs) if arr is amps else (amps, dn)
            Wu, Wd = correction_by_hand(*args_up), correction_by_hand(*args_dn)
            var_m += ((np.abs(Wu) - np.abs(Wd)) / (2 * h) * sigma) ** 2
            var_a += (np.degrees(np.angle(Wu / Wd)) / (2 * h) * sigma) ** 2
    for j in range(2):
        lo, hi = r.intervals[j]["mass"]
        assert (hi - lo) / 2 == pytest.approx(1.96 * math.sqrt(var_m[j]), rel=0.06)
        alo, ahi = r.intervals[j]["angle"]
        assert ((ahi - alo) % 360.0) / 2 == pytest.approx(1.96 * math.sqrt(var_a[j]), rel=0.06)


def kappa_2x2(A: np.ndarray) -> float:
    """Condition number from the eigenvalues of A^H A in closed form (not an SVD)."""
    G = A.conj().T @ A
    tr, det = G.trace().real, np.linalg.det(G).real
    disc = math.sqrt(max(tr * tr - 4.0 * det, 0.0))
    return math.sqrt((tr + disc) / (tr - disc))


@pytest.mark.parametrize("eps", [2e-3, 2e-6, 2e-8])
def test_ill_conditioned_matrix_with_one_percent_noise_warns(eps: float) -> None:
    alpha = np.array([[1.0, 1.0], [1.0, 1.0 + eps]], dtype=complex)   # kappa ~ 4 / eps
    u = np.array([1.0, 0.5j])
    T = [np.array([1.0, 0]), np.array([0, 1.0])]
    runs = [(plane_masses(t), pl(alpha @ (u + t))) for t in T]
    r = influence_balance(pl(alpha @ u), runs, noise=NoiseModel(0.01, 0.0, 0.0))
    if eps >= 1e-3:                    # the closed form loses digits nearer singular
        assert r.condition_number == pytest.approx(kappa_2x2(alpha), rel=1e-6)
    assert r.condition_number > 1e3
    assert any("condition number" in w for w in r.warnings)
    assert r.amplification > 0.1
    assert r.to_dict()["warnings"] == r.warnings


def test_well_conditioned_case_has_no_warning() -> None:
    runs = [(plane_masses(t), pl(ALPHA @ (U + t))) for t in TRIALS]
    r = influence_balance(pl(ALPHA @ U), runs, noise=NoiseModel(0.01, 0.0, 1.0))
    assert r.warnings == []
    assert r.condition_number == pytest.approx(kappa_2x2(ALPHA), rel=1e-9)
    # eps_V = ||sigma_V|| / ||V|| with sigma = |V| sqrt(0.01^2 + (1 deg)^2): a constant
    assert r.amplification == pytest.approx(
        r.condition_number * math.hypot(0.01, math.radians(1.0)), rel=1e-12)


def test_small_trial_mass_warns() -> None:
    """A trial changing the readings by ~2 sigma: its coefficients are mostly noise."""
    T = [np.array([0.01, 0]), np.array([0, 0.5j])]
    runs = [(plane_masses(t), pl(ALPHA @ (U + t))) for t in T]
    r = influence_balance(pl(ALPHA @ U), runs, noise=NoiseModel(0.01, 0.0, 1.0))
    assert any(w.startswith("trial run 1 changed the readings") for w in r.warnings)
    assert not any(w.startswith("trial run 2") for w in r.warnings)


def test_trim_one_plane_by_hand() -> None:
    """Stored alpha 0.9 at 70 deg; V0 20 at 180; applied C; V1 measured. By hand:
    alpha' = (V1 - V0) / C, the trim correction -V1 / alpha'."""
    a_true, u = 0.8 * cmath.exp(1j * math.radians(60)), 25 * cmath.exp(2j * math.pi / 3)
    V0 = a_true * u
    C = 21.7 * cmath.exp(1j * math.radians(290))
    V1 = a_true * (u + C)
    r = trim_balance(pl(V0), [([(abs(C), math.degrees(cmath.phase(C)))], pl(V1))],
                     coefficients=[[(0.9, 70.0)]])
    a_hand = (V1 - V0) / C
    assert r.coefficients[0, 0] == pytest.approx(a_hand, abs=1e-12)
    assert r.corrections[0] == pytest.approx(-V1 / a_hand, abs=1e-12)
    assert r.corrections[0] == pytest.approx(-(u + C), abs=1e-11)    # the truth
    assert r.trim_runs == 1


def test_broyden_update_is_the_least_change_meeting_the_secant() -> None:
    """Two planes, stored coefficients off: after one trim run alpha' C = dV and
    alpha' - alpha0 is the minimum-norm solution of D C = dV - alpha0 C, found here
    by lstsq on the Kronecker form vec(D C) = (C^T kron I) vec(D)."""
    rng = np.random.default_rng(5)
    alpha0 = ALPHA * (1.0 + 0.2 * (rng.normal(size=(2, 2)) + 1j * rng.normal(size=(2, 2))))
    C = np.array([0.9 * cmath.exp(-2.0j), 0.6 * cmath.exp(0.4j)])
    V0, V1 = ALPHA @ U, ALPHA @ (U + C)
    r = trim_balance(pl(V0), [(plane_masses(C), pl(V1))], coefficients=alpha0)
    assert np.allclose(r.coefficients @ C, V1 - V0, atol=1e-12)
    K = np.kron(C[None, :], np.eye(2))                     # vec (column-major) form
    D, *_ = np.linalg.lstsq(K, V1 - V0 - alpha0 @ C, rcond=None)
    assert np.allclose(r.coefficients - alpha0, D.reshape(2, 2, order="F"), atol=1e-12)
    assert np.allclose(r.current, V1, atol=1e-12)


def test_trim_with_trial_runs_joins_the_least_squares() -> None:
    """Exact linear machine: the trim run is one more consistent equation, so alpha
    stays exact and the trim correction removes what is left, -(U + C)."""
    runs = [(plane_masses(t), pl(ALPHA @ (U + t))) for t in TRIALS]
    C = np.array([0.8 * cmath.exp(-2.6j), 0.6 * cmath.exp(-0.7j)])   # a rough correction
    r = influence_balance(pl(ALPHA @ U), runs, trims=[(plane_masses(C), pl(ALPHA @ (U + C)))])
    assert np.allclose(r.coefficients, ALPHA, atol=1e-12)
    assert np.allclose(r.corrections, -(U + C), atol=1e-12)


def test_errors_are_one_line() -> None:
    runs = [(plane_masses(t), pl(ALPHA @ (U + t))) for t in TRIALS]
    cases = [
        (lambda: influence_balance(pl(ALPHA @ U), runs, coefficients=ALPHA), "not both"),
        (lambda: influence_balance(pl(ALPHA @ U)), "no trial runs"),
        (lambda: trim_balance(pl(ALPHA @ U), [], coefficients=ALPHA), "at least one trim"),
        (lambda: trim_balance(pl(ALPHA @ U), [([None, None], pl(ALPHA @ U))],
                              coefficients=ALPHA), "applied no mass"),
        (lambda: influence_balance(pl(ALPHA @ U), coefficients=ALPHA[:1]), "rows"),
        (lambda: parse_noise({"relative": 0.0}, 0.0), "all 0"),
        (lambda: parse_noise({"relativ": 0.01}), "unknown key"),
        (lambda: parse_noise(None, None, 1.0), "confidence"),
    ]
    for call, text in cases:
        with pytest.raises(BalanceError) as exc:
            call()
        assert text in str(exc.value) and "\n" not in str(exc.value)
