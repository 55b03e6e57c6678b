"""Friction in the joints (seed 002 s. 2.4), as loads added to the kinetostatic solve.

Scene extension (documented in ``docs/scene-extensions.md``): a joint may carry
``friction = { mu = 0.1, radius = 0.012 }`` (revolute: pin radius r) or
``friction = { mu = 0.1, length = 0.08 }`` (prismatic: the slider's bearing length,
optional). Without it a joint has no friction.

* Revolute joint: the friction circle of radius rho = r mu (eq. 2.62); the friction
  couple on each body is rho |F| against the relative rotation of that body.
* Prismatic joint: the friction force mu N^0 against the relative sliding (s. 2.4,
  fig. 2.30). For a closed joint with a bearing length l (fig. 2.31, eqs 2.63-2.65)
  the normal reaction and its couple are carried by the two ends, N_A + N_B = N and
  (N_B - N_A) l / 2 = M, and the friction is mu (|N_A| + |N_B|).

How a row is solved. The relative motions fix the direction of every friction load,
so the loads of joint j are s_j times a unit load (a couple of 1 N m, a force of 1 N)
and only the magnitudes s_j are unknown. The reactions are linear in the loads: the
quantities the friction reads (a pin's Fx, Fy; a guide's N, M) are q = q0 + G s, q0
from the scene's loads and the columns of G from one solve per unit friction load.
Each magnitude is a positively homogeneous convex function of them, s_j = h_j(q)
(rho |F|, mu |N| or mu (|N_A| + |N_B|)), so a row is the small system

    s = h(q0 + G s),    s >= 0,

solved directly by Newton's method, row by row on each row's own scale (no global
tolerance, no fixed-point passes that stall as the friction feedback nears 1).

Self-locking (s. 2.4: the motion cannot be driven). The friction feedback G can make
the system have no finite solution: the friction force needed grows without bound
(the massless slider-crank locks where mu tan(psi) >= 1). To tell the rows apart the
system is followed from no friction to the given one, every coefficient scaled by
lambda in [0, 1], in projective form, which stays finite through the blow-up:

    s = lambda h(sigma q0 + G s),    sigma + sum w_j s_j = 1,

(w_j > 0 the row's scale of s_j). A finite solution is s / sigma with sigma > 0. The
branch ends before lambda = 1 where sigma reaches 0 (the force grows without bound)
or where it turns back at a fold (no equilibrium nearby for higher friction): such a
row is self-locking (no finite driving effort moves it), and with every coefficient
below lambda* (where the branch ended) times the given one it would move. Where several
finite solutions exist (a load that drives the motion can wedge a guide as well), the
branch from no friction is the one kept. Rows whose friction feedback is a
contraction (a Lipschitz bound below 1) have exactly one solution for every lambda:
they go straight to Newton's method from s = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.errors import WorkbenchError
from ..model.scene import GROUND, Joint, Scene
from . import _arith as A
from .kinematics import Kinematics
from .loads import PointLoad, resultants
from .reactions import DriverReaction, JointReaction, solve_reactions

NEWTON_ITERATIONS = 40      # per continuation step and for the final solve
NEWTON_TOLERANCE = 1e-12    # on the row's own scale (normalised unknowns)
FIRST_STEP = 1.0            # first continuation step in lambda
MAX_PATH_STEP = 0.25        # largest change of the normalised unknowns in one step
MIN_STEP = 1e-9             # a step in lambda below this: the row does not settle
MAX_STEPS = 400


class SelfLockingError(WorkbenchError):
    """Joint friction locks the mechanism at every position of the sweep."""


@dataclass
class _Spec:
    """One joint with friction: its unit loads and how its magnitude reads the reactions."""

    joint: Joint
    coeff: float                # rho = mu r (revolute, eq. 2.62) or mu (prismatic)
    length: float               # bearing length of a prismatic joint (0: none)
    width: int                  # reaction quantities read: 2 (Fx, Fy or N, M) or 1 (N)
    unit: list[PointLoad]       # the friction loads for s_j = 1, signs from the motion


def has_friction(scene: Scene) -> bool:
    """True when some joint carries a ``friction`` table."""
    return any(j.friction is not None and j.friction.mu > 0 for j in scene.joints.values())


def _unit_loads(scene: Scene, kin: Kinematics, j: Joint) -> list[PointLoad]:
    """Friction loads of unit magnitude against the relative motion (zero where the
    joint does not move)."""
    n = kin.n
    out: list[PointLoad] = []
    if j.kind == "R":
        b0, b1 = j.bodies
        w0 = np.broadcast_to(kin.bodies[b0].omega, (n,))
        w1 = np.broadcast_to(kin.bodies[b1].omega, (n,))
        m1 = -np.sign(w1 - w0)                          # on b1, against omega_10
        for body, m in ((b1, m1), (b0, -m1)):
            if body != GROUND:
                out.append(PointLoad(body, "friction", 0.0, 0.0, 0.0, 0.0, m,
                                     f"friction couple in {j.name}"))
        return out
    g, s = kin.bodies[j.guide], kin.bodies[j.slider]
    if j.slider == GROUND:
        sx, sy = scene.ground[j.points[1]]
    else:
        sx, sy = s.point(scene.bodies[j.slider].local(j.points[1]))
    ux, uy = g.rotate(np.cos(np.deg2rad(j.line_angle)), np.sin(np.deg2rad(j.line_angle)))
    vsx, vsy = s.vel_at(sx, sy)
    vgx, vgy = g.vel_at(sx, sy)
    vrel = np.broadcast_to(A.add(A.mul(ux, A.sub(vsx, vgx)), A.mul(uy, A.sub(vsy, vgy))),
                           (n,))
    f = -np.sign(vrel)                                  # on the slider, along u
    ffx, ffy = A.mul(f, ux), A.mul(f, uy)
    for body, sign in ((j.slider, 1.0), (j.guide, -1.0)):
        if body == GROUND:
            continue
        m = kin.bodies[body]
        out.append(PointLoad(body, "friction", A.sub(sx, m.ox), A.sub(sy, m.oy),
                             A.mul(sign, ffx), A.mul(sign, ffy), 0.0,
                             f"friction force in {j.name}"))
    return out


def _specs(scene: Scene, kin: Kinematics) -> list[_Spec]:
    out = []
    for j in scene.joints.values():
        fr = j.friction
        if fr is None or fr.mu == 0.0 or (j.kind == "R" and fr.radius == 0.0):
            continue                    # no friction (a pin of radius 0 has none)
        if j.kind == "R":
            out.append(_Spec(j, fr.radius * fr.mu, 0.0, 2, _unit_loads(scene, kin, j)))
        else:
            out.append(_Spec(j, fr.mu, fr.length, 2 if fr.length > 0.0 else 1,
                             _unit_loads(scene, kin, j)))
    return out


def _quantities(spec: _Spec, r: JointReaction, n: int) -> list[np.ndarray]:
    """The reaction quantities the joint's friction reads: (Fx, Fy), (N, M) or (N,)."""
    if spec.joint.kind == "R":
        return list(r.force(n))
    nn = np.broadcast_to(r.N, (n,))
    return [nn, np.broadcast_to(r.M, (n,))] if spec.width == 2 else [nn]


