"""Joint friction in the simulation: the same laws as kinetostatics (seed 002 s. 2.4), set
on the bodies before every step from the reactions pymunk measured in the steps before.

- A revolute joint with ``friction = {mu, radius}``: a couple rho |F| (rho = mu r, the
  friction circle, eq. 2.62) on each of its bodies against their relative rotation.
- A prismatic joint with ``friction = {mu}``: a force mu |N| along the line against the
  relative sliding, on the slider at its slider point and the opposite on the guide.

pymunk's constraints do not know these loads, so they are applied as external loads:
|F| (|N|) is the joint's constraint impulse over dt, read after each step and
extrapolated to the step about to be taken (2 F_n - F_(n-1)); the direction comes from
the relative velocity extrapolated the same way as a ``resist`` load's (1.5 v_n -
0.5 v_(n-1)). A one-step lag alone costs about 2e-4 of Me on the four-bar; extrapolated,
the errors are those of the frictionless run (1e-5 at 3600 steps per revolution).

Where a joint's relative motion reverses, its friction flips: the step change excites
the scheme's transient (as a ``when = "resisting"`` force's switch does), and near the
reversal kinetostatics' own direction is uncertain. Readings within ``SWITCH_SETTLE``
steps after a flip, or where the relative speed is below ``RESIST_UNSURE`` of its top,
are flagged and left out of the errors.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..model.scene import GROUND
from .loads import RESIST_UNSURE, SWITCH_BOOST, SWITCH_SETTLE
from .reference import reference_solution

__all__: list[str] = []          # used by the other simulation modules only

if TYPE_CHECKING:
    from .model import SimModel
    from .stepper import BodyAccess


def rubbing_joints(scene) -> list[str]:
    """Joints whose friction the simulation applies (mu > 0; a pin of radius 0 has none)."""
    return [n for n, j in scene.joints.items() if j.friction is not None and j.friction.mu > 0
            and not (j.kind == "R" and j.friction.radius == 0.0)]


def relative_velocity(scene, kin, name: str) -> np.ndarray:
    """The relative angular velocity (revolute: of its second body against its first) or
    sliding speed (prismatic: of the slider along the guide's line) of a joint over a
    solved sweep."""
    j = scene.joints[name]
    n = kin.n

    def omega(body):
        return np.zeros(n) if body == GROUND else np.broadcast_to(kin.bodies[body].omega, (n,))

    if j.kind == "R":
        b0, b1 = j.bodies
        return omega(b1) - omega(b0)
    g, s = j.guide, j.slider
    sp = scene.ground[j.points[1]] if s == GROUND else scene.bodies[s].local(j.points[1])
    if s == GROUND:
        sx, sy = np.full(n, sp[0]), np.full(n, sp[1])
    else:
        sx, sy = (np.broadcast_to(v, (n,)) for v in kin.bodies[s].point(sp))
    beta = j.beta
    if g == GROUND:
        ux, uy = np.full(n, math.cos(beta)), np.full(n, math.sin(beta))
    else:
        ux, uy = (np.broadcast_to(v, (n,)) for v in kin.bodies[g].rotate(math.cos(beta),
                                                                           math.sin(beta)))
    vel = []
    for body in (s, g):
        if body == GROUND:
            vel.append((np.zeros(n), np.zeros(n)))
        else:
            vel.append(tuple(np.broadcast_to(v, (n,)) for v in kin.bodies[body].vel_at(sx, sy)))
    (vsx, vsy), (vgx, vgy) = vel
    return ux * (vsx - vgx) + uy * (vsy - vgy)


def prepare_friction(model: SimModel, sweep) -> None:
    """Record, per rubbing joint, what the stepping loop needs: its constraint, bodies,
    coefficient, geometry, the top relative speed over the motion, and the friction
    load's magnitude at the start (from kinetostatics with friction)."""
    sc = model.scene
    names = rubbing_joints(sc)
    if not names:
        model.joint_friction = []
        return
    start = reference_solution(sc, [model.start]).reactions
    out = []
    for name in names:
        j = sc.joints[name]
        info = next(i for i in model.constraints if i.joint == name
                    and i.role in ("pivot", "groove"))
        top = float(np.max(np.abs(relative_velocity(sc, sweep.kin, name))))
        f0 = float(start[start.joint == name].F.to_numpy()[1])
        if j.kind == "R":
            b0, b1 = j.bodies
            out.append(("R", name, info.constraint, b0, b1, j.friction.radius * j.friction.mu,
                        top, f0, None))
        else:
            g, s = j.guide, j.slider
            sp = sc.ground[j.points[1]] if s == GROUND else sc.bodies[s].local(j.points[1])
            beta = j.beta
            out.append(("T", name, info.constraint, g, s, j.friction.mu, top, f0,
                        (sp, (math.cos(beta), math.sin(beta)))))
    model.joint_friction = out


def friction_function(model: SimModel, acc: BodyAccess, unsure: list):
    """Two functions, or None without friction: one that adds the joints' friction loads
    to the bodies before a step (after the scene's loads are set; it sets ``unsure[0]``
    where a reading must be left out, module docstring), and one that reads the joints'
    reactions after the step."""
    if not getattr(model, "joint_friction", None):
        return None
    dt = model.dt
    get_t, set_t, get_i = acc.torque, acc.set_torque, acc.impulse
    copysign = math.copysign
    joints = _friction_joints(model, acc)
    settle = [0]
    boost = model.boost                 # steps left with more solver iterations
    relative = _relative_speed(acc, dt)
    push = _push(acc)

    def apply_friction() -> None:
        flag = settle[0] > 0
        if flag:
            settle[0] -= 1
        for kind, _hc, ha, hb, coeff, still, cogs, geo, st in joints:
            fp = 2.0 * st[1] - st[0]                    # |F| or |N| extrapolated
            rel, arms = relative(kind, ha, hb, cogs, geo)
            prev = st[2] if st[2] is not None else rel
            st[2] = rel
            pred = 1.5 * rel - 0.5 * prev
            sign = (pred > 0.0) - (pred < 0.0)
            if sign != st[3] and st[3] != 0:
                settle[0] = SWITCH_SETTLE
                boost[0] = SWITCH_BOOST
                flag = True
            st[3] = sign
            if abs(pred) <= still:
                flag = True
            if sign:
                load = -copysign(coeff * fp, pred)
                if kind == "R":                         # a couple on b, the opposite on a
                    if hb is not None:
                        set_t(hb, get_t(hb) + load)
                    if ha is not None:
                        set_t(ha, get_t(ha) - load)
                else:                                   # a force along the line at S
                    ux, uy, sxr, syr, gxr, gyr = arms
                    if hb is not None:                  # b: the slider
                        push(hb, load * ux, load * uy, sxr, syr)
                    if ha is not None:                  # a: the guide
                        push(ha, -load * ux, -load * uy, gxr, gyr)
        if flag:
            unsure[0] = True

    def read_after_step() -> None:
        for j in joints:
            st = j[-1]
            st[0], st[1] = st[1], abs(get_i(j[1])) / dt

    return apply_friction, read_after_step


def _friction_joints(model: SimModel, acc: BodyAccess) -> list[tuple]:
    """Per joint with friction: its kind, constraint and bodies' handles (None: the
    ground), the friction coefficient, the relative speed under which a reading is
    unsure, the bodies' centres of mass, the guide's geometry and the state ``[F_(n-1),
    F_n, last relative velocity, last sign]``."""
    H = acc.handle
    bodies = model.bodies
    joints = []
    for kind, _name, con, a, b, coeff, top, f0, geo in model.joint_friction:
        ha = None if a == GROUND else H(bodies[a])
        hb = None if b == GROUND else H(bodies[b])
        cogs = tuple((0.0, 0.0) if x == GROUND else tuple(bodies[x].center_of_gravity)
                     for x in (a, b))
        joints.append((kind, acc.chandle(con), ha, hb, coeff, RESIST_UNSURE * top, cogs, geo,
                       [f0, f0, None, 0]))
    return joints


def _push(acc: BodyAccess):
    """A function adding the force (fx, fy) at the arm (rx, ry) from a body's centre of
    mass to the body's force and torque."""
    get_f, get_t, set_f, set_t = acc.force, acc.torque, acc.set_force, acc.set_torque

    def push(h, fx, fy, rx, ry):
        f = get_f(h)
        set_f(h, (f.x + fx, f.y + fy))
        set_t(h, get_t(h) + rx * fy - ry * fx)
    return push


def _relative_speed(acc: BodyAccess, dt: float):
    """A function giving a joint's relative speed (rad/s of b against a in a revolute
    joint; m/s of the slider b along the guide a in a prismatic one) and, for a prismatic
    joint, the line and the arms at the pose the step reaches (the loads act there: see
    :mod:`kinetostatics.simulation.loads`)."""
    get_a, get_w, get_v, get_p = acc.angle, acc.omega, acc.velocity, acc.position
    cos, sin = math.cos, math.sin

    def ahead(h, cog):
        """A body's centre of mass and angle at the pose the step will reach (x + v dt)."""
        p, ang, v, w = get_p(h), get_a(h), get_v(h), get_w(h)
        c, s = cos(ang), sin(ang)
        return (p.x + c * cog[0] - s * cog[1] + v.x * dt,
                p.y + s * cog[0] + c * cog[1] + v.y * dt, ang + w * dt, v, w)

    def relative(kind, ha, hb, cogs, geo):
        if kind == "R":
            return (0.0 if hb is None else get_w(hb)) - (0.0 if ha is None else get_w(ha)), None
        (sp, (ux0, uy0)) = geo
        hs, hg = hb, ha                         # b: the slider, a: the guide
        if hs is None:
            sx, sy, sxr, syr = sp[0], sp[1], 0.0, 0.0
            vsx = vsy = 0.0
        else:
            cx, cy, ang, v, w = ahead(hs, cogs[1])
            lx, ly = sp[0] - cogs[1][0], sp[1] - cogs[1][1]
            sxr, syr = cos(ang) * lx - sin(ang) * ly, sin(ang) * lx + cos(ang) * ly
            sx, sy = cx + sxr, cy + syr
            vsx, vsy = v.x - w * syr, v.y + w * sxr
        if hg is None:
            ux, uy, gxr, gyr = ux0, uy0, 0.0, 0.0
            vgx = vgy = 0.0
        else:
            cx, cy, ang, v, w = ahead(hg, cogs[0])
            ux, uy = cos(ang) * ux0 - sin(ang) * uy0, sin(ang) * ux0 + cos(ang) * uy0
            gxr, gyr = sx - cx, sy - cy
            vgx, vgy = v.x - w * gyr, v.y + w * gxr
        return ux * (vsx - vgx) + uy * (vsy - vgy), (ux, uy, sxr, syr, gxr, gyr)
    return relative


def near_reversals(scene, kin, times: np.ndarray, dt: float) -> np.ndarray:
    """Rows (of a solution whose row 0 is left out, at ``times``) within ``SWITCH_SETTLE``
    steps of a reversal of some rubbing joint's relative motion in the exact kinematics:
    there the friction flips and the simulation passes it a step early or late."""
    out = np.zeros(times.size, dtype=bool)
    window = SWITCH_SETTLE * dt
    for name in rubbing_joints(scene):
        rel = np.broadcast_to(relative_velocity(scene, kin, name), (times.size + 1,))[1:]
        for i in np.flatnonzero(np.sign(rel[:-1]) != np.sign(rel[1:])):
            den = rel[i] - rel[i + 1]
            f = rel[i] / den if den != 0.0 else 0.5
            t_flip = times[i] + f * (times[i + 1] - times[i])
            out |= np.abs(times - t_flip) <= window
    return out
