"""A ``[cam]`` scene's ``[units]``: the scene rewritten into the contract's units, once, where
it is read (docs/cam-scenes.md, "Units"), and the checks for unit slips.

Which quantity each field is (declared once, in :data:`kinetostatics.model.fields.CAM`):
length: ``base_radius``, ``roller_radius``, the follower's
``stroke``, ``offset`` (a number), ``arm``, ``pivot_distance``, the loads' ``guide_length``,
``guide_gap`` and ``pin_radius``; angle: ``transmission_angle``, ``stroke_angle``, every
segment's ``angle``; speed: ``speed`` (``speed_rpm`` stays rpm); force: a translating
follower's ``force`` and ``spring_preload``; force/length: its ``spring_rate``; mass:
its ``mass``; length/s^2: its ``gravity``; moment (force x length): an oscillating
follower's ``moment``, ``spring_preload`` and ``spring_rate`` (per rad); inertia (mass x
length^2): its ``inertia``.
"""

from __future__ import annotations

from typing import Any

from ..model.fields import CAM, to_contract_units
from ..model.slips import DEG, Slip, angle_list_slip, typed
from ..model.units import Units, radians, rpm_to_rad_s

__all__ = ["cam_slips", "cam_speed_slips", "cam_summary_units", "cam_to_contract_units"]


def _num(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def cam_to_contract_units(raw: Any) -> tuple[Any, Units]:
    """The raw cam scene with its numbers in the contract's units (m, kg, N, N m, rad/s,
    degrees), without ``[units]``, and the scene's units: the declared fields
    (:data:`kinetostatics.model.fields.CAM`) through the one units stage. A scene in the
    default units is returned untouched.

    Raises
    ------
    SceneError
        A ``[units]`` that is not a table, or names an unknown quantity or unit.
    """
    return to_contract_units(raw, CAM)


CAM_TIP_SPEED = 50.0
"""m/s: a cam whose outline moves faster than this looks like rpm typed for rad/s (a
racing engine's camshaft at 9000 rpm moves its 35 mm outline at 33 m/s; 3000 rpm typed as
rad/s moves the bundled translating cam's 24 mm at 73 m/s, and spins its 4 mm roller at
175 000 rpm)."""


def cam_slips(raw: Any, units: Units) -> list[Slip]:
    """The suspected unit slips of a cam scene (``raw`` in the contract's units), judged on
    the physical quantity (:mod:`kinetostatics.model.slips`): the segments' angles as a
    list (radians typed for degrees); any angle beyond two turns (degrees typed under
    ``angle = "rad"``); a speed that moves the cam's outline faster than
    :data:`CAM_TIP_SPEED` (rpm typed for rad/s). A single small angle (a real 4.5 deg
    swing) is never judged alone."""
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
    if _num(cam.get("base_radius")):
        out += cam_speed_slips(raw, units, cam["base_radius"])
    return out


def cam_speed_slips(raw: dict, units: Units, base_radius: float) -> list[Slip]:
    """The cam's speed judged on its outline (the base circle of ``base_radius``, given or
    computed from the admissible transmission angle, the roller and the lift): faster
    than :data:`CAM_TIP_SPEED` at its edge is rpm typed for rad/s."""
    cam = raw["cam"]
    fol = cam.get("follower") if isinstance(cam.get("follower"), dict) else {}
    w = cam.get("speed")
    # the cam's outline: its base circle, the roller, and the lift at the roller (a
    # translating follower's stroke; an oscillating one's arm times its swing)
    lift = fol.get("stroke") if fol.get("kind") != "oscillating" else (
        fol["arm"] * radians(fol["stroke_angle"])
        if _num(fol.get("arm")) and _num(fol.get("stroke_angle")) else None)
    size = abs(base_radius) + sum(abs(x) for x in (cam.get("roller_radius"), lift) if _num(x))
    out = []
    if _num(w) and abs(w) * size > CAM_TIP_SPEED:
        out.append(Slip("speed", "cam.speed", typed(w, "speed", units),
                        f"moves the cam's outline ({size:.3g} m) at {abs(w) * size:.3g} m/s",
                        f"{rpm_to_rad_s(w):.4g} rad/s (rpm typed for rad/s)"))
    return out


def cam_summary_units(summary: dict) -> dict[str, str]:
    """The unit of each number of a cam's summary (docs/cam-scenes.md, "Results"): SI,
    angles in degrees; a translating follower's forces in N, an oscillating one's in N m."""
    translating = summary.get("follower") == "translating"
    load = "N" if translating else "N m"
    return {"base_radius": "m", "working_base_radius": "m", "transmission_angle_min": "deg",
            "transmission_angle_min_at": "deg", "pressure_angle_max": "deg",
            "velocity_max": "m/s", "acceleration_max": "m/s^2", "omega2_max": "rad/s",
            "eps2_max": "rad/s^2", "F12_max": "N", "F12_max_at": "deg", "torque_max": "N m",
            "torque_min": "N m", "torque_mean": "N m", "friction_work": "J",
            "efficiency_rise": "1", "curvature_max": "1/m", "preload_needed": load,
            "offset": "m", "s0": "m", "stroke": "m", "beta0": "deg", "stroke_angle": "deg",
            "critical_angle_max": "deg", "transmission_angle_admissible": "deg"}
