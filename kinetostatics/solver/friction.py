"""Friction in the joints (seed 002 s. 2.4), as loads added to the kinetostatic solve.

Scene extension (documented in ``docs/scene-extensions.md``): a joint may carry
``friction = { mu = 0.1, radius = 0.012 }`` (revolute: pin radius r) or
``friction = { mu = 0.1, length = 0.08 }`` (prismatic: the slider's bearing length,
optional). Without it a joint has no friction.

* At rest (no relative velocity in the joint at a row) the friction opposes the
  relative acceleration, the motion about to start; where both vanish its direction is
  undefined: no friction load there, and the row is flagged ``undefined_load``.
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
from the scene's loads and the columns of G from one solve per unit friction load, and
s = h(q0 + G s) with h the friction laws. :mod:`kinetostatics.solver.friction_rows`
solves that small system on each row's own scale (no global tolerance, no fixed-point
passes that stall as the friction feedback nears 1), following it from no friction to
the given coefficients: where several finite solutions exist (where a load drives the
motion, a large driving effort can also wedge a joint) the one continuous with the
frictionless motion is kept, and a row whose friction force grows without bound first
is self-locking (s. 2.4: no finite driving effort moves the mechanism; e.g. the
massless slider-crank where mu tan(psi) >= 1).
"""

from __future__ import annotations

import numpy as np

from ..model.errors import SelfLockingError
from ..model.scene import GROUND, Joint, Scene
from . import arith as A
from .friction_rows import Spec, settle
from .kinematics import Kinematics
from .loads import RESIST_STILL, PointLoad, motion_scales, resultants
from .reactions import DriverReaction, JointReaction, solve_reactions


def has_friction(scene: Scene) -> bool:
    """True when some joint carries a ``friction`` table."""
    return any(j.friction is not None and j.friction.mu > 0 for j in scene.joints.values())


