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

from kinetostatics.common.lazy import group, lazy_names

# the virtual balancing machine loads pymunk: its names are looked up each time
_MACHINE = ("BalancingMachine", "CoastDown", "pivot_reaction", "coast_down_study")
# the static balancing of mechanisms needs pandas and the kinetostatic solver
_MECHANISM = ("CounterRotatingPair", "Counterweight", "MechanismBalancing", "balanced_scene",
              "centre_of_mass", "h_vectors", "harmonic_amplitude", "shaking_force",
              "solve_mechanism_balancing")
# Every public name -> its module, imported when first asked for (PEP 562), so that
# ``import balance`` costs less than ``import numpy``: each method's module (and numpy)
# loads with its first use; a subpackage asked for as an attribute is imported.
_NAMES = {
    **group(("example_path", "examples", "solve", "solve_results"), "api"),
    **group(("BalanceError", "BalanceWarning"), "errors"),
    **group(("InfluenceResult", "influence_balance", "influence_coefficients",
             "influence_single_plane", "influence_two_plane", "trim_balance"),
            "field.influence"),
    **group(("NoiseModel",), "field.influence_stats"),
    **group(("GRADES", "IsoAllocation", "IsoCheck", "IsoTolerances", "iso_allocate", "iso_check",
             "iso_permissible_unbalance", "iso_tolerances", "kgm_to_gmm", "to_bearing_planes"),
            "field.iso"),
    **group(("Combined", "Split", "combine_weights", "split_correction"), "field.weights"),
    **group(("ResonanceResult", "four_run", "parallelogram", "trial_runs"), "resonance.methods"),
    **group(("Correction", "CorrectionPlane", "RotorResult", "Unbalance", "balance_rotor"),
            "rotor.design"),
    **group(("StaticDeviceResult", "static_device"), "rotor.static_device"),
    **group(("BalanceScene", "load_scene"), "model.scene"),
    **group(("Interval",), "uncertainty"),
    **group(("Units",), "model.units"),
    **group(_MECHANISM, "mechanism"),
    **group(_MACHINE, "machine"),
}
__all__ = sorted(_NAMES)
__getattr__, __dir__ = lazy_names(__name__, _NAMES, globals(), __all__,
                                  kept=lambda name: name not in _MACHINE)
