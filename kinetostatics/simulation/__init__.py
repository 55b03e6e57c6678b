"""pymunk simulations built from the same scenes, and the cross-check of the joint
reactions against :func:`kinetostatics.solve`.

The names load lazily: importing this package (or its ``cli``) does not import pymunk
until a simulation name is used.
"""

from __future__ import annotations

import importlib

_HOME = {
    "SERIAL": "batch",
    "run_batch": "batch",
    "ACCEPTABLE_ERROR": "runner",
    "BUDGET": "runner",
    "TARGET_ERROR": "runner",
    "MAX_AUTO_STEPS": "runner",
    "first_guess_steps": "stepsize",
    "check_scene": "model",
    "CrossCheck": "comparison",
    "ZERO_COUPLE": "comparison",
    "compare": "comparison",
    "DRIFT_FACTOR": "drift",
    "DRIFT_LIMIT": "drift",
    "drift_bound": "drift",
    "drift_rows": "drift",
    "joint_drift": "drift",
    "SimulationDiverged": "errors",
    "SimulationError": "errors",
    "RESIST_UNSURE": "loads",
    "SWITCH_SETTLE": "loads",
    "ConstraintInfo": "model",
    "DEFAULT_ITERATIONS": "model",
    "GROOVE_MARGIN": "model",
    "SimModel": "model",
    "build_space": "model",
    "plot_comparison": "plots",
    "plot_study": "plots",
    "reference_solution": "reference",
    "sweep_positions": "reference",
    "translating_bodies": "reference",
    "AUTO_ITERATIONS": "runner",
    "DEFAULT_STEPS_PER_REVOLUTION": "runner",
    "MAX_STEPS": "runner",
    "SETTLE_FRACTION": "runner",
    "converged_iterations": "runner",
    "crosscheck": "runner",
    "crosscheck_many": "runner",
    "plan": "runner",
    "PYMUNK_VERSION": "stepper",
    "SimRecord": "stepper",
    "VERIFY_EVERY": "stepper",
    "WARMUP_ITERATIONS": "stepper",
    "WARMUP_STEPS": "stepper",
    "fast_path_available": "stepper",
    "make_stepper": "stepper",
    "run": "stepper",
    "warmup_schedule": "stepper",
    "ORDER_FLOOR": "studies",
    "STUDY_ITERATIONS": "studies",
    "STUDY_STEPS": "studies",
    "Study": "studies",
    "study": "studies",
}

__all__ = sorted(_HOME)


def __getattr__(name: str):
    """Load a simulation name from its module on first use (PEP 562)."""
    if name in _HOME:
        value = getattr(importlib.import_module(f".{_HOME[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
