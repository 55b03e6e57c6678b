"""A mechanism scene's ``[units]``: the scene rewritten into the contract's units, once, where
it is read (the checks for unit slips follow in :mod:`kinetostatics.model.slips`).

A scene may name the units its numbers are written in (scene-format.md, opening; the
factors in :mod:`kinetostatics.model.units`). :func:`to_contract_units` returns a copy of the
raw mapping with every number in the contract's units (m, kg, N, rad/s, and degrees for
the angles a file holds) and without ``[units]``; the scene reader then checks it as any
other scene, and ``Scene.raw`` is that copy, so the modules that rebuild a scene from it
(simulation, concentration, balancing) see one system of units. A scene in the default
units is returned as it is: its numbers are never touched.

Which quantity each field is (declared once, in :data:`kinetostatics.model.fields.MECHANISM`,
which the conversion walks):

- length: ``ground``, body ``points`` and ``cog``, ``near``, joint ``friction.radius`` and
  ``friction.length``, a sliding driver's ``start``/``stop``/``positions``,
  ``[balancing]`` counterweight ``radius``;
- mass: body ``mass``; inertia (mass x length^2): body ``inertia``, ``[motion]`` ``flywheel``;
- angle: a rotating driver's ``start``/``stop``/``positions``, ``line_angle``, the angles
  of ``[motion]`` ``motor_table``;
- speed: a rotating driver's ``speed``, ``[motion]`` ``omega0`` and the motor's
  ``no_load_speed`` (``speed_rpm`` is rpm whatever the table says); a sliding driver's
  ``speed`` is length/s;
- force: load ``force`` and ``resist``; moment (force x length): load ``moment``, the
  motor's ``stall_moment`` and the moments of ``motor_table``;
- acceleration (length/s^2): ``gravity``, a sliding driver's ``acceleration``; a rotating
  driver's ``acceleration`` is rad/s^2 always.
"""

from __future__ import annotations

from .fields import MECHANISM, convert
from .fields import to_contract_units as _to_contract_units
from .units import Units

__all__ = ["convert_mechanism", "to_contract_units"]


def to_contract_units(raw: dict) -> tuple[dict, Units]:
    """The raw scene with its numbers in the contract's units, and the scene's units.

    Parameters
    ----------
    raw : dict
        The mapping as read (it is not changed).

    Returns
    -------
    (dict, Units)
        Without ``[units]``, every number in m, kg, N, N m, kg m^2, rad/s, m/s^2 and degrees.

    Raises
    ------
    SceneError
        ``[units]`` that is not a table, or names an unknown quantity or unit.
    """
    return _to_contract_units(raw, MECHANISM)


def convert_mechanism(raw: dict, units: Units) -> dict:
    """A copy of a mechanism scene's mapping (without ``[units]``) with the numbers written in
    ``units`` rewritten in the contract's units; keys it does not know are left as they are.
    In the default units, ``raw`` itself is returned."""
    return convert(raw, units, MECHANISM)
