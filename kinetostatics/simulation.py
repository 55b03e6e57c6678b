"""A pymunk model of a mechanism scene, and the run that measures its joint reactions.

The cross-check of issue 5 (SPEC, "simulation cross-check"): the same scene that
:func:`kinetostatics.solve` takes is turned into a pymunk ``Space`` with only what the
physics needs, driven at the scene's constant speed, and the reactions are read from
the constraints while it moves.

What is built (:func:`build_space`)
-----------------------------------
- one dynamic body per moving body: mass, moment of inertia about the centre of mass
  and the centre of mass from the scene; no shapes (nothing collides), no sleeping;
- a ``PivotJoint`` per revolute joint; a ``GrooveJoint`` per prismatic joint (the
  groove along the guide's line, the pin at the slider point), plus a ``GearJoint``
  of ratio 1 that locks the slider's rotation to the guide's where the scene needs it
  (see :func:`needs_rotation_lock`);
- a crank driver: a ``PivotJoint`` and a ``SimpleMotor`` that holds the speed (its
  impulse is the driving moment); a sliding driver: a kinematic body moving at the
  constant speed along the line and a ``GrooveJoint`` across the line that pushes the
  slider (its impulse is the driving force);
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
exactly 3n unknowns; the magnitudes of the solution are checked against the public
impulses at run time (:attr:`SimRecord.vector_check`).

The start is the exact kinematic state of the scene (from the kinematic solution),
shifted half a step as the scheme carries it in its steady motion (positions
x - a dt^2 / 2, velocities v + a dt / 2): no start-up transient.
"""

from __future__ import annotations

import copy
import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pymunk

from .errors import WorkbenchError
from .scene import GROUND, Scene, load_scene

PYMUNK_VERSION = "7.3.1"
"""The pymunk version the settings were measured with (docs/simulation.md)."""

DEFAULT_ITERATIONS = 30
"""Solver iterations: about 10 suffice for a four-bar, about 30 for a slider-crank
(fewer make ``error_bias = 0`` diverge); more change nothing but cost."""

DEFAULT_STEPS_PER_REVOLUTION = 3600
"""Default time step: a tenth of a degree of the crank per step (about 1e-6 error)."""

GROOVE_MARGIN = 10.0
"""A groove reaches this many times the slider's stroke (at least 1 m) beyond it."""

WARMUP_STEPS = 5
WARMUP_ITERATIONS = 200
"""The first steps of a fresh model run with this many iterations: the solver's cached
impulses start at zero, and with the chosen count they would take a few hundred steps
to settle (a start-up transient of about 1e-3 on the first readings)."""

