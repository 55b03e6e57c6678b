"""Unit slips and answers written with units.

An answer that is wrong, but equals the key times a unit factor of its quantity
within the question's tolerance, is a *unit slip*: 1000x the key in N m is the
answer in N mm, the key in deg times pi/180 is the answer in rad. Such a row is named
(``status`` ``unit slip``, and a ``note`` such as ``"1000x the key: N mm instead of
N m?"``) and earns the credit the teacher chose (:func:`~kinetostatics.teaching.grade`
``unit_slip_credit``, default 0).

The factors, by the key's unit: 1e3 and 1e-3 for N m <-> N mm, m <-> mm, kg <-> g
(and the other lengths, forces and masses); 180/pi and pi/180 for deg <-> rad;
60/(2 pi) for rad/s <-> rpm; -1 (the sign flipped) for a signed quantity (moments,
force components, normal forces, angular velocities and accelerations,
coordinates), alone or with a unit factor.

Answers written as text with a unit (``"300.8 N m"``, ``"300800 N mm"``,
``"75.9 deg"``) are read by :func:`kinetostatics.model.units.parse_quantity` (the
scenes' unit table) and converted to the key's unit; a unit of another kind is
refused naming both.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from ..model.errors import WorkbenchError
from ..model.units import parse_quantity, unit_kind
from .questions import parse_question, to_float, wrap_angle

__all__ = ["SIGNED", "SLIPS", "answer_value", "slip_note", "slip_status"]

_LEAD = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_K, _M = 1e3, 1e-3
_DEG = 180.0 / math.pi      # degrees kept (6/10): the factor a deg/rad slip multiplies by
_RPM = 60.0 / (2.0 * math.pi)
SLIPS: dict[str, list[tuple[float, str]]] = {
    "N m": [(_K, "N mm instead of N m"), (_M, "kN m instead of N m")],
    "N": [(_M, "kN instead of N"), (_K, "mN instead of N")],
    "m": [(_K, "mm instead of m"), (_M, "km instead of m")],
    "m/s": [(_K, "mm/s instead of m/s"), (_M, "m/s divided by 1000")],
    "m/s^2": [(_K, "mm/s^2 instead of m/s^2"), (_M, "m/s^2 divided by 1000")],
    "kg": [(_K, "g instead of kg"), (_M, "t instead of kg")],
    "kg m": [(_K, "g m or kg mm instead of kg m"), (_M, "kg m divided by 1000"),
             (1e6, "g mm instead of kg m")],
    "um": [(_M, "mm instead of um"), (_K, "nm instead of um")],
    "deg": [(1.0 / _DEG, "rad instead of deg"), (_DEG, "deg converted to deg again")],
    "rad": [(_DEG, "deg instead of rad"), (1.0 / _DEG, "rad converted to rad again")],
    "rad/s": [(_RPM, "rpm instead of rad/s"), (_DEG, "deg/s instead of rad/s")],
    "rpm": [(1.0 / _RPM, "rad/s instead of rpm")],
    "rad/s^2": [(_DEG, "deg/s^2 instead of rad/s^2")],
}
"""Key unit -> [(factor, what the student probably did)]: answer = factor x key."""

SIGNED = frozenset({"Me", "Fe", "Me_mean", "Me_max", "Me_min", "Fe_mean", "Fe_max", "Fe_min",
                    "Fx", "Fy", "N", "M", "omega", "alpha", "x", "y"})
"""Quantities with a sign (a flipped sign is a slip); magnitudes and angles are not."""

# a vibration unit of the unit table is a length (um, mils) or a velocity (mm/s)
_VIBRATION = {"um": "length", "mils": "length", "mm/s": "velocity"}


def _kind(unit: str, kind: str) -> str:
    if kind != "vibration":
        return kind
    name = " ".join(unit.split())
    return _VIBRATION.get({"µm": "um", "μm": "um", "mil": "mils"}.get(name, name), kind)


def _times(f: float) -> str:
    for x, s in ((_K, "1000x"), (_M, "1/1000 of"), (1e6, "1e6x"), (_DEG, "180/pi x"),
                 (1.0 / _DEG, "pi/180 x"), (_RPM, "60/(2 pi) x"), (1.0 / _RPM, "2 pi/60 x")):
        if math.isclose(f, x, rel_tol=1e-12):
            return s
    return f"{f:g}x"


def _candidates(question: str, unit: str) -> list[tuple[float, str]]:
    out = list(SLIPS.get(unit, []))
    try:
        signed = parse_question(question).q in SIGNED
    except WorkbenchError:
        signed = False
    if signed:
        out = [(-1.0, "sign flipped")] + out + [(-f, f"{w}, and the sign flipped")
                                                for f, w in out]
    return out


def slip_note(question: str, unit: str, kind: str, answer: float, expected: float,
              tol: float) -> str:
    """The unit slip a wrong answer shows, as a note for the grade row, or ``""``.

    Parameters
    ----------
    question, unit, kind : str
        The question, the key's unit and kind (``"angle"`` compares modulo 360 deg).
    answer, expected, tol : float
        The student's answer (in the key's unit), the key, the question's tolerance.

    Returns
    -------
    str
        E.g. ``"1000x the key: N mm instead of N m?"``; ``""`` when the answer is no
        known factor of the key within ``tol / factor`` (and for a key so near zero
        that its tolerance cannot tell the factors apart).
    """
    if not (np.isfinite(answer) and np.isfinite(expected) and tol > 0):
        return ""
    if abs(expected) <= 4.0 * tol and kind != "angle":
        return ""
    for f, what in _candidates(question, unit):
        if kind == "angle" and abs(f) < 1.0 and abs(answer) > 2.0 * math.pi + abs(f) * tol:
            continue        # no angle in radians: a degree-sized answer is no such slip
        back = answer / f                     # the answer, undone by the slip
        diff = float(wrap_angle(back - expected)) if kind == "angle" else back - expected
        if abs(diff) <= tol:
            if f == -1.0:
                return "the sign flipped?"
            head = _times(abs(f)) + (" minus" if f < 0 else "")
            return f"{head} the key: {what}?"
    return ""


def slip_status(note: str) -> str:
    """The grade row's status of a slip :func:`slip_note` named: ``"sign slip"`` (the
    sign alone flipped: not a unit slip), ``"unit and sign slip"`` or ``"unit slip"``."""
    if note == "the sign flipped?":
        return "sign slip"
    return "unit and sign slip" if "sign flipped" in note else "unit slip"


def answer_value(x: Any, unit: str) -> tuple[float, str]:
    """A student's answer as a number in the key's unit, and a note when it was written
    with a unit (converted) or could not be read.

    Parameters
    ----------
    x : any
        A number, text (``"12.5"``, ``"12,5"``, ``"300800 N mm"``, ``"75.9 deg"``) or None.
    unit : str
        The key's unit.

    Returns
    -------
    value : float
        NaN when there is no number.
    note : str
        ``"read as 300800 N mm = 300.8 N m"``, ``"'7 N' is a force, the key is in N m"``,
        ``"unknown unit 'Nmx'"`` or ``""``.
    """
    if not isinstance(x, str):
        return to_float(x), ""
    t = x.strip()
    if t.count(",") == 1 and "." not in t:
        t = t.replace(",", ".")
    try:
        si, kind = parse_quantity(t)
    except ValueError:
        v = to_float(x)
        if math.isnan(v) and t:
            return v, f"{x!r} is not a number with a unit the workbench reads"
        return v, ""
    if not kind:
        return si, ""
    try:
        f_key, k_key = unit_kind(unit) if unit else (1.0, "")
    except ValueError:
        return math.nan, f"{x!r}: the key's unit {unit!r} is not in the unit table"
    lead = _LEAD.match(t)
    written = t[lead.end():].strip() if lead else ""
    kind, k_key = _kind(written, kind), _kind(unit, k_key)
    if kind != k_key:
        what = k_key or "a plain number"
        art = "an" if kind[:1] in "aeiou" else "a"
        return math.nan, (f"{x!r} is {art} {kind}, the question asks for {what} "
                          f"({unit or '-'})")
    v = si / f_key
    same = lead is not None and math.isclose(float(lead.group(0)), v, rel_tol=1e-12)
    return v, "" if same else f"read {x!r} as {v:.6g} {unit}"
