"""Units of a balancing scene: the workbench's one table of factors
(:mod:`kinetostatics.model.units`), with balancing's own quantities.

A scene may name the units of its numbers in a ``[units]`` table::

    [units]
    mass = "g"            # "kg" (default) | "g" | "t"
    length = "mm"         # "m" (default) | "mm" | "cm" | "in"
    angle = "deg"         # "deg" (default) | "rad"
    unbalance = "g mm"    # "kg m" (default) | "g mm" | "g cm" | "g m" | "kg mm"
    vibration = "um"      # "" (default: the readings' own unit) | "um" | "mils" | "mm/s"

(``speed`` and ``force`` are accepted too, as in every scene kind.) Inside the workbench
every quantity is SI; :class:`Units` converts a number read from the scene into SI
(:meth:`Units.to_si`) and an SI result back into the scene's unit
(:meth:`Units.from_si`); :mod:`balance.model.scene_units` rewrites a scene when it is read.

The factors are definitions: 1 g = 1e-3 kg, 1 mm = 1e-3 m, 1 g mm = 1e-6 kg m,
1 um = 1e-6 m, 1 mil = 25.4 um (1/1000 inch), 1 mm/s = 1e-3 m/s. A vibration unit
only converts within its kind (displacement um <-> mils); the influence method is
linear in the readings, so the readings' unit carries through to the residual
vibration unchanged.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kinetostatics.model.units import BASE, DEFAULTS, FACTORS, Units
from kinetostatics.model.units import parse_units as _parse_units

from ..errors import BalanceError

__all__ = ["FACTORS", "QUANTITIES", "SI", "Units", "parse_units"]

QUANTITIES = (*BASE, "unbalance", "vibration")
"""The quantities a balancing scene's ``[units]`` may name."""

SI = {q: DEFAULTS[q] for q in QUANTITIES}
"""The default unit of each quantity (the contract's units; vibration: as read)."""


def parse_units(table: Mapping[str, Any] | None, where: str = "[units]") -> Units:
    """Check a ``[units]`` table and return :class:`Units` (defaults where absent).

    Raises
    ------
    BalanceError
        An unknown quantity or unit, with the known ones listed.
    """
    return _parse_units(table, where, quantities=QUANTITIES, error=BalanceError)
