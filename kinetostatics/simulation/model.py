"""A pymunk model of a mechanism scene (:func:`build_space`).

The same scene that :func:`kinetostatics.solve` takes is turned into a pymunk ``Space``
with only what the physics needs, driven at the scene's constant speed; the reactions
are read from its constraints while it moves (:mod:`.stepper`).

What is built
-------------
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
  step, evaluated at the pose the step will reach (:mod:`.loads`).

Every constraint has ``error_bias = 0`` (the whole drift corrected in the next step),
``max_bias`` infinite, ``collide_bodies`` off. The solver sweeps the joints in the
scene's order and the driver's constraint last, or, on request, from the driver
outwards (:func:`solver_order`). See ``docs/simulation.md`` for the
measured effect of these settings and of the iteration count.

The start is the exact kinematic state of the scene (from the kinematic solution),
shifted half a step as the scheme carries it in its steady motion (positions
x - a dt^2 / 2, velocities v + a dt / 2): no start-up transient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import pymunk

from ..common.angles import degree_value
from ..model.scene import GROUND, Scene, load_scene
from .ballast import ballast_plan, describe, start_state
from .errors import SimulationError
from .friction import prepare_friction
from .geometry import cog_on_line, first_value, joint_line, line_foot, local_point, pin_range
from .loads import prepare_loads
from .reference import (
    point_acceleration,
    reference_solution,
    sweep_positions,
    translating_bodies,
)

__all__ = ["ConstraintInfo", "DEFAULT_ITERATIONS", "GROOVE_MARGIN", "SimModel", "build_space",
           "check_scene"]

DEFAULT_ITERATIONS = 30
"""Solver iterations: about 10 suffice for a four-bar, about 30 for a slider-crank
(fewer make ``error_bias = 0`` diverge); more change nothing but cost."""

GROOVE_MARGIN = 10.0
"""A groove reaches this many times the slider's stroke (at least 1 m) beyond it."""


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
    accel_scale : float
        The largest acceleration of a named point over the motion (m/s^2): the scale
        of a converged run's drift (:func:`~kinetostatics.simulation.drift_bound`).
    notes : list of str
        Modelling remarks (e.g. a prismatic joint whose groove cannot be laid out
        exactly; see :func:`build_space`).
    driver_first : bool
        The solver sweeps from the driver outwards instead of the scene's order with
        the driver last (:func:`solver_order`).
    ballast : dict
        Body name -> (extra mass, extra moment of inertia) the body is built with, its
        effect cancelled by a force before every step (:mod:`.ballast`); empty without.
    slider_local : tuple
        A sliding driver's point on its body, in the body's frame (m).
    body_loads, resist_loads : list
        The scene's loads as each step applies them, per body (filled by
        :func:`~kinetostatics.simulation.loads.prepare_loads`).
    joint_friction : list
        The joints with friction and their constants (filled by
        :func:`~kinetostatics.simulation.friction.prepare_friction`).
    boost : list
        ``[steps]``: steps left run with more solver iterations (set by the loads and
        friction that reverse, read by the stepper).
    ballast_state : dict
        Per ballasted body, what its cancelling force needs from the step before.
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
    accel_scale: float = 0.0
    stepped: int = 0
    notes: list[str] = field(default_factory=list)
    actuator: pymunk.Body | None = None
    line: tuple[tuple[float, float], tuple[float, float]] | None = None   # driver line
    slider_local: tuple[float, float] = (0.0, 0.0)
    body_loads: list = field(default_factory=list, repr=False)
    resist_loads: list = field(default_factory=list, repr=False)
    joint_friction: list = field(default_factory=list, repr=False)
    driver_first: bool = False
    boost: list = field(default_factory=lambda: [0], repr=False)   # steps left boosted
    ballast: dict[str, tuple[float, float]] = field(default_factory=dict)
    ballast_state: dict = field(default_factory=dict, repr=False)

    def built_mass(self, name: str) -> tuple[float, float]:
        """Mass and moment of inertia of a moving body as pymunk has it (the scene's
        plus its ballast; a body that only translates: infinite inertia)."""
        b = self.scene.bodies[name]
        dm, di = self.ballast.get(name, (0.0, 0.0))
        return b.mass + dm, (math.inf if name in self.translating else b.inertia + di)

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
            return degree_value(body.angle)
        (lx, ly), (ux, uy) = self.line
        px, py = body.local_to_world(self.slider_local)
        return (px - lx) * ux + (py - ly) * uy


