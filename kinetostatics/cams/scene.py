"""The ``[cam]`` scene (docs/cam-scenes.md): loading and solving it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from ..model.fields import CAM, read_number, section
from ..model.memory import check_memory
from ..model.slips import emit, read_checks
from ..model.tomlio import as_float, as_int, as_list, as_str, check_keys, read_source, suggest
from ..model.units import Units, degrees, radians, rpm_to_rad_s
from ..transmission.efficiency import mean_efficiency
from .followers import (
    Follower,
    OscillatingFollower,
    TranslatingFollower,
    base_radius_oscillating,
    base_radius_translating,
    check_tau,
    cross2,
    follower_points,
    optimal_offset,
    perp,
    polar_profile_oscillating,
    polar_profile_translating,
    profile,
    tau_of,
    transmission_angle,
)
from .forces import (
    cam_angles,
    cam_table,
    critical_transmission_angle,
    critical_transmission_angle_oscillating,
    oscillating_follower_force,
    translating_follower_forces,
)
from .laws import (
    ALIASES,
    LAW_COEFFICIENTS,
    LAWS,
    CamError,
    CamLaw,
    Segment,
    constant_acceleration,
    cosine_acceleration,
    cycle_extreme,
    fall,
    law_name,
    law_peaks,
    rise,
    sine_acceleration,
    zero_acceleration,
)
from .units import cam_slips, cam_speed_slips, cam_to_contract_units

# --------------------------------------------------------------------------- scenes

TOP_KEYS = ("title", "format", "cam")
CAM_KEYS = ("speed", "speed_rpm", "rotation", "count", "base_radius", "transmission_angle",
            "roller_radius", "follower", "segments", "loads")
FOLLOWER_KEYS = {"translating": ("kind", "stroke", "offset"),
                 "oscillating": ("kind", "stroke_angle", "arm", "pivot_distance",
                                 "rise_sense")}
SEGMENT_KEYS = ("kind", "law", "angle")
LOAD_KEYS = {"translating": ("force", "mass", "gravity", "spring_rate", "spring_preload",
                             "friction", "guide_length", "guide_gap"),
             "oscillating": ("moment", "inertia", "spring_rate", "spring_preload", "friction",
                             "pin_radius")}


@dataclass(frozen=True)
class CamLoads:
    """Loads on the follower (``[cam.loads]``); names as in ``docs/cam-scenes.md``."""

    force: float = 0.0            # N (translating) or N m (oscillating: the `moment` key)
    mass: float = 0.0             # kg, or kg m^2 about C (oscillating: `inertia`)
    gravity: float = 0.0          # m/s^2 along the axis towards the cam (translating)
    spring_rate: float = 0.0      # N/m or N m/rad
    spring_preload: float = 0.0   # N or N m at the lowest position
    friction: float = 0.0         # guide (translating) or pin (oscillating) coefficient
    guide_length: float = 0.0     # b, m
    guide_gap: float = 0.0        # a at the lowest position, m
    pin_radius: float = 0.0       # r, m


@dataclass(frozen=True)
class CamScene:
    """A checked ``[cam]`` scene: the program, the follower, the speed and the loads."""

    title: str
    law: CamLaw
    follower: Follower
    speed: float
    rotation: str
    count: int
    loads: CamLoads
    transmission_angle: float | None = None     # admissible, rad, if the radius came from it
    units: Units = field(default_factory=Units)  # the file's [units] (the numbers here are SI)
    warnings: tuple[str, ...] = ()               # the suspected unit slips, as warned


_CAM, _FOLLOWER = section(CAM, "cam"), section(CAM, "cam", "follower")
_SEGMENT, _LOADS = section(CAM, "cam", "segments", "[]"), section(CAM, "cam", "loads")


def _loads_number(table: dict, key: str, units: Units) -> float:
    """A ``[cam.loads]`` number read through its declaration (bounds, default 0)."""
    return read_number(table, _LOADS[key], "cam.loads", units)


def load_cam_scene(source: Any) -> CamScene:
    """Read and check a ``[cam]`` scene (a path, TOML text or a dict; ``docs/cam-scenes.md``).

    Unknown keys are refused with the nearest known key suggested; every error is one line
    (:class:`~kinetostatics.model.errors.SceneError` for the file's form, :class:`CamError` for a
    cam that cannot be built). Suspected unit slips are warned (``warnings`` keeps them).
    """
    raw, quiet = read_checks(read_source(source, "cam scene"))
    raw, units = cam_to_contract_units(raw)
    texts = emit(cam_slips(raw, units), quiet)
    if isinstance(raw, dict) and "cam" not in raw and "driver" in raw:
        raise CamError("this is a mechanism scene (it has [driver]); the cam command takes a "
                       "[cam] scene (docs/cam-scenes.md), e.g. the bundled translating_roller")
    raw = check_keys(raw, TOP_KEYS, "cam scene", required=("cam",))
    if "format" in raw and raw["format"] != 1:
        raise CamError(f"cam scene: format must be 1, got {raw['format']!r}")
    title = as_str(raw["title"], "title") if "title" in raw else ""
    cam = check_keys(raw["cam"], CAM_KEYS, "cam", required=("follower", "segments"))
    kind, fol, stroke = _follower_table(cam["follower"], units)
    try:
        law = CamLaw(stroke, tuple(_segments(cam["segments"], units)))
    except CamError as exc:
        raise CamError(f"cam.segments: {exc}") from None
    speed = _speed(cam, units)
    rotation = as_str(cam.get("rotation", "ccw"), "cam.rotation")
    if rotation not in ("ccw", "cw"):
        raise CamError(f"cam.rotation must be 'ccw' or 'cw', not {rotation!r}")
    count = as_int(cam.get("count", 361), "cam.count", lo=2, hi=10_000_000)
    if ("base_radius" in cam) == ("transmission_angle" in cam):
        raise CamError("cam: give exactly one of base_radius (m) and transmission_angle "
                       "(the admissible one, deg)")
    tau_adm = None
    if "transmission_angle" in cam:
        tau_adm = radians(read_number(cam, _CAM["transmission_angle"], "cam", units))
        check_tau(tau_adm, units)
    loads = _load_loads(cam.get("loads", {}), kind, stroke, units)
    follower = _follower(kind, fol, cam, law, tau_adm, loads, units)
    if "base_radius" not in cam:        # the speed judged on the base radius computed
        texts += emit(cam_speed_slips(raw, units, follower.base_radius), quiet)
    return CamScene(title, law, follower, speed, rotation, count, loads, tau_adm, units, texts)


def _follower_table(fol: Any, units: Units) -> tuple[str, dict, float]:
    """The follower's kind, its checked table and its stroke (m, or rad)."""
    if not isinstance(fol, dict) or "kind" not in fol:
        check_keys(fol, (*fol, "kind") if isinstance(fol, dict) else (), "cam.follower",
                   required=("kind",))
    kind = as_str(fol["kind"], "cam.follower.kind")
    if kind not in FOLLOWER_KEYS:
        raise CamError(f"cam.follower.kind must be 'translating' or 'oscillating', not "
                       f"{kind!r}{suggest(kind, FOLLOWER_KEYS)}")
    other = "oscillating" if kind == "translating" else "translating"
    for key in fol:
        if key in FOLLOWER_KEYS[other] and key not in FOLLOWER_KEYS[kind]:
            raise CamError(f"cam.follower.{key} belongs to an {other} follower, not a {kind} one")
    fol = check_keys(fol, FOLLOWER_KEYS[kind], "cam.follower",
                     required=("stroke",) if kind == "translating"
                     else ("stroke_angle", "arm", "pivot_distance"))
    if kind == "translating":
        return kind, fol, read_number(fol, _FOLLOWER["stroke"], "cam.follower", units)
    return kind, fol, radians(read_number(fol, _FOLLOWER["stroke_angle"], "cam.follower",
                                          units))


