"""A ``[cam]`` scene's ``[units]``: the scene rewritten into the contract's units, once, where
it is read (docs/cam-scenes.md, "Units"), and the warnings for unit slips.

Which quantity each field is: length: ``base_radius``, ``roller_radius``, the follower's
``stroke``, ``offset`` (a number), ``arm``, ``pivot_distance``, the loads' ``guide_length``,
``guide_gap`` and ``pin_radius``; angle: ``transmission_angle``, ``stroke_angle``, every
segment's ``angle``; speed: ``speed`` (``speed_rpm`` stays rpm); force: a translating
follower's ``force`` and ``spring_preload``; force/length: its ``spring_rate``; mass:
its ``mass``; length/s^2: its ``gravity``; moment (force x length): an oscillating
follower's ``moment``, ``spring_preload`` and ``spring_rate`` (per rad); inertia (mass x
length^2): its ``inertia``.
"""

from __future__ import annotations

import copy
import math
import warnings
from typing import Any

from ..model.errors import UnitWarning
from ..model.scene_units import SPEED_SLIP
from ..model.units import Units, angle_slip, parse_units

__all__ = ["cam_to_contract_units", "check_cam_slips"]


def _num(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def _scale(table: Any, key: str, f: float) -> None:
    if isinstance(table, dict) and _num(table.get(key)) and f != 1.0:
        table[key] = table[key] * f


def cam_to_contract_units(raw: Any) -> tuple[Any, Units]:
    """The raw cam scene with its numbers in the contract's units (m, kg, N, N m, rad/s,
    degrees), without ``[units]``, and the scene's units. A scene in the default units is
    returned untouched.

    Raises
    ------
    SceneError
        A ``[units]`` that is not a table, or names an unknown quantity or unit.
    """
    if not isinstance(raw, dict) or "units" not in raw:
        return raw, Units()
    units = parse_units(raw["units"])
    out = {k: v for k, v in raw.items() if k != "units"}
    cam = out.get("cam")
    if units.is_default or not isinstance(cam, dict):
        return out, units
    out = copy.deepcopy(out)
    cam = out["cam"]
    f = units.file_factor
    L, A = f("length"), f("angle")
    for key in ("base_radius", "roller_radius"):
        _scale(cam, key, L)
    _scale(cam, "transmission_angle", A)
    _scale(cam, "speed", f("speed"))
    fol = cam.get("follower")
    for key in ("stroke", "offset", "arm", "pivot_distance"):
        _scale(fol, key, L)
    _scale(fol, "stroke_angle", A)
    segs = cam.get("segments")
    for seg in segs if isinstance(segs, list) else ():
        _scale(seg, "angle", A)
    loads = cam.get("loads")
    oscillating = isinstance(fol, dict) and fol.get("kind") == "oscillating"
    if oscillating:
        for key in ("moment", "spring_preload", "spring_rate"):
            _scale(loads, key, f("moment"))
        _scale(loads, "inertia", f("inertia"))
        _scale(loads, "pin_radius", L)
    else:
        _scale(loads, "force", f("force"))
        _scale(loads, "spring_preload", f("force"))
        _scale(loads, "spring_rate", f("force") / L)
        _scale(loads, "mass", f("mass"))
        _scale(loads, "gravity", f("acceleration"))
        _scale(loads, "guide_length", L)
        _scale(loads, "guide_gap", L)
    return out, units


def check_cam_slips(raw: Any, units: Units) -> None:
    """Warn (:class:`~kinetostatics.model.errors.UnitWarning`) where a cam scene's numbers
    look like unit slips: its angles (the segments' alone, ``stroke_angle`` or
    ``transmission_angle`` alone, or all of them) all within 2 pi with fractional values
    under ``angle = "deg"`` (radians typed for degrees), a speed above 1e4 rad/s (rpm
    typed for rad/s). ``raw`` is the scene in the contract's units."""
    cam = raw.get("cam") if isinstance(raw, dict) else None
    if not isinstance(cam, dict):
        return
    fol = cam.get("follower")
    segs = cam.get("segments")
    seg_angles = [seg["angle"] for seg in (segs if isinstance(segs, list) else ())
                  if isinstance(seg, dict) and _num(seg.get("angle"))]
    angles = list(seg_angles)
    for table, key in ((fol, "stroke_angle"), (cam, "transmission_angle")):
        if isinstance(table, dict) and _num(table.get(key)):
            angles.append(table[key])
    singles = [[a] for a in angles[len(seg_angles):]]      # stroke_angle, transmission_angle
    if angles and (angle_slip(angles, units.angle) or angle_slip(seg_angles, units.angle)
                   or any(angle_slip(a, units.angle) for a in singles)):
        warnings.warn(f"cam angles {[float(a) for a in angles[:5]]} look like radians (all "
                      "within 2 pi, with fractional values) but angles are in degrees (the "
                      "segments add up to 360); write them in degrees, or angle = \"rad\" in "
                      "[units]", UnitWarning, stacklevel=3)
    w = cam.get("speed")
    if _num(w) and abs(w) > SPEED_SLIP:
        warnings.warn(f"cam.speed = {w:.6g} rad/s ({abs(w) * 30 / math.pi:.4g} rpm) looks like "
                      "rpm in a rad/s field; give speed_rpm, or speed = \"rpm\" in [units]",
                      UnitWarning, stacklevel=3)
