"""The virtual balancing machine (seed 002 fig. 3.10) simulated with pymunk.
"""

from __future__ import annotations

from .core import (
    ENVELOPE_PASSES,
    PIVOT_STEPS_PER_REVOLUTION,
    BalancingMachine,
    CoastDown,
    MachineRecord,
    MachineResult,
    PivotReaction,
    coast_down_study,
    envelope,
    peak,
    pivot_reaction,
    random_unbalance,
    unbalance_vector,
)

__all__ = [
    "BalancingMachine",
    "CoastDown",
    "ENVELOPE_PASSES",
    "MachineRecord",
    "MachineResult",
    "PIVOT_STEPS_PER_REVOLUTION",
    "PivotReaction",
    "coast_down_study",
    "envelope",
    "peak",
    "pivot_reaction",
    "random_unbalance",
    "unbalance_vector",
]
