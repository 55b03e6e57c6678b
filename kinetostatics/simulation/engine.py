"""A pymunk model of a mechanism scene, and the run that measures its joint reactions.

The cross-check of issue 5 (SPEC, "simulation cross-check"): the same scene that
:func:`kinetostatics.solve` takes is turned into a pymunk ``Space`` with only what the
physics needs, driven at the scene's constant speed, and the reactions are read from
the constraints while it moves.

What is built (:func:`build_space`)
-----------------------------------
- one dynamic body per moving body: mass, moment of inertia about the centre of mass
  and the centre of mass from the scene; no shapes (nothing collides), no sleeping.
  A body that only translates (its angle is constant over the motion: a piston, a
  yoke, a ram) gets an infinite moment of inertia, which is exact for it;
- a ``PivotJoint`` per revolute joint;
- a ``GrooveJoint`` per prismatic joint, laid out so that pymunk's solution of it is
  exact (see :func:`build_space`), plus a ``GearJoint`` of ratio 1 that locks the
  slider's rotation to the guide's where both turn (between bodies that cannot turn
  no lock is needed);
- a crank driver: a ``PivotJoint`` and a ``SimpleMotor`` that holds the speed (its
  impulse is the driving moment); a sliding driver: a kinematic body moving at the
  constant speed along the line and a ``GrooveJoint`` across the line, through the
  slider point, that pushes the slider (its impulse is the driving force);
- gravity as the space's gravity; the scene's loads set on the bodies before every
  step, evaluated at the pose the step will reach.

Every constraint has ``error_bias = 0`` (the whole drift corrected in the next step),
``max_bias`` infinite, ``collide_bodies`` off. See ``docs/simulation.md`` for the
measured effect of these settings and of the iteration count.

How a step works and what is measured
-------------------------------------
``Space.step(dt)`` first moves every body with its present velocity (x += v dt,
angle += omega dt), then adds gravity and the forces set on the bodies to the
velocities, then lets the constraints apply the impulses that make the velocities
consistent with the new pose; forces are cleared afterwards. The impulses of a step
are therefore the reactions at the pose the step reaches, and the loads must be
evaluated at that pose (``x + v dt``), not at the pose before the step.

``constraint.impulse / dt`` is the magnitude of a reaction (public API). The signed
values (the reaction vectors, the normal force and couple of a slider, and the sign
of the driving moment, i.e. of the power the motor delivers) are derived from the
momentum balance of every body over the step: m (v' - v) / dt = m g + F + sum of the
constraint forces, I (w' - w) / dt = T + sum of their moments, with the constraint
forces along the directions pymunk uses at the new pose (public state only: poses,
velocities and the forces we set). For a driver + dyads chain these 3n equations have
exactly 3n unknowns (a prismatic joint between bodies that cannot turn contributes its
couple as an unknown, with no pymunk constraint); the magnitudes of the solution are
checked against the public impulses at run time (:attr:`SimRecord.vector_check`).

The stepping loop can call Chipmunk's C functions directly (``fast``, pinned to
pymunk 7.3.1 and checked against the public properties during the run): the same
calls as pymunk's properties, without the Python wrappers, two to three times faster.

The start is the exact kinematic state of the scene (from the kinematic solution),
shifted half a step as the scheme carries it in its steady motion (positions
x - a dt^2 / 2, velocities v + a dt / 2): no start-up transient.

Batches of runs (a study's settings, many scenes, a balancing machine's runs) go
through :func:`run_batch`: one process per core by default, in this process with
``executor="serial"``, or through any ``concurrent.futures.Executor``.
"""

from __future__ import annotations

import copy
import math
import os
import time
from collections.abc import Callable, Iterable
from concurrent.futures import Executor, ProcessPoolExecutor
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pymunk

from ..model.errors import WorkbenchError
from ..model.scene import GROUND, Scene, load_scene

PYMUNK_VERSION = "7.3.1"
"""The pymunk version the settings were measured with (docs/simulation.md)."""

DEFAULT_ITERATIONS = 30
"""Solver iterations: about 10 suffice for a four-bar, about 30 for a slider-crank
(fewer make ``error_bias = 0`` diverge); more change nothing but cost."""

DEFAULT_STEPS_PER_REVOLUTION = 3600
"""Default time step: a tenth of a degree of the crank per step (errors near 1e-5 on
the bundled four-bar and slider-crank; they fall as dt^2)."""

GROOVE_MARGIN = 10.0
"""A groove reaches this many times the slider's stroke (at least 1 m) beyond it."""

WARMUP_STEPS = 50
WARMUP_ITERATIONS = 200
"""The first steps of a fresh model: the iterations fall geometrically from 200 to the
chosen count over 50 steps. The solver's cached impulses start at zero; with, say, 10
iterations from the start they take a few hundred steps to settle (errors near 1e-2
on the first readings), and an abrupt change of the count leaves a transient too."""

RESIST_UNSURE = 1e-4
SWITCH_SETTLE = 16
"""Steps after a ``when = "resisting"`` force switches on or off whose readings are
flagged: the step change of the load excites a transient of the scheme that falls by
about 8x every two steps whatever dt is (3e-2 of the scale at the switch, 1e-6 after
about 12 steps, measured on the bundled shaper)."""
"""Rows where a ``resist`` point is slower than this fraction of its top speed: the
step's estimate of the velocity's direction may be wrong there; flagged."""


class SimulationError(WorkbenchError):
    """A scene that the simulation cannot reproduce (or a bad simulation setting)."""


# ----------------------------------------------------------------------------- model
@dataclass
class ConstraintInfo:
    """One pymunk constraint and what it measures.

    ``role`` is ``"pivot"`` (revolute joint: the force on body ``b`` from ``a``),
    ``"groove"`` (prismatic joint: the force on ``b``, the pin body, along the groove's
    left normal ``normal``, given in ``a``'s frame), ``"lock"`` (the couple on ``b``,
    the slider, from ``a``, the guide), ``"motor"`` (the moment on the crank ``b``) or
    ``"actuator"`` (the force on the sliding driver ``b`` along its line), or
    ``"couple"``: no pymunk constraint (``constraint`` is None), the couple on the
    slider ``b`` of a prismatic joint between bodies that cannot turn, found from
    their momentum balance. ``joint`` is the scene's joint name (``None`` for the
    driver's motor or actuator).
    ``anchor_a`` is the groove's start (grooves) or the joint point on ``a`` (pivots);
    ``anchor_b`` the joint point (pin) on ``b``. For a groove, ``slider`` names the
    joint's slider and ``slider_point`` its slider point (local), from which the couple
    M of the kinetostatic tables is measured.
    """

    constraint: pymunk.Constraint | None
    role: str
    joint: str | None
    a: str
    b: str
    anchor_a: tuple[float, float] = (0.0, 0.0)
    anchor_b: tuple[float, float] = (0.0, 0.0)
    normal: tuple[float, float] = (0.0, 0.0)
    slider: str = ""
    slider_point: tuple[float, float] = (0.0, 0.0)


