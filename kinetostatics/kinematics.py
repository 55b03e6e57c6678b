"""Kinematics of the driver and of every dyad kind, closed form, vectorised over positions.

Seed 000: the driving element (ch. 4) and the dyads RRR (ch. 5), RTR with the guide on
either link (ch. 6, 7), TRR (ch. 8), RRT (ch. 9), TRT (ch. 10), RTT (ch. 11), TTR (ch. 12).

One formulation serves every kind. A dyad body joined to a known body K by

* a revolute joint at P rotates about P: its unknown is its angle (``rot``);
* a prismatic joint keeps K's angle (plus the line angle) and translates relative to K
  along a direction u fixed in K: its unknown is the displacement s (``trans``).

The inner joint then closes the dyad: a revolute one makes the two bodies' points Q
coincide (circle-circle, circle-line or line-line intersection: the seed's indicator
k = +-1 picks one of two assemblies, eqs 6.1, 8.1 of seed 000), a prismatic one makes
the slider's angle follow the guide's and its point S stay on the guide's line. The
velocities solve the 2 x 2 linear system ``G qdot = r`` whose columns are the
velocities of the closing point per unit of each body's unknown; the accelerations
solve the same system with the centripetal and Coriolis terms on the right.

Coordinates are kept as separate x and y arrays (one element per position).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .errors import AssemblyError
from .scene import GROUND, Body, Scene
from .structure import Dyad, Structure

SINGULAR_WARN = 1e-3    # sin(transmission angle) below this: the row is flagged singular
SINGULAR_FAIL = 1e-12   # below this the velocity system cannot be solved: refused


@dataclass
class BodyMotion:
    """Planar motion of a body: angle, angular velocity and acceleration, and the global
    position, velocity and acceleration of its local origin (arrays over positions)."""

    theta: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    ox: np.ndarray
    oy: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    ax: np.ndarray
    ay: np.ndarray

    def rotate(self, lx: float, ly: float) -> tuple[np.ndarray, np.ndarray]:
        """A local vector turned into global axes: R(theta) l."""
        return self.cos * lx - self.sin * ly, self.sin * lx + self.cos * ly

    def point(self, local: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
        """Global position of a local point."""
        rx, ry = self.rotate(*local)
        return self.ox + rx, self.oy + ry

    def vel_at(self, x, y):
        """Velocity of the body's point that is at the global position (x, y)."""
        return self.vx - self.omega * (y - self.oy), self.vy + self.omega * (x - self.ox)

    def acc_at(self, x, y):
        """Acceleration of the body's point at (x, y): a_O + alpha k x r - omega^2 r."""
        rx, ry = x - self.ox, y - self.oy
        w2 = self.omega * self.omega
        return self.ax - self.alpha * ry - w2 * rx, self.ay + self.alpha * rx - w2 * ry

    def take(self, index) -> BodyMotion:
        """The motion at some rows only (scalars broadcast)."""
        def t(a):
            return a[index] if np.ndim(a) else a
        return BodyMotion(*(t(getattr(self, f)) for f in self.__dataclass_fields__))


def ground_motion() -> BodyMotion:
    """The fixed body: zero everything, unit rotation."""
    z = np.float64(0.0)
    return BodyMotion(z, np.float64(1.0), z, z, z, z, z, z, z, z, z)


@dataclass
class Param:
    """How a dyad body moves relative to the known body ``known`` through its outer joint.

    ``kind == "rot"``: turns about P (``px, py``; velocity, acceleration of P as a
    point of the known body) with ``local`` the joint point in the body frame.
    ``kind == "trans"``: angle ``theta`` known; origin = ``base + s u`` with u fixed
    in the known body.
    """

    kind: str
    known: BodyMotion
    local: tuple[float, float] = (0.0, 0.0)
    px: np.ndarray | None = None
    py: np.ndarray | None = None
    theta: np.ndarray | None = None
    ux: np.ndarray | None = None
    uy: np.ndarray | None = None
    bx: np.ndarray | None = None
    by: np.ndarray | None = None


