"""The field-balancing sections solved: ``[[influence]]`` (with its trim runs), ``[iso]``,
``[[split]]`` and ``[[combine]]``, each read into a spec by
:func:`balance.model.field_scene.parse_field` and solved here by the plain functions of
:mod:`balance.field`. The influence method, split and combine are linear in the masses and
readings, so their results come out in the units the scene names; the ISO numbers need SI
(U_per = 1000 G m / Omega, ISO 21940-11) and are converted here, through
:class:`~balance.model.units.Units`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from kinetostatics.model.errors import SceneError
from kinetostatics.model.units import Units

from ..common import within
from ..model.field_scene import FIELD_SECTIONS, FieldScene, parse_field
from .influence import InfluenceResult, influence_balance
from .iso import (
    IsoTolerances,
    iso_permissible_unbalance,
    iso_tolerances,
    to_bearing_planes,
)
from .weights import Combined, Split, combine_weights, split_correction

__all__ = ["FIELD_SECTIONS", "FieldScene", "IsoResult", "parse_field", "solve_field", "solve_iso"]


# ------------------------------------------------------------------ solving
@dataclass(frozen=True)
class IsoResult:
    """The ``[iso]`` section solved: U_per, its allocation and the residual check (SI).

    Attributes
    ----------
    grade, rotor_mass, speed_rpm : float
        G (mm/s), m (kg), n (rpm).
    U_per : float
        Permissible residual unbalance (kg m).
    tolerances : IsoTolerances or None
        Allocation to bearing and correction planes (None for a single plane).
    check : dict or None
        ``{residual, bearing_residual, ratio, ok, exact}`` when residuals were given.
    units : Units
        The scene's units (for :meth:`to_dict`).
    warnings : list of str
    """

    grade: float
    rotor_mass: float
    speed_rpm: float
    U_per: float
    tolerances: IsoTolerances | None
    check: dict | None
    units: Units
    warnings: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready, in the scene's units (unbalance, mass, length)."""
        u = self.units

        def U(x: float | None) -> float | None:
            return None if x is None else float(u.from_si(x, "unbalance"))

        d: dict[str, Any] = {
            "grade": self.grade, "rotor_mass": float(u.from_si(self.rotor_mass, "mass")),
            "speed_rpm": self.speed_rpm, "U_per": U(self.U_per),
            "e_per": float(u.from_si(self.U_per / self.rotor_mass, "length")),
            "unbalance_unit": u.unbalance, "warnings": list(self.warnings),
        }
        t = self.tolerances
        if t is not None:
            d["kind"] = t.kind
            d["limited"] = t.limited
            d["bearing_planes"] = [{"name": n, "z": float(u.from_si(z, "length")),
                                    "permissible": U(p)}
                                   for n, z, p in zip("AB", t.bearings, t.bearing_tolerances,
                                                      strict=True)]
            if t.planes is not None:
                tol = t.plane_tolerances or (None, None)
                d["correction_planes"] = [{"plane": k + 1, "z": float(u.from_si(z, "length")),
                                           "permissible": U(p)}
                                          for k, (z, p) in enumerate(zip(t.planes, tol,
                                                                         strict=True))]
            if t.kind == "narrow":
                d["static"], d["couple"] = U(t.static), U(t.couple)
        if self.check is not None:
            c = dict(self.check)
            for key in ("residual", "bearing_residual", "permissible"):
                if c.get(key) is not None:
                    c[key] = [U(x) for x in c[key]]
            d["check"] = c
        return d


