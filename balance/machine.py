"""A virtual balancing machine: a rotor on a spring-damper mount, simulated in pymunk.

Seed 002 s. 3.3.2: the rotor swings on a frame; at resonance the amplitude is
proportional to the exciting unbalance force (eq. 3.23), so the amplitudes of three
runs (the rotor as it is, a trial mass at the 0 deg mark, at the 180 deg mark) give
the unbalance through the amplitude parallelogram (eqs 3.24-3.31,
:func:`balance.parallelogram`), and runs at 0, 120 and 240 deg give it without the
mirror ambiguity (:func:`balance.trial_runs`, the four-run method).

The machine here is one correction plane of it, in the plane of the rotor: a frame of
mass ``frame_mass`` slides along x (a ``GrooveJoint`` on the ground; it cannot turn)
on a linear spring and a viscous damper (a ``DampedSpring`` along x); the rotor turns
on a pin of the frame (``PivotJoint``) at a constant speed held by a ``SimpleMotor``.
The rotor is one body: its own mass and moment of inertia plus every eccentric mass
(the unbalance and the trial mass), with the centre of mass and the moment of inertia
about it that these give. Nothing is built that the motion does not need (no shapes,
no gravity: the motion is horizontal). The frame's x motion obeys

    (M + m) x'' + c x' + k x = |sum m_i r_i| omega^2 cos(omega t + phi),

so its steady amplitude is proportional to the resultant unbalance. The spring and
damper are tuned for the frame with the nominal rotor (``natural_frequency``,
``damping_ratio``); the machine runs at that natural frequency (resonance). A trial
mass adds a little mass to the rotor, which detunes the resonance slightly: the
method's own error (of order (m_trial / (2 zeta M))^2 relative, and the unbalance's
own mass likewise).

Each run starts from rest (frame at x = 0, rotor at speed), waits ``settle`` time
constants 1 / (zeta omega_n) for the free motion to die out, then records the frame's
x over ``periods`` whole turns and fits x = a cos(omega t) + b sin(omega t) + x0 by
least squares: the amplitude is hypot(a, b).
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .errors import BalanceError
from .resonance import ResonanceResult, parallelogram, trial_runs
from .rotor import Unbalance

__all__ = ["BalancingMachine", "MachineRecord", "MachineResult", "unbalance_vector"]


def _unbalances(items: Iterable[Any], where: str) -> list[Unbalance]:
    """Unbalance objects, dicts {mass, radius, angle} or (mass, radius, angle) tuples."""
    out = []
    for i, u in enumerate(items):
        if isinstance(u, Unbalance):
            m, r, a = u.mass, u.radius, u.angle
        elif isinstance(u, dict):
            try:
                m, r, a = u["mass"], u["radius"], u.get("angle", 0.0)
            except KeyError as exc:
                raise BalanceError(f"{where}[{i}]: missing {exc.args[0]!r}; give mass (kg), "
                                   "radius (m) and angle (deg)") from None
        else:
            try:
                m, r, a = u
            except (TypeError, ValueError):
                raise BalanceError(f"{where}[{i}]: give (mass, radius, angle) or an "
                                   "Unbalance") from None
        try:
            m, r, a = float(m), float(r), float(a)
        except (TypeError, ValueError):
            raise BalanceError(f"{where}[{i}]: mass, radius and angle must be numbers") \
                from None
        if not (math.isfinite(m) and m >= 0.0 and math.isfinite(r) and r >= 0.0
                and math.isfinite(a)):
            raise BalanceError(f"{where}[{i}]: mass {m!r} kg and radius {r!r} m must be "
                               ">= 0 and the angle finite")
        out.append(Unbalance(m, r, a))
    return out


def unbalance_vector(unbalances: Iterable[Any]) -> complex:
    """The resultant unbalance sum m_i r_i (kg m) as a complex number (angle from the
    rotor's 0 deg mark, counter-clockwise), eq. 3.3."""
    return sum((u.U for u in _unbalances(unbalances, "unbalances")), 0j)


@dataclass
class MachineRecord:
    """One run of the machine.

    Attributes
    ----------
    time, x : ndarray
        The recorded part of the run: time (s) and the frame's displacement (m).
    amplitude : float
        Steady amplitude of x at the rotor's frequency (m).
    phase : float
        Its phase (deg): x ~ amplitude cos(omega t - phase).
    speed : float
        Rotor speed (rad/s).
    wall : float
        Wall time of the simulation (s).
    """

    time: np.ndarray
    x: np.ndarray
    amplitude: float
    phase: float
    speed: float
    wall: float


@dataclass
class MachineResult:
    """The runs of a balancing method on the machine and what they give.

    Attributes
    ----------
    result : ResonanceResult
        From :func:`balance.parallelogram` (three runs) or :func:`balance.trial_runs`.
    amplitudes : dict
        ``"A1"`` (no trial mass) and the trial runs' amplitudes by mark (deg), in m.
    unbalance : complex
        The resultant unbalance put in (kg m).
    unbalance_error : float
        |recovered m r - put-in m r| / put-in m r.
    angle_error : float
        Angle (deg) between the recovered correction ``angle`` and the true one (put-in
        angle + 180); for the three-run method the nearer of ``angle`` and
        ``mirror_angle`` (the method cannot tell them apart).
    records : list of MachineRecord
    """

    result: ResonanceResult
    amplitudes: dict[str, float]
    unbalance: complex
    unbalance_error: float
    angle_error: float
    records: list[MachineRecord] = field(default_factory=list, repr=False)


@dataclass(frozen=True)
class BalancingMachine:
    """A rotor on a spring-damper mount, simulated in pymunk (see the module docstring).

    Parameters
    ----------
    frame_mass : float
        Mass of the frame on the springs (kg).
    rotor_mass : float
        Mass of the rotor without its eccentric masses (kg); also the nominal rotor the
        mount is tuned for.
    rotor_inertia : float
        Its moment of inertia about the axis (kg m^2).
    natural_frequency : float
        Natural frequency of the frame with the nominal rotor (Hz); the machine runs
        at it (resonance) unless ``speed`` is given.
    damping_ratio : float
        zeta of the mount, in (0, 1).
    speed : float, optional
        Rotor speed (rad/s); default the natural frequency.
    dt : float
        Time step (s).
    iterations : int
        Solver iterations (10: more change no amplitude).
    settle : float
        Time constants 1 / (zeta omega_n) waited before recording (12: the free motion
        has decayed to e^-12, 6e-6 of its start).
    periods : int
        Whole turns recorded.
    samples_per_period : int
        Readings of x per turn.
    fast : bool, optional
        Step through Chipmunk directly (pinned pymunk version; see
        :func:`kinetostatics.simulation.make_stepper`).
    """

    frame_mass: float = 20.0
    rotor_mass: float = 5.0
    rotor_inertia: float = 0.02
    natural_frequency: float = 10.0
    damping_ratio: float = 0.1
    speed: float | None = None
    dt: float = 1e-4
    iterations: int = 10
    settle: float = 12.0
    periods: int = 10
    samples_per_period: int = 50
    fast: bool | None = None

    def __post_init__(self) -> None:
        for name in ("frame_mass", "rotor_mass", "rotor_inertia", "natural_frequency", "dt",
                     "settle"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise BalanceError(f"BalancingMachine.{name} = {v!r}: give a positive number")
        if not 0.0 < self.damping_ratio < 1.0:
            raise BalanceError(f"BalancingMachine.damping_ratio = {self.damping_ratio!r}: "
                               "give a fraction in (0, 1)")
        if self.speed is not None and not (math.isfinite(self.speed) and self.speed > 0):
            raise BalanceError(f"BalancingMachine.speed = {self.speed!r}: give rad/s > 0")
        for name in ("iterations", "periods", "samples_per_period"):
            v = getattr(self, name)
            if int(v) != v or v < 1:
                raise BalanceError(f"BalancingMachine.{name} = {v!r}: give a whole number >= 1")
        if self.dt * self.omega > 0.05:
            raise BalanceError(f"BalancingMachine.dt = {self.dt:g} s: too coarse for "
                               f"{self.omega:.4g} rad/s (keep omega dt <= 0.05)")

    # -- the mount -------------------------------------------------------------
    @property
    def omega_n(self) -> float:
        """Natural angular frequency of the frame with the nominal rotor (rad/s)."""
        return 2.0 * math.pi * self.natural_frequency

    @property
    def stiffness(self) -> float:
        """k = (M + m) omega_n^2 (N/m)."""
        return (self.frame_mass + self.rotor_mass) * self.omega_n ** 2

    @property
    def damping(self) -> float:
        """c = 2 zeta sqrt(k (M + m)) (N s/m)."""
        return 2.0 * self.damping_ratio * math.sqrt(self.stiffness
                                                    * (self.frame_mass + self.rotor_mass))

    @property
    def omega(self) -> float:
        """Rotor speed (rad/s)."""
        return self.omega_n if self.speed is None else float(self.speed)

    # -- one run ---------------------------------------------------------------
    def record(self, unbalances: Iterable[Any] = ()) -> MachineRecord:
        """Run the machine with these eccentric masses on the rotor and measure the
        frame's steady amplitude.

        Parameters
        ----------
        unbalances : iterable
            :class:`balance.Unbalance`, ``{mass, radius, angle}`` dicts or
            ``(mass, radius, angle)`` tuples (kg, m, deg from the 0 deg mark).

        Returns
        -------
        MachineRecord
        """
        from kinetostatics.simulation import make_stepper
        space, frame, _ = self.build(unbalances)
        w = self.omega
        dt = float(self.dt)
        step = make_stepper(space, self.fast)
        period = 2.0 * math.pi / w
        n_settle = int(math.ceil(self.settle / (self.damping_ratio * self.omega_n) / dt))
        every = max(1, int(round(period / dt / self.samples_per_period)))
        n_samples = int(math.ceil(self.periods * period / (every * dt)))
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
                             float(math.degrees(math.atan2(b, a))), w, wall)

    def build(self, unbalances: Iterable[Any] = ()):
        """The pymunk space of a run, at rest on its mount with the rotor at speed.

        Returns
        -------
        (pymunk.Space, pymunk.Body, pymunk.Body)
            The space, the frame and the rotor (whose local origin is on the axis).
        """
        import pymunk
        us = _unbalances(unbalances, "unbalances")
        m = self.rotor_mass + sum(u.mass for u in us)
        U = sum((u.U for u in us), 0j)
        g = U / m                                          # rotor's centre of mass
        inertia = self.rotor_inertia - m * abs(g) ** 2 \
            + sum(u.mass * u.radius ** 2 for u in us)      # about the cog (parallel axes)
        w = self.omega
        space = pymunk.Space()
        space.iterations = int(self.iterations)
        space.sleep_time_threshold = math.inf
        frame = pymunk.Body(self.frame_mass, math.inf)     # slides, cannot turn
        rotor = pymunk.Body(m, inertia)
        rotor.center_of_gravity = (g.real, g.imag)
        rotor.angular_velocity = w
        v = 1j * w * g
        rotor.velocity = (v.real, v.imag)
        space.add(frame, rotor)
        length = 1.0
        joints = [
            pymunk.GrooveJoint(space.static_body, frame, (-length, 0.0), (length, 0.0),
                               (0.0, 0.0)),
            pymunk.PivotJoint(frame, rotor, (0.0, 0.0), (0.0, 0.0)),
            pymunk.SimpleMotor(rotor, frame, w),           # frame.w - rotor.w = -w
            pymunk.DampedSpring(space.static_body, frame, (-length, 0.0), (0.0, 0.0), length,
                                self.stiffness, self.damping),
        ]
        for c in joints:
            c.error_bias = 0.0
            c.collide_bodies = False
            space.add(c)
        return space, frame, rotor

    def steady_amplitude(self, unbalances: Iterable[Any] = ()) -> float:
        """The exact steady amplitude of the model (m): |U| omega^2 / |k - (M + m) omega^2
        + i c omega|, U the resultant unbalance, m the rotor's whole mass."""
        us = _unbalances(unbalances, "unbalances")
        mass = self.frame_mass + self.rotor_mass + sum(u.mass for u in us)
        w = self.omega
        U = abs(sum((u.U for u in us), 0j))
        return U * w * w / abs(complex(self.stiffness - mass * w * w, self.damping * w))

    def amplitude(self, unbalances: Iterable[Any] = ()) -> float:
        """Steady amplitude of the frame (m) with these eccentric masses on the rotor."""
        return self.record(unbalances).amplitude

    # -- the methods -------------------------------------------------------------
    def three_run(self, unbalances: Iterable[Any], trial_mass: float, trial_radius: float,
                  correction_radius: float) -> MachineResult:
        """The amplitude-parallelogram method on the machine: the rotor as it is, the
        trial mass at the 0 deg and at the 180 deg mark; :func:`balance.parallelogram`.

        Returns
        -------
        MachineResult
            With the recovered unbalance, its error against the one put in and the
            angle error (the nearer of the two mirror candidates).
        """
        us = _unbalances(unbalances, "unbalances")
        recs = [self.record(us), self.record([*us, Unbalance(trial_mass, trial_radius, 0.0)]),
                self.record([*us, Unbalance(trial_mass, trial_radius, 180.0)])]
        A1, A2, A3 = (r.amplitude for r in recs)
        res = parallelogram(A1, A2, A3, trial_mass, trial_radius, correction_radius)
        return self._result(res, {"A1": A1, "0": A2, "180": A3}, us, recs,
                            candidates=(res.angle, res.mirror_angle))

    def four_run(self, unbalances: Iterable[Any], trial_mass: float, trial_radius: float,
                 correction_radius: float,
                 marks: tuple[float, ...] = (0.0, 120.0, 240.0)) -> MachineResult:
        """The four-run method on the machine: the rotor as it is and the trial mass at
        each of ``marks`` (default 0, 120, 240 deg); :func:`balance.trial_runs`."""
        us = _unbalances(unbalances, "unbalances")
        recs = [self.record(us)] + [self.record([*us, Unbalance(trial_mass, trial_radius, a)])
                                    for a in marks]
        A1 = recs[0].amplitude
        runs = [(a, r.amplitude) for a, r in zip(marks, recs[1:], strict=True)]
        res = trial_runs(A1, runs, trial_mass, trial_radius, correction_radius)
        amps = {"A1": A1, **{f"{a:g}": A for a, A in runs}}
        return self._result(res, amps, us, recs, candidates=(res.angle,))

    @staticmethod
    def _result(res: ResonanceResult, amps: dict, us: list[Unbalance], recs: list,
                candidates: tuple) -> MachineResult:
        U = sum((u.U for u in us), 0j)
        if abs(U) == 0.0:
            err = abs(res.unbalance)
            ang = float("nan")
        else:
            err = abs(res.unbalance - abs(U)) / abs(U)
            true = math.degrees(math.atan2(U.imag, U.real)) + 180.0
            ang = min(abs((c - true + 180.0) % 360.0 - 180.0) for c in candidates
                      if c is not None)
        return MachineResult(res, amps, U, float(err), float(ang), recs)
