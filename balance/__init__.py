"""Balancing of rotors and mechanisms (seed 002, chapter 3), and beyond.

One scene API, :func:`solve` (scene-format.md section 2), and every method as a
plain function for notebooks:

- design-stage rotor balancing in one or two planes: :func:`balance_rotor`
  (eqs 3.3-3.14);
- the static balancing device: :func:`static_device` (eqs 3.18-3.21);
- resonance amplitude methods: :func:`parallelogram` (three runs, eqs 3.22-3.31),
  :func:`trial_runs` (any marks, least squares), :func:`four_run`;
- with measured phase: :func:`influence_single_plane`, :func:`influence_two_plane`,
  :func:`influence_balance` (influence coefficients, least squares over sensors and
  speeds, intervals from amplitude and phase noise, conditioning warnings),
  :func:`trim_balance` (trim runs);
- the field balancer's weights: :func:`split_correction` (onto N fixed positions),
  :func:`combine_weights`; units at the boundary: :class:`Units`;
- ISO 21940-11 tolerances: :func:`iso_permissible_unbalance`, :func:`iso_allocate`,
  :func:`iso_tolerances` (bearing and correction planes, narrow rotors),
  :func:`to_bearing_planes`, :func:`iso_check`;
- a balancing report (HTML or PDF): :func:`balance.report.write_report`;
- static balancing of mechanisms (s. 3.4): :func:`solve_mechanism_balancing`,
  :func:`shaking_force`, :func:`centre_of_mass`, :func:`h_vectors`,
  :func:`harmonic_amplitude`, :func:`balanced_scene`;
- the virtual balancing machine in pymunk: :class:`BalancingMachine` (at resonance, or
  coasting down through it: :class:`CoastDown`), :func:`pivot_reaction` and
  :func:`coast_down_study` (imported on first use, with pymunk).

Pictures are in :mod:`balance.plot` and :mod:`balance.mechanism.plot` (imported on
demand: matplotlib is not loaded by ``import balance``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from kinetostatics.common.lazy import group, lazy_names

if TYPE_CHECKING:
    from .api import example_path, examples, solve, solve_results
    from .errors import BalanceError, BalanceWarning
    from .field.influence import (
        InfluenceResult,
        influence_balance,
        influence_coefficients,
        influence_single_plane,
        influence_two_plane,
        trim_balance,
    )
    from .field.influence_stats import NoiseModel
    from .field.iso import (
        GRADES,
        IsoAllocation,
        IsoCheck,
        IsoTolerances,
        iso_allocate,
        iso_check,
        iso_permissible_unbalance,
        iso_tolerances,
        kgm_to_gmm,
        to_bearing_planes,
    )
    from .field.weights import Combined, Split, combine_weights, split_correction
    from .machine import BalancingMachine, CoastDown, coast_down_study, pivot_reaction
    from .mechanism import (
        CounterRotatingPair,
        Counterweight,
        MechanismBalancing,
        balanced_scene,
        centre_of_mass,
        h_vectors,
        harmonic_amplitude,
        shaking_force,
        solve_mechanism_balancing,
    )
    from .model.scene import BalanceScene, load_scene
    from .model.units import Units
    from .resonance.methods import ResonanceResult, four_run, parallelogram, trial_runs
    from .rotor.design import Correction, CorrectionPlane, RotorResult, Unbalance, balance_rotor
    from .rotor.static_device import StaticDeviceResult, static_device
    from .uncertainty import Interval

# Every public name is imported when first asked for (PEP 562), so that ``import balance``
# costs less than ``import numpy``: each method's module (and numpy) loads with its first use.
_LAZY = {
    "example_path": "api",
    "examples": "api",
    "solve": "api",
    "solve_results": "api",
    "BalanceError": "errors",
    "BalanceWarning": "errors",
    "InfluenceResult": "field.influence",
    "influence_balance": "field.influence",
    "influence_coefficients": "field.influence",
    "influence_single_plane": "field.influence",
    "influence_two_plane": "field.influence",
    "trim_balance": "field.influence",
    "NoiseModel": "field.influence_stats",
    "GRADES": "field.iso",
    "IsoAllocation": "field.iso",
    "IsoCheck": "field.iso",
    "IsoTolerances": "field.iso",
    "iso_allocate": "field.iso",
    "iso_check": "field.iso",
    "iso_permissible_unbalance": "field.iso",
    "iso_tolerances": "field.iso",
    "kgm_to_gmm": "field.iso",
    "to_bearing_planes": "field.iso",
    "Combined": "field.weights",
    "Split": "field.weights",
    "combine_weights": "field.weights",
    "split_correction": "field.weights",
    "ResonanceResult": "resonance.methods",
    "four_run": "resonance.methods",
    "parallelogram": "resonance.methods",
    "trial_runs": "resonance.methods",
    "Correction": "rotor.design",
    "CorrectionPlane": "rotor.design",
    "RotorResult": "rotor.design",
    "Unbalance": "rotor.design",
    "balance_rotor": "rotor.design",
    "StaticDeviceResult": "rotor.static_device",
    "static_device": "rotor.static_device",
    "BalanceScene": "model.scene",
    "load_scene": "model.scene",
    "Interval": "uncertainty",
    "Units": "model.units",
}

__all__ = [
    "GRADES",
    "BalancingMachine",
    "CoastDown",
    "CounterRotatingPair",
    "Counterweight",
    "MechanismBalancing",
    "balanced_scene",
    "coast_down_study",
    "pivot_reaction",
    "centre_of_mass",
    "h_vectors",
    "harmonic_amplitude",
    "shaking_force",
    "solve_mechanism_balancing",
    "BalanceError",
    "BalanceScene",
    "BalanceWarning",
    "Combined",
    "IsoTolerances",
    "NoiseModel",
    "Split",
    "Units",
    "combine_weights",
    "iso_tolerances",
    "split_correction",
    "to_bearing_planes",
    "trim_balance",
    "Correction",
    "CorrectionPlane",
    "InfluenceResult",
    "Interval",
    "IsoAllocation",
    "IsoCheck",
    "ResonanceResult",
    "RotorResult",
    "StaticDeviceResult",
    "Unbalance",
    "balance_rotor",
    "example_path",
    "examples",
    "four_run",
    "influence_balance",
    "influence_coefficients",
    "influence_single_plane",
    "influence_two_plane",
    "iso_allocate",
    "iso_check",
    "iso_permissible_unbalance",
    "kgm_to_gmm",
    "load_scene",
    "parallelogram",
    "solve",
    "solve_results",
    "static_device",
    "trial_runs",
]


_MACHINE = ("BalancingMachine", "CoastDown", "pivot_reaction", "coast_down_study")
# the static balancing of mechanisms needs pandas and the kinetostatic solver: imported
# on first use, so that ``import balance`` costs little more than ``import numpy``
_MECHANISM = ("CounterRotatingPair", "Counterweight", "MechanismBalancing", "balanced_scene",
              "centre_of_mass", "h_vectors", "harmonic_amplitude", "shaking_force",
              "solve_mechanism_balancing")


# every public name, imported on first use (the virtual balancing machine's names,
# ``BalancingMachine``, ``CoastDown``, ``pivot_reaction``, ``coast_down_study``, load
# pymunk and are looked up each time; the static balancing of mechanisms,
# ``solve_mechanism_balancing``, ... pandas and the kinetostatic solver); a subpackage
# asked for as an attribute is imported
__getattr__, __dir__ = lazy_names(
    __name__, {**_LAZY, **group(_MECHANISM, "mechanism"), **group(_MACHINE, "machine")},
    globals(), __all__, kept=lambda name: name not in _MACHINE)