@dataclass
class DyadMotion:
    """What the reactions need from a solved dyad: its parameters, the closing point X
    (the inner joint's point; for a prismatic inner joint the slider point), the
    columns of the velocity system at X and the transmission measure."""

    dyad: Dyad
    params: tuple[Param, Param]
    k: int
    xx: np.ndarray
    xy: np.ndarray
    c1: tuple[np.ndarray, np.ndarray]
    c2: tuple[np.ndarray, np.ndarray]
    det: np.ndarray
    sin_tau: np.ndarray
    cos_tau: np.ndarray
    slider_first: bool = False      # prismatic inner joint: body 1 is the slider
    nx: np.ndarray | None = None    # prismatic inner joint: left normal of the line
    ny: np.ndarray | None = None


@dataclass
class Kinematics:
    """Motions of every body over the sweep, and the solved dyads."""

    scene: Scene
    structure: Structure
    positions: np.ndarray
    bodies: dict[str, BodyMotion]
    dyads: list[DyadMotion] = field(default_factory=list)

    @property
    def n(self) -> int:
        return self.positions.size

    def sin_tau_min(self) -> np.ndarray:
        """Per position, the smallest sin(transmission angle) over the dyads (1 if none)."""
        out = np.ones(self.n)
        for d in self.dyads:
            out = np.minimum(out, np.abs(d.sin_tau))
        return out

    @property
    def singular(self) -> np.ndarray:
        """Rows near a dead centre of some dyad (contract: |det| <= 1e-3 |c1||c2|)."""
        return self.sin_tau_min() <= SINGULAR_WARN


def _fmt_positions(scene: Scene, rows: np.ndarray, values: np.ndarray | None = None,
                   unit: str = "m") -> str:
    pos = scene.driver.positions
    pu = "deg" if scene.driver.kind == "R" else "m"
    items = []
    for i, r in enumerate(rows[:6]):
        s = f"{pos[r]:g} {pu}"
        if values is not None:
            s += f" (by {values[i]:.3g} {unit})"
        items.append(s)
    more = f" and {rows.size - 6} more" if rows.size > 6 else ""
    return ", ".join(items) + more


def driver_motion(scene: Scene) -> BodyMotion:
    """Motion of the driving element (seed 000 ch. 4): a crank turning about its ground
    joint (position = angle of its local x axis) or a slider on a ground guide (position
    = distance of its slider point from the line point along the line)."""
    drv = scene.driver
    joint = scene.joints[drv.joint]
    body = scene.bodies[drv.body]
    n = drv.positions.size
    zero = np.zeros(n)
    if drv.kind == "R":
        th = np.deg2rad(drv.positions)
        c, s = np.cos(th), np.sin(th)
        px, py = scene.ground[joint.point_on(GROUND)]
        lx, ly = body.local(joint.point_on(drv.body))
        rx, ry = -(c * lx - s * ly), -(s * lx + c * ly)      # o - P
        w, a = drv.speed, drv.acceleration
        return BodyMotion(th, c, s, np.full(n, w), np.full(n, a), px + rx, py + ry,
                          -w * ry, w * rx, -a * ry - w * w * rx, a * rx - w * w * ry)
    beta = np.deg2rad(joint.line_angle)
    pos = drv.positions
    if joint.guide == GROUND:
        th = beta
        ux, uy = np.cos(beta), np.sin(beta)
        lx, ly = scene.ground[joint.points[0]]
        sx, sy = body.local(joint.points[1])
        c, s = np.cos(th), np.sin(th)
        ox = lx + pos * ux - (c * sx - s * sy)
        oy = ly + pos * uy - (s * sx + c * sy)
        sign = 1.0
    else:   # the driver carries the guide and slides along a ground slider point
        th = -beta
        ux, uy = 1.0, 0.0
        px, py = scene.ground[joint.points[1]]
        lx, ly = body.local(joint.points[0])
        c, s = np.cos(th), np.sin(th)
        ox = px - pos * ux - (c * lx - s * ly)
        oy = py - pos * uy - (s * lx + c * ly)
        sign = -1.0
    v, a = sign * drv.speed, sign * drv.acceleration
    return BodyMotion(np.full(n, th), np.full(n, c), np.full(n, s), zero, zero, ox, oy,
                      np.full(n, v * ux), np.full(n, v * uy), np.full(n, a * ux),
                      np.full(n, a * uy))


