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
on a pin of the frame (``PivotJoint``) at a speed held by a ``SimpleMotor``.
The rotor is one body: its own mass and moment of inertia plus every eccentric mass
(the unbalance and the trial mass), with the centre of mass and the moment of inertia
about it that these give. Nothing is built that the motion does not need (no shapes,
no gravity: the motion is horizontal). With the rotor's angle theta(t) the frame's x
motion obeys

    (M + m) x'' + c x' + k x = Re(U (theta'^2 - i theta'') e^(i theta)),

U = sum m_i r_i e^(i angle_i) the resultant unbalance (eq. 3.3): at constant speed
|U| omega^2 cos(omega t + phi), the force of eq. 3.23, so the steady amplitude is
proportional to |U|. The spring and damper are tuned for the frame with the nominal
rotor (``natural_frequency``, ``damping_ratio``).

Two ways to run it:

- at constant speed (default: the natural frequency, resonance). Each run starts from
  rest (frame at x = 0, rotor at speed), waits ``settle`` time constants
  1 / (zeta omega_n) for the free motion to die out, then records the frame's x over
  ``periods`` whole turns and fits x = a cos(omega t) + b sin(omega t) + x0 by least
  squares: the amplitude is hypot(a, b);
- coasting down through resonance, as the seed runs the machine (``coast_down``, a
  :class:`CoastDown`): the run starts in the steady motion at 1.5 omega_n and the
  motor brings the speed down along the same prescribed history in every run; x and
  the rotor's angle are read after every step, x is demodulated against the angle
  (:func:`envelope`, a lock-in on the 0 deg mark) and the amplitude of the run is the
  envelope's peak (:func:`peak`). The system being linear in U for a given mass and
  speed history, the peak is proportional to |U| and independent of its angle.

A trial mass adds a little mass to the mount, which changes its response slightly:
the method's own error, about m_trial / (M + m) in the recovered unbalance for a
trial unbalance of the order of the rotor's, amplified where the trial is much
smaller or much larger (docs/simulation.md). ``mass_correction`` in :meth:`three_run`
and :meth:`four_run` removes it exactly at constant speed and mostly in a coast-down
(:meth:`BalancingMachine.mass_factor`).

:func:`pivot_reaction` checks the force itself: a rotor on a rigid pivot, whose
bearing force pymunk measures as |sum m_i r_i| omega^2 (eqs 3.3-3.5).
:func:`coast_down_study` measures how the methods' errors grow with the trial mass and
the speed of the coast-down. The runs of a method or a study are a batch
(:meth:`BalancingMachine.runs`): by default one process per core, or any
``concurrent.futures.Executor``.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable
from concurrent.futures import Executor
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

import numpy as np

from ..errors import BalanceError
from ..resonance import ResonanceResult, parallelogram, trial_runs
from ..rotor import Unbalance

__all__ = [
    "BalancingMachine",
    "CoastDown",
    "MachineRecord",
    "MachineResult",
    "PivotReaction",
    "coast_down_study",
    "envelope",
    "peak",
    "pivot_reaction",
    "random_unbalance",
    "unbalance_vector",
]


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
        Rotor speed (rad/s); of a coast-down, the speed at the envelope's peak.
    wall : float
        Wall time of the simulation (s), measured in the process that ran it.
    envelope : ndarray or None
        Coast-down: the amplitude envelope of x at ``time`` (m), NaN where the
        demodulation window does not fit (:func:`envelope`); None at constant speed.
    rotor_speed : ndarray or None
        Coast-down: the rotor's measured speed at ``time`` (rad/s).
    peak_time : float or None
        Coast-down: when the envelope peaks (s); ``amplitude`` is its peak value.
    """

    time: np.ndarray
    x: np.ndarray
    amplitude: float
    phase: float
    speed: float
    wall: float
    envelope: np.ndarray | None = field(default=None, repr=False)
    rotor_speed: np.ndarray | None = field(default=None, repr=False)
    peak_time: float | None = None


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
        The runs (their ``amplitude`` as measured).
    mass_factors : dict or None
        With ``mass_correction``: the factor each run's amplitude was multiplied by
        before it was fed to the method (:meth:`BalancingMachine.mass_factor`).
    """

    result: ResonanceResult
    amplitudes: dict[str, float]
    unbalance: complex
    unbalance_error: float
    angle_error: float
    records: list[MachineRecord] = field(default_factory=list, repr=False)
    mass_factors: dict[str, float] | None = None


