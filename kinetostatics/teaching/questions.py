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

Tolerances: a number passes when |answer - key| <= atol + rtol |key| (rtol 1 % by
default; atol 1e-3 of the quantity's scale over the cycle, so that a value near zero
is not judged by its relative error); an angle passes when the difference, wrapped
into (-180, 180], is at most 0.5 deg.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..model.errors import WorkbenchError

__all__ = ["ANGLE_ATOL", "ANSWER_TAG", "ATOL_FRACTION", "DEFAULT_RTOL", "Question",
           "is_mechanism", "parse_question", "to_float", "var_name", "wrap_angle"]

DEFAULT_RTOL = 0.01
ATOL_FRACTION = 1e-3        # atol = this fraction of the quantity's scale over the sweep
ANGLE_ATOL = 0.5            # deg
ANSWER_TAG = "answers"      # cell tag (and nbgrader grade_id) of a notebook's answer cell

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

