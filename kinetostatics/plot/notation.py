"""One notation on every picture (docs/notation.md): English with the course's symbols,
magnitudes positive with the sense in words, angles from 0 to 360 deg, no "-0",
subscripts as mathtext. The course's Romanian terms live in the glossary
(:data:`GLOSS`, docs/notation.md) and the sheets' text, never on a picture;
:func:`notation_problems` finds a text that breaks the notation.
"""

from __future__ import annotations

import re

import numpy as np

from ..common.angles import degree_column

__all__ = ["GLOSS", "POLE", "direction_text", "gloss", "notation_problems", "number",
           "reading", "round_scale", "signed_text", "titled", "force_symbol",
           "couple_subscript", "load_symbol"]

#: The pole of the velocity and of the acceleration plan (fixed points sit on it).
POLE = "o"

#: The Romanian name of each course construction (the course text: planul vitezelor,
#: poligonul forțelor, unghiul de transmitere, momentul de echilibrare, reacțiunea,
#: forțele de inerție, centrul instantaneu): the glossary of docs/notation.md.
GLOSS = {
    "velocity plan": "planul vitezelor",
    "acceleration plan": "planul accelerațiilor",
    "force polygon": "poligonul forțelor",
    "polar diagram": "diagrama polară a reacțiunii",
    "free-body diagram": "diagrama corpului liber",
    "Wittenbauer diagram": "diagrama Wittenbauer",
    "instantaneous centres": "centrele instantanee de rotație",
    "transmission angle": "unghiul de transmitere",
    "equilibrating moment": "momentul de echilibrare",
    "equilibrating force": "forța de echilibrare",
    "unbalance": "dezechilibrul",
    "mechanism": "mecanismul",
}


def gloss(term: str) -> str:
    """The Romanian term of a course construction (``KeyError`` for an unknown one)."""
    return GLOSS[term]


def titled(term: str) -> str:
    """The English name of a course construction as a picture's title names it (a
    ``KeyError`` for one not in the glossary: every titled term has its Romanian name in
    docs/notation.md)."""
    GLOSS[term]
    return term


def number(x: float, fmt: str = ".4g") -> str:
    """A number formatted with ``fmt``, a negative zero written ``0``."""
    s = format(float(x), fmt)
    if s.startswith("-") and float(s) == 0.0:
        s = s[1:]
    return s


def force_symbol(joint: str) -> str:
    """The reaction in a joint as every drawing and polygon writes it: ``F`` with the
    joint's name as a subscript (mathtext), ``force_symbol("A")`` is ``$F_{\\mathrm{A}}$``
    (one notation for the free-body diagrams and the force polygons)."""
    return f"$F{couple_subscript(joint)}$" if joint else "F"


def couple_subscript(joint: str) -> str:
    """``_{\\mathrm{A}}``: a joint's name as a mathtext subscript (empty for none)."""
    if not joint:
        return ""
    return "_{\\mathrm{" + joint.replace("_", r"\_").replace("$", "") + "}}"


def load_symbol(kind: str, body: str) -> str:
    """A load as the free-body diagrams, the mechanism and the polygons write it
    (mathtext): the applied force $F_{\\mathrm{body}}$, the weight $G_{\\mathrm{body}}$,
    the inertia force $F^{i}_{\\mathrm{body}}$, friction $F^{f}_{\\mathrm{body}}$."""
    head = {"gravity": "G", "inertia": "F^{i}", "friction": "F^{f}"}.get(kind, "F")
    return f"${head}{couple_subscript(body)}$"


def reading(x: float, digits: int = 4) -> str:
    """A value a student reads off, with ``digits`` significant digits and never in
    e-notation: ``reading(3702.6)`` is ``"3703"``, ``reading(0.0004113)`` ``"0.0004113"``;
    a negative zero is ``"0"``."""
    x = float(x)
    if x == 0.0 or not np.isfinite(x):
        return number(x)
    s = np.format_float_positional(x, precision=digits, unique=False, fractional=False,
                                   trim="-")
    return "0" if float(s) == 0.0 else s


def round_scale(x: float, down: bool = True) -> float:
    """The round number 1, 2 or 5 x 10^k at or below ``x`` (``down=False``: at or above):
    the scales of arrows and plans, e.g. 0.0411 -> 0.02 and 900.4 -> 500."""
    x = abs(float(x))
    if x == 0.0 or not np.isfinite(x):
        return 1.0
    k = np.floor(np.log10(x))
    steps = [m * 10.0 ** (k + e) for e in (-1, 0, 1) for m in (1.0, 2.0, 5.0)]
    if down:
        return float(max(v for v in steps if v <= x * (1 + 1e-12)))
    return float(min(v for v in steps if v >= x * (1 - 1e-12)))


