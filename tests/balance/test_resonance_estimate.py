"""The best estimate from amplitudes: maximum likelihood of the readings themselves,
profile-likelihood intervals, chi-square quantiles, conditioning warnings (a linear
machine A = k |U + T| with multiplicative Gaussian noise is the reference)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import balance
from balance import BalanceError, BalanceWarning, parallelogram, trial_runs
from balance.resonance.amplitude_fit import fit_amplitudes
from balance.resonance.chi2 import chi2_cdf, chi2_quantile

Q95 = chi2_quantile(0.95, 1)


def draws(ratio: float, noise: float, marks, n: int, seed: int):
    """n amplitude sets of a linear machine (trial amplitude 1) with the unbalance
    ratio x the trial at a uniform random angle, each reading times (1 + noise N(0, 1))."""
    rng = np.random.default_rng(seed)
    theta = rng.uniform(0.0, 2.0 * np.pi, n)
    u = ratio * np.exp(1j * theta)
    A = np.column_stack([np.abs(u)] + [np.abs(u + np.exp(1j * math.radians(m)))
                                       for m in marks])
    return theta, A * (1.0 + noise * rng.standard_normal(A.shape))


def in_arc(angle, lo, hi):
    """angle inside the arc counterclockwise from lo to hi (rad); NaN bounds: whole circle."""
    inside = np.mod(angle - lo, 2 * np.pi) <= np.mod(hi - lo, 2 * np.pi)
    return np.where(np.isnan(lo), True, inside)


# ---------------------------------------------------------------- chi-square
@pytest.mark.parametrize(("p", "k", "want"), [
    (0.95, 1, 3.841458820694124), (0.95, 2, 5.991464547107979),
    (0.95, 3, 7.814727903251178), (0.95, 10, 18.307038053275146),
    (0.90, 1, 2.705543454095404), (0.99, 5, 15.08627246938899),
    (0.5, 1, 0.454936423119572), (0.999, 30, 59.70306430442994)])
def test_chi2_quantiles_match_the_tables(p, k, want):
    assert chi2_quantile(p, k) == pytest.approx(want, rel=1e-12)
    assert chi2_cdf(want, k) == pytest.approx(p, rel=1e-12)


def test_chi2_quantile_refuses_a_confidence_outside_0_1():
    with pytest.raises(BalanceError, match="confidence"):
        chi2_quantile(1.0, 1)


# --------------------------------------------------- against an independent fit
def independent_fit(A, marks, sigma):
    """Multi-start least squares (scipy: MINPACK's Levenberg-Marquardt with the exact
    Jacobian) of the same likelihood in (u_x, u_y, log a): a different parametrisation
    and a different optimiser. (The same 24 starts by the trust-region method with a
    finite-difference Jacobian found the same minima, chi2 within 1e-13 and U/T within
    7e-9 on the 53 draws below, at 3.3 times the CPU: 21.6 s against 6.4 s.)"""
    from scipy.optimize import least_squares  # the [test] extra: missing is a failure

    e = np.concatenate([[0.0], np.exp(1j * np.radians(marks))])     # e_0 = 0: the A1 run

    def model(p):
        a = np.exp(p[2])
        z = p[0] + 1j * p[1] + a * e                     # u + a e_k
        return z, np.abs(z), a

    def res(p):
        return (A - model(p)[1]) / sigma

    def jac(p):
        # d|z_k| / d(u_x, u_y, log a) = (Re, Im, Re(conj(z) a e_k)) / |z_k|
        z, m, a = model(p)
        zh = np.where(m > 0, z / np.where(m > 0, m, 1.0), 0.0)
        return -np.column_stack([zh.real, zh.imag, np.real(np.conj(zh) * a * e)]) \
            / sigma[:, None]

    best = None
    for th in np.linspace(0.0, 2.0 * np.pi, 8, endpoint=False):
        for scale in (0.3, 1.0, 3.0):
            a0 = scale * np.mean(np.abs(A[1:] - A[0])) + 1e-9
            r = least_squares(res, [A[0] * np.cos(th), A[0] * np.sin(th), np.log(a0)],
                              jac=jac, method="lm", xtol=1e-14, ftol=1e-14, gtol=1e-14)
            if best is None or 2.0 * r.cost < best[0]:
                best = (2.0 * r.cost, r.x)
    return best


# (the three runs on 8 draws cost 0.5-0.7 s of CPU; each case of four or five runs, 15
# multi-start fits by scipy, 1.2-2.3 s: slow. Measured 2026-11-30, load 7-9; by the
# trust region with finite differences 1.5 s and 5.5-10.7 s)
@pytest.mark.parametrize(("ratio", "noise", "marks", "n"), [
    pytest.param(10.0, 0.005, (0.0, 90.0, 180.0, 270.0), 15,  # a small trial mass
                 marks=pytest.mark.slow),
    pytest.param(1.0, 0.01, (0.0, 0.1, 180.0), 15,           # nearly coincident marks
                 marks=pytest.mark.slow),
    (2.0, 0.01, (0.0, 180.0), 8),                 # three runs: exact fit or on the mark line
    pytest.param(1.0, 0.03, (0.0, 120.0, 240.0), 15,         # four runs, readings near zero
                 marks=pytest.mark.slow)])
def test_the_estimate_is_the_maximum_likelihood(ratio, noise, marks, n):
    theta, A = draws(ratio, noise, marks, n, seed=11)
    fit = fit_amplitudes(A, np.array(marks), noise * A, Q95)
    for i in range(len(A)):
        chi2, x = independent_fit(A[i], np.array(marks), noise * A[i])
        # never a worse minimum than scipy's: measured on these 53 draws at most 2.1e-8 of
        # chi^2 above it (draw 1 of the runs at 0/120/240, where the estimate's descent
        # stops; the same against either scipy method), 4.1e-14 elsewhere; often the same
        # point, its ratio U/T within 5.2e-7 (same draw; 2.1e-8 elsewhere)
        assert fit.chi2[i, 0] <= chi2 + 1e-7 * max(1.0, chi2)
        if fit.chi2[i, 0] >= chi2 - 1e-9:
            rho = math.hypot(x[0], x[1]) / math.exp(x[2])
            assert fit.rho[i, 0] == pytest.approx(rho, rel=2e-6) or \
                fit.rho[i, 1] == pytest.approx(rho, rel=2e-6)


def test_small_trial_errors_and_no_refusal():
    """U/T = 10, 0.5 % noise, runs at 0/90/180/270: the linear fit in squared amplitudes
    errs by 27 % / 178 % (p50 / p95) and refuses a fifth of the draws; the estimate
    (measured on these 300 draws: 2.5 % / 7.3 %) never refuses."""
    theta, A = draws(10.0, 0.005, (0.0, 90.0, 180.0, 270.0), 300, seed=3)
    fit = fit_amplitudes(A, np.array([0.0, 90.0, 180.0, 270.0]), 0.005 * A, Q95)
    err = np.abs(fit.rho[:, 0] / 10.0 - 1.0)
    assert np.all(np.isfinite(err))
    assert np.median(err) < 0.04 and np.quantile(err, 0.95) < 0.11


# ------------------------------------------------------------ the reproducers
def test_nearly_coincident_marks_give_both_candidates_and_warnings():
    """The issue's call: 272.7 deg with no mirror and no warning, the truth 70 deg."""
    with pytest.warns(BalanceWarning):
        r = trial_runs(2.008, [(0, 2.28283), (0.1, 2.30519), (180, 3.27661)], 1, 1, 1)
    est = r.estimate
    assert {round(est.angle), round(est.mirror_angle)} == {290, 70}
    arcs = [est.interval["angle"], est.mirror_interval["angle"]]
    assert any(in_arc(math.radians(70.0), *np.radians(a)) for a in arcs)
    text = " ".join(r.warnings)
    assert "cannot tell the correction angle" in text and "falls outside" in text
    assert "7.38" in text                                    # the linear fit's ratio