def _param(scene: Scene, dyad: Dyad, i: int, motions: dict[str, BodyMotion]) -> Param:
    name = dyad.bodies[i]
    joint = dyad.outer[i]
    kname = joint.other(name)
    kb = motions[kname]
    body = scene.bodies[name]
    if joint.kind == "R":
        px, py = _point(scene, kname, kb, joint.point_on(kname))
        return Param("rot", kb, body.local(joint.point_on(name)), px=px, py=py)
    beta = np.deg2rad(joint.line_angle)
    if joint.guide == kname:                         # known body carries the guide
        th = kb.theta + beta
        c, s = np.cos(th), np.sin(th)
        lx, ly = _point(scene, kname, kb, joint.points[0])
        sx, sy = body.local(joint.points[1])
        bx, by = lx - (c * sx - s * sy), ly - (s * sx + c * sy)
        ux, uy = c, s
    else:                                            # the dyad body carries the guide
        th = kb.theta - beta
        c, s = np.cos(th), np.sin(th)
        px, py = _point(scene, kname, kb, joint.points[1])
        lx, ly = body.local(joint.points[0])
        bx, by = px - (c * lx - s * ly), py - (s * lx + c * ly)
        ux, uy = kb.cos, kb.sin
    return Param("trans", kb, theta=th + 0.0 * kb.omega, ux=ux, uy=uy, bx=bx, by=by)


def _point(scene: Scene, bname: str, motion: BodyMotion, pname: str):
    if bname == GROUND:
        x, y = scene.ground[pname]
        return np.float64(x), np.float64(y)
    return motion.point(scene.bodies[bname].local(pname))


def _rot_angle(dx, dy, local_vec, r2):
    """cos, sin of the angle that turns the local vector onto (dx, dy) (|d|^2 = r2)."""
    lx, ly = local_vec
    return (dx * lx + dy * ly) / r2, (dy * lx - dx * ly) / r2


