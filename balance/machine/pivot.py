"""The bearing force of an unbalanced rotor on a rigid pivot, measured in pymunk
(seed 002 eqs 3.3-3.5)."""

from __future__ import annotations

import math
import time
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kinetostatics.common.angles import degree_column, degree_value

from ..errors import BalanceError
from .unbalances import add_rigid, as_unbalances, spinning_rotor

PIVOT_STEPS_PER_REVOLUTION = 8000
"""Default time step of :func:`pivot_reaction`: the error is about 0.42 (omega dt)^2,
2.6e-7 at 8000 steps per turn."""


@dataclass
class PivotReaction:
    """The bearing force of an unbalanced rotor on a rigid pivot, measured in pymunk.

    Attributes
    ----------
    force : float
        Mean of the measured |F| = |pivot impulse| / dt over the compared steps (N).
    expected : float
        |sum m_i r_i| omega^2 (N): the resultant of the eccentric masses' inertia
        forces (seed 002 eqs 3.3-3.5).
    error : float
        Largest | |F| - expected | / expected over the compared steps.
    phase : float
        Mean direction of the force on the bearing, measured from the rotor's 0 deg mark
        (deg, in (-180, 180]).
    expected_phase : float
        The resultant unbalance's angle (deg): the bearing is pulled towards it.
    phase_error : float
        Largest |direction - expected_phase| over the compared steps (deg).
    motor_moment : float
        Largest moment the motor applied (N m): zero in theory (constant speed about a
        fixed axis, eq. 3.1 with epsilon = 0).
    vector_check : float
        Largest | |m (v' - v) / dt| - |F| | / expected: the rotor's momentum balance
        (the pivot is the only force on it) against the public impulse.
    time, force_history, direction : ndarray
        Per compared step: time (s), |F| (N) and the direction (deg from the 0 mark).
    settings : dict
        speed, dt, steps_per_revolution, iterations, revolutions, rotor_mass, mass.
    wall : float
        Wall time of the stepping loop (s).
    """

    force: float
    expected: float
    error: float
    phase: float
    expected_phase: float
    phase_error: float
    motor_moment: float
    vector_check: float
    time: np.ndarray = field(repr=False)
    force_history: np.ndarray = field(repr=False)
    direction: np.ndarray = field(repr=False)
    settings: dict[str, Any] = field(default_factory=dict, repr=False)
    wall: float = 0.0