@pytest.mark.slow
def test_nearly_coincident_marks_are_never_silently_on_the_wrong_side():
    """Marks 0/0.1/180 at 1 % noise: the two minima (phi and its mirror) are about as
    good, and the estimate lands nearer the mirror of the truth in 79 of 200 draws
    (measured). Wherever it does, it warns that the readings cannot tell the correction
    angle from its mirror (measured: all 79); and the truth lies in one of the two
    intervals or a warning says why not (0 silent misses in 200; the seed's angle was
    off by more than 90 deg in 67)."""
    marks = (0.0, 0.1, 180.0)
    theta, A = draws(1.0, 0.01, marks, 200, seed=5)
    silent, wrong_side, told = 0, 0, 0
    # every warning recorded here (a match would let the others through, 360 of them);
    # the one that matters is checked per draw on the result's warnings below
    with pytest.warns(BalanceWarning):
        for t, a in zip(theta, A, strict=True):
            r = trial_runs(a[0], list(zip(marks, a[1:], strict=True)), 1.0, 1.0, 1.0)
            est = r.estimate
            truth = math.degrees(t) + 180.0
            arcs = [est.interval["angle"]] + ([est.mirror_interval["angle"]]
                                              if est.mirror_interval else [])
            covered = any(in_arc(math.radians(truth), *np.radians(arc)) for arc in arcs)
            silent += not covered and not r.warnings
            if est.mirror_angle is not None and \
                    _apart(truth, est.mirror_angle) < _apart(truth, est.angle):
                wrong_side += 1
                told += any("cannot tell the correction angle" in w for w in r.warnings)
    assert wrong_side >= 40                 # the case is the ambiguous one: measured 79
    assert told == wrong_side
    assert silent == 0                      # measured 0


