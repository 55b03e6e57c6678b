"""Maximum-likelihood estimate of an unbalance from vibration amplitudes alone, with
profile-likelihood intervals (the best estimate beside the seed's amplitude methods).

Model (seed 002 eqs 3.23-3.28, a linear machine at resonance): the reading without
trial mass is A_0 = |u| and the reading with the trial mass at mark theta_k is
A_k = |u + a e^(i theta_k)|, where u (a plane vector) is the unbalance's amplitude and
a > 0 the trial mass's, in the amplitudes' unit. Every reading is noisy, A_0
included, with a Gaussian 1-sigma sigma_k = sqrt((relative A_k)^2 + absolute^2)
computed from the reading. The estimate minimises

    chi2 = sum_k ((A_k - model_k) / sigma_k)^2          (-2 log-likelihood + const).

Writing u = rho a e^(i theta) (rho = |u| / a, the unbalance over the trial mass), the
model is a g_k(rho, theta) with g_0 = rho, g_k = |rho e^(i theta) + e^(i theta_k)|:
linear in a, so a is eliminated in closed form, a = sum w g A / sum w g^2 (w = 1 /
sigma^2), and chi2 becomes a function of (log rho, theta) only. That surface is
searched on a grid (every basin), each grid minimum is refined by a damped Newton
method, and every minimum whose chi2 lies within the interval threshold of the best
is kept (e.g. the mirror pair of three runs at 0 and 180 deg).

Intervals are profile-likelihood intervals (Wilks): the set of rho (of theta) where
the profile, chi2 minimised over the other unknowns, stays within the chi-square
quantile q_1(confidence) of the best chi2. They are found on a window round each
minimum, sized from the local curvature and widened until the set lies inside it; a
set that reaches rho -> infinity gives an unbounded (None) upper limit, one that runs
round the circle the whole circle. dof = readings - 3.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinetostatics.common.angles import radian_column

__all__ = ["AmplitudeFit", "LR_RANGE", "fit_amplitudes"]

LR_RANGE = (np.log(1e-4), np.log(1e4))
"""Range of log(rho) searched: an unbalance from 1e-4 to 1e4 times the trial mass."""

_GRID_R, _GRID_T = 48, 72          # global search grid (log rho x theta)
_LOCAL = 41                        # local window grid per axis (odd: the minimum at centre)
_STARTS = 4                        # grid minima refined per problem
_NEWTON_STEPS = 60
_SAME = 1e-6                       # two refined minima closer than this are one
_CHUNK = 128                       # problems per descent group (see _lm)
_BLOCK = 4 * _CHUNK                # problems per vectorised block (numpy's calls)
_PIECE = 32                        # problems per grid of chi2 (its arrays in the caches)
_TWO_PI = 2.0 * np.pi


@dataclass(frozen=True)
class AmplitudeFit:
    """Best estimates of a batch of B amplitude sets (K minima kept per set, best first).

    Attributes
    ----------
    rho, theta, a, chi2 : numpy.ndarray, shape (B, K)
        rho = |u| / a, the unbalance's angle theta (rad, [0, 2 pi)), the trial mass's
        amplitude a and chi2 at each minimum; NaN where no minimum is kept.
    rho_lo, rho_hi : numpy.ndarray, shape (B, K)
        The profile-likelihood interval of rho round each minimum (rho_hi inf where
        unbounded).
    theta_lo, theta_hi : numpy.ndarray, shape (B, K)
        The interval of theta, counterclockwise from lo to hi (rad, [0, 2 pi)); both
        NaN where it is the whole circle.
    dof : int
        Readings minus 3.
    threshold : float
        The chi-square quantile q_1(confidence) that bounds the intervals.
    at_bound : numpy.ndarray of bool, shape (B, K)
        True where a minimum's rho sits on the edge of the searched range
        (:data:`LR_RANGE`, 1e-4 to 1e4): the likelihood still rises beyond it, so that
        is no true maximum; the estimate must be flagged, not reported as found.
    """

    rho: np.ndarray
    theta: np.ndarray
    a: np.ndarray
    chi2: np.ndarray
    rho_lo: np.ndarray
    rho_hi: np.ndarray
    theta_lo: np.ndarray
    theta_hi: np.ndarray
    dof: int
    threshold: float
    at_bound: np.ndarray | None = None


BOUND_TOL = 1e-6
"""|log rho - range end| within which a minimum counts as sitting on the range's edge."""