def pivot_reaction(unbalances: Iterable[Any], speed: float, *, rotor_mass: float = 5.0,
                   rotor_inertia: float = 0.02, dt: float | None = None,
                   steps_per_revolution: int | None = None, iterations: int = 10,
                   revolutions: float = 2.0, fast: bool | None = None) -> PivotReaction:
    """Spin an unbalanced rotor on a rigid pivot in pymunk and measure the bearing force.

    The rotor (its own mass and inertia plus the eccentric masses, folded into one
    body as in :class:`BalancingMachine`) turns about a ``PivotJoint`` to the ground at
    a constant speed held by a ``SimpleMotor``; every constraint has ``error_bias = 0``,
    nothing collides or sleeps. The pivot's force |impulse| / dt is compared, step by
    step, with the resultant inertia force of the eccentric masses: each m_j r_j omega^2
    (the terms of eq. 3.5), adding up to |U_d| omega^2 with U_d = sum m_j r_j (eq. 3.3);
    the rotor's own (centred) mass adds nothing. Its direction comes from the rotor's
    momentum balance (the pivot's impulse is the only force on the rotor; the motor's
    is a couple): the bearing is pulled towards the resultant unbalance, which turns
    with the rotor. The first revolution (the start) is left out.

    Parameters
    ----------
    unbalances : iterable
        :class:`balance.Unbalance`, ``{mass, radius, angle}`` dicts or
        ``(mass, radius, angle)`` tuples (kg, m, deg).
    speed : float
        Rotor speed (rad/s, non-zero; negative turns clockwise).
    rotor_mass, rotor_inertia : float
        The rotor without its eccentric masses (kg, kg m^2 about the axis).
    dt : float, optional
        Time step (s); default a turn in ``steps_per_revolution`` steps.
    steps_per_revolution : int, optional
        Default 8000 (the error is about 0.42 (omega dt)^2: 2.6e-7).
    iterations : int
        Solver iterations (the result does not depend on them: one is exact here).
    revolutions : float
        Turns simulated (> 1; the first is left out).
    fast : bool, optional
        Step through Chipmunk directly (see :func:`kinetostatics.simulation.make_stepper`).

    Returns
    -------
    PivotReaction

    Raises
    ------
    BalanceError
        Bad masses, speed or settings; or no unbalance (nothing to measure).

    Examples
    --------
    >>> r = pivot_reaction([(0.02, 0.1, 30.0)], 200.0)
    >>> r.error < 1e-6, round(r.expected, 6), abs(r.phase - 30.0) < 1e-4
    (True, 80.0, True)
    """
    import pymunk

    from kinetostatics.simulation import make_stepper
    us = as_unbalances(unbalances, "unbalances")
    w, period, dt = _pivot_settings(rotor_mass, rotor_inertia, speed, dt,
                                    steps_per_revolution, iterations, revolutions)
    U = sum((u.U for u in us), 0j)                                 # eq. 3.3
    if abs(U) == 0.0:
        raise BalanceError("pivot_reaction: the rotor is balanced (sum m r = 0): there is no "
                           "bearing force to measure")
    space = pymunk.Space()
    space.iterations = int(iterations)
    space.sleep_time_threshold = math.inf
    rotor, _, _ = spinning_rotor(us, rotor_mass, rotor_inertia, w)
    m = rotor.mass
    space.add(rotor)
    pivot = pymunk.PivotJoint(space.static_body, rotor, (0.0, 0.0), (0.0, 0.0))
    motor = pymunk.SimpleMotor(space.static_body, rotor, -w)      # rotor.w - 0 = -(-w)
    add_rigid(space, (pivot, motor))
    step = make_stepper(space, fast)
    dt = float(dt)
    n = int(round(revolutions * period / dt))
    skip = int(round(period / dt))
    imp = np.empty(n)
    mot = np.empty(n)
    vel = np.empty(n, dtype=complex)
    ang = np.empty(n)
    v0 = complex(*rotor.velocity)
    t0 = time.perf_counter()
    for k in range(n):
        step(dt)
        imp[k] = pivot.impulse
        mot[k] = motor.impulse
        vx, vy = rotor.velocity
        vel[k] = complex(vx, vy)
        ang[k] = rotor.angle
    wall = time.perf_counter() - t0
    before = np.concatenate([[v0], vel[:-1]])
    on_bearing = -m * (vel - before) / dt          # minus the pivot's force on the rotor
    F = imp / dt
    expected = abs(U) * w * w                                      # eqs 3.3-3.5
    sl = slice(skip, n)
    direction = degree_column(np.angle(on_bearing * np.exp(-1j * ang)))
    true = degree_value(math.atan2(U.imag, U.real))
    dev = (direction[sl] - true + 180.0) % 360.0 - 180.0
    return PivotReaction(
        force=float(np.mean(F[sl])), expected=float(expected),
        error=float(np.max(np.abs(F[sl] - expected)) / expected),
        phase=float((true + np.mean(dev) + 180.0) % 360.0 - 180.0),
        expected_phase=float(true), phase_error=float(np.max(np.abs(dev))),
        motor_moment=float(np.max(mot[sl]) / dt),
        vector_check=float(np.max(np.abs(np.abs(on_bearing[sl]) - F[sl])) / expected),
        time=(np.arange(skip, n) + 1) * dt, force_history=F[sl], direction=direction[sl],
        settings={"speed": w, "dt": dt, "steps_per_revolution": period / dt,
                  "iterations": int(iterations), "revolutions": float(revolutions),
                  "rotor_mass": float(rotor_mass), "mass": float(m), "pymunk": pymunk.version},
        wall=wall)


def _pivot_settings(rotor_mass, rotor_inertia, speed, dt, steps_per_revolution, iterations,
                    revolutions) -> tuple[float, float, float]:
    """:func:`pivot_reaction`'s arguments checked: the speed (rad/s), the period (s) and
    the time step (s)."""
    for name, v in (("rotor_mass", rotor_mass), ("rotor_inertia", rotor_inertia)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise BalanceError(f"pivot_reaction: {name} = {v!r}; give a positive number")
    if not (isinstance(speed, (int, float)) and math.isfinite(speed) and speed != 0.0):
        raise BalanceError(f"pivot_reaction: speed = {speed!r}; give a non-zero speed in rad/s")
    if int(iterations) != iterations or iterations < 1:
        raise BalanceError(f"pivot_reaction: iterations = {iterations!r}; give a whole "
                           "number >= 1")
    if not (math.isfinite(revolutions) and revolutions > 1.0):
        raise BalanceError(f"pivot_reaction: revolutions = {revolutions!r}; give more than "
                           "1 (the first is left out)")
    w = float(speed)
    period = 2.0 * math.pi / abs(w)
    if dt is None:
        n_rev = PIVOT_STEPS_PER_REVOLUTION if steps_per_revolution is None \
            else steps_per_revolution
        if int(n_rev) != n_rev or n_rev < 10:
            raise BalanceError(f"pivot_reaction: steps_per_revolution = {n_rev!r}; give a "
                               "whole number >= 10")
        dt = period / n_rev
    elif steps_per_revolution is not None:
        raise BalanceError("pivot_reaction: give dt or steps_per_revolution, not both")
    if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0.0) \
            or abs(w) * dt > 0.05:
        raise BalanceError(f"pivot_reaction: dt = {dt!r}; give a positive step with "
                           "|speed| dt <= 0.05")
    return w, period, dt