class _DyadSolver:
    """Closed-form position analysis of one dyad for a given assembly k."""

    def __init__(self, scene: Scene, dyad: Dyad):
        self.scene = scene
        self.dyad = dyad
        self.b = [scene.bodies[n] for n in dyad.bodies]
        inner = dyad.inner
        if inner.kind == "R":
            self.q = [self.b[i].local(inner.point_on(dyad.bodies[i])) for i in range(2)]
        else:
            self.slider_first = inner.slider == dyad.bodies[0]
            self.beta = np.deg2rad(inner.line_angle)

    @property
    def branches(self) -> int:
        kinds = (self.p_kind(0), self.p_kind(1))
        if self.dyad.inner.kind == "R":
            return 1 if kinds == ("trans", "trans") else 2
        return 2 if kinds == ("rot", "rot") else 1

    def p_kind(self, i: int) -> str:
        return "rot" if self.dyad.outer[i].kind == "R" else "trans"

    # -- positions ------------------------------------------------------------------
    def positions(self, pr: tuple[Param, Param], k: int):
        """Return (cos, sin, theta-or-None, s-or-None) per body and the gap (>0 where the
        dyad cannot close, in m) for assembly k."""
        if self.dyad.inner.kind == "R":
            return self._inner_r(pr, k)
        return self._inner_t(pr, k)

    def _inner_r(self, pr, k):
        p1, p2 = pr
        (q1x, q1y), (q2x, q2y) = self.q
        a1 = (q1x - p1.local[0], q1y - p1.local[1])
        a2 = (q2x - p2.local[0], q2y - p2.local[1])
        out = [None, None]
        if p1.kind == "rot" and p2.kind == "rot":
            # circle-circle (RRR, seed 000 ch. 5): Q = P1 + x e + k h J e
            r1s, r2s = a1[0] ** 2 + a1[1] ** 2, a2[0] ** 2 + a2[1] ** 2
            ex, ey = p2.px - p1.px, p2.py - p1.py
            d2 = ex * ex + ey * ey
            d = np.sqrt(d2)
            with np.errstate(divide="ignore", invalid="ignore"):
                x = (r1s - r2s + d2) / (2.0 * d)
                h2 = r1s - x * x
            r1, r2 = np.sqrt(r1s), np.sqrt(r2s)
            gap = np.maximum(d - (r1 + r2), np.abs(r1 - r2) - d)
            gap = np.where(np.isfinite(h2), gap, np.inf)
            h = np.sqrt(np.maximum(h2, 0.0))
            with np.errstate(divide="ignore", invalid="ignore"):
                ex, ey = ex / d, ey / d
            qx = p1.px + x * ex - k * h * ey
            qy = p1.py + x * ey + k * h * ex
            out[0] = _rot_angle(qx - p1.px, qy - p1.py, a1, r1s)
            out[1] = _rot_angle(qx - p2.px, qy - p2.py, a2, r2s)
            return out, (None, None), gap
        if p1.kind == "trans" and p2.kind == "trans":
            # line-line (TRT, seed 000 ch. 10): Q01 + s1 u1 = Q02 + s2 u2
            q01 = self._trans_point(p1, self.q[0])
            q02 = self._trans_point(p2, self.q[1])
            rx, ry = q02[0] - q01[0], q02[1] - q01[1]
            det = -p1.ux * p2.uy + p1.uy * p2.ux
            with np.errstate(divide="ignore", invalid="ignore"):
                s1 = (-rx * p2.uy + ry * p2.ux) / det
                s2 = (p1.ux * ry - p1.uy * rx) / det
            gap = np.where(np.isfinite(s1) & np.isfinite(s2), -1.0, np.inf)
            return [(np.cos(p1.theta), np.sin(p1.theta)), (np.cos(p2.theta), np.sin(p2.theta))], \
                (s1, s2), gap
        # circle-line (RRT / TRR, seed 000 ch. 9 and 8)
        ir, it = (0, 1) if p1.kind == "rot" else (1, 0)
        pr_, pt = pr[ir], pr[it]
        ar = a1 if ir == 0 else a2
        rs = ar[0] ** 2 + ar[1] ** 2
        q0 = self._trans_point(pt, self.q[it])
        wx, wy = q0[0] - pr_.px, q0[1] - pr_.py
        b = pt.ux * wx + pt.uy * wy
        disc = b * b - (wx * wx + wy * wy) + rs
        dist = np.abs(pt.ux * wy - pt.uy * wx)
        gap = dist - np.sqrt(rs)
        s = -b + k * np.sqrt(np.maximum(disc, 0.0))
        qx, qy = q0[0] + s * pt.ux, q0[1] + s * pt.uy
        out[ir] = _rot_angle(qx - pr_.px, qy - pr_.py, ar, rs)
        out[it] = (np.cos(pt.theta), np.sin(pt.theta))
        ss = [None, None]
        ss[it] = s
        return out, tuple(ss), gap

    @staticmethod
    def _trans_point(p: Param, local):
        """Position of a local point of a translating body at s = 0."""
        c, s = np.cos(p.theta), np.sin(p.theta)
        return p.bx + c * local[0] - s * local[1], p.by + s * local[0] + c * local[1]

    def _inner_t(self, pr, k):
        inner = self.dyad.inner
        i_s, i_g = (0, 1) if self.slider_first else (1, 0)
        ps, pg = pr[i_s], pr[i_g]
        s_loc = self.b[i_s].local(inner.points[1])
        l_loc = self.b[i_g].local(inner.points[0])
        beta = self.beta
        ex, ey = np.cos(beta), np.sin(beta)
        out = [None, None]
        ss = [None, None]
        if ps.kind == "rot" and pg.kind == "rot":
            # RTR (seed 000 ch. 6-7): sin(delta - theta_g - beta) = -c / |D|
            cb, sb = np.cos(beta), np.sin(beta)
            asx, asy = s_loc[0] - ps.local[0], s_loc[1] - ps.local[1]
            rax, ray = cb * asx - sb * asy, sb * asx + cb * asy
            vx_, vy_ = rax - (l_loc[0] - pg.local[0]), ray - (l_loc[1] - pg.local[1])
            c = ex * vy_ - ey * vx_
            dx, dy = ps.px - pg.px, ps.py - pg.py
            dn = np.sqrt(dx * dx + dy * dy)
            with np.errstate(divide="ignore", invalid="ignore"):
                y = -c / dn
            gap = np.where(np.isfinite(y), np.abs(c) - dn, np.inf)
            x = np.arcsin(np.clip(y, -1.0, 1.0))
            delta = np.arctan2(dy, dx)
            th = delta - beta - x if k > 0 else delta - beta - np.pi + x
            th = np.asarray(th, dtype=float)
            out[i_g] = (np.cos(th), np.sin(th))
            out[i_s] = (np.cos(th + beta), np.sin(th + beta))
            return out, (None, None), gap
        if ps.kind == "trans" and pg.kind == "trans":
            raise AssemblyError("a TTT group is not a dyad")
        # RTT / TTR (seed 000 ch. 11-12): the rotating body's angle follows the other's
        if ps.kind == "rot":
            th_s = pg.theta + beta
            cs, sn = np.cos(th_s), np.sin(th_s)
            asx, asy = s_loc[0] - ps.local[0], s_loc[1] - ps.local[1]
            sx, sy = ps.px + cs * asx - sn * asy, ps.py + sn * asx + cs * asy
            l0 = self._trans_point(pg, l_loc)
            ux, uy = cs, sn                                   # line direction
            den = ux * pg.uy - uy * pg.ux
            with np.errstate(divide="ignore", invalid="ignore"):
                s = (ux * (sy - l0[1]) - uy * (sx - l0[0])) / den
            out[i_s] = (cs, sn)
            out[i_g] = (np.cos(pg.theta), np.sin(pg.theta))
            ss[i_g] = s
        else:
            th_g = ps.theta - beta
            cg, sg = np.cos(th_g), np.sin(th_g)
            alx, aly = l_loc[0] - pg.local[0], l_loc[1] - pg.local[1]
            lx, ly = pg.px + cg * alx - sg * aly, pg.py + sg * alx + cg * aly
            ux, uy = np.cos(ps.theta), np.sin(ps.theta)
            s0 = self._trans_point(ps, s_loc)
            den = ux * ps.uy - uy * ps.ux
            with np.errstate(divide="ignore", invalid="ignore"):
                s = -(ux * (s0[1] - ly) - uy * (s0[0] - lx)) / den
            out[i_g] = (cg, sg)
            out[i_s] = (np.cos(ps.theta), np.sin(ps.theta))
            ss[i_s] = s
        gap = np.where(np.isfinite(s), -1.0, np.inf)
        return out, tuple(ss), gap


