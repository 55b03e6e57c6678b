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

The friction loads depend on the reactions, which depend on them: the solve is
repeated with the friction of the previous pass until nothing changes (a contraction
for the usual mu; rows that do not settle are reported as self-locking: the reactions
grow without bound there, the motion cannot be driven, s. 2.4).
"""

from __future__ import annotations

import numpy as np

from ..model.scene import GROUND, Scene
from . import _arith as A
from .kinematics import Kinematics
from .loads import PointLoad, resultants
from .reactions import DriverReaction, JointReaction, solve_reactions

MAX_PASSES = 200
TOLERANCE = 1e-13


def has_friction(scene: Scene) -> bool:
    """True when some joint carries a ``friction`` table."""
    return any(j.friction is not None and j.friction.mu > 0 for j in scene.joints.values())


def friction_loads(scene: Scene, kin: Kinematics, reactions: dict[str, JointReaction]
                   ) -> list[PointLoad]:
    """The friction couples (revolute) and forces (prismatic) for the given reactions."""
    n = kin.n
    out: list[PointLoad] = []
    for name, j in scene.joints.items():
        fr = j.friction
        if fr is None or fr.mu == 0.0:
            continue
        r = reactions[name]
        fx, fy = r.force(n)
        if j.kind == "R":
            rho = fr.radius * fr.mu                                   # eq. 2.62
            b0, b1 = j.bodies
            w0 = np.broadcast_to(kin.bodies[b0].omega, (n,))
            w1 = np.broadcast_to(kin.bodies[b1].omega, (n,))
            m1 = -rho * np.hypot(fx, fy) * np.sign(w1 - w0)           # on b1, against w10
            for body, m in ((b1, m1), (b0, -m1)):
                if body != GROUND:
                    out.append(PointLoad(body, "friction", 0.0, 0.0, 0.0, 0.0, m,
                                         f"friction couple in {name}"))
            continue
        nn = np.broadcast_to(r.N, (n,))
        if fr.length > 0.0:                                           # eqs 2.63-2.65
            mm = np.broadcast_to(r.M, (n,))
            normal = np.abs(0.5 * nn - mm / fr.length) + np.abs(0.5 * nn + mm / fr.length)
        else:
            normal = np.abs(nn)
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
        f = -fr.mu * normal * np.sign(vrel)                           # on the slider, along u
        ffx, ffy = A.mul(f, ux), A.mul(f, uy)
        for body, sign in ((j.slider, 1.0), (j.guide, -1.0)):
            if body == GROUND:
                continue
            m = kin.bodies[body]
            out.append(PointLoad(body, "friction", A.sub(sx, m.ox), A.sub(sy, m.oy),
                                 A.mul(sign, ffx), A.mul(sign, ffy), 0.0,
                                 f"friction force in {name}"))
    return out


def solve_with_friction(scene: Scene, kin: Kinematics, loads: list[PointLoad]
                        ) -> tuple[dict[str, JointReaction], DriverReaction, list[PointLoad],
                                   np.ndarray]:
    """Reactions and Me with joint friction by repeated solves.

    Returns the reactions, the driver's Me/Fe, the friction loads of the last pass and
    the ``self_locking`` mask (rows whose passes did not settle).
    """
    n = kin.n
    reactions, drive = solve_reactions(kin, resultants(loads, scene.bodies, n))
    prev = np.asarray(drive.value, dtype=float)
    settled = np.zeros(n, dtype=bool)
    fl: list[PointLoad] = []
    for _ in range(MAX_PASSES):
        fl = friction_loads(scene, kin, reactions)
        reactions, drive = solve_reactions(kin, resultants(loads + fl, scene.bodies, n))
        cur = np.asarray(drive.value, dtype=float)
        scale = max(float(np.max(np.abs(cur))), 1e-300)
        change = np.abs(cur - prev)
        settled = change <= TOLERANCE * scale
        prev = cur
        if settled.all():
            break
    return reactions, drive, fl, ~settled
