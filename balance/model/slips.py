"""Numbers of a balancing scene that look like unit slips, judged on the physical quantity
after conversion (the rules and the :class:`~kinetostatics.model.slips.Slip` are
:mod:`kinetostatics.model.slips`'; docs/scene-format.md, "Unit slips", has the table).

- ``angles``: per list, a rotor's unbalance angles, a resonance test's run marks, an
  influence section's phases and mass angles (its runs, not its trims), a combine's
  weight angles: all within 2 pi degrees, spread over a degree, not all whole (radians
  typed for degrees); any angle beyond two turns (degrees typed under ``angle = "rad"``).
  A single angle (a split's, the static device's ``alpha``) is judged on the second only.
- ``unbalance_mass``: a rotor's unbalance masses 300 times apart or more, the heavier
  1 kg or more or the lighter under 1 mg (a 0.15 g clip beside a 200 g weight is real).
- ``trial_mass``: a trial mass above 2 kg, or above a hundredth of ``[iso]`` rotor_mass
  when that is larger (grams typed as kilograms); an influence section's trial masses
  300 times apart, on the same terms as the unbalance masses (one warning per section).
  A trim mass is never judged (a trim after a good correction is small).
- ``readings``: one run's largest reading 300 times off the median of the other runs'
  (resonance amplitudes, influence initial and trial runs; trims are not judged, and a
  small reading beside larger ones of its run, a node, is never judged).
- ``correction``: a correction more than 100 times its trial mass
  (:func:`correction_slips`, on the results).

Every warning is a :class:`~balance.errors.BalanceWarning` (the command line prints a
``warning:`` line; the exit code is unchanged) and its text is kept on the scene
(``BalanceScene.warnings``) for every output.
"""

from __future__ import annotations

import statistics
from typing import TYPE_CHECKING, Any

from kinetostatics.model.slips import DEG, Slip, angle_list_slip, typed

if TYPE_CHECKING:
    from .scene import BalanceScene

__all__ = ["CORRECTION_RATIO", "RATIO", "TRIAL_MASS", "correction_slips", "scene_slips"]

CORRECTION_RATIO = 100.0
"""A correction more than this many times the trial mass looks like a slip."""

RATIO = 300.0
"""Masses (readings) of one kind this many times apart look like one typed in another
unit (g among kg is 1000)."""

HEAVY = 1.0
"""kg: of masses ``RATIO`` times apart, a heavier one this heavy looks like grams typed as
kilograms (a 20 g unbalance typed ``20`` in a kg scene)."""

LIGHTEST = 1e-6
"""kg: of masses ``RATIO`` times apart, a lighter one under a milligram looks like
kilograms typed as grams (no clip or trial weight is lighter)."""

TRIAL_MASS = 2.0
"""kg: a heavier trial mass looks like grams typed as kilograms (unless the rotor's mass
makes it plausible)."""


def _angles(where: str, deg: list[float], units: Any) -> list[Slip]:
    why = angle_list_slip([a * DEG for a in deg])
    if why is None:
        return []
    return [Slip("angles", where, typed(deg, "angle", units), why,
                 "write them in degrees, or angle = \"rad\" in [units]")]


def _ratio(rule: str, where: str, si: list[float], quantity: str, units: Any,
           what: str) -> list[Slip]:
    """Masses ``RATIO`` times apart, the heavier ``HEAVY`` or more (grams typed as
    kilograms) or the lighter under ``LIGHTEST`` (kilograms typed as grams): a 0.15 g clip
    beside a 200 g weight is real, and so is a 1.15 g trial beside a 200 g one."""
    mags = [abs(v) for v in si if v]
    if len(mags) < 2 or max(mags) < RATIO * min(mags):
        return []
    lo, hi = min(mags), max(mags)
    if hi < HEAVY and lo >= LIGHTEST:
        return []
    return [Slip(rule, where, typed(si, quantity, units, file=False),
                 f"the {what} range from {lo:.4g} kg to {hi:.4g} kg, {hi / lo:.3g} times apart",
                 "one was typed in another unit (g for kg: 1000 times)")]


