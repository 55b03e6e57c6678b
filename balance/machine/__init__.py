"""The virtual balancing machine (seed 002 fig. 3.10) simulated with pymunk.

Modules: ``mount`` (the machine: the rotor on its spring-damper mount, its runs as a
batch and the balancing methods), ``runs`` (one run, at constant speed or coasting
down), ``coastdown`` (the speed history), ``demodulation`` (the envelope and its peak),
``records`` (what a run and a method give), ``unbalances`` (the eccentric masses and
the rotor body they make), ``pivot`` (the bearing force on a rigid pivot) and
``studies`` (errors against trial mass and coast-down speed).
"""

from __future__ import annotations

from .coastdown import CoastDown
from .demodulation import ENVELOPE_PASSES, envelope, peak
from .mount import BalancingMachine
from .pivot import PIVOT_STEPS_PER_REVOLUTION, PivotReaction, pivot_reaction
from .records import MachineRecord, MachineResult
from .studies import coast_down_study
from .unbalances import random_unbalance, unbalance_vector

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
