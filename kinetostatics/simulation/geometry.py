"""Points and lines of a scene in a body's frame, and body points in the world frame
over sampled poses (shared by the model builder, the momentum balance and the drift)."""

from __future__ import annotations

import math

import numpy as np

from ..model.scene import GROUND, Scene

__all__: list[str] = []          # used by the other simulation modules only


def local_point(scene: Scene, body: str, point: str) -> tuple[float, float]:
    if body == GROUND:
        return scene.ground[point]
    return scene.bodies[body].local(point)


def first_value(x) -> float:
    return float(np.asarray(x, dtype=float).reshape(-1)[0])


def joint_line(scene: Scene, joint: str, body: str) -> tuple[np.ndarray, np.ndarray]:
    """A prismatic joint's line in ``body``'s frame (the guide's or the slider's):
    a point on it and its unit direction."""
    j = scene.joints[joint]
    if body == j.guide:
        beta = j.beta
        return np.array(local_point(scene, body, j.points[0])), np.array([math.cos(beta),
                                                                      math.sin(beta)])
    # the slider's local x axis lies along the line, through the slider point
    return np.array(local_point(scene, body, j.points[1])), np.array([1.0, 0.0])


def cog_on_line(scene: Scene, joint: str, body: str) -> bool:
    """Whether ``body``'s centre of mass lies on the joint's line (or it is the ground)."""
    if body == GROUND:
        return True
    p, u = joint_line(scene, joint, body)
    g = np.asarray(scene.bodies[body].cog, dtype=float) - p
    size = max(1.0, float(np.hypot(*g)))
    return abs(float(u[0] * g[1] - u[1] * g[0])) <= 1e-12 * size


def line_foot(scene: Scene, joint: str, body: str) -> tuple[float, float]:
    """The point of the joint's line (in ``body``'s frame) nearest ``body``'s centre of
    mass: the groove's pin on that body (its arm from the cog is normal to the line)."""
    p, u = joint_line(scene, joint, body)
    if body == GROUND:
        return tuple(p)
    g = np.asarray(scene.bodies[body].cog, dtype=float)
    return tuple(p + float(np.dot(g - p, u)) * u)



def pin_range(sc: Scene, sweep, q: str, p: str, pin, lp, u) -> tuple[float, float]:
    """Range over the motion of the pin's coordinate along the groove body's line."""
    kin = sweep.kin
    n = kin.n
    if p == GROUND:
        wx, wy = np.full(n, pin[0]), np.full(n, pin[1])
    else:
        wx, wy = (np.broadcast_to(v, (n,)) for v in kin.bodies[p].point(pin))
    if q == GROUND:
        lx, ly = wx, wy
    else:
        m = kin.bodies[q]
        dx, dy = wx - m.ox, wy - m.oy
        c, s = np.broadcast_to(m.cos, (n,)), np.broadcast_to(m.sin, (n,))
        lx, ly = c * dx + s * dy, -s * dx + c * dy
    t = (lx - lp[0]) * u[0] + (ly - lp[1]) * u[1]
    return float(np.min(t)), float(np.max(t))



def pose_world(pose: np.ndarray, index: dict[str, int], body: str, local,
               cos: np.ndarray | None = None, sin: np.ndarray | None = None):
    """World coordinates of a body's local point over sampled poses.

    ``pose`` is (samples, bodies, 3): x, y of each moving body's origin and its angle;
    ``index`` maps a moving body's name to its column. The ground's points stay put.
    ``cos`` and ``sin`` of every pose angle may be passed when already computed.
    """
    K = pose.shape[0]
    if body == GROUND:
        return np.full(K, local[0]), np.full(K, local[1])
    i = index[body]
    c = np.cos(pose[:, i, 2]) if cos is None else cos[:, i]
    s = np.sin(pose[:, i, 2]) if sin is None else sin[:, i]
    return (pose[:, i, 0] + c * local[0] - s * local[1],
            pose[:, i, 1] + s * local[0] + c * local[1])