def _body_positions(pr: Param, cs, s) -> tuple[np.ndarray, np.ndarray]:
    """Origin of a dyad body from its parameter and solved unknown."""
    c, sn = cs
    if pr.kind == "rot":
        lx, ly = pr.local
        return pr.px - (c * lx - sn * ly), pr.py - (sn * lx + c * ly)
    return pr.bx + s * pr.ux, pr.by + s * pr.uy


def _columns(pr: Param, xx, xy):
    """Velocity of the body's point at X per unit of its unknown (the column c_i), the
    known part k_i of that velocity, and the weight of the unknown in the body's
    angular velocity (1 for rot, 0 for trans)."""
    kb = pr.known
    if pr.kind == "rot":
        kvx, kvy = kb.vel_at(pr.px, pr.py)
        return (-(xy - pr.py), xx - pr.px), (kvx, kvy), 1.0
    kvx, kvy = kb.vel_at(xx, xy)
    return (pr.ux, pr.uy), (kvx, kvy), 0.0


def _solve2(a11, a12, a21, a22, r1, r2, det):
    return (r1 * a22 - a12 * r2) / det, (a11 * r2 - r1 * a21) / det


def solve_dyad(scene: Scene, dyad: Dyad, motions: dict[str, BodyMotion]) -> DyadMotion:
    """Positions, velocities and accelerations of a dyad's two bodies over the sweep.

    Adds both bodies' :class:`BodyMotion` to ``motions`` and returns the dyad data the
    reactions need.

    Raises
    ------
    AssemblyError
        Where the dyad cannot close (which positions and by how much), where two
        assemblies exist and no ``[near]`` hint settles them, or at an exactly singular
        position.
    """
    solver = _DyadSolver(scene, dyad)
    pr = (_param(scene, dyad, 0, motions), _param(scene, dyad, 1, motions))
    k = 1
    if solver.branches == 2:
        k = _choose_branch(scene, dyad, solver, motions)
    cs, ss, gap = solver.positions(pr, k)
    bad = np.flatnonzero(gap > 1e-9 * _scale(scene))
    if bad.size:
        raise AssemblyError(
            f"dyad {dyad.label} cannot be assembled at driver position(s) "
            f"{_fmt_positions(scene, bad, np.broadcast_to(gap, scene.driver.positions.shape)[bad])}"
            ": the links do not reach; shorten the sweep or change the lengths")
    # origins and the closing point X
    org = [_body_positions(pr[i], cs[i], ss[i]) for i in range(2)]
    inner = dyad.inner
    if inner.kind == "R":
        loc = solver.q[0]
        ib = 0
    else:
        ib = 0 if solver.slider_first else 1
        loc = solver.b[ib].local(inner.points[1])
    c0, s0 = cs[ib]
    xx = org[ib][0] + c0 * loc[0] - s0 * loc[1]
    xy = org[ib][1] + s0 * loc[0] + c0 * loc[1]
    (c1, k1, w1), (c2, k2, w2) = _columns(pr[0], xx, xy), _columns(pr[1], xx, xy)
    n = scene.driver.positions.size
    if inner.kind == "R":
        a11, a12, a21, a22 = c1[0], -c2[0], c1[1], -c2[1]
        r1, r2 = k2[0] - k1[0], k2[1] - k1[1]
        det = a11 * a22 - a12 * a21
        sin_tau = det / (np.hypot(*c1) * np.hypot(*c2))
        cos_tau = (c1[0] * c2[0] + c1[1] * c2[1]) / (np.hypot(*c1) * np.hypot(*c2))
        nx = ny = None
    else:
        th_g = np.arctan2(cs[1 - ib][1], cs[1 - ib][0])
        ux, uy = np.cos(th_g + solver.beta), np.sin(th_g + solver.beta)
        nx, ny = -uy, ux
        om0 = [0.0 if pr[i].kind == "rot" else pr[i].known.omega for i in range(2)]
        a11, a12, r1 = w1, -w2, om0[1] - om0[0]
        a21, a22 = nx * c1[0] + ny * c1[1], -(nx * c2[0] + ny * c2[1])
        r2 = nx * (k2[0] - k1[0]) + ny * (k2[1] - k1[1])
        det = a11 * a22 - a12 * a21
        sin_tau, cos_tau = _inner_t_tau(pr, ux, uy)
    sin_tau = np.broadcast_to(sin_tau, (n,))
    cos_tau = np.broadcast_to(cos_tau, (n,))
    exact = np.flatnonzero(np.abs(sin_tau) <= SINGULAR_FAIL)
    if exact.size:
        raise AssemblyError(
            f"dyad {dyad.label} is exactly singular (dead centre: transmission angle 0) at "
            f"driver position(s) {_fmt_positions(scene, exact)}; its velocities are undefined "
            "there: leave those positions out of the sweep")
    qd1, qd2 = _solve2(a11, a12, a21, a22, r1, r2, det)
    qd = (qd1, qd2)
    # accelerations: the same matrix, centripetal and Coriolis terms on the right
    ka = []
    for i, p in enumerate(pr):
        kb = p.known
        if p.kind == "rot":
            ax_, ay_ = kb.acc_at(p.px, p.py)
            w2_ = qd[i] * qd[i]
            ka.append((ax_ - w2_ * (xx - p.px), ay_ - w2_ * (xy - p.py)))
        else:
            ax_, ay_ = kb.acc_at(xx, xy)
            f = 2.0 * kb.omega * qd[i]
            ka.append((ax_ - f * p.uy, ay_ + f * p.ux))
    if inner.kind == "R":
        r1, r2 = ka[1][0] - ka[0][0], ka[1][1] - ka[0][1]
    else:
        al0 = [0.0 if pr[i].kind == "rot" else pr[i].known.alpha for i in range(2)]
        r1 = al0[1] - al0[0]
        # relative velocity of the slider point along the line and the guide's omega
        v1 = (k1[0] + c1[0] * qd1, k1[1] + c1[1] * qd1)
        v2 = (k2[0] + c2[0] * qd2, k2[1] + c2[1] * qd2)
        sgn = 1.0 if solver.slider_first else -1.0
        rdot = sgn * (ux * (v1[0] - v2[0]) + uy * (v1[1] - v2[1]))
        ig = 1 if solver.slider_first else 0
        om_g = qd[ig] if pr[ig].kind == "rot" else pr[ig].known.omega
        r2 = sgn * 2.0 * om_g * rdot - (nx * (ka[0][0] - ka[1][0]) + ny * (ka[0][1] - ka[1][1]))
    qdd = _solve2(a11, a12, a21, a22, r1, r2, det)
    for i in range(2):
        p = pr[i]
        c, sn = cs[i]
        ox, oy = org[i]
        kb = p.known
        if p.kind == "rot":
            th = np.arctan2(sn, c)
            om, al = qd[i], qdd[i]
            vpx, vpy = kb.vel_at(p.px, p.py)
            apx, apy = kb.acc_at(p.px, p.py)
            rx, ry = ox - p.px, oy - p.py
            vx, vy = vpx - om * ry, vpy + om * rx
            ax_, ay_ = apx - al * ry - om * om * rx, apy + al * rx - om * om * ry
        else:
            th = p.theta
            om, al = kb.omega, kb.alpha
            vkx, vky = kb.vel_at(ox, oy)
            akx, aky = kb.acc_at(ox, oy)
            f = 2.0 * kb.omega * qd[i]
            vx, vy = vkx + qd[i] * p.ux, vky + qd[i] * p.uy
            ax_ = akx + qdd[i] * p.ux - f * p.uy
            ay_ = aky + qdd[i] * p.uy + f * p.ux
        full = [np.broadcast_to(np.asarray(a, dtype=float), (n,))
                for a in (th, c, sn, om, al, ox, oy, vx, vy, ax_, ay_)]
        motions[dyad.bodies[i]] = BodyMotion(*full)
    return DyadMotion(dyad, pr, k, np.broadcast_to(xx, (n,)), np.broadcast_to(xy, (n,)),
                      c1, c2, det, sin_tau, cos_tau,
                      slider_first=inner.kind == "T" and solver.slider_first, nx=nx, ny=ny)