class _Data:
    """Readings, weights and mark directions of a block of problems."""

    def __init__(self, A: np.ndarray, sigma: np.ndarray, marks: np.ndarray) -> None:
        self.A = A                                         # (P, n+1), A[:, 0] = A_0
        self.w = 1.0 / sigma**2
        self.c = np.cos(marks)
        self.s = np.sin(marks)

    def take(self, idx: np.ndarray) -> _Data:
        out = object.__new__(_Data)
        out.A, out.w, out.c, out.s = self.A[idx], self.w[idx], self.c, self.s
        return out

    def chi2(self, lr: np.ndarray, th: np.ndarray, with_a: bool = False):
        """chi2 minimised over a, at (log rho, theta) of shape (P, ...), or of shapes that
        broadcast to it, with the same axes (each number computed once where an axis is
        of length 1: the same numbers, fewer of them). The readings' axis comes first
        in the terms: numpy's loops then run along theta and log rho, not along the few
        readings (each number as it was; the coverage test's 3600 fits took 11.0 s of
        CPU with it last, 7.6 s so, measured 2026-11-30)."""
        extra = (1,) * (lr.ndim - 1)
        A = self.A.T.reshape(-1, self.A.shape[0], *extra)          # (n+1, P, 1, ...)
        w = self.w.T.reshape(A.shape)
        marks = (slice(None),) + (None,) * th.ndim
        rho = np.exp(lr)
        cos_d = np.cos(th) * self.c[marks] + np.sin(th) * self.s[marks]   # (n, ...)
        # g = |u/a + e^(i t_k)| = sqrt(rho^2 + 2 rho cos(theta - t_k) + 1), its terms
        # added in place in another order (a sum of two, then 1: the same numbers)
        g = 2.0 * rho * cos_d
        g += rho * rho
        g += 1.0
        g = np.sqrt(np.maximum(g, 0.0, out=g), out=g)
        w0, A0, wk, Ak = w[0], A[0], w[1:], A[1:]
        wg = wk * g
        t = wg * Ak                                      # (one buffer for the full terms)
        num = _first_sum(t)
        a = (w0 * rho * A0 + num) / (w0 * rho * rho + _first_sum(np.multiply(wg, g, out=t)))
        r0 = A0 - a * rho
        rk = np.subtract(Ak, np.multiply(a, g, out=t), out=t)                # A_k - a g_k
        wrr = np.multiply(np.multiply(wk, rk, out=wg), rk, out=wg)            # w_k r_k^2
        chi2 = w0 * r0 * r0 + _first_sum(wrr)            # no cancellation in sharp valleys
        return (chi2, a) if with_a else chi2


def _first_sum(x: np.ndarray) -> np.ndarray:
    """``x.sum(axis=0)`` as :func:`_last_sum` sums a last axis, bit for bit."""
    return _sum(list(x))


def _last_sum(x: np.ndarray) -> np.ndarray:
    """``x.sum(axis=-1)`` bit for bit (:func:`_sum` of its slices)."""
    return _sum([x[..., k] for k in range(x.shape[-1])])


def _sum(terms: list[np.ndarray]) -> np.ndarray:
    """The terms (of one shape) summed as numpy's ``sum(axis=-1)`` of them stacked on a
    last axis, bit for bit: fewer than 8 it adds one after the other from 0.0 (its
    pairwise sum starts at 8), here without the stacked array and the reduction over so
    short an axis (a seventh of its time)."""
    if not 0 < len(terms) < 8:
        return np.stack(terms, axis=-1).sum(axis=-1)
    s = terms[0] + 0.0                                   # (-0.0 + 0.0 is 0.0, as numpy's)
    for x in terms[1:]:
        s += x
    return s


def _wrap(t: np.ndarray) -> np.ndarray:
    return np.mod(t, _TWO_PI)


