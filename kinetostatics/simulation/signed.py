"""Signed reactions from the momentum balance of every body over a step.

``constraint.impulse / dt`` is the magnitude of a reaction (public API). The signed
values (the reaction vectors, the normal force and couple of a slider, and the sign
of the driving moment, i.e. of the power the motor delivers) are derived from the
momentum balance of every body over the step: m (v' - v) / dt = m g + F + sum of the
constraint forces, I (w' - w) / dt = T + sum of their moments, with the constraint
forces along the directions pymunk uses at the new pose (public state only: poses,
velocities and the forces we set). For a driver + dyads chain these 3n equations have
exactly 3n unknowns (a prismatic joint between bodies that cannot turn contributes its
couple as an unknown, with no pymunk constraint); the magnitudes of the solution are
checked against the public impulses at run time (:attr:`SimRecord.vector_check`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..model.scene import GROUND
from .errors import SimulationError
from .geometry import pose_world
from .model import reading_label

__all__: list[str] = []          # used by the other simulation modules only

if TYPE_CHECKING:
    from .model import SimModel


class SingularBalance(ArithmeticError):
    """The momentum balance has no unique solution at sample ``row``."""

    def __init__(self, row: int):
        super().__init__(f"singular momentum balance at sample {row}")
        self.row = row


def signed_reactions(model: SimModel, pose, vel0, vel1, frc, mag):
    """Signed constraint forces from the momentum balance of every body over the step.

    Unknowns, per constraint: the force on ``b`` (two components) for a pivot, the
    force along the groove's normal for a groove or the actuator, the couple on ``b``
    for a lock or the motor; ``a`` gets the opposite. Equations: per moving body
    m (v' - v) / dt - m g - F (two rows) and I (w' - w) / dt - T, the arms taken at
    the pose after the step (where pymunk forms its constraints).
    """
    sc = model.scene
    dt = model.dt
    names = model.moving
    index = {n: i for i, n in enumerate(names)}
    K = pose.shape[0]
    nb = len(names)
    mass = np.array([sc.bodies[n].mass for n in names])
    inert = np.array([sc.bodies[n].inertia for n in names])
    cog = np.array([sc.bodies[n].cog for n in names], dtype=float)
    ang = pose[:, :, 2]
    c, s = np.cos(ang), np.sin(ang)
    gxw = pose[:, :, 0] + c * cog[:, 0] - s * cog[:, 1]      # cog, world
    gyw = pose[:, :, 1] + s * cog[:, 0] + c * cog[:, 1]
    gvec = np.asarray(model.scene.gravity, dtype=float)

    # right-hand side: rows (body, fx / fy / m)
    rhs = np.empty((K, nb, 3))
    rhs[:, :, 0] = mass * (vel1[:, :, 0] - vel0[:, :, 0]) / dt - mass * gvec[0] - frc[:, :, 0]
    rhs[:, :, 1] = mass * (vel1[:, :, 1] - vel0[:, :, 1]) / dt - mass * gvec[1] - frc[:, :, 1]
    rhs[:, :, 2] = inert * (vel1[:, :, 2] - vel0[:, :, 2]) / dt - frc[:, :, 2]

    cols = []        # (label, list of (body index, fx, fy, m) arrays over K)

    def world(body: str, local) -> tuple[np.ndarray, np.ndarray]:
        return pose_world(pose, index, body, local, c, s)

    def rot(body: str, v) -> tuple[np.ndarray, np.ndarray]:
        if body in (GROUND, "actuator"):
            return np.full(K, v[0]), np.full(K, v[1])
        i = index[body]
        return c[:, i] * v[0] - s[:, i] * v[1], s[:, i] * v[0] + c[:, i] * v[1]

    def arm(body: str, x, y):
        i = index[body]
        return x - gxw[:, i], y - gyw[:, i]

    for info in model.constraints:
        a, b = info.a, info.b
        if info.role == "pivot":
            ax_, ay_ = world(a, info.anchor_a)
            bx_, by_ = world(b, info.anchor_b)
            for ux, uy in ((1.0, 0.0), (0.0, 1.0)):
                ent = []
                if b in index:
                    rx, ry = arm(b, bx_, by_)
                    ent.append((index[b], ux, uy, rx * uy - ry * ux))
                if a in index:
                    rx, ry = arm(a, ax_, ay_)
                    ent.append((index[a], -ux, -uy, -(rx * uy - ry * ux)))
                cols.append(ent)
        elif info.role in ("groove", "actuator"):
            nx, ny = rot(a, info.normal)
            px, py = world(b, info.anchor_b)      # the pin (the force acts along n there)
            ent = []
            if b in index:
                rx, ry = arm(b, px, py)
                ent.append((index[b], nx, ny, rx * ny - ry * nx))
            if a in index:
                rx, ry = arm(a, px, py)
                ent.append((index[a], -nx, -ny, -(rx * ny - ry * nx)))
            cols.append(ent)
        else:    # lock, motor, couple: a couple on b, the opposite on a
            ent = []
            if b in index:
                ent.append((index[b], 0.0, 0.0, 1.0))
            if a in index:
                ent.append((index[a], 0.0, 0.0, -1.0))
            cols.append(ent)

    n_unk = len(cols)
    A = np.zeros((K, nb, 3, n_unk))
    for j, ent in enumerate(cols):
        for i, fx, fy, m in ent:
            A[:, i, 0, j] += fx
            A[:, i, 1, j] += fy
            A[:, i, 2, j] += m
    A = A.reshape(K, nb * 3, n_unk)
    b = rhs.reshape(K, nb * 3)
    if A.shape[1] != n_unk:
        raise SimulationError(f"the momentum balance has {A.shape[1]} equations for {n_unk} "
                              "unknowns: the chain is not a driver plus dyads")
    try:
        lam = np.linalg.solve(A, b[..., None])[..., 0]
    except np.linalg.LinAlgError:
        lam = None
    if lam is None or not np.all(np.isfinite(lam)):
        # poses no mechanism takes (a run that blew up): name the first such row
        with np.errstate(all="ignore"):
            cond = np.linalg.cond(A)
        bad = ~np.isfinite(cond) | (cond > 1e15)
        if lam is not None:
            bad |= ~np.all(np.isfinite(lam), axis=1)
        raise SingularBalance(int(np.argmax(bad)) if bad.any() else 0)

    signed: dict[str, Any] = {}
    check = 0.0
    j = 0
    ci = -1
    real = [i for i in model.constraints if i.constraint is not None]
    forces = [k for k, i in enumerate(real) if i.role not in ("lock", "motor")]
    fmax = float(np.max(mag[:, forces])) if K and forces else 0.0
    size = sc.size
    for info in model.constraints:
        if info.constraint is not None:
            ci += 1
        label = reading_label(info)
        if info.role == "pivot":
            fx, fy = lam[:, j], lam[:, j + 1]
            j += 2
            signed[label] = (fx, fy)
            got = np.hypot(fx, fy)
        else:
            val = lam[:, j]
            j += 1
            got = np.abs(val)
            if info.role == "groove":
                jt = sc.joints[info.joint]
                nx, ny = rot(info.a, info.normal)
                # N: the force on the slider along the line's left normal (the groove's
                # normal, whichever body carries the groove)
                N = val if info.b == info.slider else -val
                sign = 1.0 if jt.on_by[0] == info.slider else -1.0
                signed[label] = (sign * N * nx, sign * N * ny)
                signed[f"{label}:N"] = N
                # its moment about the slider point: the pin lies on the line, d along it
                px, py = world(info.b, info.anchor_b)
                sx, sy = world(info.slider, info.slider_point)
                d = (px - sx) * ny - (py - sy) * nx          # (pin - S) . u, u = (ny, -nx)
                signed[f"{label}:M"] = signed.get(f"{label}:M", 0.0) + d * N
            elif info.role in ("lock", "couple"):
                signed[f"{info.joint}:M"] = signed.get(f"{info.joint}:M", 0.0) + val
            else:
                signed["driver"] = val
        if info.constraint is None:
            continue            # a couple of a translating body: no pymunk constraint
        # relative to the constraint's largest reading, but not below 1e-6 of the
        # largest force (times the mechanism's size for a couple): a lock that carries
        # next to nothing is checked on the scale of the mechanism's forces
        floor = 1e-6 * fmax * (size if info.role in ("lock", "motor") else 1.0)
        scale = max(float(np.max(mag[:, ci])) if K else 0.0, floor)
        if scale > 0.0:
            check = max(check, float(np.max(np.abs(got - mag[:, ci]))) / scale)
    for name in sc.joints:
        if sc.joints[name].kind == "T":
            signed[f"{name}:M"] = np.broadcast_to(signed.get(f"{name}:M", 0.0), (K,)).copy()
    return signed, check