def _apart(a: float, b: float) -> float:
    """Angle between two directions (deg, 0 to 180)."""
    return abs((a - b + 180.0) % 360.0 - 180.0)


def test_trial_too_small_for_the_noise_warns_with_numbers():
    """U/T = 100 read at 1 %: the trial's effect is within the noise."""
    with pytest.warns(BalanceWarning) as seen:
        r = parallelogram(100.0, 100.5, 99.6, 0.002, 0.06, 0.05)
    said = [str(w.message) for w in seen]
    assert said == list(r.warnings)                # each warning raised is in the result
    assert any("too small for the unbalance" in w for w in said)
    assert any("under 0.1 of A1" in w for w in said)   # and the seed's own warning
    assert r.estimate.interval["unbalance"][1] is None         # unbounded above
    assert any("U/T = " in w for w in r.warnings)


def test_inconsistent_readings_are_flagged():
    with pytest.warns(BalanceWarning) as seen:
        r = trial_runs(4.0, [(0.0, 5.0), (90.0, 2.0), (180.0, 5.0), (270.0, 2.0)],
                       0.01, 0.1, 0.1)
    said = [str(w.message) for w in seen]
    assert said == list(r.warnings)
    assert any("do not fit a linear machine" in w for w in said)
    assert any("A^2 = -1.5 <= 0" in w for w in said)       # the seed's linear fit fails
    assert r.estimate.consistent is False and r.estimate.dof == 2


# ------------------------------------------------------------ three runs, keys
def test_three_runs_keep_both_candidates_and_match_the_seed_when_exact():
    r = parallelogram(546.5, 1071.9, 495.0, 0.002, 0.06, 0.05)
    est = r.estimate
    assert est.dof == 0 and est.consistent is None and est.chi2 < 1e-9
    assert est.angle == pytest.approx(r.angle, abs=1e-6)        # measured 4e-9 deg
    assert est.mirror_angle == pytest.approx(r.mirror_angle, abs=1e-6)
    assert est.unbalance == pytest.approx(r.unbalance, rel=1e-8)
    assert est.mirror_interval["unbalance"] == pytest.approx(est.interval["unbalance"])
    assert r.warnings == ()
    lo, hi = est.interval["angle"]
    assert lo < est.angle < hi


def test_contract_keys_from_a_scene_with_noise_and_confidence():
    text = """
[[resonance_test]]
trial_mass = 0.002
trial_radius = 0.06
correction_radius = 0.05
A1 = 546.5
runs = [{ angle = 0.0, A = 1071.9 }, { angle = 120.0, A = 390.2 }, { angle = 240.0, A = 805.7 }]
noise = { relative = 0.02, absolute = 1.0 }
confidence = 0.9
"""
    # readings 2 % apart from a linear machine: chi2 = 16.7 for 1 dof, and the seed's
    # result outside the estimate's intervals; both said, in the result as well
    with pytest.warns(BalanceWarning) as seen:
        out = balance.solve(text)["resonance_test"][0]
    assert [str(w.message) for w in seen] == out["warnings"]
    assert any("chi2 = 16.7" in w for w in out["warnings"])
    json.dumps(out, allow_nan=False)
    est = out["estimate"]
    assert set(est) == {"unbalance", "correction_mass", "angle", "mirror_angle", "A", "chi2",
                        "dof", "consistent", "interval", "mirror_interval"}
    assert est["dof"] == 1 and isinstance(est["consistent"], bool)
    assert est["mirror_angle"] is None and est["mirror_interval"] is None
    assert all(0.0 <= a < 360.0 for a in est["interval"]["angle"])
    assert isinstance(out["warnings"], list)
    with pytest.warns(BalanceWarning) as seen:
        wider = balance.solve(text.replace("0.9\n", "0.99\n"))["resonance_test"][0]
    assert [str(w.message) for w in seen] == wider["warnings"]
    wider = wider["estimate"]
    (lo9, hi9), (lo99, hi99) = est["interval"]["unbalance"], wider["interval"]["unbalance"]
    assert lo99 < lo9 < est["unbalance"] < hi9 < hi99