def _segments(items: Any, units: Units) -> list[Segment]:
    """The program's segments, checked (angles in radians)."""
    segments = []
    for i, seg in enumerate(as_list(items, "cam.segments"), 1):
        where = f"cam.segments[{i}]"
        seg = check_keys(seg, SEGMENT_KEYS, where, required=("kind", "angle"))
        skind = as_str(seg["kind"], f"{where}.kind")
        if skind == "dwell" and "law" in seg:
            raise CamError(f"{where}: a dwell has no law")
        law = as_str(seg["law"], f"{where}.law") if "law" in seg else None
        if skind in ("rise", "return") and law is None:
            raise CamError(f"{where}: a {skind} needs a law ({', '.join(LAWS)})")
        try:
            law = law_name(law) if law is not None else None
        except CamError as exc:
            raise CamError(f"{where}.law: {exc}") from None
        segments.append(Segment(skind, radians(read_number(seg, _SEGMENT["angle"], where,
                                                           units)), law))
    return segments


def _speed(cam: dict, units: Units) -> float:
    """The cam's angular speed (rad/s), from ``speed`` or ``speed_rpm``."""
    if ("speed" in cam) == ("speed_rpm" in cam):
        raise CamError("cam: give exactly one of speed (rad/s) and speed_rpm")
    if "speed" in cam:
        return read_number(cam, _CAM["speed"], "cam", units)
    return rpm_to_rad_s(read_number(cam, _CAM["speed_rpm"], "cam", units))