@dataclass
class SimModel:
    """A pymunk ``Space`` built from a scene and what is needed to run and read it.

    Attributes
    ----------
    scene : Scene
        The checked scene.
    space : pymunk.Space
        Bodies and constraints only (no shapes).
    bodies : dict
        Scene body name -> ``pymunk.Body`` (``"ground"`` -> the space's static body,
        ``"actuator"`` -> the kinematic body of a sliding driver).
    constraints : list of ConstraintInfo
        Every constraint, with its role.
    dt : float
        Time step (s).
    iterations : int
        Solver iterations per step.
    start : float
        Driver position at t = 0 (deg for a crank, m for a sliding driver).
    speed : float
        Driver speed (rad/s or m/s).
    translating : set of str
        Bodies that only translate (their angle is constant over the motion): built
        with an infinite moment of inertia, so their prismatic joints need no lock.
    notes : list of str
        Modelling remarks (e.g. a prismatic joint whose groove cannot be laid out
        exactly; see :func:`build_space`).
    """

    scene: Scene
    space: pymunk.Space
    bodies: dict[str, pymunk.Body]
    constraints: list[ConstraintInfo]
    dt: float
    iterations: int
    start: float
    speed: float
    translating: set[str] = field(default_factory=set)
    error_bias: float = 0.0
    stepped: int = 0
    notes: list[str] = field(default_factory=list)
    actuator: pymunk.Body | None = None
    line: tuple[tuple[float, float], tuple[float, float]] | None = None   # driver line
    _slider_local: tuple[float, float] = (0.0, 0.0)
    _loads: list = field(default_factory=list, repr=False)
    _resist: list = field(default_factory=list, repr=False)

    @property
    def kind(self) -> str:
        """``"R"`` (crank) or ``"T"`` (sliding driver)."""
        return self.scene.driver.kind

    @property
    def moving(self) -> list[str]:
        """Names of the moving bodies (scene order)."""
        return list(self.scene.bodies)

    def driver_position(self) -> float:
        """Present driver position: the crank's angle (deg) or the slider point's distance
        from the line point along the line (m)."""
        d = self.scene.driver
        body = self.bodies[d.body]
        if d.kind == "R":
            return math.degrees(body.angle)
        (lx, ly), (ux, uy) = self.line
        px, py = body.local_to_world(self._slider_local)
        return (px - lx) * ux + (py - ly) * uy


def _raw_with_positions(scene: Scene, positions) -> dict:
    """A copy of the scene's raw dict with ``positions`` as the driver's sweep."""
    raw = copy.deepcopy(scene.raw)
    drv = dict(raw["driver"])
    for k in ("start", "stop", "count", "positions"):
        drv.pop(k, None)
    drv["positions"] = [float(p) for p in positions]
    raw["driver"] = drv
    return raw


def reference_solution(scene: Any, positions):
    """Kinetostatics of ``scene`` at the given driver positions (deg or m).

    The scene's first position is solved first, as row 0, so that the assembly chosen
    by the ``[near]`` hints is the scene's own; the positions asked for are rows 1...
    """
    from ..solver.pipeline import solve
    sc = load_scene(scene)
    pos = np.concatenate([[sc.driver.positions[0]], np.asarray(positions, dtype=float)])
    return solve(_raw_with_positions(sc, pos))


def sweep_positions(scene: Scene, count: int = 73) -> np.ndarray:
    """Driver positions covering the motion: a whole turn when the scene's sweep is one
    (or a single position), else the sweep's range."""
    pos = np.asarray(scene.driver.positions, dtype=float)
    if scene.driver.kind == "R" and (pos.size < 2 or np.ptp(pos) >= 360.0 - 1e-9):
        return np.linspace(pos[0], pos[0] + 360.0, count)
    if pos.size < 2:
        return pos
    return np.linspace(pos.min(), pos.max(), count)


def translating_bodies(scene: Scene, sweep) -> set[str]:
    """Moving bodies whose angle never changes over the motion (omega = alpha = 0 at
    every position of the sweep): pistons, yokes, rams, blocks on fixed guides."""
    out = set()
    for name in scene.bodies:
        m = sweep.kin.bodies[name]
        if not np.any(np.asarray(m.omega) != 0.0) and not np.any(np.asarray(m.alpha) != 0.0):
            out.add(name)
    return out


def _check_scene(scene: Scene) -> None:
    d = scene.driver
    if d.acceleration != 0.0:
        raise SimulationError(
            f"driver.acceleration = {d.acceleration:g}: the rows of such a scene are "
            "snapshots at one speed and acceleration, not a motion; the simulation needs "
            "a constant-speed driver (acceleration = 0)")
    if d.speed == 0.0:
        raise SimulationError("driver.speed = 0: nothing moves; give the driver a speed")
    for name, b in scene.bodies.items():
        if b.mass <= 0.0 or b.inertia <= 0.0:
            raise SimulationError(
                f"body {name!r} has mass {b.mass:g} kg and inertia {b.inertia:g} kg m^2: "
                "pymunk needs mass > 0 and inertia > 0 for every moving body; give it both "
                "(and a cog) for the simulation")


def _local(scene: Scene, body: str, point: str) -> tuple[float, float]:
    if body == GROUND:
        return scene.ground[point]
    return scene.bodies[body].local(point)


def _first(x) -> float:
    return float(np.asarray(x, dtype=float).reshape(-1)[0])


def _line(scene: Scene, joint: str, body: str) -> tuple[np.ndarray, np.ndarray]:
    """A prismatic joint's line in ``body``'s frame (the guide's or the slider's):
    a point on it and its unit direction."""
    j = scene.joints[joint]
    if body == j.guide:
        beta = math.radians(j.line_angle)
        return np.array(_local(scene, body, j.points[0])), np.array([math.cos(beta),
                                                                      math.sin(beta)])
    # the slider's local x axis lies along the line, through the slider point
    return np.array(_local(scene, body, j.points[1])), np.array([1.0, 0.0])


