"""A mechanism scene's ``[units]``: the scene rewritten into the contract's units, once, where
it is read (the checks for unit slips follow in :mod:`kinetostatics.model.slips`).

A scene may name the units its numbers are written in (scene-format.md, opening; the
factors in :mod:`kinetostatics.model.units`). :func:`to_contract_units` returns a copy of the
raw mapping with every number in the contract's units (m, kg, N, rad/s, and degrees for
the angles a file holds) and without ``[units]``; the scene reader then checks it as any
other scene, and ``Scene.raw`` is that copy, so the modules that rebuild a scene from it
(simulation, concentration, balancing) see one system of units. A scene in the default
units is returned as it is: its numbers are never touched.

Which quantity each field is:

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

import copy
from typing import Any

from .units import Units, parse_units

__all__ = ["convert_mechanism", "to_contract_units"]

def _number(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def _scale(table: Any, key: str, f: float) -> None:
    """table[key] times f, where it is a number or a list of numbers (nested lists too);
    anything else is left for the reader to refuse with its own message."""
    if isinstance(table, dict) and key in table:
        table[key] = _scaled(table[key], f)


def _scaled(value: Any, f: float) -> Any:
    if _number(value):
        return value * f
    if isinstance(value, list):
        return [_scaled(v, f) for v in value]
    return value


def _each(items: Any) -> list:
    return [x for x in items if isinstance(x, dict)] if isinstance(items, list) else []


def _points(table: Any, f: float) -> None:
    if isinstance(table, dict):
        for key in table:
            _scale(table, key, f)


def _driver_kind(raw: dict) -> str | None:
    drv = raw.get("driver")
    name = drv.get("joint") if isinstance(drv, dict) else None
    for j in _each(raw.get("joints")):
        if j.get("name") == name:
            return j.get("kind")
    return None


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
    if "units" not in raw:
        return raw, Units()
    units = parse_units(raw["units"])
    return convert_mechanism({k: v for k, v in raw.items() if k != "units"}, units), units


def convert_mechanism(raw: dict, units: Units) -> dict:
    """A copy of a mechanism scene's mapping (without ``[units]``) with the numbers written in
    ``units`` rewritten in the contract's units; keys it does not know are left as they are
    (a balancing scene's sections: :mod:`balance.model.scene_units` converts those). In the
    default units, ``raw`` itself is returned."""
    if units.is_default:
        return raw
    out = _copy(raw)
    f = units.file_factor
    L, M, I, A, W, F, T = (f("length"), f("mass"), f("inertia"), f("angle"), f("speed"),
                           f("force"), f("moment"))
    _scale(out, "gravity", f("acceleration"))
    _points(out.get("ground"), L)
    _points(out.get("near"), L)
    for b in _each(out.get("bodies")):
        _scale(b, "mass", M)
        _scale(b, "inertia", I)
        _scale(b, "cog", L)
        _points(b.get("points"), L)
    for j in _each(out.get("joints")):
        _scale(j, "line_angle", A)
        fr = j.get("friction")
        _scale(fr, "radius", L)
        _scale(fr, "length", L)
    for ld in _each(out.get("loads")):
        _scale(ld, "force", F)
        _scale(ld, "resist", F)
        _scale(ld, "moment", T)
    drv = out.get("driver")
    if isinstance(drv, dict):
        rotating = _driver_kind(out) != "T"
        for key in ("start", "stop", "positions"):
            _scale(drv, key, A if rotating else L)
        _scale(drv, "speed", W if rotating else f("velocity"))
        if not rotating:
            _scale(drv, "acceleration", f("acceleration"))
    mo = out.get("motion")
    if isinstance(mo, dict):
        _scale(mo, "flywheel", I)
        _scale(mo, "omega0", W)
        motor = mo.get("motor")
        _scale(motor, "stall_moment", T)
        _scale(motor, "no_load_speed", W)
        table = mo.get("motor_table")
        if isinstance(table, list):
            mo["motor_table"] = [[_scaled(r[0], A), _scaled(r[1], T)]
                                 if isinstance(r, list) and len(r) == 2 else r for r in table]
    bal = out.get("balancing")
    if isinstance(bal, dict):
        for cw in _each(bal.get("counterweights")):
            _scale(cw, "radius", L)
        _scale(bal, "pair_radius", L)
    return out


_PLAIN = (str, int, float, bool, type(None))


def _copy(value: Any) -> Any:
    """``copy.deepcopy`` of a scene's mapping, quicker on what TOML gives (tables, lists,
    texts, numbers: each plain value is immutable and kept as it is)."""
    t = type(value)
    if t is dict:
        return {k: _copy(v) for k, v in value.items()}
    if t is list:
        return [_copy(v) for v in value]
    if t in _PLAIN:
        return value
    return copy.deepcopy(value)