def _grid_starts(d: _Data) -> tuple[np.ndarray, np.ndarray]:
    """Up to _STARTS grid minima of chi2(log rho, theta) per problem, plus each best
    minimum's mirror image theta -> -theta: (P, _STARTS + 1) arrays."""
    A0 = d.A[:, 0]
    Ak = d.A[:, 1:]
    rho_lo = A0 / (Ak.min(axis=1) + A0)
    rho_hi = A0 / np.maximum(np.abs(Ak - A0[:, None]).max(axis=1), 1e-12 * Ak.max(axis=1))
    lo = np.clip(np.log(np.maximum(rho_lo, 1e-300)) - 1.5, *LR_RANGE)
    hi = np.clip(np.log(np.maximum(rho_hi, 1e-300)) + 1.5, *LR_RANGE)
    hi = np.maximum(hi, lo + 1.0)
    u = np.linspace(0.0, 1.0, _GRID_R)
    lr = lo[:, None, None] + (hi - lo)[:, None, None] * u[None, :, None]
    th = np.arange(_GRID_T) * (_TWO_PI / _GRID_T)
    f = d.chi2(lr, th[None, None, :])       # the axes as they are: chi2 broadcasts them
    lr = np.broadcast_to(lr, f.shape)
    pad = np.pad(f, ((0, 0), (1, 1), (0, 0)), constant_values=np.inf)
    pad = np.concatenate([pad[:, :, -1:], pad, pad[:, :, :1]], axis=2)     # theta periodic
    is_min = np.ones(f.shape, dtype=bool)
    for dr in (-1, 0, 1):
        for dt in (-1, 0, 1):
            if dr or dt:
                is_min &= f <= pad[:, 1 + dr:1 + dr + _GRID_R, 1 + dt:1 + dt + _GRID_T]
    score = np.where(is_min, f, np.inf).reshape(len(lo), -1)
    k = min(_STARTS, score.shape[1])
    best = np.argsort(score, axis=1)[:, :k]
    found = np.isfinite(np.take_along_axis(score, best, axis=1))
    best = np.where(found, best, best[:, :1])           # a flat surface: the best point only
    ir, it = np.divmod(best, _GRID_T)
    lr0 = np.take_along_axis(lr.reshape(len(lo), -1), best, axis=1)
    th0 = th[it]
    lr0 = np.concatenate([lr0, lr0[:, :1]], axis=1)
    th0 = np.concatenate([th0, _wrap(-th0[:, :1])], axis=1)
    return lr0, th0


def _derivatives(d: _Data, lr: np.ndarray, th: np.ndarray, h: float = 1e-5):
    """chi2, gradient (.., 2) and Hessian (.., 2, 2) by central differences."""
    o = np.array([[0, 0], [h, 0], [-h, 0], [0, h], [0, -h], [h, h], [h, -h], [-h, h],
                  [-h, -h]])
    f = d.chi2(lr[..., None] + o[:, 0], th[..., None] + o[:, 1])
    f0 = f[..., 0]
    g = np.stack([(f[..., 1] - f[..., 2]) / (2 * h), (f[..., 3] - f[..., 4]) / (2 * h)],
                 axis=-1)
    hrr = (f[..., 1] - 2 * f0 + f[..., 2]) / h**2
    htt = (f[..., 3] - 2 * f0 + f[..., 4]) / h**2
    hrt = (f[..., 5] - f[..., 6] - f[..., 7] + f[..., 8]) / (4 * h * h)
    H = np.stack([np.stack([hrr, hrt], -1), np.stack([hrt, htt], -1)], -2)
    return f0, g, H


def _residuals(d: _Data, ce: np.ndarray, sw: np.ndarray, p: np.ndarray):
    """Weighted residuals (A_k - model_k) / sigma_k, (P, S, n+1), and their Jacobian
    (P, S, n+1, 3), in polar coordinates about a centre c: p = (log t, phi, log a) with
    u / a = c + t e^(i phi); ce = c + e_k (P, S, n+1: e_0 = 0, the A1 run) and sw =
    1 / sigma (P, 1, n+1) as :func:`_lm` makes them once."""
    a = np.exp(p[..., 2])[..., None]
    arm = np.exp(p[..., 0] + 1j * p[..., 1])[..., None]             # t e^(i phi)
    z = ce + arm
    az = np.abs(z)
    m = a * az
    r = (d.A[:, None, :] - m) * sw
    zh = np.where(az > 0, z / np.where(az > 0, az, 1.0), 1.0)
    J = -np.stack([a * np.real(np.conj(zh) * arm), a * np.real(np.conj(zh) * 1j * arm), m],
                  axis=-1) * sw[..., None]
    return r, J