@pytest.mark.parametrize(("extra", "words"), [
    ("noise = { relative = 0.0 }", "both 0"),
    ("noise = { relative = 0.01, abs = 1.0 }", "abs"),
    ("confidence = 1.0", "(0, 1)")])
def test_bad_noise_or_confidence_refused(extra, words):
    text = ("[[resonance_test]]\ntrial_mass = 0.002\ntrial_radius = 0.06\n"
            "correction_radius = 0.05\nA1 = 546.5\nA2 = 1071.9\nA3 = 495.0\n" + extra + "\n")
    with pytest.raises(ValueError) as exc:
        balance.solve(text)
    assert words in str(exc.value)


def test_A1_zero_read_exactly():
    r = parallelogram(0.0, 5.0, 5.0, 0.002, 0.06, 0.05)
    assert r.estimate.unbalance == 0.0 and r.estimate.angle is None
    assert r.estimate.A == pytest.approx(5.0)


def test_worst_case_corners_never_clip_cos_phi():
    """cos phi = 0.982 at the nominal readings, 1.037 at a corner of +-0.1: refused, not
    clipped into a bound."""
    # dA = 0.02 leaves the angle within +-15.4 deg (measured): the call says so
    with pytest.warns(BalanceWarning, match="do not determine the correction") as seen:
        r = parallelogram(4.0, 6.9, 1.25, 0.002, 0.06, 0.05, dA=0.02)
    assert len(seen) == 1
    assert r.uncertainty is not None
    with pytest.raises(BalanceError, match="cannot be bounded"):
        parallelogram(4.0, 6.9, 1.25, 0.002, 0.06, 0.05, dA=0.1)


# ------------------------------------------------------------ calibration
def coverage(n: int, seed: int):
    """Coverage of the 95 % unbalance and angle intervals of the four-run method over
    U/T in {0.2, 1, 3} x noise in {0.5, 1, 3} %, n draws per cell."""
    marks = np.array([0.0, 120.0, 240.0])
    cells = {}
    for k, ratio in enumerate((0.2, 1.0, 3.0)):
        for j, noise in enumerate((0.005, 0.01, 0.03)):
            theta, A = draws(ratio, noise, marks, n, seed + 10 * k + j)
            f = fit_amplitudes(A, marks, noise * A, Q95)
            cov_u = (f.rho_lo[:, 0] <= ratio) & (ratio <= f.rho_hi[:, 0])
            cov_t = in_arc(theta, f.theta_lo[:, 0], f.theta_hi[:, 0])
            cells[ratio, noise] = (cov_u, cov_t)
    return cells


#: Draws per cell of the coverage check, and the band around 95 % each cell's coverage
#: and the pooled one must fall in: three binomial sigmas (sqrt(0.95 * 0.05 / n)).
COVERAGE_DRAWS = 400
COVERAGE_SIGMAS = 3.0


@pytest.mark.slow
def test_intervals_cover_the_truth_95_percent_in_every_cell():
    """400 draws per cell (binomial sigma 1.09 %): each cell within 95 +- 3.3 %
    (3 sigma). Measured (seed 2024): unbalance 92.0-96.25 %, angle 92.25-96.25 %
    (12 s of CPU; 1000 draws a cell took 25-30 s). Pooled over the nine cells, 3600
    draws (sigma 0.36 %): within 95 +- 1.09 %; measured unbalance 94.89 %, angle
    94.78 %. Intervals drawn at 90, 92.5 or 97.5 % fail a cell; at 93.5 or 96.5 % the
    pooled check (tried: 93.3 / 93.3 %, 96.7 / 96.4 %).
    """
    cells = coverage(COVERAGE_DRAWS, seed=2024)
    half = COVERAGE_SIGMAS * math.sqrt(0.95 * 0.05 / COVERAGE_DRAWS)
    for key, (cov_u, cov_t) in cells.items():
        assert abs(cov_u.mean() - 0.95) <= half, key
        assert abs(cov_t.mean() - 0.95) <= half, key
    cov_u = np.concatenate([c[0] for c in cells.values()]).mean()
    cov_t = np.concatenate([c[1] for c in cells.values()]).mean()
    pooled = half / 3.0                 # 9 cells: a third of the sigma
    assert abs(cov_u - 0.95) <= pooled and abs(cov_t - 0.95) <= pooled, (cov_u, cov_t)