def _on_line(scene: Scene, joint: str, body: str) -> bool:
    """Whether ``body``'s centre of mass lies on the joint's line (or it is the ground)."""
    if body == GROUND:
        return True
    p, u = _line(scene, joint, body)
    g = np.asarray(scene.bodies[body].cog, dtype=float) - p
    size = max(1.0, float(np.hypot(*g)))
    return abs(float(u[0] * g[1] - u[1] * g[0])) <= 1e-12 * size


def _foot(scene: Scene, joint: str, body: str) -> tuple[float, float]:
    """The point of the joint's line (in ``body``'s frame) nearest ``body``'s centre of
    mass: the groove's pin on that body (its arm from the cog is normal to the line)."""
    p, u = _line(scene, joint, body)
    if body == GROUND:
        return tuple(p)
    g = np.asarray(scene.bodies[body].cog, dtype=float)
    return tuple(p + float(np.dot(g - p, u)) * u)


def build_space(scene: Any, *, dt: float, iterations: int = DEFAULT_ITERATIONS,
                start: float | None = None, error_bias: float = 0.0) -> SimModel:
    """Build the pymunk model of a scene, on its exact kinematic state at ``start``.

    Prismatic joints: a ``GrooveJoint`` solves its two directions together and then
    keeps the normal part of the impulse; that is exact only when the joint's
    effective-mass matrix is diagonal in the groove's frame (else the pin lags the
    groove by an amount proportional to the sliding speed times dt: first-order
    errors). So the groove goes on a body that is the ground, cannot turn, or has
    its centre of mass on the line, and the pin on the other body at the foot of the
    normal from its centre of mass (on a body that cannot turn: at the joint's own
    point): both arms are then along the line or normal to it. Where no body
    qualifies, the groove goes on the guide and a note says so.

    Bodies that only translate (:func:`translating_bodies`) get an infinite moment of
    inertia: they cannot turn, which is exact for them, and a prismatic joint between
    two such bodies (or one and the ground) needs no lock; its couple M is then an
    unknown of the momentum balance (see the module docstring). Between bodies that
    turn, a ``GearJoint`` of ratio 1 locks the relative rotation and carries M.

    Parameters
    ----------
    scene : Scene, path, TOML text or dict
        A mechanism scene with a constant-speed driver.
    dt : float
        Time step (s) the model will be stepped with (it sets the start's half-step
        shift and the loads' prediction).
    iterations : int
        Solver iterations per step (``Space.iterations``).
    start : float, optional
        Driver position at t = 0 (deg or m); default the scene's first position.
    error_bias : float
        ``error_bias`` of every joint: the fraction of a joint's drift left after one
        second. 0 (the default) corrects it in one step; pymunk's own default,
        ``(1 - 0.1) ** 60``, is far too soft for force measurement.

    Returns
    -------
    SimModel

    Raises
    ------
    SimulationError
        A driver with acceleration, a body without mass or inertia, bad settings.
    """
    sc = load_scene(scene)
    _check_scene(sc)
    if not (dt > 0.0 and math.isfinite(dt)):
        raise SimulationError(f"dt = {dt!r}: the time step must be a positive number of s")
    if int(iterations) != iterations or iterations < 1:
        raise SimulationError(f"iterations = {iterations!r}: give a whole number >= 1")
    if not 0.0 <= error_bias <= 1.0:
        raise SimulationError(f"error_bias = {error_bias!r}: give a fraction in [0, 1]")
    d = sc.driver
    p0 = float(d.positions[0]) if start is None else float(start)
    kin0 = reference_solution(sc, [p0]).kin
    sweep = reference_solution(sc, sweep_positions(sc))

    space = pymunk.Space()
    space.iterations = int(iterations)
    space.gravity = tuple(sc.gravity)
    space.sleep_time_threshold = math.inf
    space.damping = 1.0
    bodies: dict[str, pymunk.Body] = {GROUND: space.static_body}
    frozen = translating_bodies(sc, sweep)
    half = 0.5 * dt
    for name, b in sc.bodies.items():
        m = kin0.bodies[name].take(slice(1, 2))
        # a body that only translates cannot turn: an infinite moment of inertia keeps
        # it so with no constraint (its couples follow from its momentum balance)
        body = pymunk.Body(b.mass, math.inf if name in frozen else b.inertia)
        body.center_of_gravity = tuple(b.cog)
        gx, gy = (_first(v) for v in m.point(b.cog))
        vx, vy = (_first(v) for v in m.vel_at(gx, gy))
        ax, ay = (_first(v) for v in m.acc_at(gx, gy))
        theta, omega, alpha = _first(m.theta), _first(m.omega), _first(m.alpha)
        # the steady motion of the scheme: x - a dt^2/2, v + a dt/2 (module docstring)
        angle = theta - alpha * half * dt
        cx, cy = gx - ax * half * dt, gy - ay * half * dt
        c, s = math.cos(angle), math.sin(angle)
        body.angle = angle
        body.position = (cx - (c * b.cog[0] - s * b.cog[1]), cy - (s * b.cog[0] + c * b.cog[1]))
        body.velocity = (vx + ax * half, vy + ay * half)
        body.angular_velocity = omega + alpha * half
        bodies[name] = body
        space.add(body)

    infos: list[ConstraintInfo] = []

    def add(c: pymunk.Constraint, info: ConstraintInfo) -> None:
        c.error_bias = error_bias
        c.max_bias = math.inf
        c.collide_bodies = False
        space.add(c)
        infos.append(info)

    notes: list[str] = []
    fixed = {GROUND} | frozen
    for name, j in sc.joints.items():
        if j.kind == "R":
            on, by = j.on_by
            pa = _local(sc, by, j.point_on(by))
            pb = _local(sc, on, j.point_on(on))
            c = pymunk.PivotJoint(bodies[by], bodies[on], pa, pb)
            add(c, ConstraintInfo(c, "pivot", name, by, on, pa, pb))
            continue
        g, s = j.guide, j.slider
        # the groove on a body whose arm to the pin's contact runs along the line
        # (the ground, a body that cannot turn, or one whose cog is on the line), the
        # pin on the other at the foot of the normal from its cog (see the docstring)
        found = next(((q, p) for q, p in ((g, s), (s, g))
                      if q in fixed or _on_line(sc, name, q)), None)
        q, p = found or (g, s)
        if found is None:
            notes.append(f"prismatic joint {name!r}: neither body's centre of mass lies on "
                         "the line and both turn; pymunk's groove then lags by a first-order "
                         "amount (expect errors proportional to dt)")
        if p in fixed:
            pin = _local(sc, p, j.points[1] if p == s else j.points[0])
        else:
            pin = _foot(sc, name, p)
        lp, u = _line(sc, name, q)
        lo, hi = _pin_range(sc, sweep, q, p, pin, lp, u)
        reach = GROOVE_MARGIN * max(hi - lo, 0.1)
        ga = tuple(lp + (lo - reach) * u)
        gb = tuple(lp + (hi + reach) * u)
        c = pymunk.GrooveJoint(bodies[q], bodies[p], ga, gb, pin)
        add(c, ConstraintInfo(c, "groove", name, q, p, ga, pin, (-u[1], u[0]), s,
                              _local(sc, s, j.points[1])))
        if g in fixed and s in fixed:
            # neither turns: no lock; the couple follows from the angular momentum
            # balance of the translating body (or bodies)
            infos.append(ConstraintInfo(None, "couple", name, g, s))
        else:
            phase = bodies[s].angle - bodies[g].angle
            c = pymunk.GearJoint(bodies[g], bodies[s], phase, 1.0)
            add(c, ConstraintInfo(c, "lock", name, g, s))

    model = SimModel(sc, space, bodies, infos, float(dt), int(iterations), p0, d.speed,
                     frozen, error_bias=float(error_bias), notes=notes)
    drv = bodies[d.body]
    if d.kind == "R":
        # SimpleMotor(a, b, rate) holds b.w - a.w = -rate: here the crank turns at `speed`
        c = pymunk.SimpleMotor(drv, space.static_body, d.speed)
        add(c, ConstraintInfo(c, "motor", None, GROUND, d.body))
    else:
        j = sc.joints[d.joint]
        if j.guide != GROUND:
            raise SimulationError("a sliding driver whose guide is not the ground is not "
                                  "supported by the simulation")
        lp = sc.ground[j.points[0]]
        beta = math.radians(j.line_angle)
        ux, uy = math.cos(beta), math.sin(beta)
        sp = sc.bodies[d.body].local(j.points[1])
        model._slider_local = sp
        model.line = (lp, (ux, uy))
        px, py = drv.local_to_world(sp)
        # a kinematic body moves at the constant speed along the line; a groove across
        # the line, through the slider point, pushes the driver: its force is Fe
        act = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        act.position = (px, py)
        act.velocity = (d.speed * ux, d.speed * uy)
        space.add(act)
        ga, gb = (-uy, ux), (uy, -ux)          # its left normal is the line direction u
        c = pymunk.GrooveJoint(act, drv, ga, gb, sp)
        add(c, ConstraintInfo(c, "actuator", None, "actuator", d.body, ga, sp, (ux, uy)))
        model.actuator = act
        bodies["actuator"] = act
    _prepare_loads(model, sweep)
    return model


