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

A scene in the default units is returned untouched.
"""

from __future__ import annotations

from typing import Any

from kinetostatics.model.scene_units import convert_mechanism

from .units import Units, parse_units

__all__ = ["to_contract_units"]


def _num(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def _scale(table: Any, key: str, f: float) -> None:
    if isinstance(table, dict) and _num(table.get(key)) and f != 1.0:
        table[key] = table[key] * f


def _each(items: Any) -> list:
    return [x for x in items if isinstance(x, dict)] if isinstance(items, list) else []


def _pair_angles(items: Any, f: float) -> Any:
    """[[amplitude or mass, angle], ...] with each angle times f."""
    if not isinstance(items, list):
        return items
    return [[x[0], x[1] * f] if isinstance(x, list) and len(x) == 2 and _num(x[1]) else x
            for x in items]


def to_contract_units(raw: Any) -> tuple[Any, Units]:
    """The raw balancing scene in its solvers' units (see the module's text), without
    ``[units]``, and the scene's :class:`Units`.

    Raises
    ------
    BalanceError
        A ``[units]`` that is not a table, or names an unknown quantity or unit.
    """
    if not isinstance(raw, dict) or "units" not in raw:
        return raw, Units()
    units = parse_units(raw["units"])
    out = convert_mechanism({k: v for k, v in raw.items() if k != "units"}, units)
    if units.is_default:
        return out, units
    f = units.file_factor
    M, L, A = f("mass"), f("length"), f("angle")
    rotor = out.get("rotor")
    if isinstance(rotor, dict):
        for u in _each(rotor.get("unbalance")):
            _scale(u, "mass", M)
            _scale(u, "radius", L)
            _scale(u, "z", L)
            _scale(u, "angle", A)
        for p in _each(rotor.get("planes")):
            _scale(p, "z", L)
            _scale(p, "radius", L)
    st = out.get("static_test")
    for key in ("disk_mass", "comparison_mass"):
        _scale(st, key, M)
    for key in ("comparison_radius", "correction_radius"):
        _scale(st, key, L)
    _scale(st, "alpha", A)
    for t in _each(out.get("resonance_test")):
        _scale(t, "trial_mass", M)
        _scale(t, "trial_radius", L)
        _scale(t, "correction_radius", L)
        for r in _each(t.get("runs")):
            _scale(r, "angle", A)
    _field_angles(out, A)
    return out, units


def _field_angles(out: dict, A: float) -> None:
    """The field sections' angles into degrees (their solvers' unit)."""
    if A == 1.0:
        return
    for t in _each(out.get("influence")):
        t["initial"] = _pair_angles(t.get("initial"), A)
        if isinstance(t.get("coefficients"), list):
            t["coefficients"] = [_pair_angles(row, A) for row in t["coefficients"]]
        for r in _each(t.get("runs")) + _each(t.get("trim")):
            _scale(r, "angle", A)
            r["readings"] = _pair_angles(r.get("readings"), A)
            if "masses" in r:
                r["masses"] = _pair_angles(r["masses"], A)
        _scale(t, "phase_noise", A)
        _scale(t.get("split"), "first", A)
    for s in _each(out.get("split")):
        _scale(s, "angle", A)
        _scale(s, "first", A)
    for c in _each(out.get("combine")):
        for w in _each(c.get("weights")):
            _scale(w, "angle", A)
    iso = out.get("iso")
    if isinstance(iso, dict) and isinstance(iso.get("residual"), list):
        iso["residual"] = _pair_angles(iso["residual"], A)