@dataclass(frozen=True)
class CoastDown:
    """A speed history for the machine: spun up above resonance, coasting down through it
    (seed 002 s. 3.3.2: each run is spun above the resonance speed and let go; the
    amplitude A1 (A2, A3) is read as the speed passes resonance, eqs 3.23, 3.24, 3.26).

    The rotor's speed falls linearly from ``start`` to ``stop`` times the mount's
    natural frequency omega_n in ``duration`` seconds. The machine's motor imposes it
    (a ``SimpleMotor`` whose rate is set before every step), so every run, whatever
    its masses, passes resonance along the same history: the method's premise (the
    amplitudes of the runs compare only if they are read the same way). A free coast
    would not do that: its run-down rate depends on the rotor's inertia (the trial
    mass changes it) and on the torque the swinging frame exerts on the eccentric
    masses near resonance.

    Parameters
    ----------
    start, stop : float
        Speeds at the start and at the end, in multiples of omega_n (start > stop > 0).
    duration : float
        Time of the run-down (s).
    """

    start: float = 1.5
    stop: float = 0.5
    duration: float = 10.0

    def __post_init__(self) -> None:
        for name in ("start", "stop", "duration"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise BalanceError(f"CoastDown.{name} = {v!r}: give a positive number")
        if not self.start > self.stop:
            raise BalanceError(f"CoastDown: start = {self.start!r} must exceed stop = "
                               f"{self.stop!r} (a coast-down slows down)")

    def speed(self, t: Any, omega_n: float) -> np.ndarray:
        """The rotor's speed (rad/s) at time(s) ``t`` (held at ``stop`` after the end)."""
        s = np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)
        return omega_n * (self.start + (self.stop - self.start) * s)

    def rate(self, omega_n: float) -> float:
        """Deceleration (rad/s^2)."""
        return (self.start - self.stop) * omega_n / self.duration

    def passage(self, omega_n: float, damping_ratio: float) -> float:
        """Time taken to cross the half-power band 2 zeta omega_n, in time constants
        1 / (zeta omega_n) of the mount: 2 zeta^2 omega_n^2 / rate. Large (10 and more):
        the run passes resonance quasi-steadily; near 1 and below: the peak shrinks and
        comes late (at a lower speed)."""
        return 2.0 * (damping_ratio * omega_n) ** 2 / self.rate(omega_n)


ENVELOPE_PASSES = 3
"""One-turn moving averages applied to the demodulated signal (:func:`envelope`)."""


def envelope(x: Any, angle: Any, passes: int = ENVELOPE_PASSES) -> np.ndarray:
    """Complex amplitude of a signal at the rotor's frequency, turn by turn (a lock-in
    against the rotor's 0 deg mark, as a balancing machine's phase reference does).

    ``z = x e^(-i angle)`` is averaged over one turn of the rotor (the angle interval
    [angle - pi, angle + pi]), ``passes`` times over. A part of x that turns with the
    rotor, Re(C e^(i angle)) with C slowly varying, becomes C / 2; the part that turns
    the other way becomes C* e^(-2 i angle) / 2, which a whole turn's average removes
    (a constant exactly, a slowly varying one to a residue that every further pass
    makes smaller by about its relative change over a turn). The integrals are the
    trapezoid rule on the samples, the window's ends interpolated consistently with
    it (the samples' linear interpolant integrated exactly).

    Parameters
    ----------
    x : array_like
        Samples of the signal.
    angle : array_like
        The rotor's angle at the same instants (rad, increasing).
    passes : int
        Number of one-turn averages (1: a boxcar over a turn; 3: a smooth window of
        three turns).

    Returns
    -------
    ndarray of complex
        C at each sample: x ~ Re(C e^(i angle)), so |C| is the envelope and -arg C the
        phase (x ~ |C| cos(angle - phase)); NaN where the windows do not fit.
    """
    th = np.asarray(angle, dtype=float)
    z = np.asarray(x, dtype=float) * np.exp(-1j * th)
    if th.size < 3 or not np.all(np.diff(th) > 0.0):
        raise BalanceError("envelope: give at least 3 samples with an increasing angle")
    if int(passes) != passes or passes < 1:
        raise BalanceError(f"envelope: passes = {passes!r}; give a whole number >= 1")
    h = np.diff(th)
    ok = np.ones(th.size, dtype=bool)
    for _ in range(int(passes)):
        zf = np.where(ok, z, 0.0)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (zf[1:] + zf[:-1]) * h)])

        def integral(a: np.ndarray, zf=zf, cum=cum) -> np.ndarray:
            k = np.clip(np.searchsorted(th, a, side="right") - 1, 0, th.size - 2)
            s = a - th[k]
            return cum[k] + s * zf[k] + 0.5 * s * s * (zf[k + 1] - zf[k]) / h[k]

        lo, hi = th - math.pi, th + math.pi
        fits = (lo >= th[0]) & (hi <= th[-1])
        # a window fits where every sample in it was valid in the pass before
        bad = np.concatenate([[0], np.cumsum(~ok)])
        ilo = np.searchsorted(th, lo, side="left")
        ihi = np.searchsorted(th, hi, side="right")
        # samples ilo - 1 .. ihi are used (the ends are interpolated)
        fits &= (bad[np.clip(ihi + 1, 0, th.size)] - bad[np.clip(ilo - 1, 0, th.size)]) == 0
        z = np.where(fits, (integral(np.clip(hi, th[0], th[-1]))
                            - integral(np.clip(lo, th[0], th[-1]))) / (2.0 * math.pi),
                     np.nan + 0j)
        ok = fits
    return 2.0 * z


