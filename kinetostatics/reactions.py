"""Joint reactions dyad by dyad and the equilibrating moment (force) on the driver.

Seed 002 s. 2.3.1 (dyads: RRR eqs 2.16-2.20, RRT 2.21-2.25, RTR 2.26-2.31, TRT
2.32-2.37, RTT 2.38-2.43 and the mirrored kinds) and s. 2.3.2 (the driver: Me, Fe and
the ground reaction F01, eqs 2.44-2.51). Dyads are solved in reverse order of the
structure (the last dyad first); each dyad's outer reactions then load, with opposite
sign, the bodies it hangs on.

One procedure serves every kind, in vector form (SPEC: cross products, not the
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

from .kinematics import DyadMotion, Kinematics
from .scene import GROUND, Joint, Scene


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


@dataclass
class DriverReaction:
    """Equilibrating moment ``Me`` (crank) or force ``Fe`` (slider) and its ground joint."""

    kind: str
    value: np.ndarray


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


class _Store:
    """Running load resultants per body, about the global origin."""

    def __init__(self, acc, motions):
        self.acc = acc
        self.motions = motions

    def add(self, body, fx, fy, x, y, m=0.0):
        if body == GROUND:
            return
        r = self.acc[body]
        r[0] = r[0] + fx
        r[1] = r[1] + fy
        r[2] = r[2] + (x * fy - y * fx) + m


def _record(out: dict, joint: Joint, body: str, fx, fy, x, y, N=None, M=None):
    """Store the reaction on ``body`` in the joint's on/by orientation."""
    on, by = joint.on_by
    if on != body:
        fx, fy = -fx, -fy
    if N is not None and joint.slider != body:
        N, M = -N, -M          # N, M are always those on the slider
    out[joint.name] = JointReaction(joint, on, by, fx, fy, N, M, x, y)


def solve_reactions(kin: Kinematics, acc: dict[str, list[np.ndarray]]
                    ) -> tuple[dict[str, JointReaction], DriverReaction]:
    """Reactions in every joint and the driver's equilibrating moment or force.

    Parameters
    ----------
    kin : Kinematics
        The solved motion.
    acc : dict
        Per moving body [Fx, Fy, M_O]: resultant of its loads (applied, gravity,
        inertia) and its moment about the global origin. Updated in place.
    """
    scene = kin.scene
    store = _Store(acc, kin.bodies)
    out: dict[str, JointReaction] = {}
    for dm in reversed(kin.dyads):
        _solve_dyad(scene, dm, store, out)
    drv = _solve_driver(scene, kin, store, out)
    return out, drv


def _generalised(pr, r):
    """Generalised force of the loads on a dyad body along its freedom: moment about the
    outer pivot P (rot) or force along the outer guide direction u (trans)."""
    if pr.kind == "rot":
        return r[2] - _cross(pr.px, pr.py, r[0], r[1])
    return r[0] * pr.ux + r[1] * pr.uy


