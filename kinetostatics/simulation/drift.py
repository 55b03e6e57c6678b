"""How far a run's joints have come apart (the drift), over sampled poses."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..model.scene import GROUND
from .geometry import pose_world

if TYPE_CHECKING:
    from .model import SimModel


def joint_drift(model: SimModel, pose: np.ndarray) -> float:
    """Largest joint error over sampled poses (m).

    Pivots: the distance between the joint's points on the two bodies; grooves: the
    pin's distance from the groove line; locks: the relative angle's error times the
    largest distance of a scene point from the origin. A converged run keeps this of
    the order of a dt^2 (about 1e-9 m); a solver short of iterations lets it grow.
    """
    names = model.moving
    index = {n: i for i, n in enumerate(names)}
    K = pose.shape[0]
    if K == 0:
        return 0.0

    def world(body: str, local):
        return pose_world(pose, index, body, local)

    def angle(body: str):
        return np.zeros(K) if body == GROUND else pose[:, index[body], 2]

    size = model.scene.size
    worst = 0.0
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
        m = float(np.max(d)) if np.all(np.isfinite(d)) else math.inf
        worst = max(worst, m)
    return worst

