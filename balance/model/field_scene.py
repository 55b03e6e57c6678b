"""The field-balancing sections of a balancing scene read: ``[[influence]]`` (with its trim
runs), ``[iso]``, ``[[split]]`` and ``[[combine]]``.

Each section is read into a spec (:func:`parse_field`) and solved by
:func:`balance.field.scene.solve_field`; ``docs/balancing.md`` shows every key with a
TOML example. Units: the influence method, split and combine are linear in
the masses and readings, so their results come out in the units the scene names
(``[units]``, see :mod:`balance.model.units`); the ISO numbers need SI (U_per = 1000 G m /
Omega, ISO 21940-11) and are converted there, through :class:`~balance.model.units.Units`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kinetostatics.model.errors import SceneError
from kinetostatics.model.fields import BALANCING, read_number, section
from kinetostatics.model.tomlio import as_float, as_int, as_list, as_str, check_keys
from kinetostatics.model.units import radians

from ..common import within
from .noise import parse_noise
from .units import Units, parse_units

__all__ = ["FIELD_SECTIONS", "FieldScene", "parse_field"]

FIELD_SECTIONS = ("influence", "iso", "split", "combine")
INFLUENCE_KEYS = ("name", "points", "initial", "runs", "coefficients", "trim", "trial_radius",
                  "correction_radius", "noise", "phase_noise", "confidence", "dA", "split")
# balancing holes of a split: more than this is a continuous ring (and the angles of
# neighbouring holes would differ by less than the rounding of the correction angle)
MAX_HOLES = 100_000
RUN_KEYS = ("plane", "mass", "angle", "masses", "readings")
SPLIT_KEYS = ("positions", "first")
SPLIT_SECTION_KEYS = ("mass", "angle", "positions", "first", "radius", "correction_radius")
COMBINE_KEYS = ("weights", "radius")
WEIGHT_KEYS = ("mass", "angle", "radius")
ISO_KEYS = ("grade", "rotor_mass", "speed_rpm", "bearings", "cog", "planes", "narrow",
            "static_share", "residual")

INFLUENCE = section(BALANCING, "influence", "[]")
RUN = {key: section(BALANCING, "influence", "[]", key, "[]") for key in ("runs", "trim")}
SPLIT = section(BALANCING, "split", "[]")
COMBINE = section(BALANCING, "combine", "[]")
WEIGHT = section(BALANCING, "combine", "[]", "weights", "[]")
ISO = section(BALANCING, "iso")
"""The declared fields (:data:`kinetostatics.model.fields.BALANCING`) each section's
numbers are read through: bounds, defaults and the unit a message quotes (the masses and
radii kept as typed, the angles in degrees)."""


@dataclass(frozen=True)
class FieldScene:
    """The field-balancing sections of a scene, checked (None / () where absent)."""

    units: Units = field(default_factory=Units)
    influence: tuple[dict, ...] = ()
    iso: dict | None = None
    split: tuple[dict, ...] = ()
    combine: tuple[dict, ...] = ()

    @property
    def sections(self) -> tuple[str, ...]:
        """The field sections present."""
        present = {"influence": bool(self.influence), "iso": self.iso is not None,
                   "split": bool(self.split), "combine": bool(self.combine)}
        return tuple(k for k in FIELD_SECTIONS if present[k])


# ------------------------------------------------------------------ parsing
def _array_of_tables(top: Mapping, key: str) -> list:
    items = top[key]
    if isinstance(items, dict):
        raise SceneError(f"{key} must be an array of tables: write [[{key}]], not [{key}]")
    items = as_list(items, key)
    if not items:
        raise SceneError(f"{key} is empty: give at least one [[{key}]]")
    return items


def _pairs(value: Any, where: str, what: str = "[amplitude, phase_deg]") -> list:
    """A list of number pairs (structure only; the solvers check the numbers)."""
    items = as_list(value, where)
    if not items:
        raise SceneError(f"{where} is empty: give {what} per measurement point")
    out = []
    for i, x in enumerate(items):
        if not (isinstance(x, list) and len(x) == 2):
            raise SceneError(f"{where}[{i}] must be {what}, not {x!r}")
        out.append((as_float(x[0], f"{where}[{i}][0]"), as_float(x[1], f"{where}[{i}][1]")))
    return out


def _run(item: Any, where: str, units: Units,
         declared: dict) -> tuple[dict[int, tuple[float, float]], list]:
    """One run table: the masses per plane (1-based) and the readings."""
    t = check_keys(item, RUN_KEYS, where, required=("readings",))
    readings = _pairs(t["readings"], f"{where}.readings")
    if "masses" in t:
        if any(k in t for k in ("plane", "mass", "angle")):
            raise SceneError(f"{where}: give masses = [[mass, angle], ...] or plane, mass and "
                             "angle, not both")
        pairs = _pairs(t["masses"], f"{where}.masses", "[mass, angle_deg] per plane")
        return {j + 1: p for j, p in enumerate(pairs)}, readings
    if "mass" not in t:
        raise SceneError(f"{where}: missing required key 'mass' (with plane and angle), or "
                         "give masses = [[mass, angle], ...] per plane")
    plane = as_int(t.get("plane", 1), f"{where}.plane", lo=1)
    mass = read_number(t, declared["mass"], where, units)
    return {plane: (mass, as_float(t.get("angle", 0.0), f"{where}.angle"))}, readings


def _masses(runs: list[dict[int, tuple[float, float]]], n: int) -> list[list]:
    """Runs' masses as lists over n planes (None where a run puts nothing)."""
    return [[r.get(j + 1) if r.get(j + 1, (0.0,))[0] else None for j in range(n)]
            for r in runs]


