"""How far a run's joints have come apart (the drift), and when a run has diverged.

With ``error_bias = 0`` every step corrects the whole drift of the step before, so a
converged run keeps its joints apart by what one step's motion along the constraint's
curvature leaves: a fraction of a dt^2, a the largest acceleration of a named point
over the motion. Measured on the bundled scenes from 200 to 7200 steps per revolution:
0.11 to 0.31 a dt^2 (1e-8 to 4e-5 m, 4e-8 to 1.3e-4 of the mechanism's size). Runs
whose Gauss-Seidel iterations could not keep up blew up: 54 to 3e6 a dt^2 (2e-5 m to
5 m, 3e-5 to 5 of the size), the readings off by 2e2 to 1e7 of their scale or not
finite. The bound (:func:`drift_bound`) is set between: ``DRIFT_FACTOR`` a dt^2, and
never more than ``DRIFT_LIMIT`` of the mechanism's size.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..model.scene import GROUND
from .errors import SimulationDiverged
from .geometry import pose_world

__all__ = ["DRIFT_FACTOR", "DRIFT_LIMIT", "drift_bound", "drift_rows", "joint_drift"]

if TYPE_CHECKING:
    from .model import SimModel

DRIFT_FACTOR = 5.0
"""A run whose joints drift apart by more than this times a dt^2 (a: the largest
acceleration of a named point over the motion) has diverged (converged runs: 0.11 to
0.31; diverged ones: 54 and more)."""

DRIFT_LIMIT = 1e-3
"""A drift above this fraction of the mechanism's size is a diverged run whatever dt is
(converged runs of 200 steps per revolution and more stay below 1.3e-4 of it)."""

DRIFT_FLOOR = 1e-12
"""The bound is never below this fraction of the mechanism's size (rounding), so that a
motion with no acceleration is not judged on a zero bound."""


def drift_bound(model: SimModel) -> float:
    """The largest joint drift (m) a converged run of ``model`` shows: ``DRIFT_FACTOR``
    a dt^2 / c, between ``DRIFT_FLOOR`` and ``DRIFT_LIMIT`` of the mechanism's size.

    c = 1 - error_bias^dt is the fraction of a joint's drift corrected per step (pymunk's
    bias coefficient): 1 with ``error_bias = 0``; a softer joint lets the drift grow to
    about a dt^2 / c before the correction balances it.
    """
    size = model.scene.size
    c = 1.0 - model.error_bias ** model.dt
    bound = DRIFT_FACTOR * model.accel_scale * model.dt ** 2 / max(c, 1e-300)
    return min(max(bound, DRIFT_FLOOR * size), DRIFT_LIMIT * size)


def drift_by_joint(model: SimModel, pose: np.ndarray) -> dict[str, np.ndarray]:
    """Each joint's error at each sampled pose (m), by joint name (a prismatic joint's
    lock as ``"<joint>:lock"``); inf where the pose is not finite.

    Pivots: the distance between the joint's points on the two bodies; grooves: the
    pin's distance from the groove line; locks: the relative angle's error times the
    mechanism's size (:attr:`Scene.size`).
    """
    names = model.moving
    index = {n: i for i, n in enumerate(names)}
    K = pose.shape[0]
    out: dict[str, np.ndarray] = {}
    if K == 0:
        return out

    def world(body: str, local):
        return pose_world(pose, index, body, local)

    def angle(body: str):
        return np.zeros(K) if body == GROUND else pose[:, index[body], 2]

    size = model.scene.size
    for info in model.constraints:
        if info.role == "pivot":
            ax_, ay_ = world(info.a, info.anchor_a)
            bx_, by_ = world(info.b, info.anchor_b)
            d = np.hypot(bx_ - ax_, by_ - ay_)
        elif info.role == "groove":
            ax_, ay_ = world(info.a, info.anchor_a)
            bx_, by_ = world(info.b, info.anchor_b)
            th = angle(info.a)
            nx = np.cos(th) * info.normal[0] - np.sin(th) * info.normal[1]
            ny = np.sin(th) * info.normal[0] + np.cos(th) * info.normal[1]
            d = np.abs((bx_ - ax_) * nx + (by_ - ay_) * ny)
        elif info.role == "lock":
            rel = angle(info.b) - angle(info.a)
            d = np.abs(rel - rel[0]) * size
        else:
            continue
        d = np.where(np.isfinite(d), d, math.inf)
        label = info.joint if info.role != "lock" else f"{info.joint}:lock"
        out[label] = np.fmax(out[label], d) if label in out else d
    return out


def drift_rows(model: SimModel, pose: np.ndarray) -> np.ndarray:
    """Largest joint error at each sampled pose (m); inf where the pose is not finite
    (:func:`drift_by_joint`, the largest over the joints)."""
    worst = np.zeros(pose.shape[0])
    for d in drift_by_joint(model, pose).values():
        worst = np.fmax(worst, d)
    return worst


def joint_drift(model: SimModel, pose: np.ndarray) -> float:
    """Largest joint error over sampled poses (m); see :func:`drift_rows`. A converged
    run keeps it near a fifth of a dt^2 (module docstring)."""
    rows = drift_rows(model, pose)
    return float(np.max(rows)) if rows.size else 0.0


def steps_per_revolution(model: SimModel) -> float:
    """Steps per driver revolution of ``model`` (a sliding driver: per sweep of its
    positions)."""
    d = model.scene.driver
    if d.kind == "R":
        return 2.0 * math.pi / abs(d.speed) / model.dt
    span = float(np.ptp(np.asarray(d.positions, dtype=float)))
    return span / abs(d.speed) / model.dt


def diverged(model: SimModel, time: float, position: float, drift: float,
             reason: str, where: str = "") -> SimulationDiverged:
    """The :class:`SimulationDiverged` error of a run of ``model``."""
    return SimulationDiverged(time=time, position=position, kind=model.kind, drift=drift,
                              size=model.scene.size, iterations=model.iterations,
                              dt=model.dt, steps_per_revolution=steps_per_revolution(model),
                              reason=reason, where=where)


def check_run(model: SimModel, times: np.ndarray, positions: np.ndarray, pose: np.ndarray,
              finite: np.ndarray) -> float:
    """The run's largest drift (m), or :class:`SimulationDiverged` at the first sample
    whose state or readings are not finite (``finite`` False) or whose drift exceeds
    :func:`drift_bound`; the error names the joint that drifted most there (or the first
    body whose state is not finite)."""
    by_joint = drift_by_joint(model, pose)
    rows = np.zeros(pose.shape[0])
    for d in by_joint.values():
        rows = np.fmax(rows, d)
    bad = ~finite | (rows > drift_bound(model))
    if bad.any():
        k = int(np.argmax(bad))
        worst = float(np.max(rows)) if np.all(finite) else math.inf
        if finite[k]:
            where = "joint " + max(by_joint, key=lambda j: by_joint[j][k])
        else:
            blown = [n for i, n in enumerate(model.moving)
                     if not np.isfinite(pose[k, i]).all()]
            where = f"body {blown[0]}" if blown else "the readings"
        raise diverged(model, float(times[k]), float(positions[k]), worst,
                       "drift" if finite[k] else "not finite", where)
    return float(np.max(rows)) if rows.size else 0.0