def peak(t: Any, values: Any) -> tuple[float, float, int]:
    """The largest of sampled values, refined by the parabola through it and its two
    neighbours: (time, value, index of the largest sample). NaNs are skipped."""
    t = np.asarray(t, dtype=float)
    v = np.asarray(values, dtype=float)
    if not np.any(np.isfinite(v)):
        raise BalanceError("peak: no finite value")
    k = int(np.nanargmax(v))
    if k == 0 or k == v.size - 1 or not (np.isfinite(v[k - 1]) and np.isfinite(v[k + 1])):
        return float(t[k]), float(v[k]), k
    y0, y1, y2 = v[k - 1], v[k], v[k + 1]
    den = y0 - 2.0 * y1 + y2
    d = 0.5 * (y0 - y2) / den if den < 0.0 else 0.0       # vertex offset, in samples
    d = max(-0.5, min(0.5, d))
    tk = t[k] + d * (t[k + 1] - t[k] if d > 0 else t[k] - t[k - 1])
    return float(tk), float(y1 - 0.25 * (y0 - y2) * d), k


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
        at it (resonance) unless ``speed`` or ``coast_down`` is given.
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
        has decayed to e^-12, 6e-6 of its start). Constant speed only.
    periods : int
        Whole turns recorded (constant speed).
    samples_per_period : int
        Readings of x per turn (constant speed; a coast-down reads every step).
    fast : bool, optional
        Step through Chipmunk directly (pinned pymunk version; see
        :func:`kinetostatics.simulation.make_stepper`).
    coast_down : CoastDown, optional
        Run each reading as a coast-down through resonance instead (seed 002 s. 3.3.2):
        the amplitude of a run is the peak of the frame's envelope.
    envelope_passes : int
        One-turn averages of the coast-down's demodulation (:func:`envelope`).
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
    coast_down: CoastDown | None = None
    envelope_passes: int = ENVELOPE_PASSES

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
        for name in ("iterations", "periods", "samples_per_period", "envelope_passes"):
            v = getattr(self, name)
            if int(v) != v or v < 1:
                raise BalanceError(f"BalancingMachine.{name} = {v!r}: give a whole number >= 1")
        if self.coast_down is not None:
            if not isinstance(self.coast_down, CoastDown):
                raise BalanceError(f"BalancingMachine.coast_down = {self.coast_down!r}: give "
                                   "a CoastDown")
            if self.speed is not None:
                raise BalanceError("BalancingMachine: give speed (constant) or coast_down, "
                                   "not both")
            if not self.coast_down.stop < 1.0 < self.coast_down.start:
                raise BalanceError(f"BalancingMachine.coast_down: the speed must pass the "
                                   f"resonance: start {self.coast_down.start:g} > 1 > stop "
                                   f"{self.coast_down.stop:g} (multiples of omega_n)")
        if self.dt * self.top_speed > 0.05:
            raise BalanceError(f"BalancingMachine.dt = {self.dt:g} s: too coarse for "
                               f"{self.top_speed:.4g} rad/s (keep omega dt <= 0.05)")

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
        """Rotor speed (rad/s) at constant speed; a coast-down's start speed."""
        if self.coast_down is not None:
            return self.coast_down.start * self.omega_n
        return self.omega_n if self.speed is None else float(self.speed)

    @property
    def top_speed(self) -> float:
        """The largest rotor speed of a run (rad/s)."""
        return self.omega

    def settings(self) -> dict[str, Any]:
        """The machine as plain data (``BalancingMachine(**settings)`` rebuilds it; the
        coast-down as a dict): what a batch sends to its workers."""
        d = {f.name: getattr(self, f.name) for f in fields(self)}
        if self.coast_down is not None:
            d["coast_down"] = asdict(self.coast_down)
        return d

    @classmethod
    def from_settings(cls, settings: dict[str, Any]) -> BalancingMachine:
        """Inverse of :meth:`settings`."""
        d = dict(settings)
        if isinstance(d.get("coast_down"), dict):
            d["coast_down"] = CoastDown(**d["coast_down"])
        return cls(**d)

    # -- one run ---------------------------------------------------------------
    def record(self, unbalances: Iterable[Any] = ()) -> MachineRecord:
        """Run the machine with these eccentric masses on the rotor and measure the
        frame's amplitude: the steady one at constant speed, the envelope's peak in a
        coast-down.

        Parameters
        ----------
        unbalances : iterable
            :class:`balance.Unbalance`, ``{mass, radius, angle}`` dicts or
            ``(mass, radius, angle)`` tuples (kg, m, deg from the 0 deg mark).

        Returns
        -------
        MachineRecord
        """
        us = _unbalances(unbalances, "unbalances")
        if self.coast_down is not None:
            return self._record_coast(us)
        from kinetostatics.simulation import make_stepper
        space, frame, _, _ = self._build(us)
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

    def _record_coast(self, us: list[Unbalance]) -> MachineRecord:
        """A coast-down run: the exact steady state at the start speed, then the speed
        history stepped, x and the rotor's angle read after every step, the envelope
        demodulated against the angle and its peak taken."""
        from kinetostatics.simulation import fast_path_available, make_stepper
        cd = self.coast_down
        wn, dt = self.omega_n, float(self.dt)
        n = int(math.ceil(cd.duration / dt))
        space, frame, rotor, motor = self._build(us, steady=True)
        fast = fast_path_available() if self.fast is None else bool(self.fast)
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
        C = envelope(xs, th, self.envelope_passes)
        E = np.abs(C)
        tp, Ap, k = peak(t, E)
        if k <= 1 or k >= n - 2 or not (np.isfinite(E[k - 2]) and np.isfinite(E[k + 2])):
            raise BalanceError("coast-down: the envelope's largest value lies at an end of "
                               "the run, not at the resonance; start higher, stop lower or "
                               "run longer")
        speed = np.gradient(th, t)
        phase = -math.degrees(float(np.angle(C[k])))
        return MachineRecord(t, xs, Ap, phase, float(np.interp(tp, t, speed)), wall,
                             envelope=E, rotor_speed=speed, peak_time=tp)

    def build(self, unbalances: Iterable[Any] = ()):
        """The pymunk space of a run, at rest on its mount with the rotor at speed (a
        coast-down: in the steady motion at its start speed).

        Returns
        -------
        (pymunk.Space, pymunk.Body, pymunk.Body)
            The space, the frame and the rotor (whose local origin is on the axis).
        """
        us = _unbalances(unbalances, "unbalances")
        return self._build(us, steady=self.coast_down is not None)[:3]

    def _build(self, us: list[Unbalance], steady: bool = False):
        import pymunk
        m = self.rotor_mass + sum(u.mass for u in us)
        U = sum((u.U for u in us), 0j)                     # eq. 3.3
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
        rotor.position = (0.0, 0.0)     # after the cog: else the origin jumps by -g
        rotor.angular_velocity = w
        v = 1j * w * g
        if steady:
            # the steady motion at speed w: (M + m) x'' + c x' + k x = Re(U w^2 e^(i w t))
            X = U * w * w / complex(self.stiffness - (self.frame_mass + m) * w * w,
                                    self.damping * w)
            frame.position = (X.real, 0.0)
            frame.velocity = ((1j * w * X).real, 0.0)
            rotor.position = (X.real, 0.0)
            v += (1j * w * X).real
        rotor.velocity = (v.real, v.imag)
        space.add(frame, rotor)
        length = 1.0
        motor = pymunk.SimpleMotor(rotor, frame, w)        # frame.w - rotor.w = -w
        joints = [
            pymunk.GrooveJoint(space.static_body, frame, (-length, 0.0), (length, 0.0),
                               (0.0, 0.0)),
            pymunk.PivotJoint(frame, rotor, (0.0, 0.0), (0.0, 0.0)),
            motor,
            pymunk.DampedSpring(space.static_body, frame, (-length, 0.0), (0.0, 0.0), length,
                                self.stiffness, self.damping),
        ]
        for c in joints:
            c.error_bias = 0.0
            c.collide_bodies = False
            space.add(c)
        return space, frame, rotor, motor

    def steady_amplitude(self, unbalances: Iterable[Any] = ()) -> float:
        """The exact steady amplitude of the model (m): |U| omega^2 / |k - (M + m) omega^2
        + i c omega|, U the resultant unbalance, m the rotor's whole mass."""
        us = _unbalances(unbalances, "unbalances")
        mass = self.frame_mass + self.rotor_mass + sum(u.mass for u in us)
        w = self.omega
        U = abs(sum((u.U for u in us), 0j))
        return U * w * w / abs(complex(self.stiffness - mass * w * w, self.damping * w))

    def amplitude(self, unbalances: Iterable[Any] = ()) -> float:
        """Amplitude of the frame (m) with these eccentric masses on the rotor: steady,
        or a coast-down's peak."""
        return self.record(unbalances).amplitude

    # -- batches -----------------------------------------------------------------
    def runs(self, unbalance_sets: Iterable[Iterable[Any]], *,
             executor: Executor | str | None = None) -> list[MachineRecord]:
        """Run the machine once per set of eccentric masses, as a batch.

        Parameters
        ----------
        unbalance_sets : iterable of iterables
            One set of eccentric masses per run (as in :meth:`record`).
        executor : Executor, ``"serial"`` or None
            None: processes, one per core (a single run: this process); ``"serial"``:
            one after another here; or any ``concurrent.futures.Executor`` (a dask
            ``Client.get_executor()``). See
            :func:`kinetostatics.simulation.run_batch`. Each run times itself in its
            worker (``MachineRecord.wall``).

        Returns
        -------
        list of MachineRecord
            In the order of the sets.
        """
        from kinetostatics.simulation import run_batch
        settings = self.settings()
        items = [(settings, [(u.mass, u.radius, u.angle)
                             for u in _unbalances(us, f"unbalance_sets[{i}]")])
                 for i, us in enumerate(unbalance_sets)]
        return run_batch(_machine_record, items, executor=executor)

    # -- the methods -------------------------------------------------------------
    def mass_factor(self, reference_mass: float, added_mass: float) -> float:
        """What a run's amplitude is multiplied by to bring it to the reference run's mass.

        A trial mass adds ``added_mass`` to the rotor of the reference run (the rotor as
        it is, whose eccentric masses weigh ``reference_mass`` in all); the mount then
        has more mass M and, the spring and damper being the same, its amplitudes are
        no longer those of the same machine. At constant speed the steady amplitude is
        |U| omega^2 / |k - M omega^2 + i c omega| (the module's equation), so the factor
        |k - M omega^2 + i c omega| / |k - M_ref omega^2 + i c omega| is exact. In a
        coast-down the factor is that of the largest steady amplitude over the speed,
        max |U| omega^2 / |...| = |U| / (c sqrt(M / k - c^2 / (4 k^2))): exact for a
        slow passage, about 90 % of the effect at 12 time constants, less for a fast one
        (docs/simulation.md).

        Parameters
        ----------
        reference_mass, added_mass : float
            Eccentric mass of the reference run, and the trial mass (kg).

        Returns
        -------
        float
        """
        k, c = self.stiffness, self.damping
        m_ref = self.frame_mass + self.rotor_mass + float(reference_mass)
        m_run = m_ref + float(added_mass)
        if self.coast_down is None:
            w = self.omega
            return abs(complex(k - m_run * w * w, c * w)) / abs(complex(k - m_ref * w * w,
                                                                         c * w))
        q = c * c / (4.0 * k * k)
        return math.sqrt((m_run / k - q) / (m_ref / k - q))

    def three_run(self, unbalances: Iterable[Any], trial_mass: float, trial_radius: float,
                  correction_radius: float, *, mass_correction: bool = False,
                  executor: Executor | str | None = None) -> MachineResult:
        """The amplitude-parallelogram method on the machine: the rotor as it is, the
        trial mass at the 0 deg and at the 180 deg mark; :func:`balance.parallelogram`
        (eqs 3.23-3.31).

        Parameters
        ----------
        unbalances : iterable
            The eccentric masses put in (as in :meth:`record`).
        trial_mass, trial_radius, correction_radius : float
            kg, m, m.
        mass_correction : bool
            Bring the trial runs' amplitudes to the mass of the first run
            (:meth:`mass_factor`) before the method takes them.
        executor : Executor, ``"serial"`` or None
            Runs the three runs as a batch (see :meth:`runs`).

        Returns
        -------
        MachineResult
            With the recovered unbalance, its error against the one put in and the
            angle error (the nearer of the two mirror candidates).
        """
        us = _unbalances(unbalances, "unbalances")
        recs = self.runs([us, [*us, Unbalance(trial_mass, trial_radius, 0.0)],
                          [*us, Unbalance(trial_mass, trial_radius, 180.0)]],
                         executor=executor)
        f = self._factors(us, trial_mass, ("0", "180"), mass_correction)
        A1 = recs[0].amplitude
        A2, A3 = (r.amplitude * f[k] for r, k in zip(recs[1:], ("0", "180"), strict=True))
        res = parallelogram(A1, A2, A3, trial_mass, trial_radius, correction_radius)
        return self._result(res, {"A1": A1, "0": A2, "180": A3}, us, recs,
                            candidates=(res.angle, res.mirror_angle),
                            factors=f if mass_correction else None)

    def four_run(self, unbalances: Iterable[Any], trial_mass: float, trial_radius: float,
                 correction_radius: float,
                 marks: tuple[float, ...] = (0.0, 120.0, 240.0), *,
                 mass_correction: bool = False,
                 executor: Executor | str | None = None) -> MachineResult:
        """The four-run method on the machine: the rotor as it is and the trial mass at
        each of ``marks`` (default 0, 120, 240 deg); :func:`balance.trial_runs`.
        ``mass_correction`` and ``executor`` as in :meth:`three_run`."""
        us = _unbalances(unbalances, "unbalances")
        recs = self.runs([us] + [[*us, Unbalance(trial_mass, trial_radius, a)]
                                 for a in marks], executor=executor)
        names = tuple(f"{a:g}" for a in marks)
        f = self._factors(us, trial_mass, names, mass_correction)
        A1 = recs[0].amplitude
        runs = [(a, r.amplitude * f[n]) for a, n, r in zip(marks, names, recs[1:], strict=True)]
        res = trial_runs(A1, runs, trial_mass, trial_radius, correction_radius)
        amps = {"A1": A1, **{n: A for n, (_, A) in zip(names, runs, strict=True)}}
        return self._result(res, amps, us, recs, candidates=(res.angle,),
                            factors=f if mass_correction else None)

    def _factors(self, us: list[Unbalance], trial_mass: float, names: tuple[str, ...],
                 on: bool) -> dict[str, float]:
        m = float(trial_mass)
        if not (math.isfinite(m) and m > 0.0):
            raise BalanceError(f"trial_mass = {trial_mass!r}: give a positive mass in kg")
        f = self.mass_factor(sum(u.mass for u in us), m) if on else 1.0
        return {"A1": 1.0, **{n: f for n in names}}

    @staticmethod
    def _result(res: ResonanceResult, amps: dict, us: list[Unbalance], recs: list,
                candidates: tuple, factors: dict | None = None) -> MachineResult:
        U = sum((u.U for u in us), 0j)
        if abs(U) == 0.0:
            err = abs(res.unbalance)
            ang = float("nan")
        else:
            err = abs(res.unbalance - abs(U)) / abs(U)
            true = math.degrees(math.atan2(U.imag, U.real)) + 180.0
            ang = min(abs((c - true + 180.0) % 360.0 - 180.0) for c in candidates
                      if c is not None)
        return MachineResult(res, amps, U, float(err), float(ang), recs, factors)