def _magnitude(spec: _Spec, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """s_j = h_j(q) and its gradient (a subgradient where h_j has a kink); q is
    (width, rows), the gradient too."""
    c = spec.coeff
    if spec.joint.kind == "R":                          # rho |F| (eq. 2.62)
        f = np.hypot(q[0], q[1])
        with np.errstate(invalid="ignore", divide="ignore"):
            g = np.where(f > 0.0, q / f, 0.0)
        return c * f, c * g
    if spec.width == 1:                                 # mu |N|
        return c * np.abs(q[0]), c * np.sign(q)
    half, arm = 0.5 * q[0], q[1] / spec.length          # eqs 2.63-2.65: mu (|N_A| + |N_B|)
    na, nb = half - arm, half + arm
    sa, sb = np.sign(na), np.sign(nb)
    grad = np.stack([0.5 * (sa + sb), (sb - sa) / spec.length])
    return c * (np.abs(na) + np.abs(nb)), c * grad


class _Rows:
    """The rows' friction system in normalised form: unknowns w_j s_j, all O(1).

    Arrays keep the rows last (contiguous along the sweep): q0 (m, n), G / w
    (m, k, n), w (k, n), unknowns (k, n)."""

    def __init__(self, specs: list[_Spec], q0: np.ndarray, g: np.ndarray, w: np.ndarray):
        self.specs = specs
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

    def linearise(self, q: np.ndarray, w: np.ndarray, gt: np.ndarray, q0: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """At the reaction quantities q: the normalised magnitudes w h(q) (k, n), and the
        products of their Jacobian d(w h)/dq with G / w (k, k, n) and with q0 (k, n)
        (each magnitude reads only its own joint's quantities)."""
        k, n = len(self.specs), q.shape[1]
        hv = np.empty((k, n))
        dhg = np.empty((k, k, n))
        dhq = np.empty((k, n))
        for j, (sp, sl) in enumerate(zip(self.specs, self.slices, strict=True)):
            h, grad = _magnitude(sp, q[sl])
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


def _newton_path(rows: _Rows, idx: np.ndarray, lam: np.ndarray, x: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on the projective system at scales ``lam`` for rows ``idx``,
    from ``x`` = (w s, sigma) (k + 1, rows). Returns the solutions and which rows
    converged."""
    k = len(rows.specs)
    x = x.copy()
    done = np.zeros(idx.size, dtype=bool)
    failed = np.zeros(idx.size, dtype=bool)
    live = np.arange(idx.size)
    for _ in range(NEWTON_ITERATIONS):
        q0, gt, w = rows.take(idx[live])
        la = lam[live]
        s, sig = x[:k, live], x[k, live]
        hv, dhg, dhq = rows.linearise(sig * q0 + _apply(gt, s), w, gt, q0)
        res = np.concatenate([s - la * hv, (sig + s.sum(axis=0) - 1.0)[None]])
        jac = np.empty((k + 1, k + 1, live.size))
        jac[:k, :k] = _eye(k) - la * dhg
        jac[:k, k] = -la * dhq
        jac[k, :] = 1.0
        step, ok = _solve_batch(jac, -res)
        x[:, live] += step
        failed[live[~ok]] = True
        done[live[ok & (np.abs(step).max(axis=0) <= NEWTON_TOLERANCE)]] = True
        live = np.flatnonzero(~done & ~failed)
        if live.size == 0:
            break
    return x, done & ~failed


def _follow(rows: _Rows, subset: np.ndarray
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
    if ((lam < 1.0) & ~crossed & ~fold).any():
        raise WorkbenchError("the friction equations could not be followed within "
                             f"{MAX_STEPS} steps; lower the friction coefficients")
    return x, crossed | fold, crossed, ended


def _newton_direct(rows: _Rows, s: np.ndarray, idx: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on s = h(q0 + G s) (normalised s, (k, rows)) at the given
    friction; convergence on each row's own scale. Returns s and the converged rows."""
    k = len(rows.specs)
    s = s.copy()
    if idx.size == 0:
        return s, np.zeros(0, dtype=bool)
    done = np.zeros(idx.size, dtype=bool)
    failed = np.zeros(idx.size, dtype=bool)
    live = np.arange(idx.size)
    for _ in range(NEWTON_ITERATIONS):
        q0, gt, w = rows.take(idx[live])
        sl = s[:, live]
        hv, dhg, _ = rows.linearise(q0 + _apply(gt, sl), w, gt, q0)
        step, ok = _solve_batch(_eye(k) - dhg, hv - sl)
        s[:, live] += step
        failed[live[~ok]] = True
        # the row's own scale: its unknowns and the terms of its residual
        scale = 1.0 + np.abs(sl).max(axis=0) + np.abs(hv).max(axis=0)
        done[live[ok & (np.abs(step).max(axis=0) <= NEWTON_TOLERANCE * scale)]] = True
        live = np.flatnonzero(~done & ~failed)
        if live.size == 0:
            break
    return s, done & ~failed


def _critical_scale(rows: _Rows, idx: np.ndarray, x: np.ndarray, lam0: np.ndarray
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


def _row_scale(specs: list[_Spec], q0: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Weights w_j (k, n): 1 / (coefficient x the row's largest force), so that the
    normalised unknowns w_j s_j are of order 1 on every row."""
    force = np.abs(q0).max(axis=0)
    top = float(force.max()) if force.size else 0.0
    if top == 0.0:     # no load anywhere: the response to the friction sets the scale
        top = 1.0 / max(float(np.abs(g).max()) if g.size else 0.0, 1e-300)
    force = np.maximum(force, 1e-12 * top)
    coeff = np.array([sp.coeff for sp in specs])
    return 1.0 / (coeff[:, None] * force[None, :])


def _scaled_loads(specs: list[_Spec], s: np.ndarray) -> list[PointLoad]:
    """The friction loads of magnitudes s (k, n) (NaN where a row has no value)."""
    out = []
    for j, sp in enumerate(specs):
        for u in sp.unit:
            out.append(PointLoad(u.body, u.kind, u.rx, u.ry, A.mul(u.fx, s[j]),
                                 A.mul(u.fy, s[j]), A.mul(u.m, s[j]), u.label))
    return out


def _lock_message(scene: Scene, specs: list[_Spec], lam: np.ndarray, dirn: np.ndarray
                  ) -> str:
    """One line for a sweep that locks at every position."""
    drv = scene.driver
    unit = "deg" if drv.kind == "R" else "m"
    pos = drv.positions
    best = int(np.argmax(lam))
    sp = specs[int(np.argmax(dirn[:, best]))]
    mu = sp.joint.friction.mu
    where = (f"at every position ({pos[0]:g} to {pos[-1]:g} {unit})" if pos.size > 1 else
             f"at position {pos[0]:g} {unit}")
    others = "" if len(specs) == 1 else " (every friction coefficient scaled alike)"
    return (f"the mechanism self-locks {where}: the friction in joint '{sp.joint.name}' "
            f"(mu = {mu:g}) jams it; it would move at position {pos[best]:g} {unit} with "
            f"mu below {lam[best] * mu:.6g}{others}, and at every position below "
            f"{float(lam.min()) * mu:.6g}")


def solve_with_friction(scene: Scene, kin: Kinematics, loads: list[PointLoad]
                        ) -> tuple[dict[str, JointReaction], DriverReaction, list[PointLoad],
                                   np.ndarray]:
    """Reactions and Me with joint friction, each row solved on its own scale.

    Returns the reactions, the driver's Me/Fe, the friction loads and the
    ``self_locking`` mask (rows where no finite driving effort moves the mechanism;
    their Me/Fe, reactions and friction loads are NaN).

    Raises
    ------
    SelfLockingError
        If every row locks: the message names the joint and the coefficient below
        which the mechanism would move.
    WorkbenchError
        If some row's friction equations cannot be followed (never met in practice).
    """
    n = kin.n
    specs = _specs(scene, kin)
    base, drive = solve_reactions(kin, resultants(loads, scene.bodies, n))
    if not specs:                       # only pins of radius 0: no friction at all
        return base, drive, [], np.zeros(n, dtype=bool)
    names = [sp.joint.name for sp in specs]
    q0 = np.stack([q for sp in specs for q in _quantities(sp, base[sp.joint.name], n)])
    cols = []
    for sp in specs:
        unit, _ = solve_reactions(kin, resultants(sp.unit, scene.bodies, n))
        cols.append(np.stack([q for sp2, name in zip(specs, names, strict=True)
                              for q in _quantities(sp2, unit[name], n)]))
    g = np.stack(cols, axis=1)                                  # (m, k, n)
    w = _row_scale(specs, q0, g)
    rows = _Rows(specs, q0, g, w)
    k = len(specs)
    s = np.full((k, n), np.nan)
    # rows where the friction feedback is a contraction: one solution, Newton from zero
    easy = np.flatnonzero(rows.lipschitz() < 1.0)
    sn, ok = _newton_direct(rows, np.zeros((k, easy.size)), easy)
    s[:, easy[ok]] = sn[:, ok] / w[:, easy[ok]]
    hard = np.ones(n, dtype=bool)
    hard[easy[ok]] = False
    # the others: follow the branch from no friction, then settle at the given friction
    x, locked, crossed, ended = _follow(rows, np.flatnonzero(hard))
    free = np.flatnonzero(hard & ~locked)
    sn, ok = _newton_direct(rows, x[:k, free] / x[k, free], free)
    if not ok.all():
        p = scene.driver.positions[free[np.flatnonzero(~ok)[0]]]
        raise WorkbenchError(f"the friction equations do not settle at driver position "
                             f"{p:g}; lower the friction coefficients there")
    s[:, free] = sn / w[:, free]
    if locked.all():
        lam, dirn = ended, x[:k]
        c = np.flatnonzero(crossed)
        lam[c], dirn[:, c] = _critical_scale(rows, c, x[:, c], ended[c])
        raise SelfLockingError(_lock_message(scene, specs, lam, dirn))
    fl = _scaled_loads(specs, s)
    reactions, drive = solve_reactions(kin, resultants(loads + fl, scene.bodies, n))
    if locked.any():
        reactions = {name: _blank(r, locked, n) for name, r in reactions.items()}
        drive = DriverReaction(drive.kind, np.where(locked, np.nan, drive.value))
    return reactions, drive, fl, locked


def _blank(r: JointReaction, rows: np.ndarray, n: int) -> JointReaction:
    """The reaction with NaN at ``rows`` (they have no value there)."""
    def nan(a):
        return None if a is None else np.where(rows, np.nan, np.broadcast_to(a, (n,)))
    return JointReaction(r.joint, r.on, r.by, nan(r.fx), nan(r.fy), nan(r.N), nan(r.M),
                         r.x, r.y, r.sign)