def _solve_dyad(scene: Scene, dm: DyadMotion, store: _Store, out: dict) -> None:
    dyad = dm.dyad
    b1, b2 = dyad.bodies
    r1, r2 = store.acc[b1], store.acc[b2]
    p1, p2 = dm.params
    q1, q2 = _generalised(p1, r1), _generalised(p2, r2)
    xx, xy = dm.xx, dm.xy
    c1, c2 = dm.c1, dm.c2
    inner = dyad.inner
    if inner.kind == "R":
        # c1 . R = Q1, c2 . R = -Q2; R: force on body 2 from body 1 at X
        det = c1[0] * c2[1] - c1[1] * c2[0]
        rx = (q1 * c2[1] + q2 * c1[1]) / det
        ry = (-c1[0] * q2 - c2[0] * q1) / det
        store.add(b1, -rx, -ry, xx, xy)
        store.add(b2, rx, ry, xx, xy)
        _record(out, inner, b2, rx, ry, xx, xy)
    else:
        # [n.c_i, w_i] (N, M) = -sigma_i Q_i ; sigma = +1 on the slider, -1 on the guide
        nx, ny = dm.nx, dm.ny
        a1 = nx * c1[0] + ny * c1[1]
        a2 = nx * c2[0] + ny * c2[1]
        w1 = 1.0 if p1.kind == "rot" else 0.0
        w2 = 1.0 if p2.kind == "rot" else 0.0
        s1, s2 = (1.0, -1.0) if dm.slider_first else (-1.0, 1.0)
        det = a1 * w2 - w1 * a2
        y1, y2 = -s1 * q1, -s2 * q2
        N = (y1 * w2 - w1 * y2) / det
        M = (a1 * y2 - y1 * a2) / det
        fx, fy = N * nx, N * ny
        slider, guide = (b1, b2) if dm.slider_first else (b2, b1)
        store.add(slider, fx, fy, xx, xy, M)
        store.add(guide, -fx, -fy, xx, xy, -M)
        _record(out, inner, slider, fx, fy, xx, xy, N, M)
    for name, pr, joint in ((b1, p1, dyad.outer[0]), (b2, p2, dyad.outer[1])):
        r = store.acc[name]
        kname = joint.other(name)
        if joint.kind == "R":
            fx, fy = -r[0], -r[1]
            store.add(kname, r[0], r[1], pr.px, pr.py)
            _record(out, joint, name, fx, fy, pr.px, pr.py)
        else:
            _outer_prismatic(scene, store, out, joint, name, kname, pr.ux, pr.uy)


def _slider_point(scene: Scene, store_motion, joint: Joint):
    body = scene.bodies.get(joint.slider)
    if body is None:
        x, y = scene.ground[joint.points[1]]
        return np.float64(x), np.float64(y)
    return store_motion[joint.slider].point(body.local(joint.points[1]))


def _outer_prismatic(scene, store, out, joint, name, kname, ux, uy):
    """Reaction of a prismatic joint on ``name`` that balances the body's loads: normal
    force through the slider point and a couple about it (the point of application)."""
    r = store.acc[name]
    sx, sy = _slider_point(scene, store.motions, joint)
    nx, ny = -uy, ux
    fn = -(r[0] * nx + r[1] * ny)
    fx, fy = fn * nx, fn * ny
    c = -(r[2] - _cross(sx, sy, r[0], r[1]))
    store.add(kname, -fx, -fy, sx, sy, -c)
    _record(out, joint, name, fx, fy, sx, sy, fn, c)


def _solve_driver(scene: Scene, kin: Kinematics, store: _Store, out: dict) -> DriverReaction:
    drv = scene.driver
    joint = scene.joints[drv.joint]
    r = store.acc[drv.body]
    m = kin.bodies[drv.body]
    if drv.kind == "R":
        px, py = scene.ground[joint.point_on(GROUND)]
        fx, fy = -r[0], -r[1]
        me = -(r[2] - _cross(px, py, r[0], r[1]))     # eqs 2.47-2.48
        _record(out, joint, drv.body, fx, fy, np.float64(px), np.float64(py))
        return DriverReaction("R", me)
    # sliding driver (eqs 2.49-2.51): Fe along the line through the slider point
    if joint.guide == GROUND:
        beta = np.deg2rad(joint.line_angle)
        ux, uy = np.cos(beta), np.sin(beta)
        sx, sy = m.point(scene.bodies[drv.body].local(joint.points[1]))
    else:
        ux, uy = 1.0, 0.0
        x, y = scene.ground[joint.points[1]]
        sx, sy = np.float64(x), np.float64(y)
    fe = -(r[0] * ux + r[1] * uy)
    nx, ny = -uy, ux
    fn = -(r[0] * nx + r[1] * ny)
    c = -(r[2] - _cross(sx, sy, r[0], r[1]))
    _record(out, joint, drv.body, fn * nx, fn * ny, sx, sy, fn, c)
    return DriverReaction("T", fe)