# ----------------------------------------------------------------- coast-down study
def random_unbalance(seed: int) -> list[Unbalance]:
    """The study's (and the tests') random unbalance: one mass of 5 to 30 g at 40 to
    100 mm, at any angle, from ``numpy.random.default_rng(seed)``."""
    rng = np.random.default_rng(seed)
    return [Unbalance(rng.uniform(0.005, 0.03), rng.uniform(0.04, 0.1), rng.uniform(0, 360))]


def _study_record(item: tuple) -> MachineRecord | None:
    """A study's run: as :func:`_machine_record`, None when the run gives no peak."""
    try:
        return _machine_record(item)
    except BalanceError:
        return None


def coast_down_study(durations: Iterable[float | None] = (None, 10.0, 3.0, 1.0, 0.5),
                     trial_factors: Iterable[float] = (0.1, 1.0, 10.0),
                     seeds: Iterable[int] = (1, 2, 3), *,
                     machine: BalancingMachine | None = None, trial_radius: float = 0.08,
                     correction_radius: float = 0.08,
                     executor: Executor | str | None = None):
    """How well the machine's methods recover an unbalance, against the speed history
    and the size of the trial mass.

    For each duration of the coast-down (None: the constant-speed machine at
    resonance), each seeded random unbalance (:func:`random_unbalance`) and each trial
    mass (``trial_factor`` x |U| / ``trial_radius``: the trial unbalance that many
    times the one put in), the machine runs the rotor as it is and with the trial mass
    at 0, 120, 180 and 240 deg; the three-run method (eqs 3.29-3.31) takes the 0 and
    180 deg runs, the four-run method the 0, 120 and 240 deg ones, each without and
    with the mass correction (:meth:`BalancingMachine.mass_factor`). All the runs are
    one batch through ``executor`` (see :meth:`BalancingMachine.runs`).

    Parameters
    ----------
    durations : iterable of float or None
        Coast-down times (s) from 1.5 to 0.5 omega_n; None for constant speed.
    trial_factors : iterable of float
        Trial unbalance / unbalance.
    seeds : iterable of int
        Random unbalances.
    machine : BalancingMachine, optional
        The machine (default ``BalancingMachine()``); its ``coast_down`` is replaced.
    trial_radius, correction_radius : float
        m.
    executor : Executor, ``"serial"`` or None
        Default: processes, one per core.

    Returns
    -------
    pandas.DataFrame
        One row per duration, trial factor and correction: ``duration`` (s),
        ``passage`` (time constants to cross the half-power band),
        ``trial_factor``, ``mass_correction``, ``three_error`` and ``three_angle``
        (largest |m r| relative error and angle error, deg, over the seeds; the
        nearer mirror candidate), ``four_error``, ``four_angle``, ``peak_speed``
        (mean speed at the A1 peak / omega_n), ``peak_ratio`` (mean A1 / the largest
        steady amplitude |U| / (c sqrt(M / k - c^2 / 4 k^2))), ``three_failed``,
        ``four_failed`` (seeds for which the method gave no result: no peak inside a
        run, or amplitudes no parallelogram joins), ``seeds``.
    """
    import warnings

    import pandas as pd
    base = machine if machine is not None else BalancingMachine()
    durs = list(durations)
    facs = [float(f) for f in trial_factors]
    sds = list(seeds)
    marks = (0.0, 120.0, 180.0, 240.0)
    machines = [replace(base, coast_down=None if d is None else CoastDown(duration=float(d)),
                        speed=None) for d in durs]
    items, index = [], {}
    for i, bm in enumerate(machines):
        st = bm.settings()
        for sd in sds:
            us = random_unbalance(sd)
            plain = [(u.mass, u.radius, u.angle) for u in us]
            index[i, sd, None, None] = len(items)
            items.append((st, plain))
            for f in facs:
                tm = f * abs(sum((u.U for u in us), 0j)) / trial_radius
                for a in marks:
                    index[i, sd, f, a] = len(items)
                    items.append((st, [*plain, (tm, trial_radius, a)]))
    from kinetostatics.simulation import run_batch
    recs = run_batch(_study_record, items, executor=executor)
    rows = []
    for i, (d, bm) in enumerate(zip(durs, machines, strict=True)):
        k, c = bm.stiffness, bm.damping
        for f in facs:
            for corr in (False, True):
                out = {"three": [], "three_angle": [], "four": [], "four_angle": [],
                       "speed": [], "ratio": []}
                failed = {"three": 0, "four": 0}
                for sd in sds:
                    us = random_unbalance(sd)
                    U = sum((u.U for u in us), 0j)
                    tm = f * abs(U) / trial_radius
                    r1 = recs[index[i, sd, None, None]]
                    rk = {a: recs[index[i, sd, f, a]] for a in marks}
                    if r1 is None or any(r is None for r in rk.values()):
                        failed["three"] += 1
                        failed["four"] += 1
                        continue
                    m_all = bm.frame_mass + bm.rotor_mass + sum(u.mass for u in us)
                    top = abs(U) / (c * math.sqrt(m_all / k - c * c / (4.0 * k * k)))
                    out["speed"].append(r1.speed / bm.omega_n)
                    out["ratio"].append(r1.amplitude / top)
                    fac = bm.mass_factor(sum(u.mass for u in us), tm) if corr else 1.0
                    A = {a: r.amplitude * fac for a, r in rk.items()}
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        try:
                            res = parallelogram(r1.amplitude, A[0.0], A[180.0], tm,
                                                trial_radius, correction_radius)
                            mr = bm._result(res, {}, us, [], (res.angle, res.mirror_angle))
                            out["three"].append(mr.unbalance_error)
                            out["three_angle"].append(mr.angle_error)
                        except BalanceError:
                            failed["three"] += 1
                        try:
                            res = trial_runs(r1.amplitude, [(a, A[a]) for a in (0.0, 120.0,
                                                                                240.0)],
                                             tm, trial_radius, correction_radius)
                            mr = bm._result(res, {}, us, [], (res.angle,))
                            out["four"].append(mr.unbalance_error)
                            out["four_angle"].append(mr.angle_error)
                        except BalanceError:
                            failed["four"] += 1

                def worst(v: list) -> float:
                    return float(max(v)) if v else float("nan")

                rows.append({
                    "duration": float("inf") if d is None else float(d),
                    "passage": float("inf") if d is None
                    else bm.coast_down.passage(bm.omega_n, bm.damping_ratio),
                    "trial_factor": f, "mass_correction": corr,
                    "three_error": worst(out["three"]), "three_angle": worst(out["three_angle"]),
                    "four_error": worst(out["four"]), "four_angle": worst(out["four_angle"]),
                    "peak_speed": float(np.mean(out["speed"])) if out["speed"] else float("nan"),
                    "peak_ratio": float(np.mean(out["ratio"])) if out["ratio"] else float("nan"),
                    "three_failed": failed["three"], "four_failed": failed["four"],
                    "seeds": len(sds)})
    return pd.DataFrame(rows)


