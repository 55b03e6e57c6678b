"""Ballast: extra mass the solver sees on the driver's side, cancelled by a force.

pymunk's solver is Gauss-Seidel over the constraints. Along a chain whose driven end
is light and whose far end is heavy (the shaper: a 0.5 kg block between the crank and
a slotted lever that drives an 8 kg ram; the slotted crank's 0.3 kg block between the
crank and a 2 kg piston) each sweep passes only a small part of the driver's impulse
through the light bodies, and with ``error_bias = 0`` a short count does not just lose
accuracy, it blows up: the shaper needed 480 iterations with the driver's constraint
solved last (docs/simulation.md).

The ballast makes the driver's side heavy for the solver and leaves the motion that
of the scene. The driver's body and the bodies jointed to it are built with the mass
of the heaviest moving body (``ballast_plan``), a crank also with a moment of inertia
of that mass at the mechanism's size; before every step each such body gets the
force dm (a - g) at its centre of mass and the moment dI alpha (:func:`ballast_function`),
a and alpha the accelerations the step is about to give it, extrapolated from the
body's own last two steps (2 a_n - a_(n-1), a_n = (v_n - v_(n-1)) / dt). So
(m + dm) a = m g + F + dm a_pred: the body moves as a body of mass m up to the
extrapolation's error, dm (a_pred - a) = dm O(a'' dt^2), second order like the scheme
itself; a crank turning at constant speed has alpha = 0, so its extra inertia is not
felt at all. Nothing here comes from kinetostatics: the cancelling force is the
simulation's own, so the cross-check stays a check.

The extrapolation is a two-step recursion on the body's acceleration error e:
(m + dm) e_(n+1) = dm (2 e_n - e_(n-1)), whose roots have modulus sqrt(dm / (m + dm))
< 1: stable for any ballast, a transient (a load switching) dying as that per step.

Measured (pymunk 7.3.1, driver's constraint solved last, 2 revolutions, 360 readings;
the slowest converging count; docs/simulation.md): the shaper at 1800 steps per
revolution 240 to 320 iterations without ballast, 60 with it (4.7e-5; 1.2e-5 at 3600
steps, where without ballast 360 are needed); the slotted lever 60 -> 10; the
slotted crank (TRT) 60 -> 30. The four-bar, slider-crank and TRR slider-crank need as
few as before, with the same errors to 1e-6.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..model.scene import GROUND, Scene
from .reference import reference_solution

if TYPE_CHECKING:
    from .model import SimModel
    from .stepper import BodyAccess

__all__ = ["BALLAST_SIZE", "ballast_plan"]

BALLAST_SIZE = 1.0
"""A crank's moment of inertia is raised to the heaviest body's mass times this many
mechanism sizes squared (measured on the shaper: 0.3 kg m^2 and more, i.e. 0.1 of this,
all give the same result; 0.1 kg m^2 needs 60 iterations where 0.3 need 45)."""


def ballast_plan(scene: Scene,
                 translating: frozenset[str] | set[str] = frozenset()
                 ) -> dict[str, tuple[float, float]]:
    """The extra mass and moment of inertia of each ballasted body: ``name -> (dm, dI)``.

    The driver's body and every body sharing a joint with it get the mass of the
    heaviest moving body (dm = 0 where a body is already as heavy); the driver's body of
    a crank gets the moment of inertia that mass has at ``BALLAST_SIZE`` times the
    mechanism's size (:attr:`Scene.size`). Bodies that only translate
    (``translating``: built with an infinite moment of inertia) get no extra inertia.
    Bodies with neither are left out.
    """
    heaviest = max(b.mass for b in scene.bodies.values())
    d = scene.driver
    near = [d.body]
    for j in scene.joints.values():
        pair = j.on_by if j.kind == "R" else (j.guide, j.slider)
        if d.body in pair:
            near += [n for n in pair if n not in near and n != GROUND]
    plan: dict[str, tuple[float, float]] = {}
    for name in near:
        b = scene.bodies[name]
        dm = max(0.0, heaviest - b.mass)
        di = 0.0
        if name == d.body and d.kind == "R" and name not in translating:
            di = max(0.0, heaviest * (BALLAST_SIZE * scene.size) ** 2 - b.inertia)
        if dm > 0.0 or di > 0.0:
            plan[name] = (dm, di)
    return plan


def start_state(model: SimModel) -> dict[str, list[float]]:
    """For each ballasted body: the velocities one step before the start and the
    accelerations at the start, ``[vx, vy, w, ax, ay, alpha]`` (the exact kinematic
    state: the start carries v(t0) + a dt / 2, so one step earlier the scheme had
    v - a dt; the first prediction is then the exact acceleration)."""
    sc = model.scene
    if not model.ballast:
        return {}
    sol = reference_solution(sc, [model.start])
    dt = model.dt
    out = {}
    for name in model.ballast:
        m = sol.kin.bodies[name].take(slice(1, 2))
        b = sc.bodies[name]
        gx, gy = m.point(b.cog)
        ax, ay = (float(np.asarray(v).reshape(-1)[0]) for v in m.acc_at(gx, gy))
        al = float(np.asarray(m.alpha).reshape(-1)[0])
        body = model.bodies[name]
        vx, vy = body.velocity
        w = body.angular_velocity
        out[name] = [vx - ax * dt, vy - ay * dt, w - al * dt, ax, ay, al]
    return out


def ballast_function(model: SimModel, acc: BodyAccess):
    """The function that adds the ballast's cancelling forces before a step (None when
    nothing is ballasted). It adds to the forces the scene's loads have set, so it is
    called after them; its state (the last velocities and accelerations) lives in the
    model, so a model stepped by several runs carries on."""
    if not model.ballast:
        return None
    gx, gy = model.scene.gravity
    inv = 1.0 / model.dt
    get_v, get_w, get_f, get_t = acc.velocity, acc.omega, acc.force, acc.torque
    set_f, set_t = acc.set_force, acc.set_torque
    items = []
    for name, (dm, di) in model.ballast.items():
        items.append((acc.handle(model.bodies[name]), dm, di, model.ballast_state[name]))

    def add_ballast() -> None:
        for h, dm, di, st in items:
            v = get_v(h)
            vx, vy, w = v.x, v.y, get_w(h)
            ax, ay, al = (vx - st[0]) * inv, (vy - st[1]) * inv, (w - st[2]) * inv
            px, py, pal = 2.0 * ax - st[3], 2.0 * ay - st[4], 2.0 * al - st[5]
            st[0], st[1], st[2], st[3], st[4], st[5] = vx, vy, w, ax, ay, al
            if dm:
                f = get_f(h)
                set_f(h, (f.x + dm * (px - gx), f.y + dm * (py - gy)))
            if di:
                set_t(h, get_t(h) + di * pal)

    return add_ballast


def describe(plan: dict[str, tuple[float, float]]) -> str:
    """One line for the notes: which bodies carry how much ballast."""
    parts = []
    for name, (dm, di) in plan.items():
        bits = ([f"+{dm:.3g} kg"] if dm else []) + ([f"+{di:.3g} kg m^2"] if di else [])
        parts.append(f"{name} {' '.join(bits)}")
    return ", ".join(parts) if parts else "none"
