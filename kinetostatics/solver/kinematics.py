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

import math
from dataclasses import dataclass, field

import numpy as np

from ..model.errors import AssemblyError
from ..model.scene import GROUND, Scene
from . import _arith as A
from .structure import Dyad, Structure

SINGULAR_WARN = 1e-3    # sin(transmission angle) below this: the row is flagged singular
SINGULAR_FAIL = 1e-12   # below this the velocity system cannot be solved: refused


class BodyMotion:
    """Planar motion of a body over the sweep: cos and sin of its angle, angular velocity
    and acceleration, and the global position, velocity and acceleration of its local
    origin. Any of them may be a scalar (a fixed pivot, a constant speed); ``theta``
    (rad) is computed when first asked for unless given."""

    __slots__ = ("cos", "sin", "omega", "alpha", "ox", "oy", "vx", "vy", "ax", "ay", "_theta")

    def __init__(self, theta, cos, sin, omega, alpha, ox, oy, vx, vy, ax, ay):
        self._theta = theta
        self.cos, self.sin = cos, sin
        self.omega, self.alpha = omega, alpha
        self.ox, self.oy, self.vx, self.vy, self.ax, self.ay = ox, oy, vx, vy, ax, ay

    @property
    def theta(self):
        if self._theta is None:
            self._theta = np.arctan2(self.sin, self.cos)
        return self._theta

    def rotate(self, lx: float, ly: float):
        """A local vector turned into global axes: R(theta) l (the lever arm from the
        origin of a local point)."""
        return A.rotate(self.cos, self.sin, lx, ly)

    def point(self, local: tuple[float, float]):
        """Global position of a local point."""
        rx, ry = self.rotate(*local)
        return A.add(self.ox, rx), A.add(self.oy, ry)

    def vel_arm(self, rx, ry):
        """Velocity of the body point at the arm (rx, ry) from the origin: v_O + omega k x r."""
        return A.sub(self.vx, A.mul(self.omega, ry)), A.add(self.vy, A.mul(self.omega, rx))

    def acc_arm(self, rx, ry):
        """Acceleration of the body point at the arm r: a_O + eps k x r - omega^2 r
        (seed 001 eq. 9)."""
        w2 = A.mul(self.omega, self.omega)
        return (A.sub(A.sub(self.ax, A.mul(self.alpha, ry)), A.mul(w2, rx)),
                A.sub(A.add(self.ay, A.mul(self.alpha, rx)), A.mul(w2, ry)))

    def vel_at(self, x, y):
        """Velocity of the body's point that is at the global position (x, y)."""
        return self.vel_arm(A.sub(x, self.ox), A.sub(y, self.oy))

    def acc_at(self, x, y):
        """Acceleration of the body's point at the global position (x, y)."""
        return self.acc_arm(A.sub(x, self.ox), A.sub(y, self.oy))

    def take(self, index) -> BodyMotion:
        """The motion at some rows only (scalars stay scalars)."""
        def t(a):
            return a[index] if np.ndim(a) else a
        th = None if self._theta is None else t(self._theta)
        return BodyMotion(th, *(t(getattr(self, f)) for f in self.__slots__[:-1]))


