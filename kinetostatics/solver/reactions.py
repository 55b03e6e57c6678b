"""Joint reactions dyad by dyad and the equilibrating moment (force) on the driver.

Seed 002 s. 2.3.1 (dyads: RRR eqs 2.16-2.20, RRT 2.21-2.25, RTR 2.26-2.31, TRT
2.32-2.37, RTT 2.38-2.43 and the mirrored kinds) and s. 2.3.2 (the driver: Me, Fe and
the ground reaction F01, eqs 2.44-2.51). Dyads are solved in reverse order of the
structure (the last dyad first); each dyad's outer reactions then load, with opposite
sign, the bodies it hangs on.

One procedure serves every kind, in vector form (cross products, not the
figures' lever arms):

1. For each dyad body the equation of equilibrium along its own freedom relative to
   its outer joint: the moment about the outer revolute joint (the seed's
   "F^t l + sum M = 0", eqs 2.17, 2.22, 2.26) or the force along the outer guide (eqs
   2.32, 2.38). The inner joint's reaction enters each with the same columns as the
   velocity system, so the two equations are a 2 x 2 system for it: for a revolute
   inner joint its two components, for a prismatic one the normal force N and the
   couple M (which give the seed's d43 = M/N, eqs 2.25, 2.30).
2. Each body's remaining equations give its outer reaction: its force balance (eqs
   2.19, 2.21, 2.28, 2.31) and, at a prismatic joint, the couple (the point of
   application, eqs 2.24-2.25, 2.29-2.30, 2.36-2.37, 2.42-2.43).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..model.scene import GROUND, Joint, Scene
from . import arith as A
from .kinematics import DyadMotion, Kinematics


@dataclass
class JointReaction:
    """Reaction at a joint, on body ``on`` from body ``by`` (global components, N).

    For a prismatic joint also ``N`` (normal force on the slider along the line's left
    normal) and ``M`` (couple of the guide on the slider about the slider point).
    """

    joint: Joint
    on: str
    by: str
    fx: np.ndarray
    fy: np.ndarray
    N: np.ndarray | None = None
    M: np.ndarray | None = None
    x: np.ndarray | None = None     # where it acts (the joint point / the slider point)
    y: np.ndarray | None = None
    sign: float = 1.0               # the force on ``on`` is sign * (fx, fy)

    def force(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """(Fx, Fy) on ``on`` from ``by`` over n positions."""
        fx, fy = np.broadcast_to(self.fx, (n,)), np.broadcast_to(self.fy, (n,))
        return (fx, fy) if self.sign > 0 else (-fx, -fy)


@dataclass
class DriverReaction:
    """Equilibrating moment ``Me`` (crank) or force ``Fe`` (slider) and its ground joint."""

    kind: str
    value: np.ndarray


class _Store:
    """Running load resultants per body: [Fx, Fy, M about the body's local origin]."""

    def __init__(self, acc, motions, n):
        self.acc = acc
        self.motions = motions
        self.tmp = np.empty(n)

    def add(self, body, fx, fy, rx, ry, m=0.0, sign: float = 1.0):
        """Add ``sign`` times a force at the arm (rx, ry) from the body's origin, and a
        couple (in place: the accumulators are arrays of their own)."""
        if body == GROUND:
            return
        r = self.acc[body]
        A.iadd(r[0], fx, sign)
        A.iadd(r[1], fy, sign)
        A.icross(r[2], rx, ry, fx, fy, self.tmp, sign)
        A.iadd(r[2], m, sign)

    def arm(self, scene: Scene, body: str, point: str):
        """Arm of a named point from the body's origin (0 on the ground)."""
        if body == GROUND:
            return 0.0, 0.0
        return self.motions[body].arm(scene.bodies[body].local(point))

    def arm_to(self, body: str, x, y):
        """Arm of the global point (x, y) from the body's origin."""
        if body == GROUND:
            return 0.0, 0.0
        m = self.motions[body]
        return A.sub(x, m.ox), A.sub(y, m.oy)


def record_reaction(out: dict, joint: Joint, body: str, fx, fy, x, y, N=None, M=None,
                    sign: float = 1.0):
    """Store the reaction ``sign * (fx, fy)`` on ``body`` in the joint's on/by orientation
    (the sign is applied when the reaction is read, not here: no pass over the arrays)."""
    on, by = joint.on_by
    if on != body:
        sign = -sign
    if N is not None and joint.slider != body:
        N, M = -N, -M          # N, M are always those on the slider
    out[joint.name] = JointReaction(joint, on, by, fx, fy, N, M, x, y, sign)


def solve_reactions(kin: Kinematics, acc: dict[str, list]
                    ) -> tuple[dict[str, JointReaction], DriverReaction]:
    """Reactions in every joint and the driver's equilibrating moment or force.

    Parameters
    ----------
    kin : Kinematics
        The solved motion.
    acc : dict
        Per moving body [Fx, Fy, M_O]: resultant of its loads (applied, gravity,
        inertia) and its moment about the body's local origin, as arrays of their own
        (from :func:`~kinetostatics.solver.loads.resultants`). Updated in place.
    """
    scene = kin.scene
    store = _Store(acc, kin.bodies, kin.n)
    out: dict[str, JointReaction] = {}
    for dm in reversed(kin.dyads):
        _solve_dyad(scene, dm, store, out)
    drv = _solve_driver(scene, kin, store, out)
    return out, drv


def _generalised(store: _Store, name: str, pr, r):
    """Generalised force of the loads on a dyad body along its freedom: moment about the
    outer pivot P (rot) or force along the outer guide direction u (trans)."""
    if pr.kind == "rot":
        px, py = store.motions[name].arm(pr.local)          # P - O
        return A.sub(r[2], A.cross(px, py, r[0], r[1]))
    return A.mul_add(r[0], pr.ux, r[1], pr.uy)


def _solve_dyad(scene: Scene, dm: DyadMotion, store: _Store, out: dict) -> None:
    dyad = dm.dyad
    b1, b2 = dyad.bodies
    p1, p2 = dm.params
    q1 = _generalised(store, b1, p1, store.acc[b1])
    q2 = _generalised(store, b2, p2, store.acc[b2])
    xx, xy = dm.xx, dm.xy
    c1, c2 = dm.c1, dm.c2
    inner = dyad.inner
    if inner.kind == "R":
        # eqs 2.17, 2.22, 2.26 in vector form: c1 . R = Q1, c2 . R = -Q2,
        # R: force on body 2 from body 1 at X
        # det = c1 x c2 is minus the velocity system's determinant (its columns are c1,
        # -c2): the same products, so -dm.det is exactly c1x c2y - c1y c2x
        ndet = dm.det
        rx = A.mul_add(q1, c2[1], q2, c1[1], den=ndet)
        rx = np.negative(rx, out=rx) if isinstance(rx, np.ndarray) else -rx
        ry = A.mul_add(c1[0], q2, c2[0], q1, den=ndet)
        a1 = store.motions[b1].arm(dm.inner_local[0])
        a2 = store.motions[b2].arm(dm.inner_local[1])
        store.add(b1, rx, ry, *a1, sign=-1.0)
        store.add(b2, rx, ry, *a2)
        record_reaction(out, inner, b2, rx, ry, xx, xy)
    else:
        # [n.c_i, w_i] (N, M) = -sigma_i Q_i ; sigma = +1 on the slider, -1 on the guide
        nx, ny = dm.nx, dm.ny
        a1 = A.mul_add(nx, c1[0], ny, c1[1])
        a2 = A.mul_add(nx, c2[0], ny, c2[1])
        w1 = 1.0 if p1.kind == "rot" else 0.0
        w2 = 1.0 if p2.kind == "rot" else 0.0
        s1, s2 = (1.0, -1.0) if dm.slider_first else (-1.0, 1.0)
        det = A.mul_sub(a1, w2, w1, a2)
        y1, y2 = A.mul(-s1, q1), A.mul(-s2, q2)
        N = A.mul_sub(y1, w2, w1, y2, den=det)
        M = A.mul_sub(a1, y2, y1, a2, den=det)
        fx, fy = A.mul(N, nx), A.mul(N, ny)
        slider, guide = (b1, b2) if dm.slider_first else (b2, b1)
        store.add(slider, fx, fy, *store.arm(scene, slider, inner.points[1]), M)
        store.add(guide, fx, fy, *store.arm_to(guide, xx, xy), M, sign=-1.0)
        record_reaction(out, inner, slider, fx, fy, xx, xy, N, M)
    for name, pr, joint in ((b1, p1, dyad.outer[0]), (b2, p2, dyad.outer[1])):
        r = store.acc[name]
        kname = joint.other(name)
        if joint.kind == "R":
            # eqs 2.19, 2.21, 2.28: the force balance of the body gives the outer reaction
            store.add(kname, r[0], r[1], *store.arm(scene, kname, joint.point_on(kname)))
            record_reaction(out, joint, name, r[0], r[1], pr.px, pr.py, sign=-1.0)
        else:
            _outer_prismatic(scene, store, out, joint, name, kname, pr.ux, pr.uy)


def _outer_prismatic(scene, store, out, joint, name, kname, ux, uy):
    """Reaction of a prismatic joint on ``name`` that balances the body's loads: normal
    force through the slider point and a couple about it (the point of application,
    eqs 2.24-2.25, 2.36-2.37, 2.42-2.43)."""
    r = store.acc[name]
    if joint.slider == GROUND:
        x, y = scene.ground[joint.points[1]]
        sx, sy = A.scalar(x), A.scalar(y)
    else:
        m = store.motions[joint.slider]
        ax, ay = store.arm(scene, joint.slider, joint.points[1])
        sx, sy = A.add(m.ox, ax), A.add(m.oy, ay)
    arm_i = store.arm_to(name, sx, sy)
    nx, ny = -uy, ux
    fn = -A.mul_add(r[0], nx, r[1], ny)
    fx, fy = A.mul(fn, nx), A.mul(fn, ny)
    c = -A.sub(r[2], A.cross(arm_i[0], arm_i[1], r[0], r[1]))
    store.add(kname, fx, fy, *store.arm_to(kname, sx, sy), c, sign=-1.0)
    record_reaction(out, joint, name, fx, fy, sx, sy, fn, c)


def _solve_driver(scene: Scene, kin: Kinematics, store: _Store, out: dict) -> DriverReaction:
    drv = scene.driver
    joint = scene.joints[drv.joint]
    r = store.acc[drv.body]
    if drv.kind == "R":
        # eqs 2.47-2.48: Me from the moments about the ground joint, F01 from the forces
        px, py = scene.ground[joint.point_on(GROUND)]
        ax, ay = store.arm(scene, drv.body, joint.point_on(drv.body))
        me = -A.sub(r[2], A.cross(ax, ay, r[0], r[1]))
        record_reaction(out, joint, drv.body, r[0], r[1], A.scalar(px), A.scalar(py), sign=-1.0)
        return DriverReaction("R", A.full(me, kin.n))
    # sliding driver (eqs 2.49-2.51): Fe along the line through the slider point
    if joint.guide == GROUND:
        beta = joint.beta
        ux, uy = float(np.cos(beta)), float(np.sin(beta))
        ax, ay = store.arm(scene, drv.body, joint.points[1])
        m = kin.bodies[drv.body]
        sx, sy = A.add(m.ox, ax), A.add(m.oy, ay)
    else:
        ux, uy = 1.0, 0.0
        x, y = scene.ground[joint.points[1]]
        sx, sy = A.scalar(x), A.scalar(y)
        ax, ay = store.arm_to(drv.body, sx, sy)
    fe = -A.mul_add(r[0], ux, r[1], uy)
    nx, ny = -uy, ux
    fn = -A.mul_add(r[0], nx, r[1], ny)
    c = -A.sub(r[2], A.cross(ax, ay, r[0], r[1]))
    record_reaction(out, joint, drv.body, A.mul(fn, nx), A.mul(fn, ny), sx, sy, fn, c)
    return DriverReaction("T", A.full(fe, kin.n))