def _iso_check(spec: dict, U_per: float, tol: IsoTolerances | None, u: Units) -> dict:
    res = [u.to_si(x, "unbalance") for x in spec["residual"]]
    exact = all(isinstance(x, complex) for x in res)
    mags = [abs(x) for x in res]
    planes = spec.get("planes", ())
    if tol is None or tol.planes is None:
        if tol is None or len(planes) == 1:          # one plane: the whole U_per there
            if len(res) != 1:
                raise SceneError(f"iso.residual: {len(res)} values for one correction plane; "
                                 "give one")
            per = [U_per]
        else:
            if len(res) != 2:
                raise SceneError("iso.residual: without correction planes give the residual "
                                 "in the two bearing planes [U_A, U_B]")
            per = list(tol.bearing_tolerances)
        ratio = [m / p for m, p in zip(mags, per, strict=True)]
        return {"residual": mags, "bearing_residual": None, "permissible": per,
                "ratio": ratio, "ok": all(r <= 1.0 for r in ratio), "exact": True}
    if len(res) != len(planes):
        raise SceneError(f"iso.residual: {len(res)} values for {len(planes)} correction planes")
    bear = to_bearing_planes(np.array(res) if exact else np.array(mags), tol.planes,
                             tol.bearings)
    per = list(tol.bearing_tolerances)
    ratio = [float(b / p) for b, p in zip(bear, per, strict=True)]
    out = {"residual": mags, "bearing_residual": [float(b) for b in bear], "permissible": per,
           "ratio": ratio, "ok": all(r <= 1.0 for r in ratio), "exact": exact}
    if tol.kind == "narrow" and exact:
        S, C = res[0] + res[1], 0.5 * (res[0] - res[1])
        out["static_ratio"] = abs(S) / tol.static
        out["couple_ratio"] = abs(C) / tol.couple
    return out


def solve_iso(spec: dict, units: Units) -> IsoResult:
    """U_per from grade, mass and speed (ISO 21940-11), its allocation and the check."""
    m = units.to_si(spec["rotor_mass"], "mass")
    U_per = Units(unbalance="g mm").to_si(
        iso_permissible_unbalance(spec["grade"], m, spec["speed_rpm"]), "unbalance")
    tol = None
    if "bearings" in spec:
        planes = spec.get("planes")
        L = [units.to_si(z, "length") for z in spec["bearings"]]
        P = None if planes is None or len(planes) == 1 else [units.to_si(z, "length")
                                                              for z in planes]
        tol = iso_tolerances(U_per, L, units.to_si(spec["cog"], "length"), P,
                             narrow=spec["narrow"], static_share=spec["static_share"])
    warns = []
    if tol is not None and tol.limited:
        warns.append("the centre of mass lies near one bearing: the lever rule's shares were "
                     "limited to 0.3 and 0.7 of U_per, as ISO 21940-11 recommends")
    check = _iso_check(spec, U_per, tol, units) if "residual" in spec else None
    if check is not None and not check["ok"]:
        warns.append("the residual unbalance exceeds its ISO tolerance (ratio "
                     f"{max(check['ratio']):.3g})")
    return IsoResult(grade=spec["grade"], rotor_mass=m, speed_rpm=spec["speed_rpm"],
                     U_per=U_per, tolerances=tol, check=check, units=units, warnings=warns)


def solve_influence(spec: dict) -> InfluenceResult:
    """One ``[[influence]]`` section."""
    kw = {k: spec[k] for k in ("trial_radius", "correction_radius", "dA", "split")
          if k in spec}
    r = influence_balance(spec["initial"], spec["runs"], trims=spec["trims"],
                          coefficients=spec["coefficients"], noise=spec["noise"], **kw)
    pts = spec.get("points")
    return replace(r, name=spec["name"], points=None if pts is None else tuple(pts))


def solve_split(spec: dict) -> Split:
    """One ``[[split]]`` section."""
    return split_correction(spec["mass"], spec["angle"], spec["positions"], spec["first"],
                            radius=spec.get("radius"),
                            correction_radius=spec.get("correction_radius"))


def solve_combine(spec: dict) -> Combined:
    """One ``[[combine]]`` section."""
    return combine_weights(spec["weights"], spec["radius"])


def solve_field(fs: FieldScene) -> dict[str, Any]:
    """Solve every field section: ``influence``, ``split``, ``combine`` (lists of result
    objects) and ``iso`` (an :class:`IsoResult`), one key per section present."""
    out: dict[str, Any] = {}
    if fs.influence:
        out["influence"] = [within(f"influence[{i}]", solve_influence, s)
                            for i, s in enumerate(fs.influence)]
    if fs.iso is not None:
        out["iso"] = within("iso", solve_iso, fs.iso, fs.units)
    if fs.split:
        out["split"] = [within(f"split[{i}]", solve_split, s) for i, s in enumerate(fs.split)]
    if fs.combine:
        out["combine"] = [within(f"combine[{i}]", solve_combine, s)
                          for i, s in enumerate(fs.combine)]
    return out