RESIST_UNSURE = 1e-4
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
    ``"actuator"`` (the force on the sliding driver ``b`` along its line). ``joint`` is
    the scene's joint name (``None`` for the driver's motor or actuator).
    ``anchor_a`` is the groove's start (grooves) or the joint point on ``a`` (pivots);
    ``anchor_b`` the joint point (pin) on ``b``. For a groove, ``slider`` names the
    joint's slider and ``slider_point`` its slider point (local), from which the couple
    M of the kinetostatic tables is measured.
    """

    constraint: pymunk.Constraint
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
    free_rotation : set of str
        Sliders whose rotation needs no lock (left free).
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
    free_rotation: set[str] = field(default_factory=set)
    error_bias: float = 0.0
    stepped: int = 0
    notes: list[str] = field(default_factory=list)
    actuator: pymunk.Body | None = None
    line: tuple[tuple[float, float], tuple[float, float]] | None = None   # driver line
    _slider_local: tuple[float, float] = (0.0, 0.0)
    _actuator_start: tuple = ((0.0, 0.0), (0.0, 0.0))
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
    from .solver import solve
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


def slider_is_free(scene: Scene, joint: str, guide_turns: bool) -> bool:
    """Whether a prismatic joint's slider keeps its angle with no lock.

    A prismatic joint keeps the slider's angle equal to the guide's plus
    ``line_angle``. The lock (a ``GearJoint``) is needed unless the slider's rotation
    is free of any couple in the exact motion, so that it keeps its angle by itself:
    the guide does not turn, the slider is a moving body whose centre of mass is the
    slider point, it has no other prismatic joint, its revolute joints are at the
    slider point, and its loads act at the slider point with no moment. Then the
    joint's couple M is zero.
    """
    j = scene.joints[joint]
    slider = j.slider
    if guide_turns or slider == GROUND:
        return False
    body = scene.bodies[slider]
    sp = body.local(j.points[1])

    def same(p) -> bool:
        return bool(np.allclose(p, sp, rtol=0.0, atol=1e-12))

    if body.cog is None or not same(body.cog):
        return False
    for other in scene.joints.values():
        if other.name == joint or slider not in other.bodies:
            continue
        if other.kind == "T" or not same(body.local(other.point_on(slider))):
            return False
    for ld in scene.loads:
        if ld.body == slider and (ld.moment != 0.0 or (ld.point is not None
                                                        and not same(body.local(ld.point)))):
            return False
    return True


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
    groove by a first-order amount, proportional to the sliding speed). So the
    groove goes on the body that is the ground or whose centre of mass lies on the
    line, and the pin on the other body at the foot of the normal from its centre of
    mass: both arms are then along the line or normal to it. A slider left free (see
    :func:`slider_is_free`) keeps the pin at its slider point (its centre of mass).
    Where no body qualifies, the groove goes on the guide and a note says so.

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
    half = 0.5 * dt
    for name, b in sc.bodies.items():
        m = kin0.bodies[name].take(slice(1, 2))
        body = pymunk.Body(b.mass, b.inertia)
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

    free: set[str] = set()
    notes: list[str] = []
    for name, j in sc.joints.items():
        if j.kind == "R":
            on, by = j.on_by
            pa = _local(sc, by, j.point_on(by))
            pb = _local(sc, on, j.point_on(on))
            c = pymunk.PivotJoint(bodies[by], bodies[on], pa, pb)
            add(c, ConstraintInfo(c, "pivot", name, by, on, pa, pb))
            continue
        g, s = j.guide, j.slider
        turns = g != GROUND and bool(np.any(np.asarray(sweep.kin.bodies[g].omega) != 0.0))
        if slider_is_free(sc, name, turns) and _on_line(sc, name, g):
            q, p, pin = g, s, _local(sc, s, j.points[1])
            free.add(s)
        else:
            if _on_line(sc, name, g):
                q, p = g, s
            elif _on_line(sc, name, s):
                q, p = s, g
            else:
                q, p = g, s
                notes.append(f"prismatic joint {name!r}: neither body's centre of mass lies "
                             "on the line; pymunk's groove then lags by a first-order amount")
            pin = _foot(sc, name, p)
        lp, u = _line(sc, name, q)
        lo, hi = _pin_range(sc, sweep, q, p, pin, lp, u)
        reach = GROOVE_MARGIN * max(hi - lo, 0.1)
        ga = tuple(lp + (lo - reach) * u)
        gb = tuple(lp + (hi + reach) * u)
        c = pymunk.GrooveJoint(bodies[q], bodies[p], ga, gb, pin)
        add(c, ConstraintInfo(c, "groove", name, q, p, ga, pin, (-u[1], u[0]), s,
                              _local(sc, s, j.points[1])))
        if s not in free:
            phase = bodies[s].angle - bodies[g].angle
            c = pymunk.GearJoint(bodies[g], bodies[s], phase, 1.0)
            add(c, ConstraintInfo(c, "lock", name, g, s))

    model = SimModel(sc, space, bodies, infos, float(dt), int(iterations), p0, d.speed, free,
                     error_bias=float(error_bias), notes=notes)
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
        model._actuator_start = ((px, py), (d.speed * ux, d.speed * uy))
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
    speed of their point over the motion."""
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
        if ld.resist is not None:
            m = kin.bodies[ld.body]
            x, y = m.point(b.local(ld.point))
            vx, vy = m.vel_at(x, y)
            top = float(np.max(np.hypot(np.broadcast_to(vx, (kin.n,)),
                                        np.broadcast_to(vy, (kin.n,)))))
            resist.append((ld.body, px, py, float(ld.resist), top))
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
    residual : float
        How far the solver was from converged at the sampled steps, as an estimate of
        the relative reaction error it causes; see :func:`solver_residual`.
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
    residual: float = 0.0


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
    only) calls the same Chipmunk functions those properties call, without the Python
    wrappers: ``cpBodyGetAngle``, ``cpBodyGetAngularVelocity``, ``cpBodyGetVelocity``,
    ``cpBodySetForce``, ``cpBodySetTorque``, ``cpBodyGetForce``, ``cpBodyGetTorque``
    and ``cpSpaceStep``. :meth:`verify` compares its reads with the public properties
    at every sample and raises if they ever differ.
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
            self.angle = lib.cpBodyGetAngle
            self.omega = lib.cpBodyGetAngularVelocity
            self.velocity = lib.cpBodyGetVelocity
            self.force = lib.cpBodyGetForce
            self.torque = lib.cpBodyGetTorque
            self.set_force = lib.cpBodySetForce
            self.set_torque = lib.cpBodySetTorque
        else:
            self.step = space.step
            self.handle = lambda body: body
            self.angle = lambda b: b.angle
            self.omega = lambda b: b.angular_velocity
            self.velocity = lambda b: b.velocity
            self.force = lambda b: b.force
            self.torque = lambda b: b.torque

            def set_force(b, f):
                b.force = f

            def set_torque(b, t):
                b.torque = t

            self.set_force = set_force
            self.set_torque = set_torque

    def verify(self, pairs) -> None:
        """Raise if a fast read differs from the public property (pinned version check)."""
        if not self.fast:
            return
        for body, h in pairs:
            v, f = self.velocity(h), self.force(h)
            ok = (self.angle(h) == body.angle and self.omega(h) == body.angular_velocity
                  and (v.x, v.y) == tuple(body.velocity) and (f.x, f.y) == tuple(body.force)
                  and self.torque(h) == body.torque)
            if not ok:
                raise SimulationError(
                    f"pymunk {pymunk.version}: the direct Chipmunk reads differ from the "
                    f"public properties (the fast path is pinned to pymunk {PYMUNK_VERSION}); "
                    "run with fast=False")


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
        Call Chipmunk's C functions directly in the stepping loop (about twice as
        fast); default: when the installed pymunk is the pinned version. Its reads are
        checked against the public properties at every sample.

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
    pstep = space.step
    fstep = acc.step
    bods = [model.bodies[n] for n in model.moving]
    cons = [i.constraint for i in model.constraints]
    H = acc.handle
    get_a, get_w, get_v = acc.angle, acc.omega, acc.velocity
    set_f, set_t = acc.set_force, acc.set_torque
    loads = [(H(b), (fx, fy), ca, cb, mm) for b, fx, fy, ca, cb, mm in model._loads]
    resist = [(H(b), px, py, mag, top) for b, px, py, mag, top in model._resist]
    loaded = {id(b): b for b, *_ in model._loads}
    loaded.update({id(b): b for b, *_ in model._resist})
    check_pairs = [(b, H(b)) for b in loaded.values()]
    # resist loads: the previous step's velocity (cog, omega), for the extrapolation
    prev = []
    if resist:
        # the start carries v(t0) + a dt / 2; one step earlier the scheme had a dt less
        for (h, *_), (ax, ay, al) in zip(resist, _start_acc(model), strict=True):
            v = get_v(h)
            prev.append([v.x - ax * dt, v.y - ay * dt, get_w(h) - al * dt])
    unsure = [False]
    cos, sin, hypot = math.cos, math.sin, math.hypot
    get_f, get_t = acc.force, acc.torque

    def apply_loads() -> None:
        for h, f, ca, cb, mm in loads:
            a = get_a(h) + get_w(h) * dt
            set_f(h, f)
            set_t(h, cos(a) * ca + sin(a) * cb + mm)
        flag = False
        for k, (h, px, py, mag, top) in enumerate(resist):
            v = get_v(h)
            w = get_w(h)
            pv = prev[k]
            # velocity at the pose the step reaches: 1.5 v_n - 0.5 v_(n-1), second order
            ex, ey, ew = 1.5 * v.x - 0.5 * pv[0], 1.5 * v.y - 0.5 * pv[1], 1.5 * w - 0.5 * pv[2]
            pv[0], pv[1], pv[2] = v.x, v.y, w
            if px or py:
                a = get_a(h) + w * dt
                c, s = cos(a), sin(a)
                rx, ry = c * px - s * py, s * px + c * py
                ex, ey = ex - ew * ry, ey + ew * rx
            else:
                rx = ry = 0.0
            sp = hypot(ex, ey)
            if sp <= RESIST_UNSURE * top:
                flag = True
            if sp == 0.0:
                continue
            fx, fy = -mag * ex / sp, -mag * ey / sp
            f = get_f(h)
            set_f(h, (f.x + fx, f.y + fy))
            set_t(h, get_t(h) + rx * fy - ry * fx)
        unsure[0] = flag

    has_loads = bool(loads or resist)
    n_samples = steps // every
    warm = 0
    if not model.stepped:
        warm = -(-WARMUP_STEPS // every)
        space.iterations = max(WARMUP_ITERATIONS, model.iterations)
    before, after, imp, flags, pos = [], [], [], [], []
    rng = range(every - 1)
    t0 = time.perf_counter()
    for k in range(n_samples):
        if k == warm:
            space.iterations = model.iterations
        if has_loads:
            for _ in rng:
                apply_loads()
                fstep(dt)
            apply_loads()
        else:
            for _ in rng:
                fstep(dt)
        acc.verify(check_pairs)
        row = []
        for b in bods:
            v, f = b.velocity, b.force
            row += (v.x, v.y, b.angular_velocity, f.x, f.y, b.torque)
        before.append(row)
        pstep(dt)
        row = []
        for b in bods:
            p, v = b.position, b.velocity
            row += (p.x, p.y, b.angle, v.x, v.y, b.angular_velocity)
        after.append(row)
        imp.append([c.impulse for c in cons])
        flags.append(unsure[0])
        pos.append(model.driver_position())
    space.iterations = model.iterations
    for _ in range(steps - n_samples * every):
        if has_loads:
            apply_loads()
        fstep(dt)
    wall = time.perf_counter() - t0
    model.stepped += steps
    nb = len(bods)
    before = np.array(before, dtype=float).reshape(n_samples, nb, 6)
    after = np.array(after, dtype=float).reshape(n_samples, nb, 6)
    imp = np.array(imp, dtype=float).reshape(n_samples, len(cons)) / dt
    times = (np.arange(n_samples) + 1) * every * dt
    impulse = {_label(info): imp[:, i] for i, info in enumerate(model.constraints)}
    signed, check = _signed(model, after[:, :, :3], before[:, :, :3], after[:, :, 3:],
                            before[:, :, 3:], imp)
    pose = after[:, :, :3].copy()
    vel = after[:, :, 3:].copy()
    return SimRecord(times, np.array(pos, dtype=float), impulse, signed,
                     np.array(flags, dtype=bool), check, wall, steps, dt, model.iterations,
                     bool(fast), pose, joint_drift(model, pose), vel,
                     solver_residual(model, pose, vel, times))


def solver_residual(model: SimModel, pose: np.ndarray, vel: np.ndarray,
                    times: np.ndarray) -> float:
    """How far each constraint's velocity equation is from satisfied after the step.

    After a converged step every constraint holds its velocity target: the relative
    velocity of a pivot's two points (a groove's along its normal, a lock's relative
    angular velocity) equals minus the joint's error times ``bias_coef / dt``, and
    the motor's crank turns at the set speed. What is left, r, changes the next
    step's momentum by about m r, i.e. the reactions by m r / dt; divided by a
    typical inertia force m a (a = speed^2 x size for a crank, speed^2 / size for a
    slider) this estimates the relative reaction error due to unfinished iterations.
    Returned: max |r| / (a dt) over the samples and constraints.
    """
    sc = model.scene
    names = model.moving
    index = {n: i for i, n in enumerate(names)}
    K = pose.shape[0]
    if K == 0:
        return 0.0
    dt = model.dt
    coef = 1.0 - model.error_bias ** dt
    cog = {n: sc.bodies[n].cog for n in names}
    size = max([1e-3] + [math.hypot(*p) for p in sc.ground.values()]
               + [math.hypot(*p) for b in sc.bodies.values() for p in b.points.values()])
    speed = abs(model.speed)
    a_ref = speed * speed * size if model.kind == "R" else speed * speed / size
    zero = np.zeros(K)

    def state(body: str, local):
        """World point, its velocity, the body's angle and angular velocity."""
        if body == GROUND:
            return local[0] + zero, local[1] + zero, zero, zero, zero, zero
        if body == "actuator":
            (x0, y0), (vx, vy) = model._actuator_start
            return (x0 + vx * times + local[0], y0 + vy * times + local[1],
                    vx + zero, vy + zero, zero, zero)
        i = index[body]
        th = pose[:, i, 2]
        c, s = np.cos(th), np.sin(th)
        lx, ly = local[0] - cog[body][0], local[1] - cog[body][1]
        rx, ry = c * lx - s * ly, s * lx + c * ly
        gx = pose[:, i, 0] + c * cog[body][0] - s * cog[body][1]
        gy = pose[:, i, 1] + s * cog[body][0] + c * cog[body][1]
        w = vel[:, i, 2]
        return gx + rx, gy + ry, vel[:, i, 0] - w * ry, vel[:, i, 1] + w * rx, th, w

    worst = 0.0
    for info in model.constraints:
        if info.role == "pivot":
            ax_, ay_, avx, avy, _, _ = state(info.a, info.anchor_a)
            bx_, by_, bvx, bvy, _, _ = state(info.b, info.anchor_b)
            r = np.hypot(bvx - avx + coef * (bx_ - ax_) / dt, bvy - avy + coef * (by_ - ay_) / dt)
        elif info.role in ("groove", "actuator"):
            bx_, by_, bvx, bvy, _, _ = state(info.b, info.anchor_b)
            ax_, ay_, _, _, th, w = state(info.a, info.anchor_a)
            nx = np.cos(th) * info.normal[0] - np.sin(th) * info.normal[1]
            ny = np.sin(th) * info.normal[0] + np.cos(th) * info.normal[1]
            # the guide's point under the pin moves with the guide
            if info.a == "actuator":
                avx, avy = model._actuator_start[1]
            elif info.a == GROUND:
                avx = avy = 0.0
            else:
                i = index[info.a]
                g = sc.bodies[info.a].cog
                c, s = np.cos(th), np.sin(th)
                gx = pose[:, i, 0] + c * g[0] - s * g[1]
                gy = pose[:, i, 1] + s * g[0] + c * g[1]
                avx = vel[:, i, 0] - w * (by_ - gy)
                avy = vel[:, i, 1] + w * (bx_ - gx)
            dn = (bx_ - ax_) * nx + (by_ - ay_) * ny
            r = np.abs((bvx - avx) * nx + (bvy - avy) * ny + coef * dn / dt)
        elif info.role == "lock":
            _, _, _, _, tha, wa = state(info.a, (0.0, 0.0))
            _, _, _, _, thb, wb = state(info.b, (0.0, 0.0))
            err = (thb - tha) - info.constraint.phase
            r = np.abs(wb - wa + coef * err / dt) * size
        else:       # motor
            r = np.abs(vel[:, index[info.b], 2] - model.speed) * size
        m = float(np.max(r)) if np.all(np.isfinite(r)) else math.inf
        worst = max(worst, m)
    return worst / (a_ref * dt)


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

    size = max([1e-3] + [math.hypot(*p) for p in model.scene.ground.values()]
               + [math.hypot(*p) for b in model.scene.bodies.values()
                  for p in b.points.values()])
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
        else:    # lock, motor: a couple on b, the opposite on a
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
    keep = np.ones((nb, 3), dtype=bool)
    for n in model.free_rotation:
        keep[index[n], 2] = False       # a free slider's moment row reads 0 = 0
    A = A[:, keep, :]
    b = rhs[:, keep]
    if A.shape[1] != n_unk:
        raise SimulationError(f"the momentum balance has {A.shape[1]} equations for {n_unk} "
                              "unknowns: the chain is not a driver plus dyads")
    lam = np.linalg.solve(A, b[..., None])[..., 0]

    signed: dict[str, Any] = {}
    check = 0.0
    j = 0
    for ci, info in enumerate(model.constraints):
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
            elif info.role == "lock":
                signed[f"{info.joint}:M"] = signed.get(f"{info.joint}:M", 0.0) + val
            else:
                signed["driver"] = val
        scale = float(np.max(mag[:, ci])) if K else 0.0
        if scale > 0.0:
            check = max(check, float(np.max(np.abs(got - mag[:, ci]))) / scale)
    for name in sc.joints:
        if sc.joints[name].kind == "T":
            signed[f"{name}:M"] = np.broadcast_to(signed.get(f"{name}:M", 0.0), (K,)).copy()
    return signed, check