def reading_label(info: ConstraintInfo) -> str:
    """The reading's label of a constraint: the joint's name, ``"<joint>:lock"`` or
    ``"driver"``."""
    if info.role in ("motor", "actuator"):
        return "driver"
    return f"{info.joint}:lock" if info.role == "lock" else str(info.joint)


def check_scene(scene: Scene) -> None:
    """Refuse what the simulation does not reproduce: a driver that accelerates or stands
    still, and the friction of a prismatic joint with a bearing length."""
    d = scene.driver
    if d.acceleration != 0.0:
        raise SimulationError(
            f"driver.acceleration = {d.acceleration:g}: the rows of such a scene are "
            "snapshots at one speed and acceleration, not a motion; the simulation needs "
            "a constant-speed driver (acceleration = 0)")
    if d.speed == 0.0:
        raise SimulationError("driver.speed = 0: nothing moves; give the driver a speed")
    for n, j in scene.joints.items():
        if j.kind == "T" and j.friction is not None and j.friction.mu > 0 \
                and j.friction.length > 0:
            raise SimulationError(
                f"joint {n!r} has friction with a bearing length ({j.friction.length:g} m): "
                "the cross-check does not model a prismatic joint's friction carried by its "
                "two ends (it needs the signed N and M at every step); remove 'length' to "
                "cross-check the friction mu |N|")


def _check_bodies(scene: Scene, translating: set[str]) -> None:
    """Every moving body needs a mass; one that turns needs a moment of inertia too (a
    body that only translates is built with an infinite one)."""
    for name, b in scene.bodies.items():
        if b.mass <= 0.0 or (b.inertia <= 0.0 and name not in translating):
            raise SimulationError(
                f"body {name!r} has mass {b.mass:g} kg and inertia {b.inertia:g} kg m^2: "
                "pymunk needs mass > 0 for every moving body and inertia > 0 for one that "
                "turns; give it both (and a cog) for the simulation")


def solver_order(scene: Scene, infos: list[ConstraintInfo],
                 driver_first: bool = False) -> list[pymunk.Constraint]:
    """The constraints in the order the solver is to sweep them.

    Chipmunk's solver is Gauss-Seidel over the constraints in the order they were
    added. Default (``driver_first`` False): the joints in the scene's order, the
    driver's constraint last, so that every step ends on the driver's exact speed.
    ``driver_first``: the driver's constraint first, then the joints by their distance
    from the driver's body (the fewest joints between them; the ground carries nothing
    on), in the scene's order where they tie: one sweep carries the prescribed motion
    down the chain, which keeps a slowly converging chain stable with far fewer
    iterations (the shaper at 3600 steps per revolution: driver last, 240 iterations
    diverge; first, 120 run), but the driver's speed is then held only to the solver's
    residual (the four-bar at 10 iterations: 1e-5 of it), and errors grow where the
    default order converges (docs/simulation.md).
    """
    if not driver_first:
        return [i.constraint for i in infos if i.constraint is not None]
    reach = {scene.driver.body: 0}
    todo = [scene.driver.body]
    while todo:
        body = todo.pop(0)
        for j in scene.joints.values():
            pair = j.on_by if j.kind == "R" else (j.guide, j.slider)
            if body in pair:
                other = pair[1] if pair[0] == body else pair[0]
                if other != GROUND and other not in reach:
                    reach[other] = reach[body] + 1
                    todo.append(other)

    def rank(info: ConstraintInfo) -> float:
        if info.role in ("motor", "actuator"):
            return -1.0
        return min(reach.get(info.a, math.inf), reach.get(info.b, math.inf))

    return [i.constraint for i in sorted(infos, key=rank) if i.constraint is not None]


