"""Resonance amplitude methods (seed 002 s. 3.3.2, eqs 3.22-3.31; runs: scene-format s. 2)."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from balance import BalanceError, BalanceWarning, four_run, parallelogram, trial_runs
from tests.balance._balance_cases import angle_diff

# Forward model of the balancing machine at resonance (eqs 3.23-3.28): an amplitude is
# k |U + Q| with U = m1 r1 e^(i theta) the unbalance and Q = m r e^(i mark) the trial.
M_TRIAL, R_TRIAL, R_CORR = 0.002, 0.06, 0.05
Q = M_TRIAL * R_TRIAL


def amp(k: float, U: complex, mark: float | None) -> float:
    q = 0j if mark is None else cmath.rect(Q, math.radians(mark))
    return k * abs(U + q)


def true_correction(U: complex) -> complex:
    """The correction vector (kg at the correction radius) that cancels U."""
    return -U / R_CORR


def correction(mass: float, angle: float) -> complex:
    return cmath.rect(mass, math.radians(angle))


near_edges = st.sampled_from([0.0, 1e-9, 1e-6, 0.01, 179.99, 180.0 - 1e-7, 180.0,
                              180.0 + 1e-7, 180.01, 359.99, 360.0 - 1e-9])
thetas = st.one_of(st.floats(0.0, 360.0, exclude_max=True), near_edges)
ratios = st.floats(0.02, 50.0)          # |U| / |Q|
scales = st.floats(1e2, 1e8)            # machine constant k (amplitude per kg m)


@pytest.mark.filterwarnings("ignore::balance.errors.BalanceWarning")  # clipped cos, small trials
@settings(max_examples=400, deadline=None)
@given(thetas, ratios, scales)
def test_parallelogram_recovers_the_unbalance(theta, ratio, k) -> None:
    U = cmath.rect(ratio * Q, math.radians(theta))
    A1, A2, A3 = amp(k, U, None), amp(k, U, 0.0), amp(k, U, 180.0)
    r = parallelogram(A1, A2, A3, M_TRIAL, R_TRIAL, R_CORR, noise=None)   # seed only
    assert r.unbalance == pytest.approx(abs(U), rel=1e-9)
    assert r.A == pytest.approx(k * Q, rel=1e-9)
    assert 0.0 <= r.phi <= 180.0
    assert 0.0 <= r.angle < 360.0 and 0.0 <= r.mirror_angle < 360.0
    # the true correction is `angle` when U lies 0..180 deg from the mark, else the mirror
    right = r.angle if theta % 360.0 <= 180.0 else r.mirror_angle
    W = true_correction(U)
    assert abs(correction(r.correction_mass, right) - W) <= 1e-6 * abs(W)
    # and both candidates are the mirror images of each other about the mark's line
    assert angle_diff(r.angle + r.mirror_angle, 0.0) <= 1e-9


@pytest.mark.filterwarnings("ignore::balance.errors.BalanceWarning")  # clipped cos, small trials
@settings(max_examples=200, deadline=None)
@given(thetas, ratios, scales)
def test_parallelogram_in_both_candidate_orders(theta, ratio, k) -> None:
    """U and its mirror image give the same amplitudes: the method returns the same
    pair of candidates, and each true correction is one of them."""
    found = []
    for t in (theta, -theta):
        U = cmath.rect(ratio * Q, math.radians(t))
        r = parallelogram(amp(k, U, None), amp(k, U, 0.0), amp(k, U, 180.0),
                          M_TRIAL, R_TRIAL, R_CORR, noise=None)
        W = true_correction(U)
        errors = [abs(correction(r.correction_mass, a) - W) for a in (r.angle, r.mirror_angle)]
        assert min(errors) <= 1e-6 * abs(W)
        found.append((r.angle, r.mirror_angle))
    assert angle_diff(found[0][0], found[1][0]) <= 1e-6
    assert angle_diff(found[0][1], found[1][1]) <= 1e-6


def test_textbook_numbers() -> None:
    r = parallelogram(546.5, 1071.9, 495.0, 0.002, 0.06, 0.05)
    A = math.sqrt((1071.9**2 + 495.0**2 - 2 * 546.5**2) / 2)                 # eq. 3.29
    cos_phi = (546.5**2 + A**2 - 495.0**2) / (2 * 546.5 * A)                 # eq. 3.31 corr.
    assert r.A == pytest.approx(A, rel=1e-14)
    assert r.phi == pytest.approx(math.degrees(math.acos(cos_phi)), abs=1e-10)
    assert r.unbalance == pytest.approx(0.002 * 0.06 * 546.5 / A, rel=1e-14)  # eq. 3.30
    assert r.angle == pytest.approx(180.0 + r.phi) and r.mirror_angle == pytest.approx(
        180.0 - r.phi)
    assert r.to_dict()["plane"] == 1
    assert parallelogram(546.5, 1071.9, 495.0, 0.002, 0.06, 0.05, plane=2).plane == 2


def spread_marks(offset: float, picks: list[int]) -> list[float]:
    return [offset + 30.0 * p for p in picks]


@pytest.mark.filterwarnings("ignore::balance.errors.BalanceWarning")  # clipped cos, small trials
@settings(max_examples=300, deadline=None)
@given(thetas, ratios, scales, st.floats(0.0, 360.0),
       st.lists(st.integers(0, 11), min_size=3, max_size=6, unique=True))
def test_runs_pick_the_right_candidate(theta, ratio, k, offset, picks) -> None:
    marks = spread_marks(offset, picks)
    assume(len({round((m % 180.0), 6) for m in marks}) > 1)
    U = cmath.rect(ratio * Q, math.radians(theta))
    runs = [(m, amp(k, U, m)) for m in marks]
    r = trial_runs(amp(k, U, None), runs, M_TRIAL, R_TRIAL, R_CORR, noise=None)
    W = true_correction(U)
    assert r.mirror_angle is None
    assert 0.0 <= r.phi < 360.0 and 0.0 <= r.angle < 360.0
    assert abs(correction(r.correction_mass, r.angle) - W) <= 1e-7 * abs(W)
    assert r.fit_ratio == pytest.approx(1.0, rel=1e-7)


def test_four_run_is_the_classic_formula() -> None:
    U = cmath.rect(1.5e-4, math.radians(200.0))
    k = 500 / 1.5e-4
    A1, A2, A3, A4 = (amp(k, U, m) for m in (None, 0.0, 120.0, 240.0))
    r = four_run(A1, A2, A3, A4, M_TRIAL, R_TRIAL, R_CORR)
    assert r.A**2 == pytest.approx((A2**2 + A3**2 + A4**2) / 3 - A1**2, rel=1e-12)
    assert r.angle == pytest.approx(20.0, abs=1e-9)
    assert r.unbalance == pytest.approx(1.5e-4, rel=1e-12)
    same = trial_runs(A1, [{"angle": 0.0, "A": A2}, {"angle": 120.0, "A": A3},
                           {"angle": 240.0, "A": A4}], M_TRIAL, R_TRIAL, R_CORR)
    assert same.to_dict() == r.to_dict()


def test_three_runs_agree_with_parallelogram_when_marks_are_0_180_and_90() -> None:
    U = cmath.rect(1e-4, math.radians(300.0))
    k = 1e6
    three = parallelogram(amp(k, U, None), amp(k, U, 0.0), amp(k, U, 180.0), M_TRIAL,
                          R_TRIAL, R_CORR)
    runs = trial_runs(amp(k, U, None), [(m, amp(k, U, m)) for m in (0.0, 90.0, 180.0)],
                      M_TRIAL, R_TRIAL, R_CORR)
    assert runs.A == pytest.approx(three.A, rel=1e-12)
    assert runs.angle == pytest.approx(three.mirror_angle, abs=1e-9)   # U at 300: mirror


def test_A1_zero_gives_zero_unbalance_and_null_angles() -> None:
    r = parallelogram(0.0, 5.0, 5.0, M_TRIAL, R_TRIAL, R_CORR)
    assert r.unbalance == 0.0 and r.correction_mass == 0.0
    assert r.phi is None and r.angle is None and r.mirror_angle is None
    assert r.A == pytest.approx(5.0)
    r = four_run(0.0, 5.0, 5.0, 5.0, M_TRIAL, R_TRIAL, R_CORR)
    assert r.unbalance == 0.0 and r.angle is None and r.phi is None


def one_line(exc: pytest.ExceptionInfo) -> str:
    msg = str(exc.value)
    assert msg and "\n" not in msg
    return msg


def test_A_squared_not_positive_refused() -> None:
    with pytest.raises(BalanceError) as exc:
        parallelogram(5.0, 4.0, 3.0, M_TRIAL, R_TRIAL, R_CORR)   # 16 + 9 - 50 < 0
    assert "A2^2 + A3^2 - 2 A1^2" in one_line(exc)
    with pytest.raises(BalanceError):
        parallelogram(5.0, 5.0, 5.0, M_TRIAL, R_TRIAL, R_CORR)   # exactly 0


def test_arccos_out_of_range_refused() -> None:
    # A1 = 1, A2 = 3, A3 = 1: A^2 = 4, cos phi = (9 - 1) / (4 * 1 * 2) = 1 exactly;
    # make A2 larger: the triangle A1, A, A2 cannot close.
    with pytest.raises(BalanceError) as exc:
        parallelogram(1.0, 3.2, 1.0, M_TRIAL, R_TRIAL, R_CORR)
    assert "cos phi" in one_line(exc)


def test_arccos_within_tolerance_is_clipped_with_a_warning() -> None:
    A1, A3 = 1.0, 1.0
    # cos phi = (A2^2 - A3^2) / (4 A1 A), A^2 = (A2^2 + A3^2 - 2 A1^2) / 2; with A3 = A1 = 1
    # cos phi = (A2^2 - 1) / (4 sqrt((A2^2 - 1) / 2)) = sqrt(A2^2 - 1) / (2 sqrt 2) = 1 at A2 = 3
    A2 = 3.0 * (1.0 + 5e-11)
    with pytest.warns(BalanceWarning, match="clipped"):
        r = parallelogram(A1, A2, A3, M_TRIAL, R_TRIAL, R_CORR)
    assert r.phi == 0.0 and r.angle == 180.0 and r.mirror_angle == 180.0
    assert r.cos_phi > 1.0
    with pytest.raises(BalanceError):
        parallelogram(A1, 3.0 * (1.0 + 1e-8), A3, M_TRIAL, R_TRIAL, R_CORR)


@pytest.mark.parametrize("args, word", [
    ((-1.0, 5.0, 4.0), "A1"),
    ((1.0, 0.0, 4.0), "A2"),
    ((1.0, 5.0, -4.0), "A3"),
    ((1.0, float("nan"), 4.0), "A2"),
])
def test_bad_amplitudes_refused(args, word) -> None:
    with pytest.raises(BalanceError) as exc:
        parallelogram(*args, M_TRIAL, R_TRIAL, R_CORR)
    assert word in one_line(exc)


@pytest.mark.parametrize("trial", [(0.0, 0.06, 0.05), (-0.002, 0.06, 0.05),
                                   (0.002, 0.0, 0.05), (0.002, 0.06, -0.05)])
def test_bad_masses_and_radii_refused(trial) -> None:
    with pytest.raises(BalanceError):
        parallelogram(4.0, 6.1, 3.2, *trial)
    with pytest.raises(BalanceError):
        four_run(4.0, 6.1, 5.2, 2.9, *trial)


@pytest.mark.parametrize("plane", [0, 3, 1.5, True])
def test_bad_plane_refused(plane) -> None:
    with pytest.raises(BalanceError):
        parallelogram(4.0, 6.1, 3.2, M_TRIAL, R_TRIAL, R_CORR, plane=plane)


@pytest.mark.parametrize("runs", [[], [(0.0, 5.0)], [(0.0, 5.0), (120.0, 4.0)]])
def test_fewer_than_three_runs_refused(runs) -> None:
    with pytest.raises(BalanceError) as exc:
        trial_runs(4.0, runs, M_TRIAL, R_TRIAL, R_CORR)
    assert "at least three" in one_line(exc)


@pytest.mark.parametrize("marks", [(0.0, 0.0, 0.0), (0.0, 180.0, 0.0), (30.0, 210.0, 390.0),
                                   (0.0, 180.0, 360.0, -180.0)])
def test_marks_equal_or_opposite_refused(marks) -> None:
    with pytest.raises(BalanceError) as exc:
        trial_runs(4.0, [(m, 5.0) for m in marks], M_TRIAL, R_TRIAL, R_CORR)
    assert "equal or opposite" in one_line(exc)


def test_two_distinct_marks_refused() -> None:
    with pytest.raises(BalanceError) as exc:
        trial_runs(4.0, [(0.0, 5.0), (0.0, 5.1), (90.0, 3.0)], M_TRIAL, R_TRIAL, R_CORR)
    assert "two different" in one_line(exc)


def test_runs_with_A_squared_not_positive_give_null_keys_a_warning_and_the_estimate() -> None:
    with pytest.warns(BalanceWarning) as seen:
        r = trial_runs(10.0, [(0.0, 1.0), (120.0, 1.0), (240.0, 1.0)], M_TRIAL, R_TRIAL,
                       R_CORR)
    assert [str(w.message) for w in seen] == list(r.warnings)
    d = r.to_dict()
    assert d["A"] is None and d["unbalance"] is None and d["angle"] is None
    assert "A^2" in r.warnings[0]
    assert d["estimate"]["unbalance"] > 0.0          # still given (and flagged as unsound)
    assert any("do not fit a linear machine" in w for w in r.warnings)


def test_bad_run_entries_refused() -> None:
    with pytest.raises(BalanceError):
        trial_runs(4.0, [{"angle": 0.0, "amp": 5.0}] * 3, M_TRIAL, R_TRIAL, R_CORR)
    with pytest.raises(BalanceError):
        trial_runs(4.0, [(0.0, 5.0), (120.0, 0.0), (240.0, 3.0)], M_TRIAL, R_TRIAL, R_CORR)


def test_small_trial_mass_warns() -> None:
    U = cmath.rect(100 * Q, math.radians(40.0))
    with pytest.warns(BalanceWarning) as seen:
        r = parallelogram(amp(1e6, U, None), amp(1e6, U, 0.0), amp(1e6, U, 180.0),
                          M_TRIAL, R_TRIAL, R_CORR)
    assert [str(w.message) for w in seen] == list(r.warnings)
    assert any("larger trial mass" in w for w in r.warnings)
    assert r.unbalance == pytest.approx(abs(U), rel=1e-6)


# ------------------------------------------------------------------ uncertainty
def test_uncertainty_bounds_contain_sampled_perturbations() -> None:
    A1, A2, A3, dA = 546.5, 1071.9, 495.0, 4.0
    r = parallelogram(A1, A2, A3, M_TRIAL, R_TRIAL, R_CORR, dA=dA)
    u = r.uncertainty
    assert u.method == "corners"
    lo, hi = u.magnitude
    assert lo <= r.correction_mass <= hi
    alo, ahi = u.angle
    assert alo <= r.angle <= ahi
    rng = np.random.default_rng(1)
    for d in rng.uniform(-dA, dA, size=(300, 3)):
        s = parallelogram(A1 + d[0], A2 + d[1], A3 + d[2], M_TRIAL, R_TRIAL, R_CORR, noise=None)
        assert lo - 1e-15 <= s.correction_mass <= hi + 1e-15
        assert alo - 1e-9 <= s.angle <= ahi + 1e-9
    # the linearised half widths agree with the corner interval to first order
    # (measured 3.8e-4 and 1.8e-4: dA / A is under 1 %)
    assert (hi - lo) / 2 == pytest.approx(u.magnitude_linear, rel=1e-3)
    assert (ahi - alo) / 2 == pytest.approx(u.angle_linear, rel=1e-3)
    assert "uncertainty" in r.to_dict() and "uncertainty" not in parallelogram(
        A1, A2, A3, M_TRIAL, R_TRIAL, R_CORR).to_dict()
    # the mirror candidate is bracketed too: its bounds mirror the angle's about the mark
    mlo, mhi = r.to_dict()["uncertainty"]["mirror_angle"]
    assert mlo == pytest.approx(360.0 - ahi, abs=1e-9) and mhi == pytest.approx(360.0 - alo,
                                                                                abs=1e-9)


def test_uncertainty_zero_width_and_runs() -> None:
    r = four_run(500.0, 184.7, 692.4, 846.4, M_TRIAL, R_TRIAL, R_CORR, dA=0.0)
    assert r.uncertainty.magnitude == (r.correction_mass, r.correction_mass)
    r = four_run(500.0, 184.7, 692.4, 846.4, M_TRIAL, R_TRIAL, R_CORR, dA=2.0)
    lo, hi = r.uncertainty.magnitude
    assert lo < r.correction_mass < hi
    alo, ahi = r.uncertainty.angle
    assert angle_diff(alo, r.angle) > 0 and angle_diff(ahi, r.angle) > 0
    assert angle_diff(alo, ahi) < 5.0


def test_uncertainty_that_breaks_the_parallelogram_refused() -> None:
    with pytest.raises(BalanceError) as exc:
        parallelogram(5.0, 6.0, 4.5, M_TRIAL, R_TRIAL, R_CORR, dA=1.0)
    assert "cannot be bounded" in one_line(exc)
