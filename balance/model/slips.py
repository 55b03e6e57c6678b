"""Numbers of a balancing scene that look like unit slips: one :class:`BalanceWarning` each
(the command line prints a ``warning:`` line; the exit code is unchanged).

A slip gives a plausible-looking number, so the scene is checked where it is read and
its results where they are made (scene-format.md, opening; docs/balancing.md, "Units"):

- angles that all lie within [-2 pi, 2 pi] with fractional values under ``angle = "deg"``
  (radians typed for degrees), per section: a rotor's unbalance angles, the static
  device's ``alpha``, a resonance test's run marks, an influence section's phases and
  mass angles, a split's or combine's angles;
- masses or readings 1000 times off the others of their kind (grams among kilograms):
  a rotor's unbalance masses, a resonance test's amplitudes, an influence section's
  trial and trim masses and its reading amplitudes, a combine's weights;
- trial masses all below 1 under ``mass = "g"`` (kilograms typed under grams: 100 g
  typed as 0.1), or all 10 or more under ``mass = "kg"`` (grams typed under kilograms);
- a correction more than 100 times the trial mass (:func:`check_corrections`).
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, Any

from kinetostatics.model.units import angle_slip, ratio_slip

from ..errors import BalanceWarning

if TYPE_CHECKING:
    from .scene import BalanceScene

__all__ = ["CORRECTION_RATIO", "check_corrections", "check_slips"]

CORRECTION_RATIO = 100.0
"""A correction more than this many times the trial mass looks like a slip."""


def _warn(text: str) -> None:
    warnings.warn(text, BalanceWarning, stacklevel=4)


def _angles(where: str, values: list[float], unit: str) -> None:
    if values and angle_slip(values, unit):
        shown = ", ".join(f"{v:g}" for v in values[:5]) + (", ..." if len(values) > 5 else "")
        _warn(f"{where}: the angles [{shown}] look like radians (all within 2 pi, with "
              "fractional values) but angles are in degrees; write them in degrees, or "
              "angle = \"rad\" in [units]")


def _ratio(where: str, what: str, values: list[float], unit: str) -> None:
    hit = ratio_slip(values)
    if hit is not None:
        u = f" {unit}" if unit else ""
        _warn(f"{where}: the {what} range from {hit[0]:g}{u} to {hit[1]:g}{u}, 1000 times "
              "apart: one typed in another unit (g for kg, um for mm)?")


def _trial_masses(where: str, masses: list[float], unit: str) -> None:
    masses = [m for m in masses if m > 0.0]
    if not masses:
        return
    if unit == "g" and max(masses) < 1.0:
        _warn(f"{where}: every trial mass is below 1 g ({', '.join(f'{m:g}' for m in masses)} "
              "g): kilograms typed under mass = \"g\"?")
    elif unit == "kg" and min(masses) >= 10.0:
        _warn(f"{where}: every trial mass is 10 kg or more ({', '.join(f'{m:g}' for m in masses)}"
              " kg): grams typed in kilograms? Name mass = \"g\" in [units]")


def check_slips(scene: BalanceScene) -> None:
    """Warn about the numbers of a read scene that look like unit slips (module text)."""
    u = scene.units
    ang = u.angle
    if scene.rotor is not None:
        ub = scene.rotor.unbalances
        _angles("rotor.unbalance", [x.angle for x in ub], ang)
        _ratio("rotor.unbalance", "masses", [x.mass for x in ub], "kg")
    if scene.static_test is not None:
        _angles("static_test.alpha", [scene.static_test.alpha], ang)
    for i, t in enumerate(scene.resonance_tests):
        w = f"resonance_test[{i}]"
        if t.runs is not None:
            _angles(f"{w}.runs", [a for a, _ in t.runs], ang)
        amps = [t.A1, *(a for _, a in t.runs or ()), *(x for x in (t.A2, t.A3) if x)]
        _ratio(w, "amplitudes", amps, "")
    fs = scene.field_scene
    for i, spec in enumerate(fs.influence):
        _influence(f"influence[{i}]", spec, ang, u.mass)
    for i, spec in enumerate(fs.split):
        _angles(f"split[{i}]", [spec["angle"], spec["first"]], ang)
    for i, spec in enumerate(fs.combine):
        _angles(f"combine[{i}].weights", [w[1] for w in spec["weights"]], ang)
        _ratio(f"combine[{i}].weights", "masses", [w[0] for w in spec["weights"]], u.mass)


def _influence(where: str, spec: dict, ang: str, mass_unit: str) -> None:
    readings = list(spec["initial"])
    masses: list[tuple[float, float]] = []
    for plane_masses, vals in spec["runs"] + spec["trims"]:
        readings += list(vals)
        masses += [m for m in plane_masses if m is not None]
    coeff = [c for row in spec["coefficients"] or () for c in row]
    _angles(where, [p for _, p in readings + coeff] + [a for _, a in masses], ang)
    _ratio(where, "reading amplitudes", [a for a, _ in readings], "")
    trial = [m for m, _ in masses]
    _ratio(where, "trial masses", trial, mass_unit)
    _trial_masses(where, [m for m, _ in (m for pm, _ in spec["runs"] for m in pm
                                          if m is not None)], mass_unit)


def check_corrections(results: dict[str, Any], scene: BalanceScene) -> None:
    """Warn where a correction is more than 100 times its trial mass (a slip in the trial
    mass's unit, or in the readings' phases): resonance tests and influence sections."""
    for i, (spec, res) in enumerate(zip(scene.resonance_tests, results.get("resonance_test",
                                                                            ()), strict=False)):
        m = getattr(res, "correction_mass", None)
        if m is not None and m > CORRECTION_RATIO * spec.trial_mass:
            _warn(f"resonance_test[{i}]: the correction mass {m:.4g} kg is "
                  f"{m / spec.trial_mass:.3g} times the trial mass {spec.trial_mass:g} kg: a "
                  "unit slip in the trial mass or the amplitudes?")
    unit = scene.units.mass
    for i, (spec, res) in enumerate(zip(scene.field_scene.influence,
                                        results.get("influence", ()), strict=False)):
        trial = [m for pm, _ in spec["runs"] for m, _ in (x for x in pm if x is not None)]
        corr = _correction_masses(res)
        if trial and corr and max(corr) > CORRECTION_RATIO * max(trial):
            _warn(f"influence[{i}]: a correction of {max(corr):.4g} {unit} is "
                  f"{max(corr) / max(trial):.3g} times the largest trial mass "
                  f"{max(trial):g} {unit}: a unit slip in the trial masses or the phases?")


def _correction_masses(res: Any) -> list[float]:
    return [abs(float(m)) for m in getattr(res, "masses", ()) if m is not None]