def _lm(d: _Data, c: np.ndarray, p: np.ndarray, group: np.ndarray
        ) -> tuple[np.ndarray, np.ndarray]:
    """Levenberg-Marquardt descent from p (P, S, 3) about the centres c; (p, chi2). The
    residuals and Jacobian at p are those of the step that moved there (p's own).

    The problems descend in groups (``group``, (P,): their chunk of :data:`_CHUNK`
    problems): a group stops when every start of each of its problems has settled,
    and the others go on without it (each problem's numbers computed on their own)."""
    ce = c[..., None] + np.concatenate([np.zeros(1), d.c + 1j * d.s])
    sw = np.sqrt(d.w)[:, None, :]
    r, J = _residuals(d, ce, sw, p)
    f = _last_sum(r * r)
    lam = np.full(f.shape, 1e-3)
    eye = np.eye(3)
    live = slice(None)                   # the problems of unsettled groups (all: a slice)
    for _ in range(_NEWTON_STEPS):
        Jl, rl, fl, laml = J[live], r[live], f[live], lam[live]
        JTJ = np.einsum("...ki,...kj->...ij", Jl, Jl)
        g = np.einsum("...ki,...k->...i", Jl, rl)
        dg = np.einsum("...ii->...i", JTJ)
        dg = dg + 1e-9 * dg.max(axis=-1, keepdims=True) + 1e-300   # a direction J misses
        diag = dg[..., None, :] * eye
        step = np.linalg.solve(JTJ + laml[..., None, None] * diag, -g[..., None])[..., 0]
        trial = p[live] + np.clip(step, -3.0, 3.0)
        dl = d if isinstance(live, slice) else d.take(live)
        rt, Jt = _residuals(dl, ce[live], sw[live], trial)
        ft = _last_sum(rt * rt)
        with np.errstate(invalid="ignore"):
            better = ft < fl
            settled = (better & (fl - ft <= 1e-13 * fl) & (laml < 1e-2)) | (laml > 1e12)
        p = _put(p, live, np.where(better[..., None], trial, p[live]))
        r = _put(r, live, np.where(better[..., None], rt, rl))
        J = _put(J, live, np.where(better[..., None, None], Jt, Jl))
        f = _put(f, live, np.where(better, ft, fl))
        lam = _put(lam, live, np.where(better, np.maximum(laml / 3.0, 1e-12), laml * 4.0))
        if group[-1] == 0:                             # one group: as it always was
            if np.all(settled):
                break
            continue
        is_open = np.zeros(group[-1] + 1, dtype=bool)
        is_open[group[live][~settled.all(axis=-1)]] = True
        stay = is_open[group[live]]
        if not stay.any():
            break
        if not stay.all():
            live = np.arange(len(p))[live][stay]
    return p, f


def _put(a: np.ndarray, live: np.ndarray | slice, v: np.ndarray) -> np.ndarray:
    """a with its rows ``live`` set to v (v itself where ``live`` is every row)."""
    if isinstance(live, slice):
        return v
    a[live] = v
    return a


def _refine(d: _Data, lr: np.ndarray, th: np.ndarray, group: np.ndarray
            ) -> tuple[np.ndarray, ...]:
    """Levenberg-Marquardt descent from (P, S) starts, twice: in polar coordinates about
    the origin (the A1 reading's cone tip: rho, theta) and about the tip of the smallest
    trial reading, -e_j, where |u + a e_j| = A_j is a straight line. A reading near zero
    with a small sigma makes a thin ring round its tip, which a descent in any other
    coordinates crawls along. Back to (log rho, theta) with a eliminated; the better of
    the two per start; ``group`` as :func:`_lm`'s."""
    _, a0 = d.chi2(lr, th, with_a=True)
    v = np.exp(lr + 1j * th)
    j = np.argmin(d.A[:, 1:], axis=1)
    tip = -(d.c[j] + 1j * d.s[j])[:, None] * np.ones(lr.shape)
    out = []
    for c in (np.zeros(lr.shape, dtype=complex), tip):
        arm = v - c
        p0 = np.stack([np.log(np.maximum(np.abs(arm), 1e-300)), np.angle(arm),
                       np.log(np.maximum(a0, 1e-300))], axis=-1)
        p, f = _lm(d, c, p0, group)
        vv = c + np.exp(p[..., 0] + 1j * p[..., 1])
        out.append((np.clip(np.log(np.maximum(np.abs(vv), 1e-300)), *LR_RANGE),
                    np.angle(vv), f))
    use2 = out[1][2] < out[0][2]
    lr = np.where(use2, out[1][0], out[0][0])
    th = np.where(use2, out[1][1], out[0][1])
    lr, th = _polish(d, lr, th)
    chi2, a = d.chi2(lr, th, with_a=True)
    return lr, _wrap(th), chi2, a


