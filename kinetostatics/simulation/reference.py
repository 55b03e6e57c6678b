"""The kinetostatic side of the simulation: the exact solution at given driver positions,
the positions that cover the motion, and the bodies that only translate."""

from __future__ import annotations

import copy
from typing import Any

import numpy as np

from ..model.scene import Scene, load_scene

__all__ = ["reference_solution", "sweep_positions", "translating_bodies"]


def _raw_with_positions(scene: Scene, positions) -> dict:
    """A copy of the scene's raw dict with ``positions`` as the driver's sweep."""
    raw = copy.deepcopy(scene.raw)
    drv = dict(raw["driver"])
    for k in ("start", "stop", "count", "positions"):
        drv.pop(k, None)
    drv["positions"] = [float(p) for p in positions]
    raw["driver"] = drv
    return raw


def reference_solution(scene: Any, positions):
    """Kinetostatics of ``scene`` at the given driver positions (deg or m).

    The scene's first position is solved first, as row 0, so that the assembly chosen
    by the ``[near]`` hints is the scene's own; the positions asked for are rows 1...
    """
    from ..results import solve
    sc = load_scene(scene)
    pos = np.concatenate([[sc.driver.positions[0]], np.asarray(positions, dtype=float)])
    return solve(_raw_with_positions(sc, pos), allow_repeats=True)


def sweep_positions(scene: Scene, count: int = 73) -> np.ndarray:
    """Driver positions covering the motion: a whole turn when the scene's sweep is one
    (or a single position), else the sweep's range."""
    pos = np.asarray(scene.driver.positions, dtype=float)
    if scene.driver.kind == "R" and (pos.size < 2 or np.ptp(pos) >= 360.0 - 1e-9):
        return np.linspace(pos[0], pos[0] + 360.0, count)
    if pos.size < 2:
        return pos
    return np.linspace(pos.min(), pos.max(), count)


def translating_bodies(scene: Scene, sweep) -> set[str]:
    """Moving bodies whose angle never changes over the motion (omega = alpha = 0 at
    every position of the sweep): pistons, yokes, rams, blocks on fixed guides."""
    out = set()
    for name in scene.bodies:
        m = sweep.kin.bodies[name]
        if not np.any(np.asarray(m.omega) != 0.0) and not np.any(np.asarray(m.alpha) != 0.0):
            out.add(name)
    return out




def point_acceleration(scene: Scene, sweep) -> float:
    """The largest acceleration (m/s^2) of a named point of a moving body over the
    motion (``sweep``: the solution at :func:`sweep_positions`)."""
    kin = sweep.kin
    top = 0.0
    for name, b in scene.bodies.items():
        m = kin.bodies[name]
        for p in b.points.values():
            ax, ay = m.acc_at(*m.point(p))
            top = max(top, float(np.max(np.hypot(ax, ay))))
    return top