# ----------------------------------------------------------------- the pivot rotor
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
    us = _unbalances(unbalances, "unbalances")
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
    U = sum((u.U for u in us), 0j)                                 # eq. 3.3
    if abs(U) == 0.0:
        raise BalanceError("pivot_reaction: the rotor is balanced (sum m r = 0): there is no "
                           "bearing force to measure")
    m = rotor_mass + sum(u.mass for u in us)
    g = U / m
    inertia = rotor_inertia - m * abs(g) ** 2 + sum(u.mass * u.radius ** 2 for u in us)
    space = pymunk.Space()
    space.iterations = int(iterations)
    space.sleep_time_threshold = math.inf
    rotor = pymunk.Body(m, inertia)
    rotor.center_of_gravity = (g.real, g.imag)
    rotor.position = (0.0, 0.0)         # after the cog: else the origin jumps by -g
    rotor.angular_velocity = w
    v = 1j * w * g
    rotor.velocity = (v.real, v.imag)
    space.add(rotor)
    pivot = pymunk.PivotJoint(space.static_body, rotor, (0.0, 0.0), (0.0, 0.0))
    motor = pymunk.SimpleMotor(space.static_body, rotor, -w)      # rotor.w - 0 = -(-w)
    for c in (pivot, motor):
        c.error_bias = 0.0
        c.collide_bodies = False
        space.add(c)
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
    direction = np.degrees(np.angle(on_bearing * np.exp(-1j * ang)))
    true = math.degrees(math.atan2(U.imag, U.real))
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


def _machine_record(item: tuple) -> MachineRecord:
    """One run of a batch: (machine settings, [(mass, radius, angle), ...]) -> record."""
    settings, us = item
    return BalancingMachine.from_settings(settings).record(us)