def _follower(kind: str, fol: dict, cam: dict, law: CamLaw, tau_adm: float | None,
              loads: CamLoads, units: Units) -> Follower:
    """The follower, its base radius given or computed from the admissible angle."""
    roller = read_number(cam, _CAM["roller_radius"], "cam", units)
    if kind == "translating":
        offset_raw = fol.get("offset", 0.0)
        if offset_raw == "optimal":
            if tau_adm is None:
                raise CamError("cam.follower.offset = 'optimal' needs cam.transmission_angle")
            offset, r0 = optimal_offset(law, tau_adm)
        else:
            offset = as_float(offset_raw, "cam.follower.offset")
            r0 = (base_radius_translating(law, tau_adm, offset) if tau_adm is not None
                  else read_number(cam, _CAM["base_radius"], "cam", units))
        if tau_adm is not None and loads.friction > 0.0:
            cr = float(np.max(critical_transmission_angle(
                loads.friction, loads.guide_gap - np.array([0, law.stroke]),
                loads.guide_length)))
            if tau_adm <= cr:
                raise CamError(f"cam.transmission_angle {units.quote(tau_adm, 'angle')} is "
                               f"not above the critical angle "
                               f"{units.quote(cr, 'angle', '.4g')} (eqs 1.44-1.45); raise it")
        return TranslatingFollower(r0, offset, roller, units)
    arm = read_number(fol, _FOLLOWER["arm"], "cam.follower", units)
    dist = read_number(fol, _FOLLOWER["pivot_distance"], "cam.follower", units)
    sense = as_str(fol.get("rise_sense", "same"), "cam.follower.rise_sense")
    if sense not in ("same", "opposite"):
        raise CamError(f"cam.follower.rise_sense must be 'same' or 'opposite', not "
                       f"{sense!r}")
    r0 = (base_radius_oscillating(law, tau_adm, arm, dist, sense, units) if tau_adm is not None
          else read_number(cam, _CAM["base_radius"], "cam", units))
    return OscillatingFollower(r0, arm, dist, roller, sense, units)


def _load_loads(raw: Any, kind: str, stroke: float, units: Units) -> CamLoads:
    other = "oscillating" if kind == "translating" else "translating"
    if isinstance(raw, dict):
        for key in raw:
            if key in LOAD_KEYS[other] and key not in LOAD_KEYS[kind]:
                raise CamError(f"cam.loads.{key} applies to an {other} follower, not a {kind} "
                               "one")
    tab = check_keys(raw, LOAD_KEYS[kind], "cam.loads")
    if kind == "translating":
        loads = CamLoads(*(_loads_number(tab, k, units) for k in (
            "force", "mass", "gravity", "spring_rate", "spring_preload", "friction",
            "guide_length", "guide_gap")))
        if loads.friction > 0.0:
            if loads.guide_length <= 0.0:
                raise CamError("cam.loads: guide friction needs guide_length (b, m) > 0")
            if "guide_gap" not in tab:
                raise CamError("cam.loads: guide friction needs guide_gap (a at the lowest "
                               "position, m)")
            if loads.guide_gap < stroke:
                raise CamError(f"cam.loads.guide_gap {units.quote(loads.guide_gap, 'length')} is "
                               f"less than the stroke {units.quote(stroke, 'length')}: the "
                               "contact point would enter the guide")
        return loads
    n = {k: _loads_number(tab, k, units) for k in ("moment", "inertia", "spring_rate",
                                                     "spring_preload", "friction", "pin_radius")}
    loads = CamLoads(force=n["moment"], mass=n["inertia"], spring_rate=n["spring_rate"],
                     spring_preload=n["spring_preload"], friction=n["friction"],
                     pin_radius=n["pin_radius"])
    return loads