def against_motion(vrel, arel, n: int, vscale: float = 0.0, ascale: float = 0.0
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The sign of a friction load, against the relative motion, and the rows where it
    has no direction.

    Where the joint moves, -sign(relative velocity). Where it is at rest (|vrel| at most
    1e-9 of its largest over the sweep or of the mechanism's scale ``vscale`` if larger:
    the same test as a ``resist`` point's), the friction opposes the motion about to
    start, -sign(relative acceleration); where that vanishes too (at most 1e-9 of its
    largest, or of ``ascale``), the direction is undefined: sign 0 and the row is
    flagged ``undefined_load`` (scene-format section 1, Results).
    """
    v = np.broadcast_to(np.asarray(vrel, dtype=float), (n,))
    a = np.broadcast_to(np.asarray(arel, dtype=float), (n,))
    vtop = max(float(np.abs(v).max()) if n else 0.0, vscale)
    atop = max(float(np.abs(a).max()) if n else 0.0, ascale)
    still = np.abs(v) <= RESIST_STILL * vtop
    if not still.any():
        return -np.sign(v), still
    quiet = np.abs(a) <= RESIST_STILL * atop
    sign = np.where(still, np.where(quiet, 0.0, -np.sign(a)), -np.sign(v))
    return sign, still & quiet


def _unit_loads(scene: Scene, kin: Kinematics, j: Joint
                ) -> tuple[list[PointLoad], np.ndarray]:
    """Friction loads of unit magnitude against the relative motion (at rest, against
    the relative acceleration: :func:`against_motion`), and the rows where the joint's
    friction has no direction (zero load there)."""
    n = kin.n
    out: list[PointLoad] = []
    if j.kind == "R":
        b0, b1 = j.bodies
        k0, k1 = kin.bodies[b0], kin.bodies[b1]
        # on b1, against omega_10 (at rest: against its angular acceleration)
        _, ws, _, als = motion_scales(scene)
        m1, undefined = against_motion(A.sub(k1.omega, k0.omega), A.sub(k1.alpha, k0.alpha), n,
                                       ws, als)
        for body, m in ((b1, m1), (b0, -m1)):
            if body != GROUND:
                out.append(PointLoad(body, "friction", 0.0, 0.0, 0.0, 0.0, m,
                                     f"friction couple in {j.name}"))
        return out, undefined
    g, s = kin.bodies[j.guide], kin.bodies[j.slider]
    if j.slider == GROUND:
        sx, sy = scene.ground[j.points[1]]
    else:
        sx, sy = s.point(scene.bodies[j.slider].local(j.points[1]))
    ux, uy = g.rotate(np.cos(j.beta), np.sin(j.beta))
    vsx, vsy = s.vel_at(sx, sy)
    vgx, vgy = g.vel_at(sx, sy)
    vrel = A.add(A.mul(ux, A.sub(vsx, vgx)), A.mul(uy, A.sub(vsy, vgy)))
    asx, asy = s.acc_at(sx, sy)
    agx, agy = g.acc_at(sx, sy)
    # at rest the Coriolis term 2 omega_g x v_rel vanishes: the relative acceleration
    # along the line is u . (a_slider - a_guide) at the slider point
    arel = A.add(A.mul(ux, A.sub(asx, agx)), A.mul(uy, A.sub(asy, agy)))
    vs, _, acs, _ = motion_scales(scene)
    f, undefined = against_motion(vrel, arel, n, vs, acs)   # on the slider, along u
    ffx, ffy = A.mul(f, ux), A.mul(f, uy)
    for body, sign in ((j.slider, 1.0), (j.guide, -1.0)):
        if body == GROUND:
            continue
        m = kin.bodies[body]
        out.append(PointLoad(body, "friction", A.sub(sx, m.ox), A.sub(sy, m.oy),
                             A.mul(sign, ffx), A.mul(sign, ffy), 0.0,
                             f"friction force in {j.name}"))
    return out, undefined


def _specs(scene: Scene, kin: Kinematics) -> tuple[list[Spec], np.ndarray]:
    """The joints with friction, and the rows where some friction has no direction."""
    out = []
    undefined = np.zeros(kin.n, dtype=bool)
    for j in scene.joints.values():
        fr = j.friction
        if fr is None or fr.mu == 0.0 or (j.kind == "R" and fr.radius == 0.0):
            continue                    # no friction (a pin of radius 0 has none)
        unit, still = _unit_loads(scene, kin, j)
        undefined |= still
        if j.kind == "R":
            out.append(Spec(j, fr.radius * fr.mu, 0.0, 2, unit))
        else:
            out.append(Spec(j, fr.mu, fr.length, 2 if fr.length > 0.0 else 1, unit))
    return out, undefined


def _quantities(spec: Spec, r: JointReaction, n: int) -> list[np.ndarray]:
    """The reaction quantities the joint's friction reads: (Fx, Fy), (N, M) or (N,)."""
    if spec.joint.kind == "R":
        return list(r.force(n))
    nn = np.broadcast_to(r.N, (n,))
    return [nn, np.broadcast_to(r.M, (n,))] if spec.width == 2 else [nn]


def _scaled_loads(specs: list[Spec], s: np.ndarray) -> list[PointLoad]:
    """The friction loads of magnitudes s (k, n) (NaN where a row has no value)."""
    out = []
    for j, sp in enumerate(specs):
        for u in sp.unit:
            out.append(PointLoad(u.body, u.kind, u.rx, u.ry, A.mul(u.fx, s[j]),
                                 A.mul(u.fy, s[j]), A.mul(u.m, s[j]), u.label))
    return out


def _lock_message(scene: Scene, pos: np.ndarray, specs: list[Spec], lam: np.ndarray,
                  dirn: np.ndarray) -> str:
    """One line for a sweep that locks at every position (``pos``)."""
    unit = "deg" if scene.driver.kind == "R" else "m"
    best = int(np.argmax(lam))
    sp = specs[int(np.argmax(dirn[:, best]))]
    mu = sp.joint.friction.mu
    where = (f"at every position ({pos.min():g} to {pos.max():g} {unit})" if pos.size > 1 else
             f"at position {pos[0]:g} {unit}")
    others = "" if len(specs) == 1 else " (every friction coefficient scaled alike)"
    return (f"the mechanism self-locks {where}: the friction in joint '{sp.joint.name}' "
            f"(mu = {mu:g}) jams it; it would move at position {pos[best]:g} {unit} with "
            f"mu below {lam[best] * mu:.6g}{others}, and at every position below "
            f"{float(lam.min()) * mu:.6g}")


def solve_with_friction(scene: Scene, kin: Kinematics, loads: list[PointLoad]
                        ) -> tuple[dict[str, JointReaction], DriverReaction, list[PointLoad],
                                   np.ndarray, np.ndarray]:
    """Reactions and Me with joint friction, each row solved on its own scale.

    Returns the reactions, the driver's Me/Fe, the friction loads, the
    ``self_locking`` mask (rows where no finite driving effort moves the mechanism;
    their Me/Fe, reactions and friction loads are NaN) and the rows where some joint's
    friction has no direction (at rest with no relative acceleration either: its load
    is zero there, the row is flagged ``undefined_load``).

    Raises
    ------
    SelfLockingError
        If every row locks: the message names the joint and the coefficient below
        which the mechanism would move.
    WorkbenchError
        If some row's friction equations cannot be followed (never met in practice).
    """
    n = kin.n
    specs, undefined = _specs(scene, kin)
    base, drive = solve_reactions(kin, resultants(loads, scene.bodies, n))
    if not specs:                       # only pins of radius 0: no friction at all
        return base, drive, [], np.zeros(n, dtype=bool), undefined
    m = sum(sp.width for sp in specs)
    q0 = np.empty((m, n))
    g = np.empty((m, len(specs), n))        # column j: the response to joint j's unit load
    for i, q in enumerate(q for sp in specs for q in _quantities(sp, base[sp.joint.name], n)):
        q0[i] = q
    for j, sp in enumerate(specs):
        unit, _ = solve_reactions(kin, resultants(sp.unit, scene.bodies, n))
        for i, q in enumerate(q for sp2 in specs for q in _quantities(sp2, unit[sp2.joint.name],
                                                                      n)):
            g[i, j] = q
    s, locked, lam, dirn = settle(specs, q0, g, np.broadcast_to(kin.positions, (n,)))
    if locked.all():
        raise SelfLockingError(_lock_message(scene, kin.positions, specs, lam, dirn))
    fl = _scaled_loads(specs, s)
    reactions, drive = solve_reactions(kin, resultants(loads + fl, scene.bodies, n))
    if locked.any():
        reactions = {name: _blank(r, locked, n) for name, r in reactions.items()}
        drive = DriverReaction(drive.kind, np.where(locked, np.nan, drive.value))
    return reactions, drive, fl, locked, undefined


def _blank(r: JointReaction, rows: np.ndarray, n: int) -> JointReaction:
    """The reaction with NaN at ``rows`` (they have no value there)."""
    def nan(a):
        return None if a is None else np.where(rows, np.nan, np.broadcast_to(a, (n,)))
    return JointReaction(r.joint, r.on, r.by, nan(r.fx), nan(r.fy), nan(r.N), nan(r.M),
                         r.x, r.y, r.sign)
