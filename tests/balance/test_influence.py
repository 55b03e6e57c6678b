"""Influence-coefficient balancing with measured phase (beyond the seed)."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from balance import (
    BalanceError,
    influence_balance,
    influence_coefficients,
    influence_single_plane,
    influence_two_plane,
)
from tests.balance._balance_cases import angle_diff

PUBLISHED = {
    "initial": [(170.0, 112.0), (53.0, 78.0)],
    "trial_plane1": [(235.0, 94.0), (58.0, 68.0)],
    "trial_plane2": [(185.0, 115.0), (77.0, 104.0)],
    "trial_mass": 1.15,
    "trial_angle": 0.0,
}


def test_published_two_plane_case() -> None:
    """1.15 g trial at 0 deg; corrections 1.979 g at 236.2 deg and 1.071 g at 121.8 deg."""
    r = influence_two_plane(**PUBLISHED)
    assert r.masses[0] == pytest.approx(1.979, abs=6e-4)
    assert r.masses[1] == pytest.approx(1.071, abs=6e-4)
    assert angle_diff(r.angles[0], 236.2) <= 0.05
    assert angle_diff(r.angles[1], 121.8) <= 0.05
    assert np.abs(r.residual).max() <= 1e-10 * 170.0
    d = r.to_dict()
    assert [c["plane"] for c in d["corrections"]] == [1, 2]


def polar_list(z: np.ndarray) -> list[tuple[float, float]]:
    return [(abs(v), math.degrees(cmath.phase(v))) for v in z]


complexes = st.builds(lambda r, t: cmath.rect(r, math.radians(t)), st.floats(0.2, 5.0),
                      st.floats(0.0, 360.0))


@settings(max_examples=200, deadline=None)
@given(st.lists(complexes, min_size=4, max_size=4), st.lists(complexes, min_size=2, max_size=2),
       complexes, complexes)
def test_two_plane_forward_model_is_recovered(a, U, T1, T2) -> None:
    alpha = np.array(a).reshape(2, 2)
    if abs(np.linalg.det(alpha)) < 0.05 * np.abs(alpha).max() ** 2:
        return                                   # nearly singular machines: skip
    U = np.array(U)
    V0 = alpha @ U
    V1 = alpha @ (U + np.array([T1, 0]))
    V2 = alpha @ (U + np.array([0, T2]))
    r = influence_two_plane(polar_list(V0), polar_list(V1), polar_list(V2), abs(T1),
                            math.degrees(cmath.phase(T1)), abs(T2), math.degrees(cmath.phase(T2)))
    assert np.allclose(r.corrections, -U, rtol=0, atol=1e-9 * np.abs(U).max())
    assert np.allclose(r.coefficients, alpha, rtol=0, atol=1e-9 * np.abs(alpha).max())
    assert all(0.0 <= x < 360.0 for x in r.angles)


def test_least_squares_over_speeds_and_extra_runs() -> None:
    rng = np.random.default_rng(7)
    alpha = rng.normal(size=(6, 2)) + 1j * rng.normal(size=(6, 2))   # 2 sensors x 3 speeds
    U = np.array([0.8 * cmath.exp(1j * 0.3), 1.3 * cmath.exp(-2.0j)])
    trials = [np.array([1.0, 0]), np.array([0, 1.0j]), np.array([0.5, 0.5])]  # 3 runs, 2 planes
    V0 = alpha @ U
    runs = [([(abs(t[0]), math.degrees(cmath.phase(t[0]))) if t[0] else None,
              (abs(t[1]), math.degrees(cmath.phase(t[1]))) if t[1] else None],
             polar_list(alpha @ (U + t))) for t in trials]
    r = influence_balance(polar_list(V0), runs)
    assert np.allclose(r.corrections, -U, atol=1e-10)
    assert np.allclose(influence_coefficients(polar_list(V0), runs), alpha, atol=1e-10)
    # with noisy initial readings the correction minimises the residual vibration
    noisy = V0 + 0.05 * (rng.normal(size=6) + 1j * rng.normal(size=6))
    r = influence_balance(polar_list(noisy), [(t, polar_list(alpha @ U + alpha @ t_vec
                                                             + (noisy - V0)))
                                              for (t, _), t_vec in zip(runs, trials,
                                                                       strict=True)])
    grad = r.coefficients.conj().T @ r.residual        # normal equations: alpha^H res = 0
    assert np.abs(grad).max() <= 1e-10 * np.abs(noisy).max()


def test_single_plane_and_radius_scaling() -> None:
    alpha = 2.0 * cmath.exp(0.7j)
    U = 0.9 * cmath.exp(1.1j)
    V0, V1 = alpha * U, alpha * (U + 1.0)
    r = influence_single_plane(polar_list(np.array([V0]))[0], polar_list(np.array([V1]))[0],
                               1.0, 0.0)
    assert r.corrections[0] == pytest.approx(-U, abs=1e-12)
    runs = [((1.0, 0.0), [(abs(V1), math.degrees(cmath.phase(V1)))])]
    r2 = influence_balance([(abs(V0), math.degrees(cmath.phase(V0)))], runs,
                           trial_radius=0.1, correction_radius=0.05)
    assert r2.masses[0] == pytest.approx(2.0 * abs(U), rel=1e-12)   # half radius, twice mass
    # complex numbers work as readings too
    r3 = influence_single_plane(V0, V1, 1.0)
    assert r3.corrections[0] == pytest.approx(-U, abs=1e-12)


def one_line(exc: pytest.ExceptionInfo) -> str:
    msg = str(exc.value)
    assert msg and "\n" not in msg
    return msg


def test_errors() -> None:
    with pytest.raises(BalanceError) as exc:      # one run for two planes
        influence_balance(PUBLISHED["initial"], [([(1.0, 0.0), None], PUBLISHED["trial_plane1"])])
    assert "at least one trial run per plane" in one_line(exc)
    with pytest.raises(BalanceError) as exc:      # both runs in plane 1
        influence_balance(PUBLISHED["initial"],
                          [([(1.0, 0.0), None], PUBLISHED["trial_plane1"]),
                           ([(2.0, 0.0), None], PUBLISHED["trial_plane2"])])
    assert "independently" in one_line(exc)
    with pytest.raises(BalanceError) as exc:      # trial changed nothing
        influence_two_plane(PUBLISHED["initial"], PUBLISHED["initial"],
                            PUBLISHED["trial_plane2"], 1.15)
    assert "cannot separate" in one_line(exc)
    with pytest.raises(BalanceError) as exc:      # reading count mismatch
        influence_two_plane(PUBLISHED["initial"], PUBLISHED["trial_plane1"][:1],
                            PUBLISHED["trial_plane2"], 1.15)
    assert "readings" in one_line(exc)
    with pytest.raises(BalanceError):
        influence_single_plane((170.0, 112.0), (235.0, 94.0), 0.0)
    with pytest.raises(BalanceError):
        influence_single_plane((-170.0, 112.0), (235.0, 94.0), 1.0)


@pytest.mark.slow     # Monte-Carlo: 100 perturbed readings
def test_uncertainty_of_the_published_case() -> None:
    dA = 2.0
    r = influence_two_plane(**PUBLISHED, dA=dA)
    assert len(r.uncertainty) == 2
    rng = np.random.default_rng(3)
    amps = np.array([a for key in ("initial", "trial_plane1", "trial_plane2")
                     for a, _ in PUBLISHED[key]])
    phases = [p for key in ("initial", "trial_plane1", "trial_plane2")
              for _, p in PUBLISHED[key]]
    for j, u in enumerate(r.uncertainty):
        assert u.method == "corners"
        assert u.magnitude[0] <= r.masses[j] <= u.magnitude[1]
    for d in rng.uniform(-dA, dA, size=(100, 6)):
        a = amps + d
        rd = [(a[i], phases[i]) for i in range(6)]
        s = influence_two_plane(rd[0:2], rd[2:4], rd[4:6], 1.15)
        for j, u in enumerate(r.uncertainty):
            assert u.magnitude[0] - 1e-12 <= s.masses[j] <= u.magnitude[1] + 1e-12
            lo, hi = u.angle
            width = (hi - lo) % 360.0
            assert (s.angles[j] - lo) % 360.0 <= width + 1e-9
    assert "uncertainty" in r.to_dict()
