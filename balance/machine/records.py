"""What the machine measures: a run (:class:`MachineRecord`) and a method's result
(:class:`MachineResult`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from kinetostatics.common.angles import degree_value

from ..errors import BalanceError
from ..resonance.methods import ResonanceResult
from ..rotor.design import Unbalance


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
        Angle (deg) between the recovered correction ``result.angle`` and the true one
        (the put-in angle + 180).
    mirror_angle_error : float or None
        The same for ``result.mirror_angle``, the other candidate of the three-run
        method (which cannot tell the two apart); None for the four-run method.
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
    mirror_angle_error: float | None = None


def method_result(res: ResonanceResult, amps: dict, us: list[Unbalance], recs: list,
                  factors: dict | None = None) -> MachineResult:
    """A method's :class:`MachineResult`: the recovered unbalance and correction angle
    (and its mirror candidate, if the method gives one) against the ones put in."""
    if res.unbalance is None:     # the runs' linear fit has no solution (A^2 <= 0)
        raise BalanceError(res.warnings[0] if res.warnings else "the fit has no solution")
    U = sum((u.U for u in us), 0j)
    mirror = None
    if abs(U) == 0.0:
        err = abs(res.unbalance)
        ang = float("nan")
    else:
        err = abs(res.unbalance - abs(U)) / abs(U)
        true = degree_value(math.atan2(U.imag, U.real)) + 180.0

        def off(c: float) -> float:
            return float(abs((c - true + 180.0) % 360.0 - 180.0))

        ang = off(res.angle)
        if res.mirror_angle is not None:
            mirror = off(res.mirror_angle)
    return MachineResult(res, amps, U, float(err), float(ang), recs, factors, mirror)