def _inner_t_tau(pr, ux, uy):
    """sin and cos of the transmission angle of a dyad with a prismatic inner joint:
    between the line and P_s - P_g (RTR) or between the line and the other guide (RTT)."""
    p1, p2 = pr
    if p1.kind == "rot" and p2.kind == "rot":
        dx, dy = p1.px - p2.px, p1.py - p2.py
        dn = np.sqrt(dx * dx + dy * dy)
        # the velocity system's columns are J(P2 - P1) and u: sin = (u . D)/|D|
        return (ux * dx + uy * dy) / dn, (ux * dy - uy * dx) / dn
    pt = p2 if p1.kind == "rot" else p1
    return ux * pt.uy - uy * pt.ux, ux * pt.ux + uy * pt.uy


def _scale(scene: Scene) -> float:
    pts = [abs(v) for b in scene.bodies.values() for p in b.points.values() for v in p]
    pts += [abs(v) for p in scene.ground.values() for v in p]
    return max(pts + [1e-3])


def _hint_points(scene: Scene, dyad: Dyad):
    """Hints that concern the dyad: (hint name, body, local point, target)."""
    out = []
    for key, target in scene.near.items():
        if "." in key:
            b, p = key.split(".", 1)
            if b in dyad.bodies:
                out.append((key, b, scene.bodies[b].local(p), target))
        else:
            j = scene.joints[key]
            for b in dyad.bodies:
                if b in j.bodies:
                    out.append((key, b, scene.bodies[b].local(j.point_on(b)), target))
                    break
    return out