def _planes(runs: list, trims: list, coefficients: list | None, where: str) -> int:
    """The number of correction planes: the coefficients' columns, else the largest plane
    the trial runs name. A plane number is bounded by the planes there can be (one trial
    run per plane; a trim run by the planes of the runs or coefficients)."""
    most = len(coefficients[0]) if coefficients else max(len(runs), 1)
    for what, items in (("runs", runs), ("trim", trims)):
        for k, (r, _) in enumerate(items):
            if max(r) > most:
                there = (f"the coefficients have {most} column(s)" if coefficients
                         else f"{len(runs)} trial run(s), one per plane")
                raise SceneError(f"{where}.{what}[{k}]: plane {max(r):_} does not exist "
                                 f"({there}); give a plane from 1 to {most}")
        if what == "runs" and not coefficients:
            most = max([max(r) for r, _ in runs] + [1])
    return max([max(r) for r, _ in runs + trims] + [len(coefficients[0]) if coefficients else 1])


def _influence(item: Any, i: int, units: Units) -> dict:
    w = f"influence[{i}]"
    t = check_keys(item, INFLUENCE_KEYS, w, required=("initial",))
    if ("runs" in t) == ("coefficients" in t):
        raise SceneError(f"{w}: give runs (trial runs) or coefficients (from an earlier "
                         "session), one of the two")
    initial = _pairs(t["initial"], f"{w}.initial")
    runs, trims = ([_run(r, f"{w}.{key}[{k}]", units, RUN[key])
                    for k, r in enumerate(as_list(t.get(key, []), f"{w}.{key}"))]
                   for key in ("runs", "trim"))
    coefficients = None
    if "coefficients" in t:
        rows = as_list(t["coefficients"], f"{w}.coefficients")
        coefficients = [_pairs(r, f"{w}.coefficients[{k}]", "[amplitude, phase_deg] per plane")
                        for k, r in enumerate(rows)]
        if not coefficients:
            raise SceneError(f"{w}.coefficients is empty: one row per measurement point")
    n = _planes(runs, trims, coefficients, w)
    spec: dict[str, Any] = {
        "name": as_str(t["name"], f"{w}.name") if "name" in t else f"influence {i + 1}",
        "initial": initial,
        "runs": list(zip(_masses([r for r, _ in runs], n), [v for _, v in runs], strict=True)),
        "trims": list(zip(_masses([r for r, _ in trims], n), [v for _, v in trims],
                          strict=True)),
        "coefficients": coefficients,
        "noise": within(w, parse_noise, t.get("noise"),
                        read_number(t, INFLUENCE["phase_noise"], w, units)
                        if "phase_noise" in t else None, t.get("confidence")),
    }
    if "points" in t:
        pts = [as_str(p, f"{w}.points[{k}]") for k, p in enumerate(as_list(t["points"],
                                                                           f"{w}.points"))]
        if len(pts) != len(initial):
            raise SceneError(f"{w}.points: {len(pts)} names for {len(initial)} readings")
        spec["points"] = pts
    for key in ("trial_radius", "correction_radius", "dA"):
        if key in t:
            spec[key] = read_number(t, INFLUENCE[key], w, units)
    if "split" in t:
        s = t["split"]
        if isinstance(s, int) and not isinstance(s, bool):
            s = {"positions": s}
        s = check_keys(s, SPLIT_KEYS, f"{w}.split", required=("positions",))
        spec["split"] = (as_int(s["positions"], f"{w}.split.positions", lo=3,
                                hi=MAX_HOLES),
                         as_float(s.get("first", 0.0), f"{w}.split.first"))
    return spec