def signed_text(name: str, value: float, unit: str, fmt: str = ".4g", *,
                rotation: bool = True) -> str:
    """A signed quantity as its magnitude and its sense in words.

    ``signed_text("ω(coupler)", -0.7873, "rad/s")`` gives ``"ω(coupler) = 0.7873 rad/s,
    clockwise"``. For a rotation (angular speed, acceleration, a couple) the sign is
    counterclockwise positive; otherwise ``rotation=False`` writes "negative".
    """
    mag = reading(abs(value), int(fmt.strip(".g"))) if fmt.endswith("g") else \
        number(abs(value), fmt)
    if float(mag) == 0.0:
        return f"{name} = 0 {unit}"
    if rotation:
        sense = "counterclockwise" if value > 0 else "clockwise"
    else:
        sense = "positive" if value > 0 else "negative"
    return f"{name} = {mag} {unit}, {sense}"


def direction_text(v) -> str:
    """The direction of a vector as an angle from +x, 0 to 360 deg: ``"299.1°"``."""
    a = float(degree_column(np.arctan2(v[1], v[0]))) % 360.0
    s = number(a, ".1f")
    return ("0.0" if s == "360.0" else s) + "°"


# the words of the glossary's Romanian side (a picture shows none of them)
_ROMANIAN = (frozenset(w for v in GLOSS.values() for w in re.findall(r"[^\W\d_]+", v.lower())
                      if len(w) > 2) | {"cinetostatica", "patrulater", "echilibrarea",
                                         "manivela", "biela", "culisa", "reacțiunea",
                                         "forțele", "inerție", "volant", "cama", "tachet"
                                         }) - {"wittenbauer"}
_DIACRITICS = re.compile("[ăâîșşțţĂÂÎȘŞȚŢ]")
# a mathtext span (subscripts belong there)
_MATH = re.compile(r"(?<!\\)\$.*?(?<!\\)\$")
# a number in e-notation: 3.7e+03
_E_NUMBER = re.compile(r"(?<![A-Za-z_])[-+]?\d+(\.\d*)?[eE][-+]?\d+(?![A-Za-z])")
# a residual may be written in e-notation (a polygon's closing error 2.5e-14 N)
_RESIDUAL = re.compile(r"clos|error|residual|rounding|round-off|gap|tolerance", re.I)
# the project's internal name of a course text ("seed 002"): no student has it
_SEED = re.compile(r"\bseed \d{3}\b", re.I)
# a Greek letter spelled out in ASCII where the course writes its symbol
_SPELLED_GREEK = re.compile(r"(?<![A-Za-z\\])(phi|omega|alpha|epsilon|tau|mu|delta|psi|"
                            r"theta)(?![A-Za-z])")


def notation_problems(texts) -> list[tuple[str, str]]:
    """The texts of a picture that break the notation (docs/notation.md).

    A text breaks it with: an underscore outside mathtext (a code name such as
    ``mirror_angle`` or a raw ``I_r``); a number in e-notation, unless the text names
    a residual (a closing error, a rounding level); a Romanian word (they belong to the
    glossary); a Greek letter spelled out (``phi`` for φ); "seed 002" (the project's
    name of a course text: docs/notation.md names the texts as a student finds them).

    Parameters
    ----------
    texts : iterable of str

    Returns
    -------
    list of (str, str)
        (text, what is wrong) for each text that breaks the notation.
    """
    out = []
    for text in texts:
        plain = _MATH.sub(" ", text)
        if "_" in plain:
            out.append((text, "an underscore outside mathtext (a code name?)"))
        if _E_NUMBER.search(plain) and not _RESIDUAL.search(plain):
            out.append((text, "a value in e-notation"))
        words = set(re.findall(r"[^\W\d_]+", plain.lower()))
        if _DIACRITICS.search(plain) or words & _ROMANIAN:
            out.append((text, "a Romanian word (the glossary's, not the picture's)"))
        if _SPELLED_GREEK.search(plain):
            out.append((text, "a Greek letter spelled out"))
        if _SEED.search(text):
            out.append((text, "a reference to a document the student does not have"))
    return out