def _pin_range(sc: Scene, sweep, q: str, p: str, pin, lp, u) -> tuple[float, float]:
    """Range over the motion of the pin's coordinate along the groove body's line."""
    kin = sweep.kin
    n = kin.n
    if p == GROUND:
        wx, wy = np.full(n, pin[0]), np.full(n, pin[1])
    else:
        wx, wy = (np.broadcast_to(v, (n,)) for v in kin.bodies[p].point(pin))
    if q == GROUND:
        lx, ly = wx, wy
    else:
        m = kin.bodies[q]
        dx, dy = wx - m.ox, wy - m.oy
        c, s = np.broadcast_to(m.cos, (n,)), np.broadcast_to(m.sin, (n,))
        lx, ly = c * dx + s * dy, -s * dx + c * dy
    t = (lx - lp[0]) * u[0] + (ly - lp[1]) * u[1]
    return float(np.min(t)), float(np.max(t))


# ----------------------------------------------------------------------------- loads
def _prepare_loads(model: SimModel, sweep) -> None:
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
    model._loads = [(model.bodies[name], *v) for name, v in per.items()]
    model._resist = [(model.bodies[name], *rest) for name, *rest in resist]


# ----------------------------------------------------------------------------- run
@dataclass
class SimRecord:
    """What a run measured, one row per sample (the state after a step).

    Attributes
    ----------
    time : ndarray
        Simulated time at the end of the sampled step (s).
    position : ndarray
        Driver position there (deg or m).
    impulse : dict
        ``constraint label -> |impulse| / dt`` (public API): N for pivots, grooves and
        the actuator, N m for locks and the motor. Labels: the joint name for its
        force constraint, ``"<joint>:lock"`` for a lock, ``"driver"``.
    signed : dict
        The same quantities signed, from the momentum balance: ``"<joint>"`` ->
        (Fx, Fy) on the ``on`` body of the reactions table (pivots and grooves),
        ``"<joint>:N"`` and ``"<joint>:M"`` for prismatic joints, ``"driver"`` -> Me
        (N m, ccw on the crank) or Fe (N, along the line).
    resist_unsure : ndarray of bool
        A ``resist`` point slower than 1e-4 of its top speed at that row.
    vector_check : float
        Largest | |signed| - impulse / dt | over every constraint and row, relative to
        that constraint's largest magnitude.
    wall : float
        Wall time of the stepping loop (s), reading included.
    steps : int
        Steps taken.
    dt, iterations : float, int
    fast : bool
        Whether the stepping loop called Chipmunk's C functions directly.
    pose : ndarray
        (samples, bodies, 3): x, y of each moving body's origin and its angle (rad).
    velocity : ndarray
        (samples, bodies, 3): velocity of each moving body's centre of mass and its
        angular velocity.
    drift : float
        Largest joint error over the samples: the separation of a pivot's two points,
        the pin's distance from its groove (m), or a lock's angle error times the
        mechanism's size; see :func:`joint_drift`.
    """

    time: np.ndarray
    position: np.ndarray
    impulse: dict[str, np.ndarray]
    signed: dict[str, Any]
    resist_unsure: np.ndarray
    vector_check: float
    wall: float
    steps: int
    dt: float
    iterations: int
    fast: bool = False
    pose: np.ndarray | None = None
    drift: float = 0.0
    velocity: np.ndarray | None = None


