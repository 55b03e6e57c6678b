"""Units at the boundary: one table of factors for every scene kind and every answer.

A scene may name the units its numbers are written in (scene-format.md, opening)::

    [units]
    length = "mm"        # "m" (default) | "mm" | "cm" | "in"
    mass = "g"           # "kg" (default) | "g" | "t"
    angle = "deg"        # "deg" (default) | "rad"
    speed = "rpm"        # "rad/s" (default) | "rpm"
    force = "N"          # "N" (default) | "kN"

Inside the workbench every quantity is SI and every angle is in radians; a number read
from a scene is converted once, by :meth:`Units.to_si`, where the scene is read. The
derived quantities follow from the base ones: a moment is force x length, an inertia
mass x length^2, a linear speed length/s, a linear acceleration length/s^2 (angular
accelerations are always rad/s^2). Balancing adds ``unbalance`` and ``vibration``.

The factors are definitions (SI value of one unit): 1 mm = 1e-3 m, 1 in = 0.0254 m,
1 g = 1e-3 kg, 1 t = 1e3 kg, 1 deg = pi/180 rad, 1 rpm = 2 pi / 60 rad/s,
1 kN = 1e3 N, 1 g mm = 1e-6 kg m, 1 um = 1e-6 m, 1 mil = 25.4 um, 1 mm/s = 1e-3 m/s.

:func:`parse_quantity` reads a number written with its unit (``"300.8 N m"``,
``"300800 N mm"``, ``"75.9 deg"``) into SI, through the same table.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Any

from .errors import SceneError

__all__ = ["BASE", "DEFAULTS", "DEG", "FACTORS", "Units", "angle_slip", "convert", "degrees",
           "labelled", "parse_quantity", "parse_units", "radians", "ratio_slip",
           "rpm_to_rad_s", "unit_kind"]

FACTORS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254},
    "mass": {"kg": 1.0, "g": 1e-3, "t": 1e3},
    "angle": {"rad": 1.0, "deg": math.pi / 180.0},
    "speed": {"rad/s": 1.0, "rpm": 2.0 * math.pi / 60.0},
    "force": {"N": 1.0, "kN": 1e3},
    "unbalance": {"kg m": 1.0, "g mm": 1e-6, "g cm": 1e-5, "g m": 1e-3, "kg mm": 1e-3},
    "vibration": {"": 1.0, "um": 1e-6, "mils": 25.4e-6, "mm/s": 1e-3},
}
"""SI value of one unit, per quantity (the scene's base quantities and balancing's own)."""

DEG = FACTORS["angle"]["deg"]
"""rad: one degree, pi/180. The degree's one home: every conversion between degrees and
radians in the scene readers goes through :func:`radians` and :func:`degrees`."""


def radians(deg: Any) -> Any:
    """Degrees (a number or a numpy array) in radians: ``deg * pi/180``, bit for bit
    ``math.radians`` and ``numpy.deg2rad``."""
    return deg * DEG


def degrees(rad: Any) -> Any:
    """Radians (a number or a numpy array) in degrees: ``rad * 180/pi``, bit for bit
    ``math.degrees`` and ``numpy.rad2deg``."""
    return rad * (180.0 / math.pi)


def rpm_to_rad_s(n: Any) -> Any:
    """A speed in rpm in rad/s, as a ``speed_rpm`` key is read: ``n * pi / 30`` (the
    rpm's one home beside ``FACTORS["speed"]["rpm"]``, the factor of ``[units] speed =
    "rpm"``; the two differ in the last bit at most, and each keeps its results')."""
    return n * math.pi / 30.0


BASE = ("length", "mass", "angle", "speed", "force")
"""The quantities every scene kind may name in ``[units]``."""

DEFAULTS: dict[str, str] = {"length": "m", "mass": "kg", "angle": "deg", "speed": "rad/s",
                            "force": "N", "unbalance": "kg m", "vibration": ""}
"""The contract's units when a scene names none (angles in files are in degrees)."""

_ALIASES = {"µm": "um", "μm": "um", "micron": "um", "mil": "mils", "gmm": "g mm",
            "g*mm": "g mm", "g.mm": "g mm", "kgm": "kg m", "kg*m": "kg m", "kg.m": "kg m",
            "degree": "deg", "degrees": "deg", "°": "deg", "radian": "rad", "radians": "rad",
            "rev/min": "rpm", "1/min": "rpm", "rad/sec": "rad/s", "inch": "in"}

# Units of derived quantities, for reading answers written with a unit: (SI factor, kind).
_DERIVED: dict[str, tuple[float, str]] = {
    "N m": (1.0, "moment"), "Nm": (1.0, "moment"), "N*m": (1.0, "moment"),
    "N mm": (1e-3, "moment"), "Nmm": (1e-3, "moment"), "N*mm": (1e-3, "moment"),
    "kN m": (1e3, "moment"), "kNm": (1e3, "moment"),
    "N cm": (1e-2, "moment"),
    "kg m^2": (1.0, "inertia"), "kg m2": (1.0, "inertia"), "g mm^2": (1e-9, "inertia"),
    "kg mm^2": (1e-6, "inertia"), "kg cm^2": (1e-4, "inertia"),
    "m/s": (1.0, "velocity"), "mm/s": (1e-3, "velocity"),
    "m/s^2": (1.0, "acceleration"), "mm/s^2": (1e-3, "acceleration"),
    "m/s2": (1.0, "acceleration"),
    "rad/s^2": (1.0, "angular acceleration"), "rad/s2": (1.0, "angular acceleration"),
    "W": (1.0, "power"), "kW": (1e3, "power"), "J": (1.0, "energy"), "kJ": (1e3, "energy"),
}


def _normal(name: str) -> str:
    """A unit name with its spaces folded and common spellings mapped to one."""
    name = " ".join(name.replace("·", " ").split())
    return _ALIASES.get(name, name)


def unit_kind(unit: str) -> tuple[float, str]:
    """The SI factor and the kind of quantity of a unit written in text.

    >>> unit_kind("N mm")
    (0.001, 'moment')
    >>> unit_kind("rpm")[1]
    'speed'

    Raises
    ------
    SceneError
        A unit the table does not know.
    """
    name = _normal(unit)
    for kind, table in FACTORS.items():
        if name in table and name:
            return table[name], kind
    if name in _DERIVED:
        return _DERIVED[name]
    raise SceneError(f"unknown unit {unit!r}")


_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


def parse_quantity(text: str, kind: str | None = None) -> tuple[float, str]:
    """A number written with its unit, converted to SI: ``"300800 N mm"`` -> (300.8,
    "moment"); a bare number is returned as it is, with kind ``""``.

    >>> parse_quantity("300800 N mm")
    (300.8, 'moment')
    >>> round(parse_quantity("75.9 deg")[0], 6)
    1.324705

    Parameters
    ----------
    text : str
        The number and its unit.
    kind : str, optional
        The kind the unit must be of (``"moment"``, ``"angle"``...): another kind is
        refused naming both.

    Raises
    ------
    SceneError
        No number, an unknown unit, or a unit of another kind.
    """
    m = _NUMBER.match(str(text))
    if not m:
        raise SceneError(f"{text!r} is not a number with a unit (e.g. '300.8 N m')")
    value, unit = float(m.group(1)), m.group(2)
    if not unit:
        return value, ""
    factor, found = unit_kind(unit)
    if kind is not None and found != kind:
        raise SceneError(f"{text!r}: {unit!r} is a unit of {found}, not of {kind}")
    return value * factor, found


def convert(value: Any, unit: str, to: str) -> Any:
    """``value`` in ``unit`` expressed in ``to`` (both of one kind).

    >>> convert(3000.0, "rpm", "rad/s")  # doctest: +ELLIPSIS
    314.159...
    """
    f1, k1 = unit_kind(unit)
    f2, k2 = unit_kind(to)
    if k1 != k2:
        raise SceneError(f"cannot convert {unit!r} ({k1}) to {to!r} ({k2})")
    return value * (f1 / f2)


@dataclass(frozen=True)
class Units:
    """The units a scene's numbers are written in; every attribute a key of
    :data:`FACTORS` for its quantity.

    The derived quantities: ``moment`` = force x length, ``inertia`` = mass x length^2,
    ``velocity`` = length/s, ``acceleration`` = length/s^2, ``stiffness`` = force/length.

    >>> u = Units(length="mm", mass="g")
    >>> u.to_si(250.0, "length"), u.to_si(1.0, "inertia")
    (0.25, 1e-09)
    """

    length: str = "m"
    mass: str = "kg"
    angle: str = "deg"
    speed: str = "rad/s"
    force: str = "N"
    unbalance: str = "kg m"
    vibration: str = ""

    def factor(self, quantity: str) -> float:
        """The SI value of one scene unit of ``quantity`` (base or derived)."""
        f = {q: FACTORS[q][getattr(self, q)] for q in FACTORS}
        derived = {
            "moment": f["force"] * f["length"],
            "inertia": f["mass"] * f["length"] ** 2,
            "velocity": f["length"],
            "acceleration": f["length"],
            "angular acceleration": 1.0,
            "stiffness": f["force"] / f["length"],
        }
        if quantity in f:
            return f[quantity]
        if quantity in derived:
            return derived[quantity]
        raise KeyError(quantity)

    def to_si(self, value: Any, quantity: str) -> Any:
        """A number (or numpy array) written in the scene's unit of ``quantity``, in SI."""
        return value * self.factor(quantity)

    def file_factor(self, quantity: str) -> float:
        """The value, in the contract's default unit (SI; degrees for an angle), of one
        scene unit of ``quantity``: 1 for a scene in the default units."""
        f = self.factor(quantity)
        return f / FACTORS["angle"]["deg"] if quantity == "angle" else f

    def to_file(self, value: Any, quantity: str) -> Any:
        """A number written in the scene's unit, in the contract's default unit (SI, and
        degrees for an angle): how a scene is rewritten into the contract's units when it is
        read. A default unit leaves the value untouched (bit for bit)."""
        f = self.file_factor(quantity)
        return value if f == 1.0 else value * f

    def from_si(self, value: Any, quantity: str) -> Any:
        """An SI number (or numpy array) in the scene's unit of ``quantity``."""
        return value / self.factor(quantity)

    def unit(self, quantity: str) -> str:
        """The scene's unit name of a quantity, base (``"mm"``) or derived (``"N mm"``,
        ``"g mm^2"``, ``"mm/s"``...)."""
        derived = {"moment": f"{self.force} {self.length}",
                   "inertia": f"{self.mass} {self.length}^2",
                   "velocity": f"{self.length}/s", "acceleration": f"{self.length}/s^2",
                   "angular acceleration": "rad/s^2",
                   "stiffness": f"{self.force}/{self.length}"}
        return derived.get(quantity) or getattr(self, quantity)

    def quote(self, value: float, quantity: str, spec: str = "g", *,
              file: bool = False) -> str:
        """An SI number (``file``: in the contract's file units, degrees for an angle)
        said in the scene's unit, for a message: the user reads the unit they typed.

        >>> Units(length="mm").quote(0.00236, "length", ".3g")
        '2.36 mm'
        >>> Units(angle="rad").quote(90.0, "angle", file=True)
        '1.5708 rad'
        """
        f = self.file_factor(quantity) if file else self.factor(quantity)
        return f"{format(value / f, spec)} {self.unit(quantity)}".rstrip()

    @property
    def is_default(self) -> bool:
        """True when every unit is the contract's default."""
        return all(getattr(self, f.name) == DEFAULTS[f.name] for f in fields(self))

    @property
    def is_si(self) -> bool:
        """The same as :attr:`is_default` (the name balancing's field sections use)."""
        return self.is_default

    def describe(self, quantities: tuple[str, ...] = BASE) -> str:
        """``length = "mm", mass = "g"``: the units that differ from the defaults."""
        return ", ".join(f'{q} = "{getattr(self, q)}"' for q in quantities
                         if getattr(self, q) != DEFAULTS[q]) or "the default units"

    def to_dict(self, quantities: tuple[str, ...] | None = None) -> dict[str, str]:
        """JSON-ready: the unit of each quantity (of ``quantities``, default all)."""
        names = quantities if quantities is not None else [f.name for f in fields(self)]
        return {q: getattr(self, q) for q in names}


def parse_units(table: Mapping[str, Any] | None, where: str = "[units]", *,
                quantities: tuple[str, ...] = BASE,
                error: type[Exception] = SceneError) -> Units:
    """Check a ``[units]`` table and return :class:`Units` (defaults where absent).

    Parameters
    ----------
    table : mapping or None
        The scene's ``[units]`` table.
    where : str
        Where the table is, for messages.
    quantities : tuple of str
        The quantities this scene kind may name (balancing adds ``unbalance`` and
        ``vibration``).
    error : exception class
        What to raise (a :class:`SceneError` unless told).

    Raises
    ------
    SceneError
        Not a table, an unknown quantity or unit (the known ones listed).
    """
    if table is None:
        return Units()
    if not isinstance(table, Mapping):
        raise error(f"{where} must be a table, e.g. [units] length = \"mm\"")
    out = {}
    for key, value in table.items():
        if key not in quantities:
            raise error(f"{where}: unknown quantity {key!r}; known: {', '.join(quantities)}")
        if not isinstance(value, str):
            raise error(f"{where}.{key} must be a unit name (text), not {value!r}")
        name = _normal(value)
        if name not in FACTORS[key]:
            known = ", ".join(repr(u) for u in FACTORS[key])
            raise error(f"{where}.{key}: unknown unit {value!r}; known: {known}")
        out[key] = name
    return Units(**out)


TWO_PI = 2.0 * math.pi


def angle_slip(values: Any, unit: str) -> bool:
    """True when angles written under ``unit`` look like radians typed in a degree field:
    the unit is ``"deg"``, every value lies within [-2 pi, 2 pi] and at least one has a
    fractional part (scene-format.md, opening). Whole numbers (0, 90, 180...) never do.

    >>> angle_slip([0.0, 2.7925, 1.5708], "deg"), angle_slip([0, 160, 90], "deg")
    (True, False)
    >>> angle_slip([0.0, 2.7925], "rad")
    False
    """
    if unit != "deg":
        return False
    vals = [float(v) for v in values]
    if not vals or not all(abs(v) <= TWO_PI + 1e-9 for v in vals):
        return False
    return any(abs(v - round(v)) > 1e-6 for v in vals)


def ratio_slip(values: Any, ratio: float = 1000.0) -> tuple[float, float] | None:
    """(smallest, largest) of the non-zero magnitudes when they are ``ratio`` or more
    apart (a value 1000 times off the others of its kind: grams among kilograms), else
    None.

    >>> ratio_slip([0.1, 80.0, 120.0])
    (0.1, 120.0)
    >>> ratio_slip([10.0, 20.0]) is None
    True
    """
    mags = [abs(float(v)) for v in values if float(v) != 0.0]
    if len(mags) < 2:
        return None
    lo, hi = min(mags), max(mags)
    return (lo, hi) if hi >= ratio * lo else None


def labelled(summary: dict, units: Units, unit_of: dict[str, Any],
             warnings: tuple[str, ...] | list[str] = ()) -> dict:
    """A summary that says its units key by key and carries its warnings: ``units`` is
    ``"SI"`` (angles in degrees), ``unit_of`` the unit of each numeric key (of a nested
    table, a table of units), ``scene_units`` the units the scene was typed in (they are
    the scene's, never the numbers'), and ``warnings`` the suspected unit slips (a list
    of strings, empty when none).

    >>> labelled({"omega_mean": 31.4}, Units(speed="rpm"), {"omega_mean": "rad/s"})["unit_of"]
    {'omega_mean': 'rad/s'}
    """
    return {**summary, "warnings": list(warnings), "units": "SI (angles in degrees)",
            "unit_of": {k: v for k, v in unit_of.items() if k in summary},
            "scene_units": units.to_dict(BASE)}
