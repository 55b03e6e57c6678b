"""A ``[cam]`` scene's ``[units]``: the scene rewritten into the contract's units, once, where
it is read (docs/cam-scenes.md, "Units"), and the checks for unit slips.

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
from typing import Any

from ..model.slips import DEG, Slip, angle_list_slip, tip_speed_slip, typed
from ..model.units import Units, parse_units

__all__ = ["cam_slips", "cam_to_contract_units"]


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


def cam_slips(raw: Any, units: Units) -> list[Slip]:
    """The suspected unit slips of a cam scene (``raw`` in the contract's units), judged on
    the physical quantity (:mod:`kinetostatics.model.slips`): the segments' angles as a
    list (radians typed for degrees); any angle beyond two turns (degrees typed under
    ``angle = "rad"``); a speed that moves the cam's outline faster than 400 m/s (rpm typed
    for rad/s). A single small angle (a real 4.5 deg swing) is never judged alone."""
    cam = raw.get("cam") if isinstance(raw, dict) else None
    if not isinstance(cam, dict):
        return []
    fol = cam.get("follower") if isinstance(cam.get("follower"), dict) else {}
    segs = cam.get("segments")
    seg = [s["angle"] for s in (segs if isinstance(segs, list) else ())
           if isinstance(s, dict) and _num(s.get("angle"))]
    out = []
    why = angle_list_slip([a * DEG for a in seg])
    if why is not None:
        out.append(Slip("angles", "cam.segments.angle", typed(seg, "angle", units), why,
                        "write them in degrees (the segments add up to 360), or angle = "
                        "\"rad\" in [units]"))
    for table, key, where in ((fol, "stroke_angle", "cam.follower.stroke_angle"),
                              (cam, "transmission_angle", "cam.transmission_angle")):
        a = table.get(key)
        if _num(a) and angle_list_slip([a * DEG]) is not None:
            out.append(Slip("angles", where, typed(a, "angle", units),
                            "beyond two turns", "write it in degrees, or angle = \"deg\""))
    w = cam.get("speed")
    # the cam's outline: base circle, stroke and roller (an oscillating follower's stroke
    # is an angle: its arm and pivot distance stand for the reach)
    reach = [abs(x) for t, k in ((cam, "base_radius"), (cam, "roller_radius"),
                                 (fol, "stroke"), (fol, "arm"), (fol, "pivot_distance"))
             if _num(x := t.get(k))]
    size = sum(reach)
    if _num(w) and tip_speed_slip(w, size):
        out.append(Slip("speed", "cam.speed", typed(w, "speed", units),
                        f"moves the cam's outline ({size:.3g} m) at {abs(w) * size:.3g} m/s",
                        f"{w * math.pi / 30:.4g} rad/s (rpm typed for rad/s)"))
    return out