def _label(info: ConstraintInfo) -> str:
    if info.role in ("motor", "actuator"):
        return "driver"
    return f"{info.joint}:lock" if info.role == "lock" else str(info.joint)


def fast_path_available() -> bool:
    """True when the installed pymunk is the pinned version, whose C functions the
    stepping loop may call directly (``pymunk._chipmunk_cffi.lib``)."""
    return pymunk.version == PYMUNK_VERSION


class _Access:
    """Reading and setting body state in the stepping loop.

    The public path uses pymunk's properties. The fast path (pinned pymunk version
    only) calls the Chipmunk functions those properties call, without the Python
    wrappers: ``cpBodyGet/SetForce``, ``cpBodySetTorque``, ``cpBodyGetAngle``,
    ``cpBodyGetAngularVelocity``, ``cpBodyGetVelocity``, ``cpBodyGetPosition``,
    ``cpBodyGetTorque``, ``cpConstraintGetImpulse`` and ``cpSpaceStep`` (after one
    public ``Space.step(0)``, which does pymunk's own checks). :meth:`verify` compares
    the fast reads with the public properties during the run and raises if they ever
    differ.
    """

    def __init__(self, model: SimModel, fast: bool):
        self.fast = fast
        space = model.space
        if fast:
            from pymunk._chipmunk_cffi import lib
            csp = space._space
            cstep = lib.cpSpaceStep
            self.step = lambda dt: cstep(csp, dt)
            self.handle = lambda body: body._body
            self.chandle = lambda c: c._constraint
            self.angle = lib.cpBodyGetAngle
            self.omega = lib.cpBodyGetAngularVelocity
            self.velocity = lib.cpBodyGetVelocity
            self.position = lib.cpBodyGetPosition
            self.force = lib.cpBodyGetForce
            self.torque = lib.cpBodyGetTorque
            self.set_force = lib.cpBodySetForce
            self.set_torque = lib.cpBodySetTorque
            self.impulse = lib.cpConstraintGetImpulse
        else:
            self.step = space.step
            self.handle = self.chandle = lambda x: x
            self.angle = lambda b: b.angle
            self.omega = lambda b: b.angular_velocity
            self.velocity = lambda b: b.velocity
            self.position = lambda b: b.position
            self.force = lambda b: b.force
            self.torque = lambda b: b.torque
            self.impulse = lambda c: c.impulse

            def set_force(b, f):
                b.force = f

            def set_torque(b, t):
                b.torque = t

            self.set_force = set_force
            self.set_torque = set_torque

    def verify(self, body: pymunk.Body, constraint: pymunk.Constraint | None) -> None:
        """Raise if a fast read differs from the public property (pinned version check)."""
        if not self.fast:
            return
        h = self.handle(body)
        v, f, p = self.velocity(h), self.force(h), self.position(h)
        ok = (self.angle(h) == body.angle and self.omega(h) == body.angular_velocity
              and (v.x, v.y) == tuple(body.velocity) and (f.x, f.y) == tuple(body.force)
              and (p.x, p.y) == tuple(body.position) and self.torque(h) == body.torque)
        if constraint is not None:
            ok = ok and self.impulse(self.chandle(constraint)) == constraint.impulse
        if not ok:
            raise SimulationError(
                f"pymunk {pymunk.version}: the direct Chipmunk reads differ from the public "
                f"properties (the fast path is pinned to pymunk {PYMUNK_VERSION}); run with "
                "fast=False")


def make_stepper(space: pymunk.Space, fast: bool | None = None):
    """A function ``step(dt)`` that advances ``space``: ``Space.step`` or, on the pinned
    pymunk version (``fast`` None or True), Chipmunk's ``cpSpaceStep`` called directly
    after one public ``Space.step(0)`` (pymunk's own checks; a zero step does nothing).
    Only for spaces whose content does not change while it steps."""
    if fast is None:
        fast = fast_path_available()
    elif fast and not fast_path_available():
        raise SimulationError(f"fast=True needs pymunk {PYMUNK_VERSION} (installed: "
                              f"{pymunk.version}); use fast=False")
    space.step(0.0)
    if not fast:
        return space.step
    from pymunk._chipmunk_cffi import lib
    csp, cstep = space._space, lib.cpSpaceStep
    return lambda dt: cstep(csp, dt)


VERIFY_EVERY = 8
"""The fast path's reads are checked against the public properties at every this many
samples (one body and one constraint each time, in turn; all of them at the first)."""