def _polish(d: _Data, lr: np.ndarray, th: np.ndarray, steps: int = 12):
    """Damped Newton steps on chi2(log rho, theta) with its full Hessian (central
    differences), never uphill: it sees the curvature Gauss-Newton misses, e.g. across
    the mark line of three runs at 0 and 180 deg, where the best fit may lie."""
    factors = 0.5 ** np.arange(8)
    for _ in range(steps):
        f0, g, H = _derivatives(d, lr, th)
        det = H[..., 0, 0] * H[..., 1, 1] - H[..., 0, 1] ** 2
        pd = (H[..., 0, 0] > 0) & (det > 0)
        safe = np.where(pd, det, 1.0)
        step_r = np.where(pd, -(H[..., 1, 1] * g[..., 0] - H[..., 0, 1] * g[..., 1]) / safe,
                          -g[..., 0] / (np.abs(H[..., 0, 0]) + np.abs(g[..., 0]) + 1e-300))
        step_t = np.where(pd, -(H[..., 0, 0] * g[..., 1] - H[..., 0, 1] * g[..., 0]) / safe,
                          -g[..., 1] / (np.abs(H[..., 1, 1]) + np.abs(g[..., 1]) + 1e-300))
        cap = np.minimum(1.0, 0.1 / np.maximum(np.hypot(step_r, step_t), 1e-300))
        lr_try = np.clip(lr[..., None] + (step_r * cap)[..., None] * factors, *LR_RANGE)
        th_try = th[..., None] + (step_t * cap)[..., None] * factors
        f_try = d.chi2(lr_try, th_try)
        j = np.argmin(f_try, axis=-1)[..., None]
        better = np.take_along_axis(f_try, j, axis=-1)[..., 0] < f0
        if not better.any():
            break
        lr = np.where(better, np.take_along_axis(lr_try, j, axis=-1)[..., 0], lr)
        th = np.where(better, np.take_along_axis(th_try, j, axis=-1)[..., 0], th)
    return lr, th


def _keep(lr, th, chi2, a, threshold: float, K: int):
    """Sort the refined minima by chi2, drop duplicates and those above best + threshold;
    (P, K) arrays, NaN where fewer are kept."""
    order = np.argsort(chi2, axis=1)
    lr, th, chi2, a = (np.take_along_axis(x, order, axis=1) for x in (lr, th, chi2, a))
    P, S = lr.shape
    keep = chi2 <= chi2[:, :1] + threshold
    for j in range(1, S):
        for i in range(j):
            same = (np.abs(lr[:, j] - lr[:, i]) < 1e-4) & \
                   (np.abs(np.angle(np.exp(1j * (th[:, j] - th[:, i])))) < 1e-4)
            keep[:, j] &= ~(same & keep[:, i])
    rank = np.cumsum(keep, axis=1) - 1
    out = [np.full((P, K), np.nan) for _ in range(4)]
    rows, cols = np.nonzero(keep & (rank < K))
    for o, x in zip(out, (lr, th, chi2, a), strict=True):
        o[rows, rank[rows, cols]] = x[rows, cols]
    return out


def _pieces(n: int) -> list[slice]:
    """Slices of :data:`_PIECE` of n problems (a grid of chi2 over 128 took 1.4-1.7 times
    the CPU of four over 32: 48 x 72 and 41 x 41 points, 3 marks; measured 2026-11-30)."""
    return [slice(i, min(n, i + _PIECE)) for i in range(0, n, _PIECE)]


def _run(inside: np.ndarray) -> tuple[np.ndarray, ...]:
    """The run of ``inside`` (P, N) that holds the centre N // 2 of each row: the last
    inside index on each side, and whether the run reaches that edge of the row."""
    N = inside.shape[1]
    c = N // 2
    idx = np.arange(N)
    out_lo = np.where(~inside & (idx < c), idx, -1).max(axis=1)          # last outside below
    out_hi = np.where(~inside & (idx > c), idx, N).min(axis=1)           # first outside above
    return out_lo + 1, out_hi - 1, out_lo < 0, out_hi >= N


