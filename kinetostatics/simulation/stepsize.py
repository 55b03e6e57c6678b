"""The first guess of a cross-check's time step, from the scene's kinematics.

The simulation's error falls as dt^2 (docs/simulation.md); its constant depends on how
fast the reactions change along the motion, which the kinematics tell only roughly.
So the guess is a step in which the fastest body turns ``STEP_ANGLE`` and the fastest
named point moves no more than ``LINK_FRACTION`` of the smallest link; the cross-check
then corrects it once with the dt^2 law if the run misses its target
(:func:`kinetostatics.simulation.crosscheck`).
"""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np

from ..common.angles import radian_value
from ..model.scene import Scene
from .reference import reference_solution, sweep_positions

__all__ = ["first_guess_steps"]

STEP_ANGLE = radian_value(0.1)
"""The fastest body turns a tenth of a degree per step (3600 steps per revolution of a
crank that is the fastest body: errors of 1e-6 to 1e-5 on the bundled scenes)."""

LINK_FRACTION = 3.0 * STEP_ANGLE
"""The fastest named point moves at most this fraction of the smallest link per step."""

MIN_STEPS = 2000
"""The first guess is never below this many steps per revolution (per sweep)."""


def revolution_time(scene: Scene) -> float:
    """Duration (s) of one driver revolution, or of a sliding driver's sweep."""
    d = scene.driver
    if d.kind == "R":
        return 2.0 * math.pi / abs(d.speed)
    return float(np.ptp(np.asarray(d.positions, dtype=float))) / abs(d.speed)


def first_guess_steps(scene: Scene, max_steps: int = 40_000) -> int:
    """Steps per revolution (per sweep) of the first run: the fastest body turns
    ``STEP_ANGLE`` per step and the fastest named point moves at most ``LINK_FRACTION``
    of the smallest link; at least ``MIN_STEPS``, at most ``max_steps``, rounded up to
    a hundred."""
    sweep = reference_solution(scene, sweep_positions(scene))
    kin = sweep.kin
    w_top = v_top = 0.0
    link = math.inf
    for name, b in scene.bodies.items():
        m = kin.bodies[name]
        w_top = max(w_top, float(np.max(np.abs(m.omega))))
        for p in b.points.values():
            vx, vy = m.vel_at(*m.point(p))
            v_top = max(v_top, float(np.max(np.hypot(vx, vy))))
        for p, q in combinations(b.points.values(), 2):
            if math.dist(p, q) > 0.0:
                link = min(link, math.dist(p, q))
    rates = [w_top / STEP_ANGLE]                       # steps per second
    if math.isfinite(link) and v_top > 0.0:
        rates.append(v_top / (LINK_FRACTION * link))
    n = max(rates) * revolution_time(scene)
    return int(min(max_steps, max(MIN_STEPS, 100 * math.ceil(n / 100.0))))
