"""The scene's loads in the simulation: folded per body when the model is built, and set
on the bodies before every step, evaluated at the pose the step will reach."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .reference import reference_solution

__all__ = ["RESIST_UNSURE", "SWITCH_SETTLE"]

if TYPE_CHECKING:
    from .model import SimModel
    from .stepper import BodyAccess

RESIST_UNSURE = 1e-4
"""Rows where a ``resist`` point is slower than this fraction of its top speed: the
step's estimate of the velocity's direction may be wrong there; flagged."""

SWITCH_SETTLE = 16
"""Steps after a ``when = "resisting"`` force switches on or off whose readings are
flagged: the step change of the load excites a transient of the scheme that falls by
about 8x every two steps whatever dt is (3e-2 of the scale at the switch, 1e-6 after
about 12 steps, measured on the bundled shaper)."""

SWITCH_BOOST = 64
"""Steps after such a switch that the solver runs with more iterations
(``kinetostatics.simulation.stepper.SWITCH_ITERATIONS``): a short count damps the
switch's transient slowly (the shaper at 120 iterations: 8e-2 of the scale three
degrees after the switch) or lets it grow."""



def prepare_loads(model: SimModel, sweep) -> None:
    """Per body, the constant loads folded into F and a moment c A + s B + M (the
    moment of fixed global forces at body points turns with the body); ``resist``
    loads kept apart (their direction follows the point's velocity), with the top
    speed of their point over the motion, and so are forces with ``when =
    "resisting"`` (on only while their power is negative), with their top power."""
    sc = model.scene
    per: dict[str, list[float]] = {}
    resist = []
    kin = sweep.kin
    for ld in sc.loads:
        b = sc.bodies[ld.body]
        acc = per.setdefault(ld.body, [0.0, 0.0, 0.0, 0.0, 0.0])   # Fx, Fy, A, B, M
        acc[4] += ld.moment
        if ld.point is None:
            continue
        px, py = (np.asarray(b.local(ld.point)) - np.asarray(b.cog)).tolist()
        if ld.resist is not None or ld.when == "resisting":
            m = kin.bodies[ld.body]
            x, y = m.point(b.local(ld.point))
            vx, vy = (np.broadcast_to(v, (kin.n,)) for v in m.vel_at(x, y))
            if ld.resist is not None:
                top = float(np.max(np.hypot(vx, vy)))
                resist.append((ld.body, px, py, float(ld.resist), top))
            else:           # a force on the working stroke only: kept with its top power
                fx, fy = ld.force
                top = float(np.max(np.abs(fx * vx + fy * vy)))
                resist.append((ld.body, px, py, (float(fx), float(fy)), top))
            continue
        fx, fy = ld.force
        acc[0] += fx
        acc[1] += fy
        acc[2] += px * fy - py * fx
        acc[3] += -(py * fy + px * fx)
    model.body_loads = [(model.bodies[name], *v) for name, v in per.items()]
    model.resist_loads = [(model.bodies[name], *rest) for name, *rest in resist]


def _start_acc(model: SimModel) -> list[tuple[float, float, float]]:
    """Exact accelerations (cog, angular) at the start of the bodies carrying resist loads."""
    sc = model.scene
    sol = reference_solution(sc, [model.start])
    out = []
    for body, *_ in model.resist_loads:
        name = next(n for n, b in model.bodies.items() if b is body)
        m = sol.kin.bodies[name].take(slice(1, 2))
        b = sc.bodies[name]
        gx, gy = m.point(b.cog)
        ax, ay = m.acc_at(gx, gy)
        out.append(tuple(float(np.asarray(v).reshape(-1)[0]) for v in (ax, ay, m.alpha)))
    return out


def loads_function(model: SimModel, acc: BodyAccess):
    """The function that sets the scene's loads before a step (None if only gravity),
    and a one-element list that it sets True when a ``resist`` point is nearly still.

    Constant loads on a body: F, and the moment cos(a) A + sin(a) B + M at the angle a
    the body will have after the step (a + omega dt). ``resist`` loads: the point's
    velocity at the pose the step reaches, extrapolated to second order from the last
    two steps' velocities (1.5 v_n - 0.5 v_(n-1)); the force is opposite to it.
    """
    unsure = [False]
    per = _loads_by_body(model)
    if not per:
        return None, unsure
    funcs = [_body_function(model, acc, d, unsure) for d in per.values()]
    if len(funcs) == 1:
        return funcs[0], unsure

    def apply_all() -> None:
        for f in funcs:
            f()

    return apply_all, unsure


def _loads_by_body(model: SimModel) -> dict[int, dict]:
    """The loads grouped by body: its constant force and moment terms
    ``(fx, fy, A, B, M)`` and its ``resist`` points with their start accelerations."""
    per: dict[int, dict] = {}
    for b, fx, fy, ca, cb, mm in model.body_loads:
        per[id(b)] = {"body": b, "const": (fx, fy, ca, cb, mm), "resist": []}
    for (b, px, py, mag, top), (ax, ay, al) in zip(model.resist_loads, _start_acc(model),
                                                    strict=True):
        d = per.setdefault(id(b), {"body": b, "const": (0.0, 0.0, 0.0, 0.0, 0.0),
                                   "resist": []})
        d["resist"].append((px, py, mag, top, ax, ay, al))
    return per


def _body_function(model: SimModel, acc: BodyAccess, d: dict, unsure: list):
    """The function that sets one body's loads: constant ones only, one resist force at
    the centre of mass of a body with no moment, or the general case."""
    h = acc.handle(d["body"])
    ca, cb, mm = d["const"][2:]
    if not d["resist"]:
        return _constant_loads(model, acc, h, d["const"])
    # the start carries v(t0) + a dt / 2; one step earlier the scheme had a dt less
    dt = model.dt
    v = acc.velocity(h)
    w0 = acc.omega(h)
    res = d["resist"]
    first = res[0]
    prev = [v.x - first[4] * dt, v.y - first[5] * dt, w0 - first[6] * dt]
    arms = [(px, py, mag, top) for px, py, mag, top, *_ in res]
    turning = bool(ca or cb or any(px or py for px, py, *_ in res))
    if not turning and not mm and len(arms) == 1 and not isinstance(arms[0][2], tuple):
        return _resist_at_centre(acc, h, d["const"], arms[0], prev, unsure)
    return _resist_loads(model, acc, h, d["const"], arms, prev, turning, unsure)


def _constant_loads(model: SimModel, acc: BodyAccess, h, const: tuple):
    """F, and the moment cos(a) A + sin(a) B + M at the angle after the step."""
    dt = model.dt
    get_a, get_w = acc.angle, acc.omega
    set_f, set_t = acc.set_force, acc.set_torque
    cos, sin = math.cos, math.sin
    fx0, fy0, ca, cb, mm = const
    f0 = (fx0, fy0)

    def apply_const() -> None:
        a = get_a(h) + get_w(h) * dt
        set_f(h, f0)
        set_t(h, cos(a) * ca + sin(a) * cb + mm)

    return apply_const


def _resist_at_centre(acc: BodyAccess, h, const: tuple, arm: tuple, prev: list,
                      unsure: list):
    """One resist force at the centre of mass of a body with no other moment (a
    piston): no angle, no angular velocity, no torque needed."""
    get_v, set_f, hypot = acc.velocity, acc.set_force, math.hypot
    fx0, fy0 = const[:2]
    _, _, mag, top = arm
    still = RESIST_UNSURE * top

    def apply_point() -> None:
        v = get_v(h)
        vx, vy = v.x, v.y
        ex, ey = 1.5 * vx - 0.5 * prev[0], 1.5 * vy - 0.5 * prev[1]
        prev[0], prev[1] = vx, vy
        sp = hypot(ex, ey)
        unsure[0] = sp <= still
        if sp > 0.0:
            set_f(h, (fx0 - mag * ex / sp, fy0 - mag * ey / sp))
        else:
            set_f(h, (fx0, fy0))

    return apply_point


def _resist_loads(model: SimModel, acc: BodyAccess, h, const: tuple, arms: list,
                  prev: list, turning: bool, unsure: list):
    """Resist forces at points of a body (or gated ``when = "resisting"`` forces, whose
    switch starts a transient of more solver iterations), with its constant loads."""
    dt = model.dt
    get_a, get_w, get_v = acc.angle, acc.omega, acc.velocity
    set_f, set_t = acc.set_force, acc.set_torque
    cos, sin, hypot = math.cos, math.sin, math.hypot
    fx0, fy0, ca, cb, mm = const
    gated_on = [None] * len(arms)       # when = "resisting": on at the last step
    settle = [0]                        # steps left in a switch's transient
    boost = model.boost                # steps left with more solver iterations

    def apply_resist() -> None:
        v = get_v(h)
        w = get_w(h)
        vx, vy = v.x, v.y
        ex, ey = 1.5 * vx - 0.5 * prev[0], 1.5 * vy - 0.5 * prev[1]
        ew = 1.5 * w - 0.5 * prev[2]
        prev[0], prev[1], prev[2] = vx, vy, w
        fx, fy, t = fx0, fy0, mm
        c = s = 0.0
        if turning:
            a = get_a(h) + w * dt
            c, s = cos(a), sin(a)
            t += c * ca + s * cb
        flag = settle[0] > 0
        if flag:
            settle[0] -= 1
        for k, (px, py, mag, top) in enumerate(arms):
            rx, ry = c * px - s * py, s * px + c * py
            qx, qy = ex - ew * ry, ey + ew * rx
            if isinstance(mag, tuple):          # when = "resisting": on while F.v < 0
                gx, gy = mag
                power = gx * qx + gy * qy
                if abs(power) <= RESIST_UNSURE * top:
                    flag = True
                on = power < 0.0
                if gated_on[k] is not None and on != gated_on[k]:
                    settle[0] = SWITCH_SETTLE
                    boost[0] = SWITCH_BOOST
                    flag = True
                gated_on[k] = on
                if on:
                    fx += gx
                    fy += gy
                    t += rx * gy - ry * gx
                continue
            sp = hypot(qx, qy)
            if sp <= RESIST_UNSURE * top:
                flag = True
            if sp > 0.0:
                gx, gy = -mag * qx / sp, -mag * qy / sp
                fx += gx
                fy += gy
                t += rx * gy - ry * gx
        set_f(h, (fx, fy))
        if turning or mm:
            set_t(h, t)
        unsure[0] = flag

    return apply_resist