def run(model: SimModel, steps: int, sample_every: int = 1, *,
        fast: bool | None = None) -> SimRecord:
    """Step the model ``steps`` times, reading every ``sample_every``-th step.

    Before every step the scene's loads are set on the bodies, evaluated at the pose
    the step will reach. At a sampled step the velocities and forces before it, and
    the pose, velocities and constraint impulses after it are read.

    Parameters
    ----------
    model : SimModel
        From :func:`build_space` (it is advanced in place).
    steps : int
        Number of steps.
    sample_every : int
        Read the constraints and bodies after every this many steps.
    fast : bool, optional
        Call Chipmunk's C functions directly in the loop (two to three times faster);
        default: when the installed pymunk is the pinned version. Its reads are
        checked against the public properties during the run.

    Returns
    -------
    SimRecord
    """
    steps, every = int(steps), max(1, int(sample_every))
    if fast is None:
        fast = fast_path_available()
    elif fast and not fast_path_available():
        raise SimulationError(f"fast=True needs pymunk {PYMUNK_VERSION} (installed: "
                              f"{pymunk.version}); run with fast=False")
    acc = _Access(model, bool(fast))
    dt = model.dt
    space = model.space
    space.step(0.0)                 # pymunk's own pre-step checks (a zero step is a no-op)
    fstep = acc.step
    bods = [model.bodies[n] for n in model.moving]
    real = [i for i in model.constraints if i.constraint is not None]
    cons = [i.constraint for i in real]
    H = acc.handle
    hb = [H(b) for b in bods]
    hc = [acc.chandle(c) for c in cons]
    get_a, get_w, get_v, get_p = acc.angle, acc.omega, acc.velocity, acc.position
    get_f, get_t, get_i = acc.force, acc.torque, acc.impulse
    apply_loads, unsure = _loads_function(model, acc)
    n_samples = steps // every
    schedule = [] if model.stepped else warmup_schedule(model.iterations)

    def advance(n: int) -> None:
        if apply_loads is None:
            for _ in range(n):
                fstep(dt)
        else:
            for _ in range(n):
                apply_loads()
                fstep(dt)

    def warm(n: int) -> None:
        for _ in range(n):
            space.iterations = schedule.pop()
            if apply_loads is not None:
                apply_loads()
            fstep(dt)
        space.iterations = schedule[-1] if schedule else model.iterations

    before, after, imp, flags = [], [], [], []
    nb, nc = len(bods), len(cons)
    t0 = time.perf_counter()
    for k in range(n_samples):
        inner = every - 1
        if schedule:
            m = min(len(schedule), inner)
            warm(m)
            inner -= m
        advance(inner)
        if schedule:
            space.iterations = schedule.pop()
        if apply_loads is not None:
            apply_loads()
        row = []
        for h in hb:
            v, f = get_v(h), get_f(h)
            row += (v.x, v.y, get_w(h), f.x, f.y, get_t(h))
        before.append(row)
        fstep(dt)
        space.iterations = schedule[-1] if schedule else model.iterations
        row = []
        for h in hb:
            p, v = get_p(h), get_v(h)
            row += (p.x, p.y, get_a(h), v.x, v.y, get_w(h))
        after.append(row)
        imp.append([get_i(c) for c in hc])
        flags.append(unsure[0])
        if k == 0:
            for i, b in enumerate(bods):
                acc.verify(b, cons[i] if i < nc else None)
            for c in cons[nb:]:
                acc.verify(bods[0], c)
        elif k % VERIFY_EVERY == 0:
            j = k // VERIFY_EVERY
            acc.verify(bods[j % nb], cons[j % nc] if nc else None)
    space.iterations = model.iterations
    advance(steps - n_samples * every)
    wall = time.perf_counter() - t0
    model.stepped += steps
    before = np.array(before, dtype=float).reshape(n_samples, nb, 6)
    after = np.array(after, dtype=float).reshape(n_samples, nb, 6)
    imp = np.array(imp, dtype=float).reshape(n_samples, nc) / dt
    times = (np.arange(n_samples) + 1) * every * dt
    impulse = {_label(info): imp[:, i] for i, info in enumerate(real)}
    signed, check = _signed(model, after[:, :, :3], before[:, :, :3], after[:, :, 3:],
                            before[:, :, 3:], imp)
    pose = after[:, :, :3].copy()
    vel = after[:, :, 3:].copy()
    return SimRecord(times, _driver_positions(model, pose), impulse, signed,
                     np.array(flags, dtype=bool), check, wall, steps, dt, model.iterations,
                     bool(fast), pose, joint_drift(model, pose), vel)


def warmup_schedule(iterations: int) -> list[int]:
    """Iteration counts of a fresh model's first steps, last step first (a stack): from
    ``WARMUP_ITERATIONS`` down to ``iterations`` geometrically over ``WARMUP_STEPS``."""
    if iterations >= WARMUP_ITERATIONS or WARMUP_STEPS < 1:
        return []
    r = (iterations / WARMUP_ITERATIONS) ** (1.0 / WARMUP_STEPS)
    counts = [max(iterations, round(WARMUP_ITERATIONS * r ** k)) for k in range(WARMUP_STEPS)]
    return counts[::-1]


def _driver_positions(model: SimModel, pose: np.ndarray) -> np.ndarray:
    """Driver positions of sampled poses: the crank's angle (deg, continuous) or the slider
    point's distance from the line point along the line (m)."""
    i = model.moving.index(model.scene.driver.body)
    th = pose[:, i, 2]
    if model.kind == "R":
        return np.degrees(th)
    (lx, ly), (ux, uy) = model.line
    sx, sy = model._slider_local
    px = pose[:, i, 0] + np.cos(th) * sx - np.sin(th) * sy
    py = pose[:, i, 1] + np.sin(th) * sx + np.cos(th) * sy
    return (px - lx) * ux + (py - ly) * uy


def _loads_function(model: SimModel, acc: _Access):
    """The function that sets the scene's loads before a step (None if only gravity),
    and a one-element list that it sets True when a ``resist`` point is nearly still.

    Constant loads on a body: F, and the moment cos(a) A + sin(a) B + M at the angle a
    the body will have after the step (a + omega dt). ``resist`` loads: the point's
    velocity at the pose the step reaches, extrapolated to second order from the last
    two steps' velocities (1.5 v_n - 0.5 v_(n-1)); the force is opposite to it.
    """
    dt = model.dt
    H = acc.handle
    get_a, get_w, get_v = acc.angle, acc.omega, acc.velocity
    set_f, set_t = acc.set_force, acc.set_torque
    unsure = [False]
    per: dict[int, dict] = {}
    for b, fx, fy, ca, cb, mm in model._loads:
        per[id(b)] = {"body": b, "const": (fx, fy, ca, cb, mm), "resist": []}
    for (b, px, py, mag, top), (ax, ay, al) in zip(model._resist, _start_acc(model),
                                                    strict=True):
        d = per.setdefault(id(b), {"body": b, "const": (0.0, 0.0, 0.0, 0.0, 0.0),
                                   "resist": []})
        d["resist"].append((px, py, mag, top, ax, ay, al))
    if not per:
        return None, unsure
    cos, sin, hypot = math.cos, math.sin, math.hypot

    def body_function(d: dict):
        h = H(d["body"])
        fx0, fy0, ca, cb, mm = d["const"]
        turning = bool(ca or cb or any(px or py for px, py, *_ in d["resist"]))
        if not d["resist"]:
            f0 = (fx0, fy0)

            def apply_const() -> None:
                a = get_a(h) + get_w(h) * dt
                set_f(h, f0)
                set_t(h, cos(a) * ca + sin(a) * cb + mm)

            return apply_const
        # the start carries v(t0) + a dt / 2; one step earlier the scheme had a dt less
        v = get_v(h)
        w0 = get_w(h)
        res = d["resist"]
        first = res[0]
        prev = [v.x - first[4] * dt, v.y - first[5] * dt, w0 - first[6] * dt]
        arms = [(px, py, mag, top) for px, py, mag, top, *_ in res]
        if not turning and not mm and len(arms) == 1 and not isinstance(arms[0][2], tuple):
            # one resist force at the centre of mass of a body with no other moment
            # (a piston): no angle, no angular velocity, no torque needed
            _, _, mag, top = arms[0]
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

        gated_on = [None] * len(arms)       # when = "resisting": on at the last step
        settle = [0]                        # steps left in a switch's transient

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

    funcs = [body_function(d) for d in per.values()]
    if len(funcs) == 1:
        return funcs[0], unsure

    def apply_all() -> None:
        for f in funcs:
            f()

    return apply_all, unsure


