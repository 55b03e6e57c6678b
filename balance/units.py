"""Units at the boundary of the field-balancing sections: one table, one place.

A scene may name the units of its numbers in a ``[units]`` table::

    [units]
    mass = "g"            # "kg" (default) | "g"
    length = "mm"         # "m" (default) | "mm"
    unbalance = "g mm"    # "kg m" (default) | "g mm"
    vibration = "um"      # "" (default: the readings' own unit) | "um" | "mils" | "mm/s"

Inside the workbench every quantity is SI (kg, m, kg m, and m or m/s for a
vibration); :class:`Units` converts a number read from the scene into SI
(:meth:`Units.to_si`) and an SI result back into the scene's unit
(:meth:`Units.from_si`). Nothing else in the package multiplies by 1e-3.

The factors are definitions: 1 g = 1e-3 kg, 1 mm = 1e-3 m, 1 g mm = 1e-6 kg m,
1 um = 1e-6 m, 1 mil = 25.4 um (1/1000 inch), 1 mm/s = 1e-3 m/s. A vibration unit
only converts within its kind (displacement um <-> mils); the influence method is
linear in the readings, so the readings' unit carries through to the residual
vibration unchanged.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .errors import BalanceError

__all__ = ["FACTORS", "QUANTITIES", "SI", "Units", "parse_units"]

FACTORS: dict[str, dict[str, float]] = {
    "mass": {"kg": 1.0, "g": 1e-3},
    "length": {"m": 1.0, "mm": 1e-3},
    "unbalance": {"kg m": 1.0, "g mm": 1e-6},
    "vibration": {"": 1.0, "um": 1e-6, "mils": 25.4e-6, "mm/s": 1e-3},
}
"""SI value of one scene unit, per quantity."""

QUANTITIES = tuple(FACTORS)
SI = {"mass": "kg", "length": "m", "unbalance": "kg m", "vibration": ""}
"""The default unit of each quantity (the contract's SI units; vibration: as read)."""

_ALIASES = {"µm": "um", "micron": "um", "mil": "mils", "gmm": "g mm", "g*mm": "g mm",
            "g.mm": "g mm", "kgm": "kg m", "kg*m": "kg m", "kg.m": "kg m"}


@dataclass(frozen=True)
class Units:
    """The units a scene's field-balancing numbers are written in.

    Attributes
    ----------
    mass, length, unbalance, vibration : str
        Unit names, keys of :data:`FACTORS`.
    """

    mass: str = "kg"
    length: str = "m"
    unbalance: str = "kg m"
    vibration: str = ""

    def unit(self, quantity: str) -> str:
        """The scene's unit of ``quantity`` ("mass", "length", "unbalance", "vibration")."""
        return getattr(self, quantity)

    def to_si(self, value: Any, quantity: str) -> Any:
        """A number (or numpy array) in the scene's unit, in SI."""
        return value * FACTORS[quantity][self.unit(quantity)]

    def from_si(self, value: Any, quantity: str) -> Any:
        """An SI number (or numpy array) in the scene's unit."""
        return value / FACTORS[quantity][self.unit(quantity)]

    @property
    def is_si(self) -> bool:
        """True when every unit is the contract's default."""
        return all(self.unit(q) == SI[q] for q in QUANTITIES)

    def to_dict(self) -> dict[str, str]:
        """JSON-ready: the unit of each quantity."""
        return {q: self.unit(q) for q in QUANTITIES}


def parse_units(table: Mapping[str, Any] | None, where: str = "[units]") -> Units:
    """Check a ``[units]`` table and return :class:`Units` (defaults where absent).

    Raises
    ------
    BalanceError
        An unknown quantity or unit, with the known ones listed.
    """
    if table is None:
        return Units()
    if not isinstance(table, Mapping):
        raise BalanceError(f"{where} must be a table, e.g. [units] mass = \"g\"")
    out = {}
    for key, value in table.items():
        if key not in FACTORS:
            raise BalanceError(f"{where}: unknown quantity {key!r}; known: "
                               f"{', '.join(QUANTITIES)}")
        if not isinstance(value, str):
            raise BalanceError(f"{where}.{key} must be a unit name (text), not {value!r}")
        name = " ".join(value.split())
        name = _ALIASES.get(name, name)
        if name not in FACTORS[key]:
            known = ", ".join(repr(u) for u in FACTORS[key])
            raise BalanceError(f"{where}.{key}: unknown unit {value!r}; known: {known}")
        out[key] = name
    return Units(**out)
