"""The question language of the exercises: parsing, units, answer values, angles.

Questions are short strings, ``quantity[argument]@position``:

========================  =====================================================
mechanism                 meaning (unit)
========================  =====================================================
``Me@30``                 equilibrating moment at driver position 30 (N m);
                          ``Fe@0.2`` on a sliding driver (N)
``Me_mean``, ``Me_max``,  mean (trapezoid rule), largest, smallest over the sweep
``Me_min``
``F[B]@30``               magnitude of the reaction in joint B (N); ``Fx[B]@30``,
                          ``Fy[B]@30`` its components on the ``on`` body
``Fmax[B]``               largest |F| in joint B over the sweep (N)
``Fangle[B]@30``          direction of the reaction (deg, an angle)
``N[C-slide]@30``,        normal force (N) and couple (N m) of a prismatic joint
``M[C-slide]@30``
``tau_min``               smallest transmission angle, min(tau, 180 - tau) (deg)
``tau[1]@30``             transmission angle of dyad 1 (deg)
``angle[rocker]@30``      angle of a body (deg, an angle); ``omega[...]``
                          (rad/s), ``alpha[...]`` (rad/s^2)
``x[coupler.P]@30``       coordinates (m), ``v[...]`` speed (m/s), ``a[...]``
                          acceleration magnitude (m/s^2) of a body point
========================  =====================================================

========================  =====================================================
balancing                 meaning (unit)
========================  =====================================================
``mass[1]``, ``angle[1]`` correction mass (kg) and its angle (deg) in plane 1
``U[1]``                  correction unbalance m r (kg m)
``initial_force``, ...    ``initial_force``, ``initial_moment``,
                          ``residual_force``, ``residual_moment``
``eccentricity``,         static device (``[static_test]``)
``correction_mass``
``res_mass[1]``,          amplitude-parallelogram test number 1: correction mass,
``res_angle[1]``,         angle, mirror angle, A, phi, unbalance
``res_mirror[1]``, ...
``shaking_before``,       mechanism balancing (``[balancing]``): largest shaking
``shaking_after``         force (N)
``rotor.corrections.0.U`` any other number of ``balance.solve``'s result, by path
========================  =====================================================

Tolerances (:data:`TOLERANCE_RULE`, applied by :func:`kinetostatics.teaching.grade`):
a number passes when |answer - key| <= max(rtol |key|, atol), rtol 1 % by default and
atol 1e-3 of the quantity's largest magnitude over the cycle (so that a value near zero
is not judged by its relative error alone); every other answer in degrees is an angle:
it passes when the difference, wrapped into (-180, 180], is at most 0.5 deg (so 330
and -30 are the same answer); the transmission angles (``tau``, ``tau_min``, in
[0, 90] deg) are plain numbers, right within 0.5 deg.
"""

from __future__ import annotations

import math
import re
import unicodedata
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..model.errors import WorkbenchError

__all__ = ["ANGLE_ATOL", "ANSWER_TAG", "ATOL_FRACTION", "DEFAULT_RTOL", "TOLERANCE_RULE",
           "Question", "describe", "is_mechanism", "normalize_id", "parse_question",
           "to_float", "tolerance_text", "var_name", "wrap_angle"]

DEFAULT_RTOL = 0.01
ATOL_FRACTION = 1e-3        # atol = this fraction of the quantity's scale over the sweep
ANGLE_ATOL = 0.5            # deg
ANSWER_TAG = "answers"      # cell tag (and nbgrader grade_id) of a notebook's answer cell
TOLERANCE_RULE = (
    "A number is right when |answer - key| <= max(1 % of |key|, 0.1 % of the quantity's "
    "largest magnitude over the cycle); an answer in degrees is an angle: right when the "
    "difference, taken modulo 360 deg into (-180, 180], is at most 0.5 deg; a "
    "transmission angle, in [0, 90] deg, is a plain number, right within 0.5 deg.")

_Q = re.compile(r"^(?P<q>[A-Za-z_][A-Za-z0-9_.]*)(?:\[(?P<arg>[^\]]+)\])?"
                r"(?:@(?P<pos>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))?$")


