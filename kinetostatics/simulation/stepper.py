"""Stepping a model and reading its constraints (:func:`run`).

How a step works and what is measured: ``Space.step(dt)`` first moves every body
with its present velocity (x += v dt, angle += omega dt), then adds gravity and the
forces set on the bodies to the velocities, then lets the constraints apply the
impulses that make the velocities consistent with the new pose; forces are cleared
afterwards. The impulses of a step are therefore the reactions at the pose the step
reaches, and the loads must be evaluated at that pose (``x + v dt``), not at the pose
before the step. ``constraint.impulse / dt`` is the magnitude of a reaction; the
signed values come from the momentum balance (:mod:`.signed`).

The stepping loop can call Chipmunk's C functions directly (``fast``, pinned to
pymunk 7.3.1 and checked against the public properties during the run): the same
calls as pymunk's properties, without the Python wrappers, two to three times faster.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import pymunk

from ..common.angles import degree_column
from .ballast import ballast_function
from .drift import check_run, diverged
from .errors import SimulationError
from .friction import friction_function
from .loads import SWITCH_BOOST, loads_function
from .model import SimModel, reading_label
from .signed import SingularBalance, signed_reactions

__all__ = ["PYMUNK_VERSION", "SimRecord", "VERIFY_EVERY", "WARMUP_ITERATIONS", "WARMUP_STEPS",
           "fast_path_available", "make_stepper", "run", "warmup_schedule"]

PYMUNK_VERSION = "7.3.1"
"""The pymunk version the settings were measured with (docs/simulation.md)."""

WARMUP_STEPS = 50
WARMUP_ITERATIONS = 200
"""The first steps of a fresh model: the iterations fall geometrically from 200 to the
chosen count over 50 steps. The solver's cached impulses start at zero; with, say, 10
iterations from the start they take a few hundred steps to settle (errors near 1e-2
on the first readings), and an abrupt change of the count leaves a transient too."""


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


def fast_path_available() -> bool:
    """True when the installed pymunk is the pinned version, whose C functions the
    stepping loop may call directly (``pymunk._chipmunk_cffi.lib``)."""
    return pymunk.version == PYMUNK_VERSION


def _fast_path(fast: bool | None) -> bool:
    """Whether to call Chipmunk directly: ``fast`` as given, or (None) when the installed
    pymunk is the pinned version; ``fast=True`` on another version is refused."""
    if fast is None:
        return fast_path_available()
    if fast and not fast_path_available():
        raise SimulationError(f"fast=True needs pymunk {PYMUNK_VERSION} (installed: "
                              f"{pymunk.version}); run with fast=False")
    return bool(fast)


class BodyAccess:
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
        self.step = make_stepper(space, fast)
        if fast:
            from pymunk._chipmunk_cffi import lib
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
        """Raise if a fast read differs from the public property (pinned version check).

        A value that is not finite reads the same both ways (NaN is not equal to
        itself): a run whose state blew up is left to :func:`check_run`, which reports
        it as diverged, never as a pymunk version problem."""
        if not self.fast:
            return
        h = self.handle(body)
        v, f, p = self.velocity(h), self.force(h), self.position(h)
        fast = [self.angle(h), self.omega(h), v.x, v.y, f.x, f.y, p.x, p.y, self.torque(h)]
        public = [body.angle, body.angular_velocity, *body.velocity, *body.force,
                  *body.position, body.torque]
        if constraint is not None:
            fast.append(self.impulse(self.chandle(constraint)))
            public.append(constraint.impulse)
        if not all(a == b or (a != a and b != b) for a, b in zip(fast, public, strict=True)):
            raise SimulationError(
                f"pymunk {pymunk.version}: the direct Chipmunk reads differ from the public "
                f"properties (the fast path is pinned to pymunk {PYMUNK_VERSION}); run with "
                "fast=False")


def make_stepper(space: pymunk.Space, fast: bool | None = None):
    """A function ``step(dt)`` that advances ``space``: ``Space.step`` or, on the pinned
    pymunk version (``fast`` None or True), Chipmunk's ``cpSpaceStep`` called directly
    after one public ``Space.step(0)`` (pymunk's own checks; a zero step does nothing).
    Only for spaces whose content does not change while it steps."""
    fast = _fast_path(fast)
    space.step(0.0)
    if not fast:
        return space.step
    from pymunk._chipmunk_cffi import lib
    csp, cstep = space._space, lib.cpSpaceStep
    return lambda dt: cstep(csp, dt)


SWITCH_ITERATIONS = 480
"""Solver iterations of the ``SWITCH_SETTLE`` steps after a load or a joint's friction
switches (:mod:`.loads`, :mod:`.friction`): the step change excites a transient that a
short count damps slowly, or lets grow (measured on the shaper, docs/simulation.md)."""

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
    fast = _fast_path(fast)
    acc = BodyAccess(model, fast)      # its step: make_stepper (a public zero step first)
    apply_loads, fstep, unsure = _step_functions(model, acc)
    t0 = time.perf_counter()
    samples = _stepping_loop(model, acc, apply_loads, fstep, unsure, steps, every)
    wall = time.perf_counter() - t0
    model.stepped += steps
    return _record(model, *samples, steps, every, wall, fast)


def _step_functions(model: SimModel, acc: BodyAccess):
    """``(apply_loads, step, unsure)``: the function that sets the loads before a step
    (None: gravity only), the step, and the flag of a nearly still ``resist`` point.
    With joint friction, the friction is set after the scene's loads and the
    reactions are read after every step (:mod:`.friction`); with ballast, its
    cancelling forces are added last (:mod:`.ballast`)."""
    fstep = acc.step
    apply_loads, unsure = loads_function(model, acc)
    rubbing = friction_function(model, acc, unsure)
    if rubbing is not None:
        apply_friction, read_reactions = rubbing
        scene_loads, plain_step = apply_loads, fstep

        def loads_and_friction() -> None:
            unsure[0] = False
            if scene_loads is not None:
                scene_loads()
            apply_friction()

        def step_and_read(h: float) -> None:
            plain_step(h)
            read_reactions()

        apply_loads, fstep = loads_and_friction, step_and_read
    add_ballast = ballast_function(model, acc)
    if add_ballast is None:
        return apply_loads, fstep, unsure
    if apply_loads is None:
        return add_ballast, fstep, unsure
    loads = apply_loads

    def loads_and_ballast() -> None:
        loads()
        add_ballast()

    return loads_and_ballast, fstep, unsure


def _advancers(model: SimModel, apply_loads, fstep, schedule: list, ramp: list):
    """``(advance, warm)``: ``advance(n)`` takes n unsampled steps (with more iterations
    while a switch's boost lasts), ``warm(n)`` n steps of the warm-up ``schedule``."""
    dt = model.dt
    space = model.space
    boost = model.boost

    def boosted() -> None:
        # a load or a friction switched: more iterations, falling back (switch_ramp)
        boost[0] -= 1
        space.iterations = ramp[min(boost[0], len(ramp) - 1)]
        fstep(dt)
        space.iterations = model.iterations

    def advance(n: int) -> None:
        if apply_loads is None:
            for _ in range(n):
                fstep(dt)
        else:
            for _ in range(n):
                apply_loads()
                if boost[0]:
                    boosted()
                else:
                    fstep(dt)

    def warm(n: int) -> None:
        for _ in range(n):
            space.iterations = schedule.pop()
            if apply_loads is not None:
                apply_loads()
            fstep(dt)
        space.iterations = schedule[-1] if schedule else model.iterations

    return advance, warm


def _stepping_loop(model: SimModel, acc: BodyAccess, apply_loads, fstep, unsure: list,
                   steps: int, every: int):
    """Step ``steps`` times; at every ``every``-th step read the velocities and forces
    before it and the pose, velocities and impulses after it (lists of rows), and
    whether a resist point was nearly still; the fast reads checked in turn."""
    dt = model.dt
    space = model.space
    bods = [model.bodies[n] for n in model.moving]
    cons = [i.constraint for i in model.constraints if i.constraint is not None]
    hb = [acc.handle(b) for b in bods]
    hc = [acc.chandle(c) for c in cons]
    get_a, get_w, get_v, get_p = acc.angle, acc.omega, acc.velocity, acc.position
    get_f, get_t, get_i = acc.force, acc.torque, acc.impulse
    n_samples = steps // every
    schedule = [] if model.stepped else warmup_schedule(model.iterations)
    boost = model.boost
    boost[0] = 0
    ramp = switch_ramp(model.iterations)
    advance, warm = _advancers(model, apply_loads, fstep, schedule, ramp)

    before, after, imp, flags = [], [], [], []
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
        if boost[0]:
            boost[0] -= 1
            space.iterations = max(space.iterations, ramp[min(boost[0], len(ramp) - 1)])
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
        _verify_sample(acc, k, bods, cons)
    space.iterations = model.iterations
    advance(steps - n_samples * every)
    return before, after, imp, flags


def _verify_sample(acc: BodyAccess, k: int, bods: list, cons: list) -> None:
    """The fast reads against the public properties (:meth:`BodyAccess.verify`): every
    body and constraint at the first sample, then one of each at every
    ``VERIFY_EVERY`` samples, in turn."""
    nb, nc = len(bods), len(cons)
    if k == 0:
        for i, b in enumerate(bods):
            acc.verify(b, cons[i] if i < nc else None)
        for c in cons[nb:]:
            acc.verify(bods[0], c)
    elif k % VERIFY_EVERY == 0:
        j = k // VERIFY_EVERY
        acc.verify(bods[j % nb], cons[j % nc] if nc else None)


def _record(model: SimModel, before: list, after: list, imp: list, flags: list,
            steps: int, every: int, wall: float, fast: bool) -> SimRecord:
    """The sampled rows as a :class:`SimRecord`: the run checked for divergence
    (:func:`check_run`), the reactions signed by the momentum balance."""
    dt = model.dt
    real = [i for i in model.constraints if i.constraint is not None]
    nb, nc = len(model.moving), len(real)
    n_samples = steps // every
    before = np.array(before, dtype=float).reshape(n_samples, nb, 6)
    after = np.array(after, dtype=float).reshape(n_samples, nb, 6)
    imp = np.array(imp, dtype=float).reshape(n_samples, nc) / dt
    times = (np.arange(n_samples) + 1) * every * dt
    impulse = {reading_label(info): imp[:, i] for i, info in enumerate(real)}
    pose = after[:, :, :3].copy()
    vel = after[:, :, 3:].copy()
    positions = _driver_positions(model, pose)
    finite = (np.isfinite(before).all(axis=(1, 2)) & np.isfinite(after).all(axis=(1, 2))
              & np.isfinite(imp).all(axis=1))
    drift = check_run(model, times, positions, pose, finite)     # or SimulationDiverged
    try:
        signed, check = signed_reactions(model, after[:, :, :3], before[:, :, :3],
                                         after[:, :, 3:], before[:, :, 3:], imp)
    except SingularBalance as exc:
        raise diverged(model, float(times[exc.row]), float(positions[exc.row]), drift,
                       "singular momentum balance") from None
    return SimRecord(times, positions, impulse, signed, np.array(flags, dtype=bool), check,
                     wall, steps, dt, model.iterations, bool(fast), pose, drift, vel)


def switch_ramp(iterations: int) -> list[int]:
    """Iterations of the steps after a load's or a friction's switch, indexed by the
    steps left (:data:`~kinetostatics.simulation.loads.SWITCH_BOOST` at the switch):
    from ``SWITCH_ITERATIONS`` down to ``iterations`` geometrically (an abrupt fall
    back leaves a transient of its own)."""
    top = max(iterations, SWITCH_ITERATIONS)
    n = max(1, SWITCH_BOOST)
    return [round(iterations * (top / iterations) ** (k / n)) for k in range(n + 1)]


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
        return degree_column(th)
    (lx, ly), (ux, uy) = model.line
    sx, sy = model.slider_local
    px = pose[:, i, 0] + np.cos(th) * sx - np.sin(th) * sy
    py = pose[:, i, 1] + np.sin(th) * sx + np.cos(th) * sy
    return (px - lx) * ux + (py - ly) * uy
