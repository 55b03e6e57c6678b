"""A balancing scene's ``[units]``: every section rewritten into the units its solver works
in, once, where the scene is read (docs/balancing.md, "Units").

- ``[rotor]``, ``[static_test]``, ``[[resonance_test]]`` (the seed's methods): masses,
  lengths and angles into kg, m and degrees, so that their results are SI as the contract
  says. ``speed_rpm`` is rpm whatever ``[units]`` says. Resonance amplitudes are not
  converted: the method uses their ratios, and ``A`` comes out in the amplitudes' unit.
- ``[[influence]]``, ``[iso]``, ``[[split]]``, ``[[combine]]`` (field balancing): their
  angles (phases, mass angles, ``first``, ``phase_noise``) into degrees; masses, radii and
  readings stay in the scene's units, and so do the results (the methods are linear in
  them; ``[iso]`` converts to SI itself, through the scene's :class:`Units`).
- A mechanism's keys (``[balancing]`` in a mechanism scene): as
  :func:`kinetostatics.model.scene_units.convert_mechanism`.

Each field and its quantity are declared once (:data:`kinetostatics.model.fields.BALANCING`
and ``MECHANISM``); the one units stage of every scene kind
(:func:`kinetostatics.model.fields.to_contract_units`) walks them. A scene in the default
units is returned untouched.
"""

from __future__ import annotations

from typing import Any

from kinetostatics.model.fields import BALANCING, MECHANISM
from kinetostatics.model.fields import to_contract_units as _to_contract_units

from .units import Units, parse_units

__all__ = ["to_contract_units"]


def to_contract_units(raw: Any) -> tuple[Any, Units]:
    """The raw balancing scene in its solvers' units (see the module's text), without
    ``[units]``, and the scene's :class:`Units`.

    Raises
    ------
    BalanceError
        A ``[units]`` that is not a table, or names an unknown quantity or unit.
    """
    return _to_contract_units(raw, MECHANISM, BALANCING, parse=parse_units)