def _split(item: Any, i: int, units: Units) -> dict:
    w = f"split[{i}]"
    t = check_keys(item, SPLIT_SECTION_KEYS, w, required=("mass", "angle", "positions"))
    out = {"mass": read_number(t, SPLIT["mass"], w, units),
           "angle": as_float(t["angle"], f"{w}.angle"),
           "positions": as_int(t["positions"], f"{w}.positions", lo=3, hi=MAX_HOLES),
           "first": as_float(t.get("first", 0.0), f"{w}.first")}
    for key in ("radius", "correction_radius"):
        if key in t:
            out[key] = read_number(t, SPLIT[key], w, units)
    return out


def _combine(item: Any, i: int, units: Units) -> dict:
    w = f"combine[{i}]"
    t = check_keys(item, COMBINE_KEYS, w, required=("weights",))
    weights = []
    for k, x in enumerate(as_list(t["weights"], f"{w}.weights")):
        ww = f"{w}.weights[{k}]"
        x = check_keys(x, WEIGHT_KEYS, ww, required=("mass", "angle"))
        wt = (read_number(x, WEIGHT["mass"], ww, units), as_float(x["angle"], f"{ww}.angle"))
        weights.append(wt + ((read_number(x, WEIGHT["radius"], ww, units),)
                             if "radius" in x else ()))
    radius = read_number(t, COMBINE["radius"], w, units) if "radius" in t else None
    return {"weights": weights, "radius": radius}


def _iso(table: Any, units: Units) -> dict:
    w = "iso"
    t = check_keys(table, ISO_KEYS, "[iso]", required=("grade", "rotor_mass", "speed_rpm"))
    out: dict[str, Any] = {k: read_number(t, ISO[k], w, units)
                           for k in ("grade", "rotor_mass", "speed_rpm", "static_share")}
    out["narrow"] = bool(t.get("narrow", False))
    if "narrow" in t and not isinstance(t["narrow"], bool):
        raise SceneError(f"{w}.narrow must be true or false")
    if "bearings" in t:
        b = as_list(t["bearings"], f"{w}.bearings")
        if len(b) != 2:
            raise SceneError(f"{w}.bearings: give the z of the two bearing planes, [z_A, z_B]")
        out["bearings"] = tuple(as_float(x, f"{w}.bearings[{k}]") for k, x in enumerate(b))
        if "cog" not in t:
            raise SceneError(f"{w}: bearings need cog, the z of the centre of mass")
        out["cog"] = read_number(t, ISO["cog"], w, units)
    if "planes" in t:
        p = as_list(t["planes"], f"{w}.planes")
        if len(p) not in (1, 2):
            raise SceneError(f"{w}.planes: give the z of one or two correction planes")
        out["planes"] = tuple(as_float(x, f"{w}.planes[{k}]") for k, x in enumerate(p))
        if len(p) == 2 and "bearings" not in out:
            raise SceneError(f"{w}: two correction planes need bearings = [z_A, z_B] and cog")
    if out["narrow"] and len(out.get("planes", ())) != 2:
        raise SceneError(f"{w}: narrow = true needs the two correction planes (planes)")
    if "residual" in t:
        r = t["residual"]
        r = [r] if isinstance(r, int | float) and not isinstance(r, bool) else as_list(
            r, f"{w}.residual")
        res = []
        for k, x in enumerate(r):
            if isinstance(x, list):
                if len(x) != 2:
                    raise SceneError(f"{w}.residual[{k}] must be U or [U, angle_deg]")
                res.append(complex(as_float(x[0], f"{w}.residual[{k}][0]", nonnegative=True)
                                   * np.exp(1j * radians(as_float(
                                       x[1], f"{w}.residual[{k}][1]")))))
            else:
                res.append(as_float(x, f"{w}.residual[{k}]", nonnegative=True))
        if any(isinstance(x, complex) for x in res) and not all(
                isinstance(x, complex) for x in res):
            raise SceneError(f"{w}.residual: give every residual as U or every one as "
                             "[U, angle_deg]")
        out["residual"] = res
    return out


def parse_field(top: Mapping[str, Any], units: Units | None = None) -> FieldScene:
    """Read the field sections of a scene's top-level mapping.

    Parameters
    ----------
    top : mapping
        The scene's top-level keys (already checked against the known ones), with its
        angles in degrees (:mod:`balance.model.scene_units`).
    units : Units, optional
        The scene's ``[units]`` (default: parsed from ``top``, for a mapping that was not
        rewritten): masses, radii and readings stay in them.
    """
    if units is None:
        units = parse_units(top.get("units"))
    infl, split, comb = (tuple(read(x, i, units) for i, x in enumerate(_array_of_tables(
        top, key))) if key in top else () for key, read in (
            ("influence", _influence), ("split", _split), ("combine", _combine)))
    iso = _iso(top["iso"], units) if "iso" in top else None
    return FieldScene(units=units, influence=infl, iso=iso, split=split, combine=comb)