def _newton_1d(fun, x: np.ndarray, f: np.ndarray, lo, hi, h, steps: int):
    """Damped 1-D Newton descent of ``fun`` from x (value f), kept within [lo, hi]; the
    step length is the best of ten halvings, never uphill. Returns (x, f).

    ``fun(live, tries)`` is the function at the flat positions ``live`` of x (a slice:
    all of them), tries of shape (positions, T). A position whose step does not go
    down stays where it is, and the step from there is the same one again: once half
    of the positions computed are such, they are left out of the later steps (the
    others' numbers are the same, each computed on its own)."""
    factors = 0.5 ** np.arange(7)
    shape = x.shape
    x, f = x.ravel().copy(), f.ravel().copy()
    lo, hi, h = (np.broadcast_to(v, shape).ravel() for v in (lo, hi, h))
    live = slice(None)
    for _ in range(steps):
        xl, fl, hl = x[live], f[live], h[live]
        fs = fun(live, xl[:, None] + hl[:, None] * np.array([1.0, -1.0]))
        g = (fs[:, 0] - fs[:, 1]) / (2.0 * hl)
        c = (fs[:, 0] - 2.0 * fl + fs[:, 1]) / (hl * hl)
        step = np.where(c > 0, -g / np.where(c > 0, c, 1.0), -np.sign(g) * 10.0 * hl)
        step = np.clip(step, -100.0 * hl, 100.0 * hl)
        tries = np.clip(xl[:, None] + step[:, None] * factors, lo[live, None], hi[live, None])
        ft = fun(live, tries)
        k = np.argmin(ft, axis=-1)[:, None]
        fk = np.take_along_axis(ft, k, axis=-1)[:, 0]
        better = fk < fl * (1.0 - 1e-13)
        moved = np.flatnonzero(better) if isinstance(live, slice) else live[better]
        if moved.size == 0:
            break
        x[moved] = np.take_along_axis(tries, k, axis=-1)[better, 0]
        f[moved] = fk[better]
        if 2 * moved.size <= better.size:
            live = moved
    return x.reshape(shape), f.reshape(shape)


