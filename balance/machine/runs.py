"""One run of the machine: stepped at constant speed (the steady amplitude fitted), or
along a coast-down (the envelope's peak)."""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

import numpy as np

from kinetostatics.common.angles import degree_value

from ..errors import BalanceError
from ..rotor.design import Unbalance
from .demodulation import envelope, peak
from .records import MachineRecord

if TYPE_CHECKING:
    from .mount import BalancingMachine


def record_steady(machine: BalancingMachine, us: list[Unbalance]) -> MachineRecord:
    """A run at constant speed: from rest on the mount, wait ``settle`` time constants
    1 / (zeta omega_n), record x over ``periods`` whole turns and fit
    x = a cos(omega t) + b sin(omega t) + x0 by least squares; the amplitude is hypot(a, b).
    """
    from kinetostatics.simulation import make_stepper
    space, frame, _, _ = machine.build_space(us)
    w = machine.omega
    dt = float(machine.dt)
    step = make_stepper(space, machine.fast)
    period = 2.0 * math.pi / w
    n_settle = int(math.ceil(machine.settle / (machine.damping_ratio * machine.omega_n) / dt))
    every = max(1, int(round(period / dt / machine.samples_per_period)))
    n_samples = int(math.ceil(machine.periods * period / (every * dt)))
    t0 = time.perf_counter()
    for _ in range(n_settle):
        step(dt)
    xs = np.empty(n_samples)
    inner = range(every)
    for k in range(n_samples):
        for _ in inner:
            step(dt)
        xs[k] = frame.position.x
    wall = time.perf_counter() - t0
    t = (n_settle + every * (np.arange(n_samples) + 1)) * dt
    # whole turns only: the fit's columns are then nearly orthogonal
    keep = t <= t[0] + math.floor((t[-1] - t[0]) / period) * period + 0.5 * every * dt
    t, xs = t[keep], xs[keep]
    A = np.column_stack([np.cos(w * t), np.sin(w * t), np.ones_like(t)])
    (a, b, _), *_ = np.linalg.lstsq(A, xs, rcond=None)
    return MachineRecord(t, xs, float(math.hypot(a, b)),
                         float(degree_value(math.atan2(b, a))), w, wall)


def record_coast(machine: BalancingMachine, us: list[Unbalance]) -> MachineRecord:
    """A coast-down run: the exact steady state at the start speed, then the speed
    history stepped, x and the rotor's angle read after every step, the envelope
    demodulated against the angle and its peak taken."""
    from kinetostatics.simulation import fast_path_available, make_stepper
    cd = machine.coast_down
    wn, dt = machine.omega_n, float(machine.dt)
    n = int(math.ceil(cd.duration / dt))
    space, frame, rotor, motor = machine.build_space(us, steady=True)
    fast = fast_path_available() if machine.fast is None else bool(machine.fast)
    step = make_stepper(space, fast)
    # the motor's rate before step k is the history's speed at the step's end
    rates = cd.speed((np.arange(n) + 1) * dt, wn).tolist()
    xs = np.empty(n)
    th = np.empty(n)
    if fast:
        from pymunk._chipmunk_cffi import lib
        mh, fh, rh = motor._constraint, frame._body, rotor._body
        set_rate, get_p, get_a = lib.cpSimpleMotorSetRate, lib.cpBodyGetPosition, \
            lib.cpBodyGetAngle
        t0 = time.perf_counter()
        for k in range(n):
            set_rate(mh, rates[k])
            step(dt)
            xs[k] = get_p(fh).x
            th[k] = get_a(rh)
        wall = time.perf_counter() - t0
        if (xs[-1], th[-1]) != (frame.position.x, rotor.angle):
            raise BalanceError("the direct Chipmunk reads differ from pymunk's public "
                               "properties; run with fast=False")
    else:
        t0 = time.perf_counter()
        for k in range(n):
            motor.rate = rates[k]
            step(dt)
            xs[k] = frame.position.x
            th[k] = rotor.angle
        wall = time.perf_counter() - t0
    t = (np.arange(n) + 1) * dt
    C = envelope(xs, th, machine.envelope_passes)
    E = np.abs(C)
    tp, Ap, k = peak(t, E)
    if k <= 1 or k >= n - 2 or not (np.isfinite(E[k - 2]) and np.isfinite(E[k + 2])):
        raise BalanceError("coast-down: the envelope's largest value lies at an end of "
                           "the run, not at the resonance; start higher, stop lower or "
                           "run longer")
    speed = np.gradient(th, t)
    phase = -degree_value(float(np.angle(C[k])))
    return MachineRecord(t, xs, Ap, phase, float(np.interp(tp, t, speed)), wall,
                         envelope=E, rotor_speed=speed, peak_time=tp)