@dataclass
class CamResults:
    """Tables and summary of a solved cam scene (see ``docs/cam-scenes.md``)."""

    scene: CamScene
    motion: pd.DataFrame
    geometry: pd.DataFrame
    forces: pd.DataFrame
    summary: dict[str, Any]


# peak bytes per cam angle: measured 670-690 B (/usr/bin/time -v, both bundled cams at
# 1e6 angles, with and without --out), and the interpreter with numpy and pandas
CAM_ROW_BYTES = 750
CAM_BASE = 80e6


def check_cam_memory(count: int) -> None:
    """Refuse, in one line, a cam whose estimated peak memory is over the budget
    (:func:`kinetostatics.model.memory.check_memory`)."""
    check_memory(CAM_BASE + CAM_ROW_BYTES * count, f"the cam at {count:,} angles",
                 "use fewer angles (cam.count)")


def solve_cam(source: Any) -> CamResults:
    """Solve a ``[cam]`` scene: follower motion, transmission angle, profile, forces, torque.

    Parameters
    ----------
    source : path, TOML text, dict or CamScene

    Returns
    -------
    CamResults
        ``motion``, ``geometry``, ``forces`` (pandas DataFrames, one row per cam angle) and
        ``summary`` (a JSON-ready dict); columns and keys in ``docs/cam-scenes.md``.
    """
    sc = source if isinstance(source, CamScene) else load_cam_scene(source)
    check_cam_memory(sc.count)
    law, fol, w, ld = sc.law, sc.follower, sc.speed, sc.loads
    table = cam_table(law, fol, sc.count, w, sc.rotation)
    phi = cam_angles(sc.count)
    s, ds, dds = law(phi)
    b, d1, _, u, vel = follower_points(fol, s, ds, dds)
    tau = tau_of(b, d1, u)
    t = d1 - perp(b)
    tn = np.hypot(t[0], t[1])
    vmax = float(np.max(np.abs(ds)))
    direction = np.where(np.abs(ds) > 1e-12 * vmax, np.sign(ds), 0.0)
    load = ld.force + ld.spring_preload + ld.spring_rate * s + ld.mass * (w * w * dds + ld.gravity)
    translating = isinstance(fol, TranslatingFollower)
    if translating:
        a = ld.guide_gap - s
        b_len = ld.guide_length if ld.friction > 0.0 else 1.0
        f12, n1, n2 = translating_follower_forces(load, tau, ld.friction, a, b_len, direction,
                                                  angles=phi)
        friction = ld.friction * (n1 + n2) * np.abs(direction)   # none in a dwell
        loss = friction * np.abs(ds)                       # friction work per rad of cam
    else:
        f12 = oscillating_follower_force(load, tau, fol.arm, ld.friction, ld.pin_radius,
                                         direction, angles=phi)
        friction = ld.friction * ld.pin_radius * f12 * np.abs(direction)   # Mf (eq. 1.46)
        loss = friction * np.abs(ds)
    torque = f12 * np.sum(b * d1, axis=0) / tn          # M = B x F12 n = F12 (B . dB) / |T|
    separation = f12 < 0.0

    motion = table[["angle", *table.columns[1:6]]].copy()
    geometry = table[["angle", "tau", "pressure_angle", "x_pitch", "y_pitch", "x_profile",
                      "y_profile", "x_outer", "y_outer", "radius", "curvature"]].copy()
    forces = pd.DataFrame({"angle": table["angle"], "load": load, "F12": f12})
    if translating:
        forces["N1"], forces["N2"] = n1, n2
    else:
        forces["F02"] = f12
    forces["friction"] = friction
    forces["torque"] = torque
    forces["separation"] = separation

    tau_min, tau_at = cycle_extreme(
        law, lambda p, s_, ds_, dds_: -tau_of(*_sel(fol, s_, ds_, dds_)))
    kmax, _ = cycle_extreme(law, lambda p, s_, ds_, dds_: _curv(fol, s_, ds_, dds_))
    rise_rows = direction > 0
    summary: dict[str, Any] = {
        "follower": "translating" if translating else "oscillating",
        "base_radius": fol.base_radius,
        "working_base_radius": fol.base_radius - fol.roller_radius,
        "transmission_angle_min": degrees(-tau_min),
        "transmission_angle_min_at": degrees(tau_at),
        "pressure_angle_max": 90.0 - degrees(-tau_min),
        ("velocity_max" if translating else "omega2_max"): w * vmax,
        ("acceleration_max" if translating else "eps2_max"): w * w * float(np.max(np.abs(dds))),
        "F12_max": float(np.max(f12)),
        "F12_max_at": float(table["angle"].iloc[int(np.argmax(f12))]),
        "torque_max": float(np.max(torque)),
        "torque_min": float(np.min(torque)),
        "torque_mean": float(np.trapezoid(torque, phi) / (phi[-1] - phi[0])),
        "friction_work": float(np.trapezoid(loss, phi)),
        "efficiency_rise": _rise_efficiency(phi, torque, load * ds, rise_rows),
        "curvature_max": kmax,
        "undercut": bool(fol.roller_radius > 0.0 and kmax * fol.roller_radius >= 1.0),
        "separation_rows": int(np.count_nonzero(separation)),
        "preload_needed": float(max(0.0, -float(np.min(load)))),
    }
    if translating:
        summary.update(offset=fol.offset, s0=fol.s0, stroke=law.stroke)
        if ld.friction > 0.0:
            cr = critical_transmission_angle(ld.friction, ld.guide_gap - s, ld.guide_length)
            summary["critical_angle_max"] = degrees(float(np.max(cr)))
    else:
        summary.update(beta0=degrees(fol.beta0), stroke_angle=degrees(law.stroke))
        if ld.friction > 0.0:
            summary["critical_angle_max"] = degrees(critical_transmission_angle_oscillating(
                ld.friction, ld.pin_radius, fol.arm))
    if sc.transmission_angle is not None:
        summary["transmission_angle_admissible"] = degrees(sc.transmission_angle)
    return CamResults(sc, motion, geometry, forces, summary)


