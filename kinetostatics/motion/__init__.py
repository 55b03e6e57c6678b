"""Motion under forces (seed 002 ch. 4): the equation of motion of the reduction element,
its integration, and the ``[motion]`` scene.
"""

from __future__ import annotations

from .integrate import (
    TWO_PI,
    Inertia,
    Moment,
    MotionError,
    MotionSolution,
    flywheel_for_delta,
    golden_max,
    periodic_solution,
    recurrence_convergence,
    simulate,
    solve_energy,
    solve_recurrence,
    stopping,
)
from .scene import (
    KEY,
    MotionResult,
    MotionSpec,
    ReducedMechanism,
    motion_spec,
    simulate_motion,
)

__all__ = [
    "Inertia",
    "KEY",
    "Moment",
    "MotionError",
    "MotionResult",
    "MotionSolution",
    "MotionSpec",
    "ReducedMechanism",
    "TWO_PI",
    "flywheel_for_delta",
    "golden_max",
    "motion_spec",
    "periodic_solution",
    "recurrence_convergence",
    "simulate",
    "simulate_motion",
    "solve_energy",
    "solve_recurrence",
    "stopping",
]