def scene_slips(scene: BalanceScene) -> list[Slip]:
    """The suspected slips of a read balancing scene (the module's rules)."""
    u = scene.units
    out: list[Slip] = []
    if scene.rotor is not None:
        ub = scene.rotor.unbalances
        out += _angles("rotor.unbalance.angle", [x.angle for x in ub], u)
        out += _ratio("unbalance_mass", "rotor.unbalance.mass", [x.mass for x in ub], "mass",
                      u, "unbalance masses")
    if scene.static_test is not None:
        out += _angles("static_test.alpha", [scene.static_test.alpha], u)
    fs = scene.field_scene
    # [iso] rotor_mass stays in the scene's unit (a field section): in kg here, so that the
    # rule is the same whatever unit it was typed in
    limit = max(TRIAL_MASS, u.to_si(fs.iso["rotor_mass"], "mass") / 100.0 if fs.iso else 0.0)
    for i, t in enumerate(scene.resonance_tests):
        w = f"resonance_test[{i}]"
        if t.runs is not None:
            out += _angles(f"{w}.runs.angle", [a for a, _ in t.runs], u)
        amps = [t.A1, *(a for _, a in t.runs or ()), *(x for x in (t.A2, t.A3) if x)]
        out += _readings(f"{w}.A", [[a] for a in amps], u)
        out += _heavy(f"{w}.trial_mass", [t.trial_mass], limit, u)
    for i, spec in enumerate(fs.influence):
        out += _influence(f"influence[{i}]", spec, u, limit)
    for i, spec in enumerate(fs.split):
        out += _angles(f"split[{i}].angle", [spec["angle"]], u)
    for i, spec in enumerate(fs.combine):
        out += _angles(f"combine[{i}].weights.angle", [w[1] for w in spec["weights"]], u)
    return out


def _heavy(where: str, kg: list[float], limit: float, units: Any) -> list[Slip]:
    heavy = [m for m in kg if m > limit]
    if not heavy:
        return []
    return [Slip("trial_mass", where, typed(heavy, "mass", units, file=False),
                 f"a trial mass of {max(heavy):.4g} kg (above {limit:.4g} kg)",
                 f"{max(heavy):.4g} g, grams typed as kilograms")]


def _readings(where: str, runs: list[list[float]], units: Any) -> list[Slip]:
    """One run's largest reading against the median of the other runs' largest."""
    peaks = [max(abs(a) for a in run) for run in runs if run]
    if len([p for p in peaks if p]) < 3:
        return []
    for k, p in enumerate(peaks):
        others = [q for j, q in enumerate(peaks) if j != k and q]
        mid = statistics.median(others)
        if p and mid and (p >= RATIO * mid or mid >= RATIO * p):
            return [Slip("readings", f"{where} (run {k + 1})", f"{p:g}",
                         f"{p / mid:.3g} times the median of the other runs' ({mid:g})",
                         "one run typed in another vibration unit (um for mm: 1000 times)")]
    return []


def _influence(where: str, spec: dict, u: Any, limit: float) -> list[Slip]:
    runs = [(pm, vals) for pm, vals in spec["runs"]]
    masses = [m for pm, _ in runs for m in pm if m is not None]
    phases = [p for _, p in spec["initial"]] + [p for _, vals in runs for _, p in vals]
    out = _angles(f"{where}.runs (phases and mass angles)",
                  phases + [a for _, a in masses], u)
    kg = [u.to_si(m, "mass") for m, _ in masses]
    # one slip, one warning: a heavy trial mass says it; else masses far apart
    out += (_heavy(f"{where}.runs.mass", kg, limit, u)
            or _ratio("trial_mass", f"{where}.runs.mass", kg, "mass", u, "trial masses"))
    out += _readings(f"{where}.readings", [[a for a, _ in spec["initial"]]]
                     + [[a for a, _ in vals] for _, vals in runs], u)
    return out


def correction_slips(results: dict[str, Any], scene: BalanceScene) -> list[Slip]:
    """A correction more than 100 times its trial mass (a slip in the trial mass's unit, or
    in the readings' phases): resonance tests and influence sections."""
    out = []
    u = scene.units
    for i, (spec, res) in enumerate(zip(scene.resonance_tests,
                                        results.get("resonance_test", ()), strict=False)):
        m = getattr(res, "correction_mass", None)
        if m is not None and m > CORRECTION_RATIO * spec.trial_mass:
            out.append(Slip("correction", f"resonance_test[{i}].trial_mass",
                            typed(spec.trial_mass, "mass", u, file=False),
                            f"the correction {m:.4g} kg is {m / spec.trial_mass:.3g} times it",
                            "a unit slip in the trial mass or the amplitudes"))
    for i, (spec, res) in enumerate(zip(scene.field_scene.influence,
                                        results.get("influence", ()), strict=False)):
        trial = [m for pm, _ in spec["runs"] for m, _ in (x for x in pm if x is not None)]
        corr = [abs(float(m)) for m in getattr(res, "masses", ()) if m is not None]
        if trial and corr and max(corr) > CORRECTION_RATIO * max(trial):
            out.append(Slip("correction", f"influence[{i}].runs.mass",
                            f"{max(trial):g} {u.mass}",
                            f"a correction of {max(corr):.4g} {u.mass} is "
                            f"{max(corr) / max(trial):.3g} times the largest trial mass",
                            "a unit slip in the trial masses or the phases"))
    return out