# ------------------------------------------------------------------------ helpers
def var_name(question: str) -> str:
    """A Python identifier for a question, for answer cells written as variables.

    Parameters
    ----------
    question : str
        E.g. ``"Me@30"``.

    Returns
    -------
    str
        ``"Me@30"`` -> ``Me_30``, ``"Fmax[B]"`` -> ``Fmax_B``, ``"x[coupler.P]@30"`` ->
        ``x_coupler_P_30``.
    """
    name = re.sub(r"[^0-9A-Za-z]+", "_", question).strip("_")
    return name if not name[:1].isdigit() else f"q_{name}"


def to_float(x: Any) -> float:
    """A student's answer as a float: numbers, '12.5', '12,5', '330°'; NaN if none."""
    if x is None:
        return math.nan
    if isinstance(x, bool):
        return math.nan
    if isinstance(x, int | float | np.integer | np.floating):
        return float(x)
    if isinstance(x, str):
        t = x.strip().replace("°", "").replace("deg", "").replace(" ", "")
        if t.count(",") == 1 and "." not in t:
            t = t.replace(",", ".")
        try:
            return float(t)
        except ValueError:
            return math.nan
    return math.nan


def wrap_angle(d: np.ndarray) -> np.ndarray:
    """Angle differences into (-180, 180]."""
    return 180.0 - np.mod(180.0 - np.asarray(d, dtype=float), 360.0)


# ------------------------------------------------------------------ question parse
@dataclass(frozen=True)
class Question:
    text: str
    q: str
    arg: str | None
    pos: float | None


def parse_question(question: str) -> Question:
    m = _Q.match(question.strip())
    if not m:
        raise WorkbenchError(f"question {question!r}: write quantity[argument]@position, e.g. "
                             "'Me@30', 'Fmax[B]', 'angle[rocker]@30', 'mass[1]'")
    pos = m.group("pos")
    return Question(question.strip(), m.group("q"), m.group("arg"),
                     None if pos is None else float(pos))


def is_mechanism(raw: Mapping) -> bool:
    return "bodies" in raw or "driver" in raw



def normalize_id(student: Any) -> str:
    """A student id as it is matched: trimmed, case-folded and Unicode-normalised (NFC)
    (``" Ana "`` -> ``"ana"``; an accent typed as one or two code points matches)."""
    return unicodedata.normalize("NFC", str(student).strip()).casefold()