def mechanism_size(sc: Scene) -> float:
    """The mechanism's size: the largest distance of a named point from its frame's origin."""
    return max([1e-3] + [math.hypot(*p) for p in sc.ground.values()]
               + [math.hypot(*p) for b in sc.bodies.values() for p in b.points.values()])


def joint_drift(model: SimModel, pose: np.ndarray) -> float:
    """Largest joint error over sampled poses (m).

    Pivots: the distance between the joint's points on the two bodies; grooves: the
    pin's distance from the groove line; locks: the relative angle's error times the
    largest distance of a scene point from the origin. A converged run keeps this of
    the order of a dt^2 (about 1e-9 m); a solver short of iterations lets it grow.
    """
    names = model.moving
    index = {n: i for i, n in enumerate(names)}
    K = pose.shape[0]
    if K == 0:
        return 0.0

    def world(body: str, local):
        if body == GROUND:
            return np.full(K, local[0]), np.full(K, local[1])
        if body == "actuator":
            return None
        i = index[body]
        c, s = np.cos(pose[:, i, 2]), np.sin(pose[:, i, 2])
        return (pose[:, i, 0] + c * local[0] - s * local[1],
                pose[:, i, 1] + s * local[0] + c * local[1])

    def angle(body: str):
        return np.zeros(K) if body == GROUND else pose[:, index[body], 2]

    size = mechanism_size(model.scene)
    worst = 0.0
    for info in model.constraints:
        if info.role == "pivot":
            ax_, ay_ = world(info.a, info.anchor_a)
            bx_, by_ = world(info.b, info.anchor_b)
            d = np.hypot(bx_ - ax_, by_ - ay_)
        elif info.role == "groove":
            ax_, ay_ = world(info.a, info.anchor_a)
            bx_, by_ = world(info.b, info.anchor_b)
            th = angle(info.a)
            nx = np.cos(th) * info.normal[0] - np.sin(th) * info.normal[1]
            ny = np.sin(th) * info.normal[0] + np.cos(th) * info.normal[1]
            d = np.abs((bx_ - ax_) * nx + (by_ - ay_) * ny)
        elif info.role == "lock":
            rel = angle(info.b) - angle(info.a)
            d = np.abs(rel - rel[0]) * size
        else:
            continue
        m = float(np.max(d)) if np.all(np.isfinite(d)) else math.inf
        worst = max(worst, m)
    return worst


def _start_acc(model: SimModel) -> list[tuple[float, float, float]]:
    """Exact accelerations (cog, angular) at the start of the bodies carrying resist loads."""
    sc = model.scene
    sol = reference_solution(sc, [model.start])
    out = []
    for body, *_ in model._resist:
        name = next(n for n, b in model.bodies.items() if b is body)
        m = sol.kin.bodies[name].take(slice(1, 2))
        b = sc.bodies[name]
        gx, gy = m.point(b.cog)
        ax, ay = m.acc_at(gx, gy)
        out.append(tuple(float(np.asarray(v).reshape(-1)[0]) for v in (ax, ay, m.alpha)))
    return out


