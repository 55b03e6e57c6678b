"""The friction equations of each row, solved on the row's own scale (seed 002 s. 2.4).

The friction magnitudes s (a pin's couple rho |F|, a guide's force mu N^0) of the k
joints with friction satisfy, row by row, s = h(q0 + G s): q0 are the reaction
quantities they read (a pin's Fx, Fy; a guide's N, M) under the scene's loads, the
columns of G those under a unit friction load of each joint (signs fixed by the
relative motions), h the friction laws (eqs 2.62-2.65). This module solves that small
system for every row at once (arrays keep the rows last, contiguous along the sweep);
:mod:`kinetostatics.solver.friction` builds q0 and G and turns s into loads.

Where the system is a contraction it has one solution, found by Newton's method from
s = 0. Elsewhere it is followed from no friction to the given coefficients (every
coefficient scaled by lambda in [0, 1]) in projective form, which stays finite where
the friction force grows without bound:

    s = lambda h(sigma q0 + G s),    sigma + sum w_j s_j = 1,

with w_j > 0 the row's scale of s_j. A finite solution is s / sigma, sigma > 0; a row
whose branch reaches sigma = 0 before lambda = 1 locks (no finite driving effort moves
it), and lambda there is the scale of the coefficients below which it would move.
Steps in lambda serve until the branch turns back at a fold; past a fold it is
followed by arc length (with the kinks of the friction laws rounded off within 1e-4 of
the row's force, so that the path has no corner; the end point is settled with the
exact laws), to lambda = 1, or to sigma = 0 or back to lambda = 0 (the row locks).
Each row is decided on its own, so the result does not depend on the other rows of
the batch. Limitation: with several joints and very high coefficients a row whose
branch from no friction ends can still have an equilibrium on a branch not connected
to it (seen at 3 of 360 rows of the scotch yoke with mu = 2.5 in all four joints);
such a row is flagged with the others.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.errors import WorkbenchError
from ..model.scene import Joint
from .loads import PointLoad

NEWTON_ITERATIONS = 40      # per continuation step and for the final solve
NEWTON_TOLERANCE = 1e-12    # on the row's own scale (normalised unknowns)
FIRST_STEP = 1.0            # first continuation step in lambda
MAX_PATH_STEP = 0.25        # largest change of the normalised unknowns in one step
MIN_STEP = 1e-9             # a step in lambda below this: the branch turns back (a fold)
MAX_STEPS = 400
ARC_STEP = 0.05             # largest arc-length step past a fold (normalised units)
MAX_ARC_STEPS = 1000
CHUNK = 65536               # rows solved together (bounds the temporaries' memory)
SOFT = 1e-4                 # kinks rounded within this fraction of the row's force

@dataclass
class Spec:
    """One joint with friction: its unit loads and how its magnitude reads the reactions."""

    joint: Joint
    coeff: float                # rho = mu r (revolute, eq. 2.62) or mu (prismatic)
    length: float               # bearing length of a prismatic joint (0: none)
    width: int                  # reaction quantities read: 2 (Fx, Fy or N, M) or 1 (N)
    unit: list[PointLoad]       # the friction loads for s_j = 1, signs from the motion


def _magnitude(spec: Spec, q: np.ndarray, soft=None) -> tuple[np.ndarray, np.ndarray]:
    """s_j = h_j(q) and its gradient (a subgradient where h_j has a kink); q is
    (width, rows), the gradient too. With ``soft`` (N, per row) every |x| is taken as
    sqrt(x^2 + soft^2): the kinks rounded off, for following a path past them."""
    c = spec.coeff

    def norm(*parts):
        sq = sum(p * p for p in parts)
        return np.sqrt(sq if soft is None else sq + soft * soft)

    if spec.joint.kind == "R":                          # rho |F| (eq. 2.62)
        f = norm(q[0], q[1])
        with np.errstate(invalid="ignore", divide="ignore"):
            g = np.where(f > 0.0, q / f, 0.0)
        return c * f, c * g
    if spec.width == 1:                                 # mu |N|
        a = norm(q[0])
        with np.errstate(invalid="ignore", divide="ignore"):
            return c * a, c * np.where(a > 0.0, q / a, 0.0)
    half, arm = 0.5 * q[0], q[1] / spec.length          # eqs 2.63-2.65: mu (|N_A| + |N_B|)
    na, nb = half - arm, half + arm
    aa, ab = norm(na), norm(nb)
    with np.errstate(invalid="ignore", divide="ignore"):
        sa, sb = np.where(aa > 0.0, na / aa, 0.0), np.where(ab > 0.0, nb / ab, 0.0)
    grad = np.stack([0.5 * (sa + sb), (sb - sa) / spec.length])
    return c * (aa + ab), c * grad


class Rows:
    """The rows' friction system in normalised form: unknowns w_j s_j, all O(1).

    Arrays keep the rows last (contiguous along the sweep): q0 (m, n), G / w
    (m, k, n), w (k, n), unknowns (k, n)."""

    def __init__(self, specs: list[Spec], q0: np.ndarray, g: np.ndarray, w: np.ndarray,
                 positions: np.ndarray):
        self.specs = specs
        self.positions = positions      # the driver positions, for messages
        self.n = q0.shape[1]
        self.q0, self.w = q0, w
        self.gt = g / w[None, :, :]     # the response to the normalised unknowns
        self.slices = []
        start = 0
        for sp in specs:
            self.slices.append(slice(start, start + sp.width))
            start += sp.width

    def take(self, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """q0, G / w and w at rows idx (the arrays themselves when idx is every row)."""
        if idx.size == self.n:
            return self.q0, self.gt, self.w
        return self.q0[:, idx], self.gt[:, :, idx], self.w[:, idx]

    def lipschitz(self) -> np.ndarray:
        """Per row, a bound L on how much the normalised magnitudes w h(q0 + G s) change
        per unit change of the normalised s (max norm). Where L < 1 the map is a
        contraction for every lambda in [0, 1]: one solution, and the branch from no
        friction leads to it."""
        out = np.zeros(self.n)
        for j, (sp, sl) in enumerate(zip(self.specs, self.slices, strict=True)):
            col = self.gt[sl]                               # (width, k, n)
            if sp.joint.kind == "R":
                per = np.hypot(col[0], col[1])
            elif sp.width == 1:
                per = np.abs(col[0])
            else:                               # |dN_A| + |dN_B| <= |dN| + 2 |dM| / l
                per = np.abs(col[0]) + 2.0 * np.abs(col[1]) / sp.length
            out = np.maximum(out, sp.coeff * self.w[j] * per.sum(axis=0))
        return out

    def linearise(self, q: np.ndarray, w: np.ndarray, gt: np.ndarray, q0: np.ndarray,
                  soft=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """At the reaction quantities q: the normalised magnitudes w h(q) (k, n), and the
        products of their Jacobian d(w h)/dq with G / w (k, k, n) and with q0 (k, n)
        (each magnitude reads only its own joint's quantities)."""
        k, n = len(self.specs), q.shape[1]
        hv = np.empty((k, n))
        dhg = np.empty((k, k, n))
        dhq = np.empty((k, n))
        for j, (sp, sl) in enumerate(zip(self.specs, self.slices, strict=True)):
            h, grad = _magnitude(sp, q[sl], soft)
            grad = grad * w[j]
            hv[j] = h * w[j]
            a = sl.start
            np.multiply(grad[0], gt[a], out=dhg[j])
            dhq[j] = grad[0] * q0[a]
            if sp.width == 2:
                dhg[j] += grad[1] * gt[a + 1]
                dhq[j] += grad[1] * q0[a + 1]
        return hv, dhg, dhq


def _apply(gt: np.ndarray, s: np.ndarray) -> np.ndarray:
    """G s per row: (m, k, n) times (k, n)."""
    out = gt[:, 0, :] * s[0]
    for j in range(1, s.shape[0]):
        out += gt[:, j, :] * s[j]
    return out


def _solve_batch(jac: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per row, solve jac x = rhs (jac (K, K, n), rhs (K, n)); rows whose matrix is
    singular (or not finite) give a zero step and False."""
    a = np.moveaxis(jac, 2, 0)
    b = rhs.T[..., None]
    ok = np.isfinite(a).all(axis=(1, 2)) & np.isfinite(b[..., 0]).all(axis=1)
    if ok.all():
        try:
            return np.linalg.solve(a, b)[..., 0].T, ok
        except np.linalg.LinAlgError:
            pass
    ok &= np.abs(np.linalg.det(np.where(ok[:, None, None], a, 1.0))) > 1e-300
    safe = np.where(ok[:, None, None], a, np.eye(a.shape[1]))
    step = np.linalg.solve(safe, np.where(ok[:, None, None], b, 0.0))[..., 0]
    return step.T, ok


def _eye(k: int) -> np.ndarray:
    return np.eye(k)[:, :, None]


def _newton(x: np.ndarray, system) -> tuple[np.ndarray, np.ndarray]:
    """Batched Newton's method, every row on its own scale: ``system(live, x_live)``
    gives, for the rows still iterating (indices into x's columns), the Jacobian
    (K, K, rows), the right-hand side -residual (K, rows) and the scale of each row's
    unknowns. A row is done when its step is at most NEWTON_TOLERANCE times its scale,
    and fails where its Jacobian is singular. Returns x and the converged rows."""
    x = x.copy()
    m = x.shape[1]
    done = np.zeros(m, dtype=bool)
    failed = np.zeros(m, dtype=bool)
    live = np.arange(m)
    for _ in range(NEWTON_ITERATIONS):
        if live.size == 0:
            break
        jac, rhs, scale = system(live, x[:, live])
        step, ok = _solve_batch(jac, rhs)
        x[:, live] += step
        failed[live[~ok]] = True
        done[live[ok & (np.abs(step).max(axis=0) <= NEWTON_TOLERANCE * scale)]] = True
        live = np.flatnonzero(~done & ~failed)
    return x, done & ~failed


def _newton_path(rows: Rows, idx: np.ndarray, lam: np.ndarray, x: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on the projective system at scales ``lam`` for rows ``idx``,
    from ``x`` = (w s, sigma) (k + 1, rows). Returns the solutions and which rows
    converged."""
    k = len(rows.specs)

    def system(live, xl):
        q0, gt, w = rows.take(idx[live])
        la = lam[live]
        s, sig = xl[:k], xl[k]
        hv, dhg, dhq = rows.linearise(sig * q0 + _apply(gt, s), w, gt, q0)
        res = np.concatenate([s - la * hv, (sig + s.sum(axis=0) - 1.0)[None]])
        jac = np.empty((k + 1, k + 1, live.size))
        jac[:k, :k] = _eye(k) - la * dhg
        jac[:k, k] = -la * dhq
        jac[k, :] = 1.0
        return jac, -res, 1.0

    return _newton(x, system)


def follow(rows: Rows, subset: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Follow every row's branch from no friction (lambda = 0) to the given one.

    The branch of a row ends before lambda = 1 in two ways, and the row locks: sigma
    reaches 0 (the friction forces grow without bound), or the branch turns back at a
    fold (the Jacobian of the system is singular there: beyond it, friction this high
    has no equilibrium near the branch). Neither is followed further.

    Only the rows in ``subset`` are followed. Returns, over every row, x = (w s, sigma)
    (k + 1, n) at lambda = 1 (where the branch ended, for locked rows), the locked
    rows, the rows whose sigma reached 0, and the scale where the branch ended (sigma =
    0 interpolated in the last step, or the fold; 1 for free rows)."""
    k = len(rows.specs)
    n = rows.n
    x = np.zeros((k + 1, n))
    x[k] = 1.0
    lam = np.ones(n)
    lam[subset] = 0.0
    step = np.full(n, FIRST_STEP)
    ended = np.ones(n)
    crossed = np.zeros(n, dtype=bool)
    fold = np.zeros(n, dtype=bool)
    for _ in range(MAX_STEPS):
        idx = np.flatnonzero((lam < 1.0) & ~crossed & ~fold)
        if idx.size == 0:
            break
        target = np.minimum(lam[idx] + step[idx], 1.0)
        xn, ok = _newton_path(rows, idx, target, x[:, idx])
        ok &= np.abs(xn - x[:, idx]).max(axis=0) <= MAX_PATH_STEP
        good, bad = idx[ok], idx[~ok]
        xg, tg = xn[:, ok], target[ok]
        cross = xg[k] <= 0.0
        if cross.any():
            c = good[cross]
            s0, s1 = x[k, c], xg[k, cross]
            ended[c] = lam[c] + (tg[cross] - lam[c]) * s0 / np.maximum(s0 - s1, 1e-300)
            crossed[c] = True
        x[:, good], lam[good] = xg, tg
        step[good] = np.minimum(2.0 * step[good], 1.0)
        step[bad] *= 0.25
        turned = bad[step[bad] < MIN_STEP]
        fold[turned] = True
        ended[turned] = lam[turned]
    open_rows = np.flatnonzero((lam < 1.0) & ~crossed & ~fold)
    if open_rows.size:
        raise WorkbenchError(f"the friction equations could not be followed within {MAX_STEPS} "
                             f"steps at driver position {rows.positions[open_rows[0]]:g}; "
                             "lower the friction coefficients there")
    return x, crossed | fold, crossed, ended


def _arc_system(rows: Rows, idx: np.ndarray, y: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """The projective system's residual (k + 1, m) and Jacobian (k + 1, k + 2, m) in
    y = (w s, sigma, lambda), at rows idx."""
    k = len(rows.specs)
    q0, gt, w = rows.take(idx)
    s, sig, la = y[:k], y[k], y[k + 1]
    soft = SOFT / (w[0] * rows.specs[0].coeff)   # the row's force (see row_scale)
    hv, dhg, dhq = rows.linearise(sig * q0 + _apply(gt, s), w, gt, q0, soft)
    res = np.concatenate([s - la * hv, (sig + s.sum(axis=0) - 1.0)[None]])
    jac = np.zeros((k + 1, k + 2, idx.size))
    jac[:k, :k] = _eye(k) - la * dhg
    jac[:k, k] = -la * dhq
    jac[:k, k + 1] = -hv
    jac[k, :k + 1] = 1.0
    return res, jac


def _arc_step(rows: Rows, rid: np.ndarray, ya: np.ndarray, tprev: np.ndarray,
              ds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One step of :func:`arc` along the branches of rows ``rid`` from ``ya``: the
    tangent (oriented by the previous one, ``tprev``), the predictor ``ds`` along it and
    Newton's corrector normal to it. Returns the new points, the tangents and the rows
    whose step converged within reach."""
    k = len(rows.specs)
    _res, jac = _arc_system(rows, rid, ya)
    rhs = np.zeros((k + 2, rid.size))
    rhs[k + 1] = 1.0
    tan, ok = _solve_batch(np.concatenate([jac, tprev[None]]), rhs)
    tan /= np.maximum(np.linalg.norm(tan, axis=0), 1e-300)
    pred = ya + ds * tan
    yn = pred.copy()
    conv = ok.copy()
    for _ in range(8):
        res, jn = _arc_system(rows, rid, yn)
        big = np.concatenate([jn, tan[None]])
        g = np.concatenate([res, (tan * (yn - pred)).sum(axis=0)[None]])
        step, okn = _solve_batch(big, -g)
        yn += step
        conv &= okn
        if np.abs(step).max() <= NEWTON_TOLERANCE:
            break
    res, _j = _arc_system(rows, rid, yn)
    conv &= (np.abs(res).max(axis=0) <= 1e3 * NEWTON_TOLERANCE) & \
        (np.abs(yn - ya).max(axis=0) <= 2.0 * ds)
    return yn, tan, conv


def arc(rows: Rows, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Follow the branch of rows idx from lambda = 0 by arc length (pseudo-arclength:
    a tangent predictor, a Newton corrector normal to it), through folds, until it
    reaches lambda = 1, sigma reaches 0, or it comes back to no friction (lambda = 0).

    Returns x = (w s, sigma) at lambda = 1 (where the branch ended for the others), the
    rows whose sigma reached 0 first, the rows whose branch came back (both lock), and
    the lambda where sigma reached 0 or the largest lambda the branch reached. A branch
    that cannot be followed to either end (a corner of the friction laws it cannot
    turn, or a loop, within the step budget) is taken as one that came back: the row
    keeps the flag its fold gave it."""
    k = len(rows.specs)
    m = idx.size
    y = np.zeros((k + 2, m))
    y[k] = 1.0
    tprev = np.zeros((k + 2, m))
    tprev[k + 1] = 1.0
    ds = np.full(m, ARC_STEP)
    live = np.ones(m, dtype=bool)
    blown = np.zeros(m, dtype=bool)
    turned = np.zeros(m, dtype=bool)
    top = np.zeros(m)
    ended = np.ones(m)
    x = np.zeros((k + 1, m))
    for _ in range(MAX_ARC_STEPS):
        a = np.flatnonzero(live)
        if a.size == 0:
            break
        ya = y[:, a]
        yn, tan, conv = _arc_step(rows, idx[a], ya, tprev[:, a], ds[a])
        good, bad = a[conv], a[~conv]
        ds[bad] /= 3.0
        stuck = bad[ds[bad] < MIN_STEP]     # a corner the path cannot turn: as a fold
        live[stuck] = False
        turned[stuck] = True
        ended[stuck] = top[stuck]
        x[:, stuck] = y[:k + 1, stuck]
        y0, y1 = y[:, good], yn[:, conv]
        top[good] = np.maximum(top[good], y1[k + 1])
        cross = (y1[k] <= 0.0) & (y0[k] > 0.0)
        arrive = ~cross & (y1[k + 1] >= 1.0)
        back = ~cross & ~arrive & (y1[k + 1] <= 0.0)    # back to no friction: locked
        ended[good[back]] = top[good[back]]
        x[:, good[back]] = y0[:k + 1, back]
        c, r = good[cross], good[arrive]
        f = y0[k, cross] / np.maximum(y0[k, cross] - y1[k, cross], 1e-300)
        ended[c] = y0[k + 1, cross] + f * (y1[k + 1, cross] - y0[k + 1, cross])
        blown[c] = True
        x[:, c] = (y0[:k + 1, cross] + f * (y1[:k + 1, cross] - y0[:k + 1, cross]))
        if r.size:                      # settle exactly at lambda = 1
            f = (1.0 - y0[k + 1, arrive]) / (y1[k + 1, arrive] - y0[k + 1, arrive])
            start = y0[:k + 1, arrive] + f * (y1[:k + 1, arrive] - y0[:k + 1, arrive])
            x[:, r], okr = _newton_path(rows, idx[r], np.ones(r.size), start)
            if not okr.all():
                ds[r[~okr]] /= 3.0
                arrive[np.flatnonzero(arrive)[~okr]] = False
                r = r[okr]
        live[c] = False
        live[r] = False
        live[good[back]] = False
        turned[good[back]] = True
        keep = conv.copy()
        keep[conv] = ~(cross | arrive | back)
        y[:, a[keep]] = yn[:, keep]
        tprev[:, a[conv]] = tan[:, conv]
        ds[good] = np.minimum(2.0 * ds[good], ARC_STEP)
    rest = np.flatnonzero(live)         # not settled within the step budget: as a fold
    turned[rest] = True
    ended[rest] = top[rest]
    x[:, rest] = y[:k + 1, rest]
    return x, blown, turned, ended


def newton_direct(rows: Rows, s: np.ndarray, idx: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on s = h(q0 + G s) (normalised s, (k, rows)) at the given
    friction; convergence on each row's own scale. Returns s and the converged rows."""
    k = len(rows.specs)
    if idx.size == 0:
        return s.copy(), np.zeros(0, dtype=bool)

    def system(live, sl):
        q0, gt, w = rows.take(idx[live])
        hv, dhg, _ = rows.linearise(q0 + _apply(gt, sl), w, gt, q0)
        # the row's own scale: its unknowns and the terms of its residual
        scale = 1.0 + np.abs(sl).max(axis=0) + np.abs(hv).max(axis=0)
        return _eye(k) - dhg, hv - sl, scale

    return _newton(s, system)


def critical_scale(rows: Rows, idx: np.ndarray, x: np.ndarray, lam0: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """For rows whose force grows without bound: the scale lambda* where the unloaded
    system s = lambda h(G s) has a solution with sum(w s) = 1, and that direction.
    Newton on (w s, lambda) from the branch's point where sigma reached 0."""
    k = len(rows.specs)
    y = np.concatenate([np.clip(x[:k], 0.0, None), lam0[None]])
    y[:k] /= np.maximum(y[:k].sum(axis=0), 1e-300)
    q0, gt, w = rows.take(idx)
    for _ in range(NEWTON_ITERATIONS):
        s, la = y[:k], y[k]
        hv, dhg, _ = rows.linearise(_apply(gt, s), w, gt, q0)
        res = np.concatenate([s - la * hv, (s.sum(axis=0) - 1.0)[None]])
        jac = np.zeros((k + 1, k + 1, idx.size))
        jac[:k, :k] = _eye(k) - la * dhg
        jac[:k, k] = -hv
        jac[k, :k] = 1.0
        step, _ok = _solve_batch(jac, -res)
        y += step
        if np.abs(step).max() <= NEWTON_TOLERANCE:
            break
    return y[k], y[:k]


def row_scale(specs: list[Spec], q0: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Weights w_j (k, n): 1 / (coefficient x the row's largest force), so that the
    normalised unknowns w_j s_j are of order 1 on every row."""
    force = np.abs(q0).max(axis=0)
    top = float(force.max()) if force.size else 0.0
    if top == 0.0:     # no load anywhere: the response to the friction sets the scale
        top = 1.0 / max(float(np.abs(g).max()) if g.size else 0.0, 1e-300)
    force = np.maximum(force, 1e-12 * top)
    coeff = np.array([sp.coeff for sp in specs])
    return 1.0 / (coeff[:, None] * force[None, :])


def _settle_chunk(rows: Rows) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """One chunk of rows: normalised s (k, m), NaN where locked; the locked rows; and for
    them the critical scale lambda* and the direction of the normalised s there."""
    k, n = len(rows.specs), rows.n
    s = np.full((k, n), np.nan)
    # rows where the friction feedback is a contraction: one solution, Newton from zero
    easy = np.flatnonzero(rows.lipschitz() < 1.0)
    sn, ok = newton_direct(rows, np.zeros((k, easy.size)), easy)
    s[:, easy[ok]] = sn[:, ok]
    hard = np.ones(n, dtype=bool)
    hard[easy[ok]] = False
    # the others: follow the branch from no friction, then settle at the given friction
    x, locked, crossed, ended = follow(rows, np.flatnonzero(hard))
    fold = np.flatnonzero(locked & ~crossed)
    if fold.size:           # past a fold the branch may still reach the given friction
        x[:, fold], blown, back, ended[fold] = arc(rows, fold)
        locked[fold], crossed[fold] = blown | back, blown
    free = np.flatnonzero(hard & ~locked)
    sn, ok = newton_direct(rows, x[:k, free] / x[k, free], free)
    if not ok.all():
        p = rows.positions[free[np.flatnonzero(~ok)[0]]]
        raise WorkbenchError(f"the friction equations do not settle at driver position "
                             f"{p:g}; lower the friction coefficients there")
    s[:, free] = sn
    lam, dirn = np.where(locked, ended, np.nan), np.where(locked, x[:k], np.nan)
    c = np.flatnonzero(crossed)
    if c.size:
        lam[c], dirn[:, c] = critical_scale(rows, c, x[:, c], ended[c])
    return s, locked, lam, dirn


def settle(specs: list[Spec], q0: np.ndarray, g: np.ndarray, positions: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Solve every row's friction system s = h(q0 + G s) (q0 (m, n), G (m, k, n)).

    Returns the magnitudes s (k, n), NaN at self-locking rows; the self-locking mask;
    and for those rows the scale lambda* of every coefficient below which the row would
    move, and the direction (k, n) of the friction forces that grow without bound there
    (NaN elsewhere). Rows are solved in chunks, each on its own scale."""
    k, n = g.shape[1], g.shape[2]
    w = row_scale(specs, q0, g)
    s = np.empty((k, n))
    locked = np.empty(n, dtype=bool)
    lam = np.empty(n)
    dirn = np.empty((k, n))
    for a in range(0, n, CHUNK):
        sl = slice(a, min(a + CHUNK, n))
        rows = Rows(specs, q0[:, sl], g[:, :, sl], w[:, sl], positions[sl])
        s[:, sl], locked[sl], lam[sl], dirn[:, sl] = _settle_chunk(rows)
    return s / w, locked, lam, dirn