# ------------------------------------------------------------ words for the sheets
_WORDS = {
    "Me": "equilibrating moment Me on the driver, counter-clockwise positive,{at}",
    "Fe": "equilibrating force Fe on the driver along its line{at}",
    "Me_mean": "mean equilibrating moment Me over the cycle",
    "Me_max": "largest equilibrating moment Me over the cycle (signed)",
    "Me_min": "smallest equilibrating moment Me over the cycle (signed)",
    "Fe_mean": "mean equilibrating force Fe over the cycle",
    "Fe_max": "largest equilibrating force Fe over the cycle (signed)",
    "Fe_min": "smallest equilibrating force Fe over the cycle (signed)",
    "F": "magnitude of the reaction in joint {arg}{at}",
    "Fx": "x component of the reaction in joint {arg}{at}",
    "Fy": "y component of the reaction in joint {arg}{at}",
    "Fmax": "largest magnitude of the reaction in joint {arg} over the cycle",
    "Fangle": "direction of the reaction in joint {arg}{at}, from the x axis, "
              "counter-clockwise",
    "N": "normal force on the slider of joint {arg}, positive along the line's left "
         "normal{at}",
    "M": "couple of the sliding joint {arg}{at}",
    "tau_min": "smallest transmission angle over the cycle, min(tau, 180 deg - tau)",
    "tau": "transmission angle of dyad {arg}, min(tau, 180 deg - tau){at}",
    "angle": "angle of the {arg} from the x axis, counter-clockwise{at}",
    "omega": "angular velocity of the {arg}, counter-clockwise positive{at}",
    "alpha": "angular acceleration of the {arg}, counter-clockwise positive{at}",
    "x": "x coordinate of point {arg}{at}", "y": "y coordinate of point {arg}{at}",
    "v": "speed (magnitude of the velocity) of point {arg}{at}",
    "a": "magnitude of the acceleration of point {arg}{at}",
    "mass": "correction mass in plane {arg}", "U": "correction unbalance m r in plane {arg}",
    "initial_force": "resultant inertia force of the unbalances before balancing",
    "initial_moment": "resultant moment of the unbalances before balancing",
    "residual_force": "resultant inertia force after balancing",
    "residual_moment": "resultant moment after balancing",
    "eccentricity": "eccentricity of the disk's centre of mass",
    "correction_mass": "correction mass of the static test",
    "res_mass": "correction mass of resonance test {arg}",
    "res_angle": "correction angle 180 deg + phi of resonance test {arg}",
    "res_mirror": "the mirror candidate 180 deg - phi of resonance test {arg}",
    "res_A": "amplitude A the trial mass alone would give (test {arg})",
    "res_phi": "angle phi between the unbalance and the 0 deg mark (test {arg})",
    "res_unbalance": "unbalance m1 r1 found by resonance test {arg}",
    "shaking_before": "largest shaking force before balancing",
    "shaking_after": "largest shaking force after balancing",
}
_SCALES = {
    "Me": "the largest |Me| over the cycle", "Fe": "the largest |Fe| over the cycle",
    **dict.fromkeys(("F", "Fx", "Fy"), "the largest reaction in joint {arg}"),
    "Fmax": "the largest reaction in {arg}",
    "N": "the largest |N| in {arg}", "M": "the largest |M| in {arg}",
    "omega": "the largest |omega| of the {arg}", "alpha": "the largest |alpha| of the {arg}",
    "x": "the point's x range plus its largest |x|",
    "y": "the point's y range plus its largest |y|",
    "v": "the point's largest speed", "a": "the point's largest acceleration",
    "mass": "the largest correction mass", "U": "the largest correction unbalance",
    **dict.fromkeys(("initial_force", "initial_moment"), "the value"),
    "residual_force": "the initial force", "residual_moment": "the initial moment",
    **dict.fromkeys(("shaking_before", "shaking_after"), "the shaking force before balancing"),
}


def describe(question: str, position: str = "phi = {pos:g} deg") -> str:
    """The question in words, for a sheet or a handout.

    Parameters
    ----------
    question : str
        E.g. ``"F[C]@30"``.
    position : str
        How a driver position reads (``{pos}`` is replaced); ``"s = {pos:g} m"`` for a
        sliding driver.

    Returns
    -------
    str
        ``"magnitude of the reaction in joint C at phi = 30 deg"``.
    """
    q = parse_question(question)
    if q.q == "Fe":
        position = "s = {pos:g} m"
    at = "" if q.pos is None else " at " + position.format(pos=q.pos)
    words = _WORDS.get(q.q)
    if words is None:
        return f"the value {q.text} of the result"
    return words.format(arg=q.arg or "1", at=at)


def tolerance_text(question: str, unit: str, rtol: float, kind: str = "angle") -> str:
    """The tolerance of one question as applied, in words (no number of the key in it).

    Parameters
    ----------
    question : str
        The question.
    unit : str
        Its unit (``"deg"`` makes it an angle).
    rtol : float
        The relative tolerance.
    kind : str
        ``"angle"`` (the default for an answer in deg: compared modulo 360 deg) or
        ``"number"`` (an angle in [0, 90] deg such as ``tau_min``: a plain number).

    Returns
    -------
    str
        E.g. ``"+-1 % (at least 0.1 % of the largest |Me| over the cycle)"`` or
        ``"+-0.5 deg, modulo 360 deg"``.
    """
    if unit == "deg":
        if kind != "angle":
            return f"+-{ANGLE_ATOL:g} deg"
        return f"+-{ANGLE_ATOL:g} deg, modulo 360 deg"
    q = parse_question(question)
    scale = _SCALES.get(q.q, _SCALES.get(q.q[:2], "the value")).format(arg=q.arg or "1")
    rel = f"+-{100 * rtol:g} %"
    if scale == "the value":
        return rel
    return f"{rel} (at least {100 * ATOL_FRACTION:g} % of {scale})"