# ----------------------------------------------------------------------------- signs
def _signed(model: SimModel, pose, vel0, vel1, frc, mag):
    """Signed constraint forces from the momentum balance of every body over the step.

    Unknowns, per constraint: the force on ``b`` (two components) for a pivot, the
    force along the groove's normal for a groove or the actuator, the couple on ``b``
    for a lock or the motor; ``a`` gets the opposite. Equations: per moving body
    m (v' - v) / dt - m g - F (two rows) and I (w' - w) / dt - T, the arms taken at
    the pose after the step (where pymunk forms its constraints).
    """
    sc = model.scene
    dt = model.dt
    names = model.moving
    index = {n: i for i, n in enumerate(names)}
    K = pose.shape[0]
    nb = len(names)
    mass = np.array([sc.bodies[n].mass for n in names])
    inert = np.array([sc.bodies[n].inertia for n in names])
    cog = np.array([sc.bodies[n].cog for n in names], dtype=float)
    ang = pose[:, :, 2]
    c, s = np.cos(ang), np.sin(ang)
    gxw = pose[:, :, 0] + c * cog[:, 0] - s * cog[:, 1]      # cog, world
    gyw = pose[:, :, 1] + s * cog[:, 0] + c * cog[:, 1]
    gvec = np.asarray(model.scene.gravity, dtype=float)

    # right-hand side: rows (body, fx / fy / m)
    rhs = np.empty((K, nb, 3))
    rhs[:, :, 0] = mass * (vel1[:, :, 0] - vel0[:, :, 0]) / dt - mass * gvec[0] - frc[:, :, 0]
    rhs[:, :, 1] = mass * (vel1[:, :, 1] - vel0[:, :, 1]) / dt - mass * gvec[1] - frc[:, :, 1]
    rhs[:, :, 2] = inert * (vel1[:, :, 2] - vel0[:, :, 2]) / dt - frc[:, :, 2]

    cols = []        # (label, list of (body index, fx, fy, m) arrays over K)

    def world(body: str, local) -> tuple[np.ndarray, np.ndarray]:
        if body == GROUND:
            return np.full(K, local[0]), np.full(K, local[1])
        i = index[body]
        return (pose[:, i, 0] + c[:, i] * local[0] - s[:, i] * local[1],
                pose[:, i, 1] + s[:, i] * local[0] + c[:, i] * local[1])

    def rot(body: str, v) -> tuple[np.ndarray, np.ndarray]:
        if body in (GROUND, "actuator"):
            return np.full(K, v[0]), np.full(K, v[1])
        i = index[body]
        return c[:, i] * v[0] - s[:, i] * v[1], s[:, i] * v[0] + c[:, i] * v[1]

    def arm(body: str, x, y):
        i = index[body]
        return x - gxw[:, i], y - gyw[:, i]

    for info in model.constraints:
        a, b = info.a, info.b
        if info.role == "pivot":
            ax_, ay_ = world(a, info.anchor_a)
            bx_, by_ = world(b, info.anchor_b)
            for ux, uy in ((1.0, 0.0), (0.0, 1.0)):
                ent = []
                if b in index:
                    rx, ry = arm(b, bx_, by_)
                    ent.append((index[b], ux, uy, rx * uy - ry * ux))
                if a in index:
                    rx, ry = arm(a, ax_, ay_)
                    ent.append((index[a], -ux, -uy, -(rx * uy - ry * ux)))
                cols.append(ent)
        elif info.role in ("groove", "actuator"):
            nx, ny = rot(a, info.normal)
            px, py = world(b, info.anchor_b)      # the pin (the force acts along n there)
            ent = []
            if b in index:
                rx, ry = arm(b, px, py)
                ent.append((index[b], nx, ny, rx * ny - ry * nx))
            if a in index:
                rx, ry = arm(a, px, py)
                ent.append((index[a], -nx, -ny, -(rx * ny - ry * nx)))
            cols.append(ent)
        else:    # lock, motor, couple: a couple on b, the opposite on a
            ent = []
            if b in index:
                ent.append((index[b], 0.0, 0.0, 1.0))
            if a in index:
                ent.append((index[a], 0.0, 0.0, -1.0))
            cols.append(ent)

    n_unk = len(cols)
    A = np.zeros((K, nb, 3, n_unk))
    for j, ent in enumerate(cols):
        for i, fx, fy, m in ent:
            A[:, i, 0, j] += fx
            A[:, i, 1, j] += fy
            A[:, i, 2, j] += m
    A = A.reshape(K, nb * 3, n_unk)
    b = rhs.reshape(K, nb * 3)
    if A.shape[1] != n_unk:
        raise SimulationError(f"the momentum balance has {A.shape[1]} equations for {n_unk} "
                              "unknowns: the chain is not a driver plus dyads")
    lam = np.linalg.solve(A, b[..., None])[..., 0]

    signed: dict[str, Any] = {}
    check = 0.0
    j = 0
    ci = -1
    real = [i for i in model.constraints if i.constraint is not None]
    forces = [k for k, i in enumerate(real) if i.role not in ("lock", "motor")]
    fmax = float(np.max(mag[:, forces])) if K and forces else 0.0
    size = mechanism_size(sc)
    for info in model.constraints:
        if info.constraint is not None:
            ci += 1
        label = _label(info)
        if info.role == "pivot":
            fx, fy = lam[:, j], lam[:, j + 1]
            j += 2
            signed[label] = (fx, fy)
            got = np.hypot(fx, fy)
        else:
            val = lam[:, j]
            j += 1
            got = np.abs(val)
            if info.role == "groove":
                jt = sc.joints[info.joint]
                nx, ny = rot(info.a, info.normal)
                # N: the force on the slider along the line's left normal (the groove's
                # normal, whichever body carries the groove)
                N = val if info.b == info.slider else -val
                sign = 1.0 if jt.on_by[0] == info.slider else -1.0
                signed[label] = (sign * N * nx, sign * N * ny)
                signed[f"{label}:N"] = N
                # its moment about the slider point: the pin lies on the line, d along it
                px, py = world(info.b, info.anchor_b)
                sx, sy = world(info.slider, info.slider_point)
                d = (px - sx) * ny - (py - sy) * nx          # (pin - S) . u, u = (ny, -nx)
                signed[f"{label}:M"] = signed.get(f"{label}:M", 0.0) + d * N
            elif info.role in ("lock", "couple"):
                signed[f"{info.joint}:M"] = signed.get(f"{info.joint}:M", 0.0) + val
            else:
                signed["driver"] = val
        if info.constraint is None:
            continue            # a couple of a translating body: no pymunk constraint
        # relative to the constraint's largest reading, but not below 1e-6 of the
        # largest force (times the mechanism's size for a couple): a lock that carries
        # next to nothing is checked on the scale of the mechanism's forces
        floor = 1e-6 * fmax * (size if info.role in ("lock", "motor") else 1.0)
        scale = max(float(np.max(mag[:, ci])) if K else 0.0, floor)
        if scale > 0.0:
            check = max(check, float(np.max(np.abs(got - mag[:, ci]))) / scale)
    for name in sc.joints:
        if sc.joints[name].kind == "T":
            signed[f"{name}:M"] = np.broadcast_to(signed.get(f"{name}:M", 0.0), (K,)).copy()
    return signed, check


# ----------------------------------------------------------------------------- batches
SERIAL = "serial"
"""``executor=SERIAL``: run a batch one item after another in this process."""


def run_batch(fn: Callable[[Any], Any], items: Iterable[Any], *,
              executor: Executor | str | None = None) -> list[Any]:
    """``[fn(item) for item in items]``, in order, run through an executor.

    The batches of the cross-check (:func:`kinetostatics.crosscheck.study`,
    :func:`kinetostatics.crosscheck.crosscheck_many`) and of the balancing machine
    (:meth:`balance.machine.BalancingMachine.runs`) go through here. Their ``fn`` is a
    top-level function and their items plain data (scene dicts, settings dicts,
    tuples), so any executor that pickles them can run them: a
    ``concurrent.futures.ProcessPoolExecutor``, or a dask.distributed
    ``Client.get_executor()`` that spreads them over a cluster.

    Parameters
    ----------
    fn : callable
        A picklable (top-level) function of one item.
    items : iterable
        The work items.
    executor : Executor, ``"serial"`` or None
        None (default): a ``ProcessPoolExecutor`` with ``min(len(items), cpu_count)``
        workers, created for the batch and shut down after it; a batch of one item,
        or a machine with one core, runs in this process (no pool to pay for).
        ``"serial"`` (:data:`SERIAL`): in this process, one after another. An
        ``Executor``: its ``map`` (it is not shut down: the caller owns it).

    Returns
    -------
    list
        The results in the order of ``items``.

    Raises
    ------
    SimulationError
        ``executor`` is none of these.
    """
    work = list(items)
    if isinstance(executor, str):
        if executor != SERIAL:
            raise SimulationError(f"executor = {executor!r}: give a concurrent.futures "
                                  f"Executor, None (processes) or {SERIAL!r}")
        return [fn(x) for x in work]
    if executor is None:
        workers = min(len(work), os.cpu_count() or 1)
        if workers < 2:
            return [fn(x) for x in work]
        with ProcessPoolExecutor(max_workers=workers) as pool:
            return list(pool.map(fn, work))
    if not isinstance(executor, Executor) and not callable(getattr(executor, "map", None)):
        raise SimulationError(f"executor = {executor!r}: give a concurrent.futures Executor, "
                              f"None (processes) or {SERIAL!r}")
    return list(executor.map(fn, work))
