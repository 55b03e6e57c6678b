"""pymunk simulations built from the same scenes, and the cross-check of the joint
reactions against :func:`kinetostatics.solve`.

The names load lazily: importing this package (or its ``cli``) does not import pymunk
until a simulation name is used.
"""

from __future__ import annotations

import importlib

_HOME = {
    "AUTO_ITERATIONS": "comparison",
    "MAX_STEPS": "comparison",
    "ORDER_FLOOR": "comparison",
    "SETTLE_FRACTION": "comparison",
    "STUDY_ITERATIONS": "comparison",
    "STUDY_STEPS": "comparison",
    "ZERO_COUPLE": "comparison",
    "CrossCheck": "comparison",
    "Study": "comparison",
    "compare": "comparison",
    "converged_iterations": "comparison",
    "crosscheck": "comparison",
    "crosscheck_many": "comparison",
    "plan": "comparison",
    "plot_comparison": "comparison",
    "plot_study": "comparison",
    "study": "comparison",
    "DEFAULT_ITERATIONS": "engine",
    "DEFAULT_STEPS_PER_REVOLUTION": "engine",
    "GROOVE_MARGIN": "engine",
    "PYMUNK_VERSION": "engine",
    "RESIST_UNSURE": "engine",
    "SERIAL": "engine",
    "SWITCH_SETTLE": "engine",
    "VERIFY_EVERY": "engine",
    "WARMUP_ITERATIONS": "engine",
    "WARMUP_STEPS": "engine",
    "ConstraintInfo": "engine",
    "SimModel": "engine",
    "SimRecord": "engine",
    "SimulationError": "engine",
    "build_space": "engine",
    "fast_path_available": "engine",
    "joint_drift": "engine",
    "make_stepper": "engine",
    "mechanism_size": "engine",
    "reference_solution": "engine",
    "run": "engine",
    "run_batch": "engine",
    "sweep_positions": "engine",
    "translating_bodies": "engine",
    "warmup_schedule": "engine",
}

__all__ = sorted(_HOME)


def __getattr__(name: str):
    """Load a simulation name from its module on first use (PEP 562)."""
    if name in _HOME:
        value = getattr(importlib.import_module(f".{_HOME[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
