"""The machine (:class:`BalancingMachine`): a rotor on a spring-damper mount, simulated
in pymunk; its runs, as a batch, and the balancing methods on their amplitudes.

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
from collections.abc import Iterable
from concurrent.futures import Executor
from dataclasses import asdict, dataclass, fields
from typing import Any

from kinetostatics.simulation import run_batch

from ..errors import BalanceError
from ..resonance.methods import parallelogram, trial_runs
from ..rotor.design import Unbalance
from .coastdown import CoastDown
from .demodulation import ENVELOPE_PASSES
from .records import MachineRecord, MachineResult, method_result
from .runs import record_coast, record_steady
from .unbalances import add_rigid, as_unbalances, spinning_rotor


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
        us = as_unbalances(unbalances, "unbalances")
        if self.coast_down is not None:
            return record_coast(self, us)
        return record_steady(self, us)

    def build(self, unbalances: Iterable[Any] = ()):
        """The pymunk space of a run, at rest on its mount with the rotor at speed (a
        coast-down: in the steady motion at its start speed).

        Returns
        -------
        (pymunk.Space, pymunk.Body, pymunk.Body)
            The space, the frame and the rotor (whose local origin is on the axis).
        """
        us = as_unbalances(unbalances, "unbalances")
        return self.build_space(us, steady=self.coast_down is not None)[:3]

    def build_space(self, us: list[Unbalance], steady: bool = False):
        import pymunk
        w = self.omega
        space = pymunk.Space()
        space.iterations = int(self.iterations)
        space.sleep_time_threshold = math.inf
        frame = pymunk.Body(self.frame_mass, math.inf)     # slides, cannot turn
        rotor, U, v = spinning_rotor(us, self.rotor_mass, self.rotor_inertia, w)
        if steady:
            # the steady motion at speed w: (M + m) x'' + c x' + k x = Re(U w^2 e^(i w t))
            X = U * w * w / complex(self.stiffness - (self.frame_mass + rotor.mass) * w * w,
                                    self.damping * w)
            frame.position = (X.real, 0.0)
            frame.velocity = ((1j * w * X).real, 0.0)
            rotor.position = (X.real, 0.0)
            v += (1j * w * X).real
            rotor.velocity = (v.real, v.imag)
        space.add(frame, rotor)
        length = 1.0
        motor = pymunk.SimpleMotor(rotor, frame, w)        # frame.w - rotor.w = -w
        add_rigid(space, [
            pymunk.GrooveJoint(space.static_body, frame, (-length, 0.0), (length, 0.0),
                               (0.0, 0.0)),
            pymunk.PivotJoint(frame, rotor, (0.0, 0.0), (0.0, 0.0)),
            motor,
            pymunk.DampedSpring(space.static_body, frame, (-length, 0.0), (0.0, 0.0), length,
                                self.stiffness, self.damping),
        ])
        return space, frame, rotor, motor

    def steady_amplitude(self, unbalances: Iterable[Any] = ()) -> float:
        """The exact steady amplitude of the model (m): |U| omega^2 / |k - (M + m) omega^2
        + i c omega|, U the resultant unbalance, m the rotor's whole mass."""
        us = as_unbalances(unbalances, "unbalances")
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
        settings = self.settings()
        items = [(settings, [(u.mass, u.radius, u.angle)
                             for u in as_unbalances(us, f"unbalance_sets[{i}]")])
                 for i, us in enumerate(unbalance_sets)]
        return run_batch(machine_record, items, executor=executor)

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
            With the recovered unbalance, its error against the one put in, the
            angle error of ``result.angle`` and that of ``result.mirror_angle`` (the
            method cannot tell which of the two is right).
        """
        us = as_unbalances(unbalances, "unbalances")
        recs = self.runs([us, [*us, Unbalance(trial_mass, trial_radius, 0.0)],
                          [*us, Unbalance(trial_mass, trial_radius, 180.0)]],
                         executor=executor)
        f = self._factors(us, trial_mass, ("0", "180"), mass_correction)
        A1 = recs[0].amplitude
        A2, A3 = (r.amplitude * f[k] for r, k in zip(recs[1:], ("0", "180"), strict=True))
        res = parallelogram(A1, A2, A3, trial_mass, trial_radius, correction_radius)
        return method_result(res, {"A1": A1, "0": A2, "180": A3}, us, recs,
                             factors=f if mass_correction else None)

    def four_run(self, unbalances: Iterable[Any], trial_mass: float, trial_radius: float,
                 correction_radius: float,
                 marks: tuple[float, ...] = (0.0, 120.0, 240.0), *,
                 mass_correction: bool = False,
                 executor: Executor | str | None = None) -> MachineResult:
        """The four-run method on the machine: the rotor as it is and the trial mass at
        each of ``marks`` (default 0, 120, 240 deg); :func:`balance.trial_runs`.
        ``mass_correction`` and ``executor`` as in :meth:`three_run`."""
        us = as_unbalances(unbalances, "unbalances")
        recs = self.runs([us] + [[*us, Unbalance(trial_mass, trial_radius, a)]
                                 for a in marks], executor=executor)
        names = tuple(f"{a:g}" for a in marks)
        f = self._factors(us, trial_mass, names, mass_correction)
        A1 = recs[0].amplitude
        runs = [(a, r.amplitude * f[n]) for a, n, r in zip(marks, names, recs[1:], strict=True)]
        res = trial_runs(A1, runs, trial_mass, trial_radius, correction_radius)
        amps = {"A1": A1, **{n: A for n, (_, A) in zip(names, runs, strict=True)}}
        return method_result(res, amps, us, recs, factors=f if mass_correction else None)

    def _factors(self, us: list[Unbalance], trial_mass: float, names: tuple[str, ...],
                 on: bool) -> dict[str, float]:
        m = float(trial_mass)
        if not (math.isfinite(m) and m > 0.0):
            raise BalanceError(f"trial_mass = {trial_mass!r}: give a positive mass in kg")
        f = self.mass_factor(sum(u.mass for u in us), m) if on else 1.0
        return {"A1": 1.0, **{n: f for n in names}}


def machine_record(item: tuple) -> MachineRecord:
    """One run of a batch: (machine settings, [(mass, radius, angle), ...]) -> record."""
    settings, us = item
    return BalancingMachine.from_settings(settings).record(us)
