"""Position closure of a dyad, closed form per kind (seed 000 ch. 5-12).

A dyad body joined to a known body K by a revolute joint rotates about that joint's point
(its unknown is its angle, ``rot``); by a prismatic joint it keeps K's angle plus the line
angle and translates along a direction fixed in K (its unknown is the displacement,
``trans``). :class:`DyadSolver` closes the inner joint for the assembly k = +-1 (the
seed's indicator, seed 000 eqs 6.1, 8.1): circle-circle, circle-line or line-line
intersection for a revolute inner joint, the guide's line through the slider point for a
prismatic one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..model.errors import AssemblyError
from ..model.scene import GROUND, Scene
from . import arith as A
from .driver import BodyMotion
from .trap import active, quiet

if TYPE_CHECKING:
    from .structure import Dyad


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


def take_rows(p: Param, index) -> Param:
    """The parameter at some rows only (scalars stay scalars; ``known`` stays the whole
    sweep's motion: the closure does not read it)."""
    out = Param(p.kind, p.known, p.local)
    for f in ("px", "py", "vpx", "vpy", "apx", "apy", "c", "s", "ux", "uy", "bx", "by"):
        v = getattr(p, f)
        setattr(out, f, v[index] if type(v) is np.ndarray and v.ndim else v)
    return out


def known_point(scene: Scene, bname: str, motion: BodyMotion, pname: str,
                speeds: bool = True):
    """Position, velocity and acceleration of a named point of a known body (``speeds``
    False: the position alone, the rest 0.0: a probe of the closeness to a dead centre,
    :func:`~kinetostatics.solver.probes.probe_closeness`)."""
    if bname == GROUND:
        x, y = scene.ground[pname]
        return A.scalar(x), A.scalar(y), 0.0, 0.0, 0.0, 0.0
    rx, ry = motion.arm(scene.bodies[bname].local(pname))
    if not speeds:
        return A.add(motion.ox, rx), A.add(motion.oy, ry), 0.0, 0.0, 0.0, 0.0
    vx, vy = motion.vel_arm(rx, ry)
    ax, ay = motion.acc_arm(rx, ry)
    return A.add(motion.ox, rx), A.add(motion.oy, ry), vx, vy, ax, ay


def dyad_param(scene: Scene, dyad: Dyad, i: int, motions: dict[str, BodyMotion],
               speeds: bool = True) -> Param:
    """A dyad body's :class:`Param` through its outer joint (``speeds`` False: its
    pivot's velocity and acceleration left at 0.0, :func:`known_point`)."""
    name = dyad.bodies[i]
    joint = dyad.outer[i]
    kname = joint.other(name)
    kb = motions[kname]
    body = scene.bodies[name]
    if joint.kind == "R":
        px, py, vx, vy, ax, ay = known_point(scene, kname, kb, joint.point_on(kname), speeds)
        return Param("rot", kb, body.local(joint.point_on(name)), px, py, vx, vy, ax, ay)
    beta = joint.beta
    cb, sb = float(np.cos(beta)), float(np.sin(beta))
    if joint.guide == kname:                         # known body carries the guide
        c, s = A.rotate(kb.cos, kb.sin, cb, sb)      # theta_i = theta_K + beta
        lx, ly = known_point(scene, kname, kb, joint.points[0])[:2]
        rx, ry = A.rotate(c, s, *body.local(joint.points[1]))
        ux, uy = c, s
    else:                                            # the dyad body carries the guide
        c, s = A.rotate(kb.cos, kb.sin, cb, -sb)     # theta_i = theta_K - beta
        lx, ly = known_point(scene, kname, kb, joint.points[1])[:2]
        rx, ry = A.rotate(c, s, *body.local(joint.points[0]))
        ux, uy = kb.cos, kb.sin
    return Param("trans", kb, c=c, s=s, ux=ux, uy=uy, bx=A.sub(lx, rx), by=A.sub(ly, ry))


def _rot_angle(dx, dy, local_vec, r2):
    """cos, sin of the angle that turns the local vector onto (dx, dy) (|d|^2 = r2)."""
    lx, ly = local_vec
    u = lx / r2
    if (type(r2) is np.ndarray and type(dx) is np.ndarray and type(dy) is np.ndarray
            and type(ly) is float and ly == 0.0 and math.copysign(1.0, ly) > 0):
        # a stack's r2 is an array over its rows, each > 0 (every link measured:
        # DyadSolver, stack.assemblies): ly / r2 would be an array of +0.0, and
        # d * (+0.0) is d * 0.0 bit for bit (kept: -0.0 + x is not always x)
        return (A.add(A.mul(dx, u), np.multiply(dy, 0.0)),
                A.sub(A.mul(dy, u), np.multiply(dx, 0.0)))
    v = ly / r2
    return A.mul_add(dx, u, dy, v), A.mul_sub(dy, u, dx, v)


def _trans_point(p: Param, local):
    """Position of a local point of a translating body at s = 0."""
    rx, ry = A.rotate(p.c, p.s, *local)
    return A.add(p.bx, rx), A.add(p.by, ry)


class DyadSolver:
    """Closed-form position analysis of one dyad for a given assembly k."""

    def __init__(self, scene: Scene, dyad: Dyad, measured: bool = False):
        self.scene = scene
        self.dyad = dyad
        self.b = [scene.bodies[n] for n in dyad.bodies]
        inner = dyad.inner
        self.slider_first = False
        if inner.kind == "R":
            self.q = [self.b[i].local(inner.point_on(dyad.bodies[i])) for i in range(2)]
            # (a run of stacked scenes, kinetostatics.solve_many: each scene's links were
            # measured once, when its assembly was chosen, stack.assemblies; not again
            # row by row)
            # (``measured``: so were a probe's, at the sweep that was solved before)
            run = measured or "segments" in scene.__dict__
            for i, (qx, qy) in enumerate([] if run else self.q):
                outer = dyad.outer[i]
                if outer.kind != "R":
                    continue
                ax, ay = self.b[i].local(outer.point_on(dyad.bodies[i]))
                link, least = _length(qx - ax, qy - ay), 1e-12 * scene.size
                if (link <= least if type(link) is float and type(least) is float
                        else np.any(link <= least)):
                    raise AssemblyError(
                        f"body {dyad.bodies[i]!r}: its joint points for {outer.name!r} and "
                        f"{inner.name!r} coincide; a dyad link needs a length")
        else:
            self.slider_first = inner.slider == dyad.bodies[0]
            self.beta = inner.beta

    @property
    def branches(self) -> int:
        kinds = (self.p_kind(0), self.p_kind(1))
        if self.dyad.inner.kind == "R":
            return 1 if kinds == ("trans", "trans") else 2
        return 2 if kinds == ("rot", "rot") else 1

    def p_kind(self, i: int) -> str:
        return "rot" if self.dyad.outer[i].kind == "R" else "trans"

    def positions(self, pr: tuple[Param, Param], k: int | None, first=None):
        """Per body (cos, sin) and the displacement s of a translating body, for assembly
        k, and the gap (m, > 0 where the dyad cannot close) or None when it closes
        everywhere.

        ``k`` None (RRR and circle-line dyads, :attr:`picks`; ``first`` given): the
        assembly is picked by ``first({1: two_1, -1: two_2})``, each the first row's
        per body (cos, sin) and displacements (numbers) for that k, from the same arrays
        as the sweep (the part of the closure that does not depend on k is worked out
        once); ``first`` may give None (not settled there), and so does this method
        when the dyad does not close at every row (the caller picks the other way).

        Sets ``reach``: the variable length the closure divides by, or None. With both
        outer joints revolute (RRR, RTR) the closure divides by the distance of the two
        outer pivots P1 P2 (RRR: the circles' centre distance, seed 000 eq. 5.1; RTR: the
        distance from the guide's pivot to the slider's, seed 000 ch. 6-7): where it
        vanishes the dyad's angles are undefined (a slotted lever whose block passes
        through its pivot). The other kinds divide by link lengths (constant) or by the
        velocity system's determinant (the transmission measure)."""
        self.reach = None
        self.pivots = None
        with quiet():
            if self.dyad.inner.kind == "R":
                return self._inner_r(pr, k, first)
            return self._inner_t(pr, k)

    @property
    def picks(self) -> bool:
        """Whether :meth:`positions` picks the assembly itself (k None): a revolute inner
        joint with a rotating body (RRR, RRT, TRR)."""
        return self.dyad.inner.kind == "R" and "rot" in (self.p_kind(0), self.p_kind(1))

    def _finish(self, close, k, first, gap, arrays):
        """``close(k, *arrays)`` for assembly k, or for the one ``first`` picks from the
        first row of ``arrays`` (None where the dyad does not close at every row, or
        ``first`` does not settle it); the assembly used is kept as ``k``."""
        if k is None:
            if gap is not None:
                return None
            row = [float(a[0]) if type(a) is np.ndarray and a.ndim else a for a in arrays]
            k = first({kk: close(kk, *row) for kk in (1, -1)})
            if k is None:
                return None
        self.k = k
        out, ss = close(k, *arrays)
        return out, ss, gap

    def _inner_r(self, pr, k, first=None):
        p1, p2 = pr
        (q1x, q1y), (q2x, q2y) = self.q
        # (a stack's local points are arrays: its exact zeros cost no pass, A.less and
        # A.squares, the same bits)
        a1 = (A.less(q1x, p1.local[0]), A.less(q1y, p1.local[1]))
        a2 = (A.less(q2x, p2.local[0]), A.less(q2y, p2.local[1]))
        if p1.kind == "rot" and p2.kind == "rot":
            # circle-circle (RRR, seed 000 ch. 5, eq. 5.1): Q = P1 + x e + k h J e
            # x * x, not x ** 2: a Python float's ** 2 (C pow) is not always x * x
            # rounded, and a stack's arrays square (kinetostatics.solve_many)
            r1s, r2s = A.squares(*a1), A.squares(*a2)
            ex, ey = A.sub(p2.px, p1.px), A.sub(p2.py, p1.py)
            d2 = ex * ex + ey * ey
            self.reach = _root(d2)
            inv = 1.0 / self.reach
            x = (d2 + (r1s - r2s)) * (0.5 * inv)
            h2 = r1s - x * x
            gap = None
            # (a NaN in h2 touches the trap of a trapped solve: looked for otherwise)
            least = _least(h2)
            if least < 0.0 or not (active() or _all_finite(h2)):
                d = np.sqrt(d2)
                r1, r2 = np.sqrt(r1s), np.sqrt(r2s)
                # (coincident pivots, d = 0: the circles are concentric, |r1 - r2| apart)
                gap = np.maximum(d - (r1 + r2), abs(r1 - r2) - d)
            root = _root(h2) if type(h2) is float else _clipped_root(h2, least)

            def close(k, ex, ey, inv, root, xi, p1x, p1y, p2x, p2y):
                kh = (k * inv) * root
                tx = xi * ex - kh * ey                    # X - P1
                ty = xi * ey + kh * ex
                return [_rot_angle(tx, ty, a1, r1s),
                        _rot_angle(A.sub(A.add(p1x, tx), p2x), A.sub(A.add(p1y, ty), p2y),
                                   a2, r2s)], (None, None)
            return self._finish(close, k, first, gap,
                                (ex, ey, inv, root, x * inv, p1.px, p1.py, p2.px, p2.py))
        if p1.kind == "trans" and p2.kind == "trans":
            # line-line (TRT, seed 000 ch. 10): Q01 + s1 u1 = Q02 + s2 u2
            q01 = _trans_point(p1, self.q[0])
            q02 = _trans_point(p2, self.q[1])
            rx, ry = A.sub(q02[0], q01[0]), A.sub(q02[1], q01[1])
            det = A.mul_sub(p1.uy, p2.ux, p1.ux, p2.uy)
            s1 = A.mul_sub(ry, p2.ux, rx, p2.uy, den=det)
            s2 = A.mul_sub(p1.ux, ry, p1.uy, rx, den=det)
            return [(p1.c, p1.s), (p2.c, p2.s)], (s1, s2), None
        # circle-line (RRT / TRR, seed 000 ch. 9 and 8)
        ir, it = (0, 1) if p1.kind == "rot" else (1, 0)
        prr, pt = pr[ir], pr[it]
        ar = a1 if ir == 0 else a2
        rs = A.squares(*ar)        # (x * x: as for r1s above)
        q0 = _trans_point(pt, self.q[it])
        wx, wy = A.sub(q0[0], prr.px), A.sub(q0[1], prr.py)
        b = A.mul_add(pt.ux, wx, pt.uy, wy)
        disc, own = _discriminant(b, wx, wy, rs)
        gap = None
        least = _least(disc)
        if least < 0.0:
            gap = np.abs(A.mul_sub(pt.ux, wy, pt.uy, wx)) - np.sqrt(rs)
        root = _root(disc) if type(disc) is float else _clipped_root(disc, least, own)

        def close(k, root, b, wx, wy, ux, uy, c, sn):
            # (k = 1: 1 * root is root, every double: a pass fewer, measured 2026-12-01,
            # the slider-crank's and the shaper's RRT dyads assemble with k = 1)
            s = (root if type(k) is int and k == 1 else k * root) - b
            out = [None, None]
            out[ir] = _rot_angle(A.add_mul(wx, s, ux), A.add_mul(wy, s, uy), ar, rs)
            out[it] = (c, sn)
            ss = [None, None]
            ss[it] = s
            return out, tuple(ss)
        return self._finish(close, k, first, gap, (root, b, wx, wy, pt.ux, pt.uy, pt.c, pt.s))

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
            d2 = dx * dx + dy * dy
            # (the arrays made here take the next step's values: the same numbers)
            own = A.fresh(d2, dx, dy)
            dn = self.reach = np.sqrt(d2, out=d2) if own else np.sqrt(d2)
            # (D = P_s - P_g and |D| kept for the transmission measure of this closing,
            # velocity_system.dead_centre_closeness2: not worked out a second time)
            self.pivots = (dx, dy, dn)
            y = -c / dn
            gap = None
            # (|y| > 1 somewhere, or a NaN or an infinity: the same test as on np.abs(y))
            if max(np.max(y), -np.min(y)) > 1.0 or not np.all(np.isfinite(y)):
                gap = np.where(np.isfinite(y), abs(c) - dn, np.inf)
            own = A.fresh(y, dn)
            x = np.arcsin(np.clip(y, -1.0, 1.0, out=y) if own else np.clip(y, -1.0, 1.0),
                          out=y if own else None)
            if np.ndim(k):      # per-row assemblies (kinetostatics.solve_many)
                th = np.arctan2(dy, dx) - self.beta + np.where(k > 0, -x, x - np.pi)
            elif own:
                th = _guide_angle(dy, dx, self.beta, np.negative(x, out=x) if k > 0 else
                                  np.subtract(x, np.pi, out=x))
            else:
                th = _guide_angle(dy, dx, self.beta, -x if k > 0 else x - np.pi)
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
            den = A.mul_sub(cs_, pg.uy, sn_, pg.ux)
            s = A.mul_sub(cs_, A.sub(sy, l0[1]), sn_, A.sub(sx, l0[0]), den=den)
            out[i_s] = (cs_, sn_)
            out[i_g] = (pg.c, pg.s)
            ss[i_g] = s
        else:
            cg, sg = A.rotate(ps.c, ps.s, cb, -sb)           # guide angle = slider's - beta
            lx, ly = A.rotate(cg, sg, l_loc[0] - pg.local[0], l_loc[1] - pg.local[1])
            lx, ly = A.add(pg.px, lx), A.add(pg.py, ly)
            ux, uy = ps.c, ps.s
            s0 = _trans_point(ps, s_loc)
            den = A.mul_sub(ux, ps.uy, uy, ps.ux)
            s = -A.sub(A.mul(ux, A.sub(s0[1], ly)), A.mul(uy, A.sub(s0[0], lx))) / den
            out[i_g] = (cg, sg)
            out[i_s] = (ps.c, ps.s)
            ss[i_s] = s
        return out, tuple(ss), None


def _guide_angle(dy, dx, beta, turn):
    """arctan2(dy, dx) - beta + turn (an RTR guide's angle, seed 000 ch. 6-7), the same
    bits, in the arctan2's own array: no pass for a beta of +0.0 (t - (+0.0) is t for
    every double, -0.0 and NaN too), no fresh array for either sum (measured
    2026-11-30, the shaper's lever: one pass and two arrays fewer a block)."""
    t = np.arctan2(dy, dx)
    if type(t) is not np.ndarray or t.shape != np.shape(turn):
        return t - beta + turn
    if not (beta == 0.0 and math.copysign(1.0, beta) > 0):
        np.subtract(t, beta, out=t)
    return np.add(t, turn, out=t)


def _length(x, y):
    """hypot(x, y) of numbers (math's, without numpy's overhead) or arrays (numpy's)."""
    if type(x) is float and type(y) is float:
        return math.hypot(x, y)
    return np.hypot(x, y)


def _least(x) -> float:
    """The smallest value of an array (a number as it is): the ndarray method, without
    np.min's dispatch."""
    if type(x) is float:
        return x
    return x.min() if type(x) is np.ndarray else np.min(x)


def _all_finite(x) -> bool:
    """No NaN and no infinity in x (an array or a number)."""
    if type(x) is float:
        return math.isfinite(x)
    return bool(np.isfinite(x).all()) if type(x) is np.ndarray else bool(np.all(np.isfinite(x)))


def _root(x):
    """np.sqrt(x); a positive Python float's by math.sqrt (the same double: both are
    correctly rounded), a Python float (the first row of a sweep in numbers,
    :func:`~kinetostatics.solver.kinematics.choose_assembly`, without numpy's scalars)."""
    if type(x) is float and x > 0.0:
        return math.sqrt(x)
    return np.sqrt(x)


def _clipped_root(x: np.ndarray, least, own: bool = False) -> np.ndarray:
    """np.sqrt(np.maximum(x, 0.0)), ``least`` x's smallest value: where none is below 0
    (nor NaN) the maximum changes nothing (x is a difference or a sum that is never
    -0.0: a - a is +0.0), and its pass is not made. ``own``: x is a temporary of the
    caller's, read no more: the root is written into it (the same values)."""
    out = x if own else None
    if least >= 0.0:
        return np.sqrt(x, out=out)
    return np.sqrt(np.maximum(x, 0.0, out=out), out=out)


def _discriminant(b, wx, wy, rs):
    """``b * b - (wx * wx + wy * wy) + rs`` (the circle-line closing's, seed 000 ch. 8-9)
    and whether it is an array of its own: where b, wx and wy are float arrays of one
    shape (and rs a number or such an array) the same operations in the same order, in
    two arrays instead of five (2026-12-01: three fresh arrays fewer an RRT dyad; its
    root is then written into the second, :func:`_clipped_root`)."""
    arrays = type(b) is np.ndarray and type(wx) is np.ndarray and type(wy) is np.ndarray
    if not (arrays and b.shape == wx.shape == wy.shape
            and b.dtype == wx.dtype == wy.dtype == np.float64
            and (type(rs) is float or type(rs) is np.ndarray and rs.shape == b.shape
                 and rs.dtype == np.float64)):
        return b * b - (wx * wx + wy * wy) + rs, False
    t = wx * wx
    q = wy * wy
    np.add(t, q, out=t)
    np.multiply(b, b, out=q)
    np.subtract(q, t, out=q)
    return np.add(q, rs, out=q), True


def body_origin(pr: Param, cs, s):
    """Origin of a dyad body from its parameter and solved unknown."""
    if pr.kind == "rot":
        rx, ry = A.rotate(cs[0], cs[1], *pr.local)
        return A.sub(pr.px, rx), A.sub(pr.py, ry)
    return A.add_mul(pr.bx, s, pr.ux), A.add_mul(pr.by, s, pr.uy)