def _sel(fol: Follower, s: np.ndarray, ds: np.ndarray,
         dds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    b, d1, _, u, _ = follower_points(fol, s, ds, dds)
    return b, d1, u


def _curv(fol: Follower, s: np.ndarray, ds: np.ndarray, dds: np.ndarray) -> np.ndarray:
    b, d1, d2, _, _ = follower_points(fol, s, ds, dds)
    t = d1 - perp(b)
    return -cross2(t, d2 - 2.0 * perp(d1) - b) / np.hypot(t[0], t[1]) ** 3


def _rise_efficiency(phi: np.ndarray, torque: np.ndarray, useful: np.ndarray,
                     rows: np.ndarray) -> float | None:
    """Mean efficiency of the rise rows (eq. 4.22): work against the load / work of the cam."""
    if np.count_nonzero(rows) < 2:
        return None
    idx = np.flatnonzero(rows)
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
    motor = sum(float(np.trapezoid(torque[r], phi[r])) for r in runs if r.size > 1)
    work = sum(float(np.trapezoid(useful[r], phi[r])) for r in runs if r.size > 1)
    if motor <= 0.0:
        return None
    return mean_efficiency(work, motor)


__all__: Sequence[str] = (
    "ALIASES", "LAWS", "LAW_COEFFICIENTS", "CamError", "CamLaw", "CamLoads", "CamResults",
    "CamScene", "OscillatingFollower", "Segment", "TranslatingFollower",
    "base_radius_oscillating", "base_radius_translating", "cam_table",
    "constant_acceleration", "cosine_acceleration", "critical_transmission_angle",
    "critical_transmission_angle_oscillating", "cycle_extreme", "fall", "law_name",
    "law_peaks", "load_cam_scene", "optimal_offset", "oscillating_follower_force",
    "polar_profile_oscillating", "polar_profile_translating", "profile", "rise",
    "sine_acceleration", "solve_cam", "transmission_angle", "translating_follower_forces",
    "zero_acceleration",
)
