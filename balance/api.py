"""The one entry point for scenes: :func:`solve` (a dict per the contract) and
:func:`solve_results` (the result objects, for plots and further work)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from kinetostatics.model.slips import emit

from .errors import BalanceError, BalanceWarning
from .field.scene import solve_field
from .model.scene import SCENES, BalanceScene, ResonanceSpec, load_scene
from .model.slips import correction_slips
from .model.units import Units
from .resonance.methods import ResonanceResult, parallelogram, trial_runs
from .rotor.design import balance_rotor
from .rotor.static_device import static_device

__all__ = ["example_path", "examples", "results_to_dict", "solve", "solve_results"]


def _resonance(spec: ResonanceSpec) -> ResonanceResult:
    model = dict(plane=spec.plane, dA=spec.dA,
                 noise=(spec.noise_relative, spec.noise_absolute), confidence=spec.confidence)
    if spec.runs is not None:
        return trial_runs(spec.A1, spec.runs, spec.trial_mass, spec.trial_radius,
                          spec.correction_radius, **model)
    return parallelogram(spec.A1, spec.A2, spec.A3, spec.trial_mass, spec.trial_radius,
                         spec.correction_radius, **model)


def _mechanism_balancing(raw: dict) -> Any:
    """Dispatch a mechanism's ``[balancing]`` (seed 002 s. 3.4) to ``balance.mechanism``
    (imported here: it needs the kinetostatics of the scene)."""
    from .mechanism import solve_mechanism_balancing

    return solve_mechanism_balancing(raw)


def solve_results(scene: Any) -> dict[str, Any]:
    """Solve every balancing section of a scene and return the result objects.

    Parameters
    ----------
    scene : pathlib.Path, str, dict or BalanceScene
        See :func:`balance.model.scene.load_scene`.

    Returns
    -------
    dict
        ``rotor`` -> :class:`~balance.rotor.RotorResult`, ``static_test`` ->
        :class:`~balance.static_device.StaticDeviceResult`, ``resonance_test`` -> list
        of :class:`~balance.resonance.ResonanceResult`, ``balancing`` -> what
        ``balance.mechanism.solve_mechanism_balancing`` returns; one key per section
        present; and ``warnings``, the suspected unit slips (a list of strings, empty
        when none), each also issued as a :class:`~balance.errors.BalanceWarning`;
        ``result_units``, the units of each section's numbers, and ``scene_units``, the
        units the scene was typed in (its own, not the numbers').

    Raises
    ------
    BalanceError, SceneError
        A scene with no balancing section, or bad data (one line).
    """
    sc: BalanceScene = load_scene(scene)
    if not sc.sections:
        raise BalanceError("the scene has no balancing section: balance.solve solves [rotor], "
                           "[static_test], [[resonance_test]], [[influence]], [iso], "
                           "[[split]], [[combine]] and a mechanism's [balancing]; "
                           "for a mechanism's reactions use kinetostatics.solve")
    out: dict[str, Any] = {}
    if sc.rotor is not None:
        out["rotor"] = balance_rotor(sc.rotor.unbalances, sc.rotor.planes, sc.rotor.speed_rpm,
                                     sc.units)
    if sc.static_test is not None:
        s = sc.static_test
        out["static_test"] = static_device(s.disk_mass, s.comparison_mass, s.comparison_radius,
                                           s.alpha, s.correction_radius)
    if sc.resonance_tests:
        out["resonance_test"] = [_resonance(spec) for spec in sc.resonance_tests]
    if sc.balancing is not None:
        out["balancing"] = _mechanism_balancing(sc.source or sc.raw)
    out.update(solve_field(sc.field_scene))
    # the mechanism's own slips (its reader judged and warned them) are the scene's too
    mechanism = getattr(getattr(out.get("balancing"), "scene", None), "warnings", ())
    out["warnings"] = [*sc.warnings, *mechanism,
                       *emit(correction_slips(out, sc), sc.quiet, BalanceWarning)]
    out["result_units"] = result_units(out, sc.units)
    out["scene_units"] = sc.units
    return out


SI_TEXT = "SI: kg, m, kg m, N, N m, s; angles in degrees"


def result_units(out: dict[str, Any], units: Units) -> dict[str, str]:
    """The units of each section's numbers: SI for the course's methods; the scene's own
    for the influence method, split and combine (linear in the masses and readings, they
    answer in the units they were given) and ``[iso]`` (computed in SI, its result written
    back in the scene's units: docs/balancing.md)."""
    scene = (f"the scene's: mass {units.mass}, length {units.length}, unbalance "
             f"{units.unbalance}, readings {units.vibration or 'as typed'}; angles in degrees")
    return {k: scene if k in ("influence", "split", "combine", "iso") else SI_TEXT
            for k in out if k not in ("warnings", "result_units", "scene_units")}


def solve(scene: Any) -> dict[str, Any]:
    """Solve a balancing scene: a dict with one key per section present (the contract's keys).

    Parameters
    ----------
    scene : pathlib.Path, str, dict or BalanceScene
        What :func:`~balance.load_scene` reads (a path, a ``.toml`` file's name, TOML
        text, a parsed mapping) or its result.

    Returns
    -------
    dict
        ``rotor``: ``{corrections, initial_force, initial_moment, residual_force,
        residual_moment}``; ``static_test``: ``{eccentricity, correction_mass}``;
        ``resonance_test``: a list of ``{plane, A, phi, unbalance, correction_mass,
        angle, mirror_angle, estimate, warnings}``; ``balancing``: the mechanism result.
        ``rotor`` also holds ``warnings``. Angles in
        [0, 360), None where undefined.

    Examples
    --------
    >>> out = solve(example_path("static_device"))
    >>> round(out["static_test"]["correction_mass"], 6)
    0.134032
    """
    return results_to_dict(solve_results(scene))


def results_to_dict(results: dict[str, Any]) -> dict[str, Any]:
    """Turn :func:`solve_results` output into the contract's JSON-ready dict."""
    out: dict[str, Any] = {}
    for key, value in results.items():
        if key in ("resonance_test", "influence", "split", "combine"):
            out[key] = [r.to_dict() for r in value]
        elif hasattr(value, "to_dict"):
            out[key] = value.to_dict()
        else:
            out[key] = value
    return out


def examples() -> list[str]:
    """Names of the example scenes bundled with the package (``balance/scenes``)."""
    return SCENES.names()


def example_path(name: str) -> Path:
    """Path of a bundled example scene, by name (with or without ``.toml``)."""
    path = SCENES.find(name)
    if path is None:
        raise BalanceError(f"no bundled example scene {name!r}; known: {', '.join(examples())}")
    return path