def ground_motion() -> BodyMotion:
    """The fixed body: zero everything, unit rotation."""
    return BodyMotion(0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


@dataclass
class Param:
    """How a dyad body moves relative to the known body ``known`` through its outer joint.

    ``kind == "rot"``: turns about the point P of the known body (position, velocity
    and acceleration ``p*``, ``vp*``, ``ap*``); ``local`` is the joint point in the
    body's frame. ``kind == "trans"``: its angle is known (``c, s``) and its origin is
    ``base + s u``, u (``ux, uy``) fixed in the known body.
    """

    kind: str
    known: BodyMotion
    local: tuple[float, float] = (0.0, 0.0)
    px: object = 0.0
    py: object = 0.0
    vpx: object = 0.0
    vpy: object = 0.0
    apx: object = 0.0
    apy: object = 0.0
    c: object = 1.0
    s: object = 0.0
    ux: object = 1.0
    uy: object = 0.0
    bx: object = 0.0
    by: object = 0.0


@dataclass
class DyadMotion:
    """What the reactions need from a solved dyad: its parameters, the closing point X
    (the inner joint's point; for a prismatic inner joint the slider point), the
    columns c1, c2 of the velocity system at X and its determinant."""

    dyad: Dyad
    params: tuple[Param, Param]
    k: int
    xx: object
    xy: object
    c1: tuple
    c2: tuple
    det: object
    n: int
    singular: np.ndarray | None = None  # |sin tau| <= 1e-3: near a dead centre
    inner_local: tuple | None = None    # revolute inner joint: its local point on each body
    slider_first: bool = False          # prismatic inner joint: body 1 is the slider
    nx: object = None                   # prismatic inner joint: left normal of the line
    ny: object = None
    _tau: tuple | None = None

    def _compute_tau(self):
        if self._tau is None:
            n = self.n
            if self.nx is None:
                c1, c2 = self.c1, self.c2
                norm = np.hypot(*c1) * np.hypot(*c2)
                sin_t = self.det / norm
                cos_t = -(A.add(A.mul(c1[0], c2[0]), A.mul(c1[1], c2[1]))) / norm
            else:
                sin_t, cos_t = _inner_t_tau(self.params, self.ny, -self.nx)
            self._tau = (_full(np.asarray(sin_t, dtype=float), n),
                         _full(np.asarray(cos_t, dtype=float), n))
        return self._tau

    @property
    def sin_tau(self) -> np.ndarray:
        """sin of the transmission angle: |det| / (|c1| |c2|) of the velocity system."""
        return self._compute_tau()[0]

    @property
    def cos_tau(self) -> np.ndarray:
        return self._compute_tau()[1]

    @property
    def transmission_angle(self) -> np.ndarray:
        """Transmission angle in [0, 180] deg (seed 002 eqs 2.60-2.61)."""
        s_, c_ = self._compute_tau()
        return np.rad2deg(np.arctan2(np.abs(s_), c_))


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

    @property
    def singular(self) -> np.ndarray:
        """Rows near a dead centre of some dyad (contract: |det| <= 1e-3 |c1||c2|)."""
        out = np.zeros(self.n, dtype=bool)
        for d in self.dyads:
            out |= d.singular
        return out


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
    w, eps = float(drv.speed), float(drv.acceleration)
    if drv.kind == "R":
        th = np.deg2rad(drv.positions)
        c, s = np.cos(th), np.sin(th)
        px, py = scene.ground[joint.point_on(GROUND)]
        rax, ray = A.rotate(c, s, *body.local(joint.point_on(drv.body)))   # o = P - R a
        w2 = w * w
        return BodyMotion(th, c, s, w, eps, A.sub(float(px), rax), A.sub(float(py), ray),
                          A.mul(w, ray), A.mul(-w, rax),
                          A.add(A.mul(eps, ray), A.mul(w2, rax)),
                          A.add(A.mul(-eps, rax), A.mul(w2, ray)))
    beta = np.deg2rad(joint.line_angle)
    pos = drv.positions
    if joint.guide == GROUND:
        th = float(beta)
        ux, uy = float(np.cos(beta)), float(np.sin(beta))
        lx, ly = scene.ground[joint.points[0]]
        loc = body.local(joint.points[1])
        sign = 1.0
    else:   # the driver carries the guide and slides along a ground slider point
        th = -float(beta)
        ux, uy = 1.0, 0.0
        lx, ly = scene.ground[joint.points[1]]
        loc = body.local(joint.points[0])
        sign = -1.0
    c, s = float(np.cos(th)), float(np.sin(th))
    rx, ry = A.rotate(c, s, *loc)
    ox = A.add(A.mul(sign * ux, pos), lx - rx)
    oy = A.add(A.mul(sign * uy, pos), ly - ry)
    v, a = sign * w, sign * eps
    return BodyMotion(th, c, s, 0.0, 0.0, ox, oy, v * ux, v * uy, a * ux, a * uy)


def _known_point(scene: Scene, bname: str, motion: BodyMotion, pname: str):
    """Position, velocity and acceleration of a named point of a known body."""
    if bname == GROUND:
        x, y = scene.ground[pname]
        return float(x), float(y), 0.0, 0.0, 0.0, 0.0
    rx, ry = motion.rotate(*scene.bodies[bname].local(pname))
    vx, vy = motion.vel_arm(rx, ry)
    ax, ay = motion.acc_arm(rx, ry)
    return A.add(motion.ox, rx), A.add(motion.oy, ry), vx, vy, ax, ay


def _param(scene: Scene, dyad: Dyad, i: int, motions: dict[str, BodyMotion]) -> Param:
    name = dyad.bodies[i]
    joint = dyad.outer[i]
    kname = joint.other(name)
    kb = motions[kname]
    body = scene.bodies[name]
    if joint.kind == "R":
        px, py, vx, vy, ax, ay = _known_point(scene, kname, kb, joint.point_on(kname))
        return Param("rot", kb, body.local(joint.point_on(name)), px, py, vx, vy, ax, ay)
    beta = np.deg2rad(joint.line_angle)
    cb, sb = float(np.cos(beta)), float(np.sin(beta))
    if joint.guide == kname:                         # known body carries the guide
        c, s = A.rotate(kb.cos, kb.sin, cb, sb)      # theta_i = theta_K + beta
        lx, ly = _known_point(scene, kname, kb, joint.points[0])[:2]
        rx, ry = A.rotate(c, s, *body.local(joint.points[1]))
        ux, uy = c, s
    else:                                            # the dyad body carries the guide
        c, s = A.rotate(kb.cos, kb.sin, cb, -sb)     # theta_i = theta_K - beta
        lx, ly = _known_point(scene, kname, kb, joint.points[1])[:2]
        rx, ry = A.rotate(c, s, *body.local(joint.points[0]))
        ux, uy = kb.cos, kb.sin
    return Param("trans", kb, c=c, s=s, ux=ux, uy=uy, bx=A.sub(lx, rx), by=A.sub(ly, ry))


def _rot_angle(dx, dy, local_vec, r2):
    """cos, sin of the angle that turns the local vector onto (dx, dy) (|d|^2 = r2)."""
    lx, ly = local_vec
    return (A.add(A.mul(dx, lx / r2), A.mul(dy, ly / r2)),
            A.sub(A.mul(dy, lx / r2), A.mul(dx, ly / r2)))


def _trans_point(p: Param, local):
    """Position of a local point of a translating body at s = 0."""
    rx, ry = A.rotate(p.c, p.s, *local)
    return A.add(p.bx, rx), A.add(p.by, ry)


class _DyadSolver:
    """Closed-form position analysis of one dyad for a given assembly k."""

    def __init__(self, scene: Scene, dyad: Dyad):
        self.scene = scene
        self.dyad = dyad
        self.b = [scene.bodies[n] for n in dyad.bodies]
        inner = dyad.inner
        self.slider_first = False
        if inner.kind == "R":
            self.q = [self.b[i].local(inner.point_on(dyad.bodies[i])) for i in range(2)]
            for i, (qx, qy) in enumerate(self.q):
                outer = dyad.outer[i]
                if outer.kind != "R":
                    continue
                ax, ay = self.b[i].local(outer.point_on(dyad.bodies[i]))
                if math.hypot(qx - ax, qy - ay) <= 1e-12 * _scale(scene):
                    raise AssemblyError(
                        f"body {dyad.bodies[i]!r}: its joint points for {outer.name!r} and "
                        f"{inner.name!r} coincide; a dyad link needs a length")
        else:
            self.slider_first = inner.slider == dyad.bodies[0]
            self.beta = float(np.deg2rad(inner.line_angle))

    @property
    def branches(self) -> int:
        kinds = (self.p_kind(0), self.p_kind(1))
        if self.dyad.inner.kind == "R":
            return 1 if kinds == ("trans", "trans") else 2
        return 2 if kinds == ("rot", "rot") else 1

    def p_kind(self, i: int) -> str:
        return "rot" if self.dyad.outer[i].kind == "R" else "trans"

    def positions(self, pr: tuple[Param, Param], k: int):
        """Per body (cos, sin) and the displacement s of a translating body, for assembly
        k, and the gap (m, > 0 where the dyad cannot close) or None when it closes
        everywhere."""
        with np.errstate(divide="ignore", invalid="ignore"):
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
            # circle-circle (RRR, seed 000 ch. 5, eq. 5.1): Q = P1 + x e + k h J e
            r1s, r2s = a1[0] ** 2 + a1[1] ** 2, a2[0] ** 2 + a2[1] ** 2
            ex, ey = A.sub(p2.px, p1.px), A.sub(p2.py, p1.py)
            d2 = ex * ex + ey * ey
            inv = 1.0 / np.sqrt(d2)
            x = (d2 + (r1s - r2s)) * (0.5 * inv)
            h2 = r1s - x * x
            gap = None
            if np.min(h2) < 0.0 or not np.all(np.isfinite(h2)):
                d = np.sqrt(d2)
                r1, r2 = np.sqrt(r1s), np.sqrt(r2s)
                gap = np.where(np.isfinite(h2), np.maximum(d - (r1 + r2), abs(r1 - r2) - d),
                               np.inf)
            kh = (k * inv) * np.sqrt(np.maximum(h2, 0.0))
            xi = x * inv
            tx = xi * ex - kh * ey                    # X - P1
            ty = xi * ey + kh * ex
            out[0] = _rot_angle(tx, ty, a1, r1s)
            out[1] = _rot_angle(A.sub(A.add(p1.px, tx), p2.px), A.sub(A.add(p1.py, ty), p2.py),
                                a2, r2s)
            return out, (None, None), gap
        if p1.kind == "trans" and p2.kind == "trans":
            # line-line (TRT, seed 000 ch. 10): Q01 + s1 u1 = Q02 + s2 u2
            q01 = _trans_point(p1, self.q[0])
            q02 = _trans_point(p2, self.q[1])
            rx, ry = A.sub(q02[0], q01[0]), A.sub(q02[1], q01[1])
            det = A.sub(A.mul(p1.uy, p2.ux), A.mul(p1.ux, p2.uy))
            s1 = A.sub(A.mul(ry, p2.ux), A.mul(rx, p2.uy)) / det
            s2 = A.sub(A.mul(p1.ux, ry), A.mul(p1.uy, rx)) / det
            return [(p1.c, p1.s), (p2.c, p2.s)], (s1, s2), None
        # circle-line (RRT / TRR, seed 000 ch. 9 and 8)
        ir, it = (0, 1) if p1.kind == "rot" else (1, 0)
        prr, pt = pr[ir], pr[it]
        ar = a1 if ir == 0 else a2
        rs = ar[0] ** 2 + ar[1] ** 2
        q0 = _trans_point(pt, self.q[it])
        wx, wy = A.sub(q0[0], prr.px), A.sub(q0[1], prr.py)
        b = A.add(A.mul(pt.ux, wx), A.mul(pt.uy, wy))
        disc = b * b - (wx * wx + wy * wy) + rs
        gap = None
        if np.min(disc) < 0.0:
            gap = np.abs(A.sub(A.mul(pt.ux, wy), A.mul(pt.uy, wx))) - np.sqrt(rs)
        s = k * np.sqrt(np.maximum(disc, 0.0)) - b
        out[ir] = _rot_angle(A.add(wx, A.mul(s, pt.ux)), A.add(wy, A.mul(s, pt.uy)), ar, rs)
        out[it] = (pt.c, pt.s)
        ss = [None, None]
        ss[it] = s
        return out, tuple(ss), gap

    def _inner_t(self, pr, k):
        inner = self.dyad.inner
        i_s, i_g = (0, 1) if self.slider_first else (1, 0)
        ps, pg = pr[i_s], pr[i_g]
        s_loc = self.b[i_s].local(inner.points[1])
        l_loc = self.b[i_g].local(inner.points[0])
        cb, sb = np.cos(self.beta), np.sin(self.beta)
        out = [None, None]
        ss = [None, None]
        if ps.kind == "rot" and pg.kind == "rot":
            # RTR (seed 000 ch. 6-7): sin(delta - theta_g - beta) = -c / |D|
            asx, asy = s_loc[0] - ps.local[0], s_loc[1] - ps.local[1]
            vx_ = cb * asx - sb * asy - (l_loc[0] - pg.local[0])
            vy_ = sb * asx + cb * asy - (l_loc[1] - pg.local[1])
            c = cb * vy_ - sb * vx_
            dx, dy = A.sub(ps.px, pg.px), A.sub(ps.py, pg.py)
            dn = np.sqrt(dx * dx + dy * dy)
            y = -c / dn
            gap = None
            if np.max(np.abs(y)) > 1.0 or not np.all(np.isfinite(y)):
                gap = np.where(np.isfinite(y), abs(c) - dn, np.inf)
            x = np.arcsin(np.clip(y, -1.0, 1.0))
            th = np.arctan2(dy, dx) - self.beta + (-x if k > 0 else x - np.pi)
            cg, sg = np.cos(th), np.sin(th)
            out[i_g] = (cg, sg)
            out[i_s] = A.rotate(cg, sg, cb, sb)
            return out, (None, None), gap
        # RTT / TTR (seed 000 ch. 11-12): the rotating body's angle follows the other's
        if ps.kind == "rot":
            cs_, sn_ = A.rotate(pg.c, pg.s, cb, sb)          # slider angle = guide's + beta
            sx, sy = A.rotate(cs_, sn_, s_loc[0] - ps.local[0], s_loc[1] - ps.local[1])
            sx, sy = A.add(ps.px, sx), A.add(ps.py, sy)
            l0 = _trans_point(pg, l_loc)
            den = A.sub(A.mul(cs_, pg.uy), A.mul(sn_, pg.ux))
            s = A.sub(A.mul(cs_, A.sub(sy, l0[1])), A.mul(sn_, A.sub(sx, l0[0]))) / den
            out[i_s] = (cs_, sn_)
            out[i_g] = (pg.c, pg.s)
            ss[i_g] = s
        else:
            cg, sg = A.rotate(ps.c, ps.s, cb, -sb)           # guide angle = slider's - beta
            lx, ly = A.rotate(cg, sg, l_loc[0] - pg.local[0], l_loc[1] - pg.local[1])
            lx, ly = A.add(pg.px, lx), A.add(pg.py, ly)
            ux, uy = ps.c, ps.s
            s0 = _trans_point(ps, s_loc)
            den = A.sub(A.mul(ux, ps.uy), A.mul(uy, ps.ux))
            s = -A.sub(A.mul(ux, A.sub(s0[1], ly)), A.mul(uy, A.sub(s0[0], lx))) / den
            out[i_g] = (cg, sg)
            out[i_s] = (ps.c, ps.s)
            ss[i_s] = s
        return out, tuple(ss), None


def _origin(pr: Param, cs, s):
    """Origin of a dyad body from its parameter and solved unknown."""
    if pr.kind == "rot":
        rx, ry = A.rotate(cs[0], cs[1], *pr.local)
        return A.sub(pr.px, rx), A.sub(pr.py, ry)
    return A.add(pr.bx, A.mul(s, pr.ux)), A.add(pr.by, A.mul(s, pr.uy))


def _columns(pr: Param, xx, xy):
    """Velocity of the body's point at X per unit of its unknown (the column c_i), the
    known part k_i of that velocity, and the weight of the unknown in the body's
    angular velocity (1 for rot, 0 for trans)."""
    if pr.kind == "rot":
        return (A.sub(pr.py, xy), A.sub(xx, pr.px)), (pr.vpx, pr.vpy), 1.0
    return (pr.ux, pr.uy), pr.known.vel_at(xx, xy), 0.0


def _solve2(a11, a12, a21, a22, r1, r2, det):
    """Cramer's rule for [[a11, a12], [a21, a22]] x = [r1, r2]."""
    return (A.sub(A.mul(r1, a22), A.mul(a12, r2)) / det,
            A.sub(A.mul(a11, r2), A.mul(r1, a21)) / det)


def _full(x, n):
    return np.broadcast_to(x, (n,)) if np.ndim(x) == 0 else x


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
    n = scene.driver.positions.size
    solver = _DyadSolver(scene, dyad)
    pr = (_param(scene, dyad, 0, motions), _param(scene, dyad, 1, motions))
    k = _choose_branch(scene, dyad, solver, motions) if solver.branches == 2 else 1
    cs, ss, gap = solver.positions(pr, k)
    if gap is not None:
        gap = _full(gap, n)
        bad = np.flatnonzero(gap > 1e-9 * _scale(scene))
        if bad.size:
            raise AssemblyError(
                f"dyad {dyad.label} cannot be assembled at driver position(s) "
                f"{_fmt_positions(scene, bad, gap[bad])}: the links do not reach; shorten "
                "the sweep or change the lengths")
    org = [_origin(pr[i], cs[i], ss[i]) for i in range(2)]
    inner = dyad.inner
    ib = 0 if inner.kind == "R" or solver.slider_first else 1
    loc = solver.q[0] if inner.kind == "R" else solver.b[ib].local(inner.points[1])
    rx, ry = A.rotate(cs[ib][0], cs[ib][1], *loc)
    xx, xy = A.add(org[ib][0], rx), A.add(org[ib][1], ry)
    (c1, k1, w1), (c2, k2, w2) = _columns(pr[0], xx, xy), _columns(pr[1], xx, xy)
    if inner.kind == "R":
        # c1 qd1 - c2 qd2 = k2 - k1
        a11, a12, a21, a22 = c1[0], -c2[0], c1[1], -c2[1]
        r1, r2 = A.sub(k2[0], k1[0]), A.sub(k2[1], k1[1])
        nx = ny = None
        ux = uy = None
    else:
        # w1 qd1 - w2 qd2 = omega0_2 - omega0_1 ; n.(c1 qd1 - c2 qd2) = n.(k2 - k1)
        ig = 1 - ib
        ux, uy = A.rotate(cs[ig][0], cs[ig][1], np.cos(solver.beta), np.sin(solver.beta))
        nx, ny = -uy, ux
        om0 = [0.0 if p.kind == "rot" else p.known.omega for p in pr]
        a11, a12, r1 = w1, -w2, A.sub(om0[1], om0[0])
        a21 = A.add(A.mul(nx, c1[0]), A.mul(ny, c1[1]))
        a22 = -A.add(A.mul(nx, c2[0]), A.mul(ny, c2[1]))
        r2 = A.add(A.mul(nx, A.sub(k2[0], k1[0])), A.mul(ny, A.sub(k2[1], k1[1])))
    det = A.sub(A.mul(a11, a22), A.mul(a12, a21))
    # |det| <= 1e-12 |c1| |c2|: exactly singular (for a prismatic inner joint the same
    # test on the transmission measure of _inner_t_tau)
    if inner.kind == "R":
        norm2 = (c1[0] * c1[0] + c1[1] * c1[1]) * (c2[0] * c2[0] + c2[1] * c2[1])
        sin2 = _full(det * det / norm2, n)
    else:
        sin2 = _full(_inner_t_tau(pr, ux, uy)[0], n) ** 2
    sing = ~(sin2 > SINGULAR_WARN**2)
    exact = np.flatnonzero(~(sin2 > SINGULAR_FAIL**2)) if sing.any() else ()
    if len(exact):
        raise AssemblyError(
            f"dyad {dyad.label} is exactly singular (dead centre: transmission angle 0) at "
            f"driver position(s) {_fmt_positions(scene, exact)}; its velocities are undefined "
            "there: leave those positions out of the sweep")
    qd = _solve2(a11, a12, a21, a22, r1, r2, det)
    # accelerations: the same matrix, centripetal and Coriolis terms on the right
    ka = []
    for i, p in enumerate(pr):
        if p.kind == "rot":
            w2_ = qd[i] * qd[i]
            ka.append((A.sub(p.apx, w2_ * A.sub(xx, p.px)), A.sub(p.apy, w2_ * A.sub(xy, p.py))))
        else:
            kax, kay = p.known.acc_at(xx, xy)
            f = A.mul(2.0 * p.known.omega, qd[i])          # Coriolis 2 omega_K x v_rel
            ka.append((A.sub(kax, A.mul(f, p.uy)), A.add(kay, A.mul(f, p.ux))))
    if inner.kind == "R":
        r1, r2 = A.sub(ka[1][0], ka[0][0]), A.sub(ka[1][1], ka[0][1])
    else:
        al0 = [0.0 if p.kind == "rot" else p.known.alpha for p in pr]
        r1 = A.sub(al0[1], al0[0])
        v1 = (A.add(k1[0], A.mul(c1[0], qd[0])), A.add(k1[1], A.mul(c1[1], qd[0])))
        v2 = (A.add(k2[0], A.mul(c2[0], qd[1])), A.add(k2[1], A.mul(c2[1], qd[1])))
        sgn = 1.0 if solver.slider_first else -1.0
        rdot = A.mul(sgn, A.add(A.mul(ux, A.sub(v1[0], v2[0])), A.mul(uy, A.sub(v1[1], v2[1]))))
        ig = 1 - ib
        om_g = qd[ig] if pr[ig].kind == "rot" else pr[ig].known.omega
        # n.(a_slider - a_guide) = 2 omega_g rdot (Coriolis, seed 001 eq. 8)
        r2 = A.sub(A.mul(2.0 * sgn, A.mul(om_g, rdot)),
                   A.add(A.mul(nx, A.sub(ka[0][0], ka[1][0])),
                         A.mul(ny, A.sub(ka[0][1], ka[1][1]))))
    qdd = _solve2(a11, a12, a21, a22, r1, r2, det)
    for i, p in enumerate(pr):
        c, sn = cs[i]
        ox, oy = org[i]
        kb = p.known
        if p.kind == "rot":
            om, al = qd[i], qdd[i]
            rax, ray = A.rotate(c, sn, -p.local[0], -p.local[1])   # o - P = -R a
            w2_ = om * om
            vx = A.sub(p.vpx, A.mul(om, ray))
            vy = A.add(p.vpy, A.mul(om, rax))
            ax_ = A.sub(A.sub(p.apx, A.mul(al, ray)), A.mul(w2_, rax))
            ay_ = A.sub(A.add(p.apy, A.mul(al, rax)), A.mul(w2_, ray))
        else:
            om, al = kb.omega, kb.alpha
            vkx, vky = kb.vel_at(ox, oy)
            akx, aky = kb.acc_at(ox, oy)
            f = A.mul(2.0 * kb.omega, qd[i])
            vx, vy = A.add(vkx, A.mul(qd[i], p.ux)), A.add(vky, A.mul(qd[i], p.uy))
            ax_ = A.sub(A.add(akx, A.mul(qdd[i], p.ux)), A.mul(f, p.uy))
            ay_ = A.add(A.add(aky, A.mul(qdd[i], p.uy)), A.mul(f, p.ux))
        motions[dyad.bodies[i]] = BodyMotion(None, c, sn, om, al, ox, oy, vx, vy, ax_, ay_)
    return DyadMotion(dyad, pr, k, xx, xy, c1, c2, det, n,
                      singular=sing,
                      inner_local=tuple(solver.q) if inner.kind == "R" else None,
                      slider_first=inner.kind == "T" and solver.slider_first, nx=nx, ny=ny)


def _inner_t_tau(pr, ux, uy):
    """sin and cos of the transmission angle of a dyad with a prismatic inner joint:
    between the line and P_s - P_g (RTR: the velocity system's columns are J(P2 - P1)
    and u, so sin = u . D / |D|) or between the line and the other guide (RTT)."""
    p1, p2 = pr
    if p1.kind == "rot" and p2.kind == "rot":
        dx, dy = A.sub(p1.px, p2.px), A.sub(p1.py, p2.py)
        dn = np.sqrt(dx * dx + dy * dy)
        return (A.add(A.mul(ux, dx), A.mul(uy, dy)) / dn,
                A.sub(A.mul(ux, dy), A.mul(uy, dx)) / dn)
    pt = p2 if p1.kind == "rot" else p1
    return A.sub(A.mul(ux, pt.uy), A.mul(uy, pt.ux)), A.add(A.mul(ux, pt.ux), A.mul(uy, pt.uy))


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
        cs, ss, _ = solver.positions(pr, k)
        cands[k] = (cs, [_origin(pr[i], cs[i], ss[i]) for i in range(2)])
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