def _choose_branch(scene: Scene, dyad: Dyad, solver: _DyadSolver,
                   motions: dict[str, BodyMotion]) -> int:
    first = {name: m.take(slice(0, 1)) for name, m in motions.items()}
    pr = (_param(scene, dyad, 0, first), _param(scene, dyad, 1, first))
    cands = {}
    for k in (1, -1):
        cs, ss, gap = solver.positions(pr, k)
        org = [_body_positions(pr[i], cs[i], ss[i]) for i in range(2)]
        cands[k] = (cs, org, float(np.max(gap)))
    hints = _hint_points(scene, dyad)
    def where(k, b, loc):
        i = dyad.bodies.index(b)
        (c, s), (ox, oy) = cands[k][0][i], cands[k][1][i]
        return (float(np.ravel(ox + c * loc[0] - s * loc[1])[0]),
                float(np.ravel(oy + s * loc[0] + c * loc[1])[0]))
    if hints:
        dist = {k: sum((where(k, b, loc)[0] - t[0]) ** 2 + (where(k, b, loc)[1] - t[1]) ** 2
                       for _, b, loc, t in hints) for k in (1, -1)}
        if abs(dist[1] - dist[-1]) > 1e-12 * _scale(scene) ** 2:
            return 1 if dist[1] < dist[-1] else -1
    # no hint settles it: list the candidates
    inner = dyad.inner
    b0 = dyad.bodies[0]
    loc = (solver.q[0] if inner.kind == "R"
           else solver.b[0].local(inner.point_on(b0)))
    pts = []
    for k in (1, -1):
        x, y = where(k, b0, loc)
        pts.append(f"({x:.4g}, {y:.4g})")
    raise AssemblyError(
        f"dyad {dyad.label} has two assemblies at the first position: joint {inner.name!r} at "
        f"{pts[0]} or {pts[1]}; add a hint, e.g. [near] {inner.name} = [x, y]"
        if inner.kind == "R" else
        f"dyad {dyad.label} has two assemblies at the first position: point "
        f"{b0}.{inner.point_on(b0)} at {pts[0]} or {pts[1]}; add a hint, e.g. "
        f"[near] \"{b0}.{inner.point_on(b0)}\" = [x, y]")


def solve_kinematics(scene: Scene, structure: Structure) -> Kinematics:
    """Motions of every body over the driver's sweep (vectorised, closed form)."""
    motions: dict[str, BodyMotion] = {GROUND: ground_motion(),
                                      scene.driver.body: driver_motion(scene)}
    kin = Kinematics(scene, structure, scene.driver.positions, motions)
    for dyad in structure.dyads:
        kin.dyads.append(solve_dyad(scene, dyad, motions))
    return kin


def body_of(scene: Scene, name: str) -> Body:
    """The scene body of that name."""
    return scene.bodies[name]