class _Profile:
    """The profile of chi2 along one unknown (the outer: log rho or theta), minimised
    over the other (the inner) on a window; ``outer_is_rho`` says which is which."""

    def __init__(self, d: _Data, outer_is_rho: bool, inner_lo, inner_hi) -> None:
        self.d, self.rho_outer = d, outer_is_rho
        self.lo, self.hi = inner_lo, inner_hi          # (P,) window of the inner unknown
        self.h = 1e-4 * (inner_hi - inner_lo)

    def chi2(self, outer: np.ndarray, inner: np.ndarray) -> np.ndarray:
        # (outer has inner's axes, of length 1 where it is constant: chi2 broadcasts them)
        return self.d.chi2(outer, inner) if self.rho_outer else self.d.chi2(inner, outer)

    def at(self, outer: np.ndarray, inner: np.ndarray, f: np.ndarray, steps: int):
        """Profile at ``outer`` (P, M) from inner starts (P, M) with values f."""
        ex = (slice(None),) + (None,) * (outer.ndim - 1)
        per_row = int(np.prod(outer.shape[1:]))          # outer has inner's shape
        flat = outer.ravel()

        def fun(live: np.ndarray | slice, x: np.ndarray) -> np.ndarray:
            if isinstance(live, slice):                  # every position: as they lie
                return self.chi2(outer[..., None], x.reshape(*outer.shape, -1)) \
                    .reshape(x.shape)
            d, o = self.d.take(live // per_row), flat[live][:, None]
            return d.chi2(o, x) if self.rho_outer else d.chi2(x, o)

        return _newton_1d(fun, inner, f, self.lo[ex], self.hi[ex], self.h[ex], steps)

    def grid(self, outer_ax: np.ndarray, inner_ax: np.ndarray, f: np.ndarray):
        """Profile on the grid f (P, N_outer, N_inner); returns (profile, inner argmin,
        whether the grid minimum lies on the inner window's edge)."""
        j = np.argmin(f, axis=-1)
        n = f.shape[-1]
        x = inner_ax[np.arange(f.shape[0])[:, None], j]
        fm = np.take_along_axis(f, j[..., None], axis=-1)[..., 0]
        x, fm = self.at(outer_ax, x, fm, 4)
        return fm, x, (j == 0) | (j == n - 1)

    def ends(self, o_in, x_in, o_out, thr, steps: int = 10):
        """The crossing of the threshold between outer values inside the set (inner
        argmin x_in) and outside it, by bisection (2^-10 of a grid cell; the walls of a
        profile can be too steep for a secant). Every argument is (P, 2): the lower and
        the upper end together."""
        for _ in range(steps):
            mid = 0.5 * (o_in + o_out)
            f0 = self.chi2(mid[..., None], x_in[..., None])[..., 0]
            x, f = self.at(mid, x_in, f0, 8)
            inside = f <= thr
            o_in = np.where(inside, mid, o_in)
            x_in = np.where(inside, x, x_in)
            o_out = np.where(inside, o_out, mid)
        return 0.5 * (o_in + o_out)


def _ends(prof: _Profile, ax: np.ndarray, p: np.ndarray, x: np.ndarray, inside: np.ndarray,
          thr: np.ndarray):
    """Both ends of the run holding the centre: found by :meth:`_Profile.ends` where the
    run stops inside the window, the window's edge (flagged) where it does not."""
    i_lo, i_hi, at_lo, at_hi = _run(inside)
    r = np.arange(ax.shape[0])[:, None]
    N = ax.shape[1]
    i_in = np.stack([i_lo, i_hi], axis=1)
    i_out = np.stack([np.maximum(i_lo - 1, 0), np.minimum(i_hi + 1, N - 1)], axis=1)
    e = prof.ends(ax[r, i_in], x[r, i_in], ax[r, i_out], thr[:, None])
    return np.where(at_lo, ax[:, 0], e[:, 0]), np.where(at_hi, ax[:, -1], e[:, 1]), \
        at_lo, at_hi


def _intervals(d: _Data, lr0, th0, thr, threshold):
    """Profile-likelihood intervals round each kept minimum (1-D arrays over problems)."""
    P = lr0.size
    out = {k: np.full(P, np.nan) for k in ("lr_lo", "lr_hi", "th_lo", "th_hi")}
    unb_hi = np.zeros(P, dtype=bool)
    unb_lo = np.zeros(P, dtype=bool)
    circle = np.zeros(P, dtype=bool)
    _, _, H = _derivatives(d, lr0, th0)
    det = H[:, 0, 0] * H[:, 1, 1] - H[:, 0, 1] ** 2
    ok = (H[:, 0, 0] > 0) & (det > 0)
    var_r = np.where(ok, 2.0 * H[:, 1, 1] / np.where(ok, det, 1.0), np.inf)
    var_t = np.where(ok, 2.0 * H[:, 0, 0] / np.where(ok, det, 1.0), np.inf)
    k = 2.0 * np.sqrt(threshold)
    wr = np.clip(k * np.sqrt(var_r), 1e-6, LR_RANGE[1] - LR_RANGE[0])
    wt = np.clip(k * np.sqrt(var_t), 1e-6, np.pi)
    todo = np.arange(P)
    u = np.linspace(-1.0, 1.0, _LOCAL)
    for _ in range(8):
        if todo.size == 0:
            break
        dd = d.take(todo)
        lr_ax = np.clip(lr0[todo, None] + wr[todo, None] * u, *LR_RANGE)
        th_ax = th0[todo, None] + wt[todo, None] * u
        f = np.concatenate([dd.take(sl).chi2(lr_ax[sl, :, None], th_ax[sl, None, :])
                            for sl in _pieces(todo.size)])      # (P, _LOCAL, _LOCAL)
        t = thr[todo]
        pr = _Profile(dd, True, th_ax[:, 0], th_ax[:, -1])      # over theta, per log rho
        pt = _Profile(dd, False, lr_ax[:, 0], lr_ax[:, -1])     # over log rho, per theta
        prof_r, x_r, edge_r = pr.grid(lr_ax, th_ax, f)
        prof_t, x_t, edge_t = pt.grid(th_ax, lr_ax, f.transpose(0, 2, 1))
        in_r, in_t = prof_r <= t[:, None], prof_t <= t[:, None]
        r_lo, r_hi, r_at_lo, r_at_hi = _ends(pr, lr_ax, prof_r, x_r, in_r, t)
        t_lo, t_hi, t_at_lo, t_at_hi = _ends(pt, th_ax, prof_t, x_t, in_t, t)
        lo_clip = lr_ax[:, 0] <= LR_RANGE[0]
        hi_clip = lr_ax[:, -1] >= LR_RANGE[1]
        full_t = wt[todo] >= np.pi
        # the set reaches the window's edge, or the inner minimum over the other unknown
        # does (the window cuts the valley): widen that axis, unless it is already whole
        grow_r = ((r_at_lo & ~lo_clip) | (r_at_hi & ~hi_clip)
                  | ((edge_t & in_t).any(axis=1) & ~(lo_clip & hi_clip)))
        grow_t = ((t_at_lo | t_at_hi) | (edge_r & in_r).any(axis=1)) & ~full_t
        done = ~(grow_r | grow_t)
        idx = todo[done]
        out["lr_lo"][idx], out["lr_hi"][idx] = r_lo[done], r_hi[done]
        unb_lo[idx], unb_hi[idx] = (r_at_lo & lo_clip)[done], (r_at_hi & hi_clip)[done]
        out["th_lo"][idx], out["th_hi"][idx] = t_lo[done], t_hi[done]
        circle[idx] = (full_t & (t_at_lo | t_at_hi))[done]
        g = todo[~done]
        wr[g] = np.where(grow_r[~done], np.minimum(wr[g] * 3.0, LR_RANGE[1] - LR_RANGE[0]),
                         wr[g])
        wt[g] = np.where(grow_t[~done], np.minimum(wt[g] * 3.0, np.pi), wt[g])
        todo = g
    if todo.size:                                   # never settled: report as unbounded
        unb_hi[todo] = True
        circle[todo] = True
        out["lr_lo"][todo] = LR_RANGE[0]
    rho_lo = np.where(unb_lo, 0.0, np.exp(out["lr_lo"]))
    rho_hi = np.where(unb_hi, np.inf, np.exp(out["lr_hi"]))
    th_lo = np.where(circle, np.nan, _wrap(out["th_lo"]))
    th_hi = np.where(circle, np.nan, _wrap(out["th_hi"]))
    return rho_lo, rho_hi, th_lo, th_hi


def fit_amplitudes(readings: np.ndarray, marks_deg: np.ndarray, sigma: np.ndarray,
                   threshold: float, keep: int = 2) -> AmplitudeFit:
    """Maximum-likelihood fit of B amplitude sets (vectorised).

    Parameters
    ----------
    readings : numpy.ndarray, shape (B, n + 1)
        A_0 (no trial mass; > 0) then the n readings with the trial mass (> 0).
    marks_deg : numpy.ndarray, shape (n,)
        The trial marks (deg), the same for every set.
    sigma : numpy.ndarray, shape (B, n + 1)
        1-sigma noise of each reading (> 0).
    threshold : float
        q_1(confidence): minima within it of the best are kept, and it bounds the
        profile-likelihood intervals.
    keep : int
        At most this many minima are reported per set.

    Returns
    -------
    AmplitudeFit
    """
    A = np.atleast_2d(np.asarray(readings, dtype=float))
    S = np.atleast_2d(np.asarray(sigma, dtype=float))
    marks = radian_column(np.asarray(marks_deg, dtype=float))
    B = A.shape[0]
    cols = {k: np.full((B, keep), np.nan) for k in
            ("rho", "theta", "a", "chi2", "rho_lo", "rho_hi", "theta_lo", "theta_hi")}
    bound = np.zeros((B, keep), dtype=bool)
    for start in range(0, B, _BLOCK):
        sl = slice(start, min(B, start + _BLOCK))
        d = _Data(A[sl], S[sl], marks)
        lr0, th0 = (np.concatenate(x) for x in
                    zip(*(_grid_starts(d.take(c)) for c in _pieces(len(d.A))), strict=True))
        group = np.arange(len(d.A)) // _CHUNK
        lr, th, chi2, a = _refine(d, lr0, th0, group)
        lr, th, chi2, a = _keep(lr, th, chi2, a, threshold, keep)
        bound[sl] = np.isfinite(chi2) & ((lr <= LR_RANGE[0] + BOUND_TOL)
                                         | (lr >= LR_RANGE[1] - BOUND_TOL))
        rows, ks = np.nonzero(np.isfinite(chi2))
        thr = chi2[:, 0][rows] + threshold
        sub = d.take(rows)
        lo, hi, tlo, thi = _intervals(sub, lr[rows, ks], th[rows, ks], thr, threshold)
        for name, v in (("rho", np.exp(lr)), ("theta", th), ("a", a), ("chi2", chi2)):
            cols[name][sl] = v
        for name, v in (("rho_lo", lo), ("rho_hi", hi), ("theta_lo", tlo), ("theta_hi", thi)):
            block = cols[name][sl]
            block[rows, ks] = v
    return AmplitudeFit(dof=A.shape[1] - 3, threshold=float(threshold), at_bound=bound,
                        **cols)