def build_space(scene: Any, *, dt: float, iterations: int = DEFAULT_ITERATIONS,
                start: float | None = None, error_bias: float = 0.0,
                driver_first: bool = False, ballast: bool = False) -> SimModel:
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
    driver_first : bool
        Let the solver sweep the constraints from the driver outwards instead of the
        scene's order with the driver last (:func:`solver_order`).
    ballast : bool
        Build the driver's side heavy for the solver, the extra mass cancelled by a
        force before every step (:mod:`.ballast`): far fewer iterations along a chain
        whose driven end is light and far end heavy.

    Returns
    -------
    SimModel

    Raises
    ------
    SimulationError
        A driver with acceleration, a body without mass or inertia, bad settings.
    """
    sc = load_scene(scene)
    check_scene(sc)
    _check_settings(dt, iterations, error_bias)
    d = sc.driver
    p0 = float(d.positions[0]) if start is None else float(start)
    sweep = reference_solution(sc, sweep_positions(sc))

    space = pymunk.Space()
    space.iterations = int(iterations)
    space.gravity = tuple(sc.gravity)
    space.sleep_time_threshold = math.inf
    space.damping = 1.0
    frozen = translating_bodies(sc, sweep)
    _check_bodies(sc, frozen)
    extra = ballast_plan(sc, frozen) if ballast else {}
    bodies = _add_bodies(sc, space, reference_solution(sc, [p0]).kin, frozen, dt, extra)
    joints = _Joints(error_bias)
    _add_joints(sc, bodies, sweep, {GROUND} | frozen, joints)
    model = SimModel(sc, space, bodies, joints.infos, float(dt), int(iterations), p0,
                     d.speed, frozen, error_bias=float(error_bias),
                     accel_scale=point_acceleration(sc, sweep), notes=joints.notes,
                     driver_first=bool(driver_first), ballast=extra)
    if extra:
        model.ballast_state = start_state(model)
        model.notes.append("ballast (solver mass on the driver's side, cancelled by a force "
                           f"before every step): {describe(extra)}")
    _add_driver(model, joints)
    space.add(*solver_order(sc, joints.infos, driver_first))
    prepare_loads(model, sweep)
    prepare_friction(model, sweep)
    return model


def _check_settings(dt: float, iterations: int, error_bias: float) -> None:
    """Refuse a time step, an iteration count or an error bias that cannot be run."""
    if not (dt > 0.0 and math.isfinite(dt)):
        raise SimulationError(f"dt = {dt!r}: the time step must be a positive number of s")
    if int(iterations) != iterations or iterations < 1:
        raise SimulationError(f"iterations = {iterations!r}: give a whole number >= 1")
    if not 0.0 <= error_bias <= 1.0:
        raise SimulationError(f"error_bias = {error_bias!r}: give a fraction in [0, 1]")


def _add_bodies(sc: Scene, space: pymunk.Space, kin0, frozen: set[str], dt: float,
                extra: dict[str, tuple[float, float]]) -> dict[str, pymunk.Body]:
    """The scene's bodies in the space, on the exact kinematic state ``kin0`` shifted by
    the scheme's half step (a body that only translates with an infinite inertia; a
    ballasted one with its ``extra`` mass and inertia)."""
    bodies: dict[str, pymunk.Body] = {GROUND: space.static_body}
    half = 0.5 * dt
    for name, b in sc.bodies.items():
        m = kin0.bodies[name].take(slice(1, 2))
        # a body that only translates cannot turn: an infinite moment of inertia keeps
        # it so with no constraint (its couples follow from its momentum balance)
        dm, di = extra.get(name, (0.0, 0.0))
        body = pymunk.Body(b.mass + dm, math.inf if name in frozen else b.inertia + di)
        body.center_of_gravity = tuple(b.cog)
        gx, gy = (first_value(v) for v in m.point(b.cog))
        vx, vy = (first_value(v) for v in m.vel_at(gx, gy))
        ax, ay = (first_value(v) for v in m.acc_at(gx, gy))
        theta, omega, alpha = first_value(m.theta), first_value(m.omega), first_value(m.alpha)
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
    return bodies


class _Joints:
    """The constraints made so far, in the scene's order, with their notes; each made
    rigid (``error_bias``, no ``max_bias``) and free of collisions."""

    def __init__(self, error_bias: float):
        self.error_bias = error_bias
        self.infos: list[ConstraintInfo] = []
        self.notes: list[str] = []

    def add(self, c: pymunk.Constraint, info: ConstraintInfo) -> None:
        c.error_bias = self.error_bias
        c.max_bias = math.inf
        c.collide_bodies = False
        self.infos.append(info)


def _add_joints(sc: Scene, bodies: dict[str, pymunk.Body], sweep, fixed: set[str],
                joints: _Joints) -> None:
    """A pivot per revolute joint; a groove per prismatic joint, with a lock where a
    body on it turns (``fixed``: the ground and the bodies that only translate)."""
    for name, j in sc.joints.items():
        if j.kind == "R":
            on, by = j.on_by
            pa = local_point(sc, by, j.point_on(by))
            pb = local_point(sc, on, j.point_on(on))
            c = pymunk.PivotJoint(bodies[by], bodies[on], pa, pb)
            joints.add(c, ConstraintInfo(c, "pivot", name, by, on, pa, pb))
            continue
        g, s = j.guide, j.slider
        # the groove on a body whose arm to the pin's contact runs along the line
        # (the ground, a body that cannot turn, or one whose cog is on the line), the
        # pin on the other at the foot of the normal from its cog (see build_space)
        found = next(((q, p) for q, p in ((g, s), (s, g))
                      if q in fixed or cog_on_line(sc, name, q)), None)
        q, p = found or (g, s)
        if found is None:
            joints.notes.append(
                f"prismatic joint {name!r}: neither body's centre of mass lies on the line "
                "and both turn; pymunk's groove then lags by a first-order amount (expect "
                "errors proportional to dt)")
        if p in fixed:
            pin = local_point(sc, p, j.points[1] if p == s else j.points[0])
        else:
            pin = line_foot(sc, name, p)
        lp, u = joint_line(sc, name, q)
        lo, hi = pin_range(sc, sweep, q, p, pin, lp, u)
        reach = GROOVE_MARGIN * max(hi - lo, 0.1)
        ga = tuple(lp + (lo - reach) * u)
        gb = tuple(lp + (hi + reach) * u)
        c = pymunk.GrooveJoint(bodies[q], bodies[p], ga, gb, pin)
        joints.add(c, ConstraintInfo(c, "groove", name, q, p, ga, pin, (-u[1], u[0]), s,
                                     local_point(sc, s, j.points[1])))
        if g in fixed and s in fixed:
            # neither turns: no lock; the couple follows from the angular momentum
            # balance of the translating body (or bodies)
            joints.infos.append(ConstraintInfo(None, "couple", name, g, s))
        else:
            phase = bodies[s].angle - bodies[g].angle
            c = pymunk.GearJoint(bodies[g], bodies[s], phase, 1.0)
            joints.add(c, ConstraintInfo(c, "lock", name, g, s))


def _add_driver(model: SimModel, joints: _Joints) -> None:
    """The driver's constraint: a motor at the crank's speed, or a kinematic body moving
    along the line that pushes the slider through a groove across it (its force Fe)."""
    sc, space, bodies = model.scene, model.space, model.bodies
    d = sc.driver
    drv = bodies[d.body]
    if d.kind == "R":
        # SimpleMotor(a, b, rate) holds b.w - a.w = -rate: here the crank turns at `speed`
        c = pymunk.SimpleMotor(drv, space.static_body, d.speed)
        joints.add(c, ConstraintInfo(c, "motor", None, GROUND, d.body))
        return
    j = sc.joints[d.joint]
    if j.guide != GROUND:
        raise SimulationError("a sliding driver whose guide is not the ground is not "
                              "supported by the simulation")
    lp = sc.ground[j.points[0]]
    beta = j.beta
    ux, uy = math.cos(beta), math.sin(beta)
    sp = sc.bodies[d.body].local(j.points[1])
    model.slider_local = sp
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
    joints.add(c, ConstraintInfo(c, "actuator", None, "actuator", d.body, ga, sp, (ux, uy)))
    model.actuator = act
    bodies["actuator"] = act

