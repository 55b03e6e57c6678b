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

    Returns ``(signed, check)``: the readings by label (:class:`SimRecord` ``signed``)
    and the largest relative gap between their magnitudes and the impulses ``mag``.
    """
    frame = _Frame(model, pose)
    rhs = _momentum_change(model, vel0, vel1, frc)
    lam = _solve_balance(_unknowns(model, frame), rhs)
    return _signed_readings(model, frame, lam, mag)


class _Frame:
    """The sampled poses of the moving bodies, with the world points, directions and
    arms about the centres of mass that the balance's columns are made of."""

    def __init__(self, model: SimModel, pose: np.ndarray):
        sc = model.scene
        self.names = model.moving
        self.index = {n: i for i, n in enumerate(self.names)}
        self.K = pose.shape[0]
        self.pose = pose
        cog = np.array([sc.bodies[n].cog for n in self.names], dtype=float)
        ang = pose[:, :, 2]
        self.c, self.s = np.cos(ang), np.sin(ang)
        c, s = self.c, self.s
        self.gxw = pose[:, :, 0] + c * cog[:, 0] - s * cog[:, 1]      # cog, world
        self.gyw = pose[:, :, 1] + s * cog[:, 0] + c * cog[:, 1]

    def world(self, body: str, local) -> tuple[np.ndarray, np.ndarray]:
        return pose_world(self.pose, self.index, body, local, self.c, self.s)

    def rot(self, body: str, v) -> tuple[np.ndarray, np.ndarray]:
        if body in (GROUND, "actuator"):
            return np.full(self.K, v[0]), np.full(self.K, v[1])
        i = self.index[body]
        return (self.c[:, i] * v[0] - self.s[:, i] * v[1],
                self.s[:, i] * v[0] + self.c[:, i] * v[1])

    def arm(self, body: str, x, y):
        i = self.index[body]
        return x - self.gxw[:, i], y - self.gyw[:, i]


def _momentum_change(model: SimModel, vel0, vel1, frc) -> np.ndarray:
    """The right-hand side, rows (sample, body, fx / fy / m): the change of momentum over
    the step less gravity and the forces set on the body."""
    sc = model.scene
    dt = model.dt
    names = model.moving
    K, nb = vel0.shape[0], len(names)
    # the masses pymunk has (with any ballast, whose cancelling force is in frc); a
    # body that only translates: its scene inertia (w' - w is zero for it)
    built = [model.built_mass(n) for n in names]
    mass = np.array([m for m, _ in built])
    inert = np.array([i if n not in model.translating else sc.bodies[n].inertia
                      for n, (_, i) in zip(names, built, strict=True)])
    gvec = np.asarray(model.scene.gravity, dtype=float)
    rhs = np.empty((K, nb, 3))
    rhs[:, :, 0] = mass * (vel1[:, :, 0] - vel0[:, :, 0]) / dt - mass * gvec[0] - frc[:, :, 0]
    rhs[:, :, 1] = mass * (vel1[:, :, 1] - vel0[:, :, 1]) / dt - mass * gvec[1] - frc[:, :, 1]
    rhs[:, :, 2] = inert * (vel1[:, :, 2] - vel0[:, :, 2]) / dt - frc[:, :, 2]
    return rhs


def _unknowns(model: SimModel, f: _Frame) -> list:
    """One column per unknown: a list of (body index, fx, fy, m) over the samples, what
    a unit value of the unknown puts on each body it acts on."""
    index = f.index
    cols = []
    for info in model.constraints:
        a, b = info.a, info.b
        if info.role == "pivot":
            ax_, ay_ = f.world(a, info.anchor_a)
            bx_, by_ = f.world(b, info.anchor_b)
            for ux, uy in ((1.0, 0.0), (0.0, 1.0)):
                cols.append(_pair(index, f, a, (ax_, ay_), b, (bx_, by_), ux, uy))
        elif info.role in ("groove", "actuator"):
            nx, ny = f.rot(a, info.normal)
            pin = f.world(b, info.anchor_b)         # the force acts along n there
            cols.append(_pair(index, f, a, pin, b, pin, nx, ny))
        else:    # lock, motor, couple: a couple on b, the opposite on a
            ent = []
            if b in index:
                ent.append((index[b], 0.0, 0.0, 1.0))
            if a in index:
                ent.append((index[a], 0.0, 0.0, -1.0))
            cols.append(ent)
    return cols


def _solve_balance(cols: list, rhs: np.ndarray) -> np.ndarray:
    """The unknowns at every sample: the square system of the columns against the
    momentum change; :class:`SingularBalance` at the first sample it cannot be solved."""
    K, nb = rhs.shape[:2]
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
    return lam


def _signed_readings(model: SimModel, f: _Frame, lam: np.ndarray, mag) -> tuple[dict, float]:
    """The unknowns as the record's signed readings (a slider's normal force and couple
    about its point, the driving moment), and the check of their magnitudes against the
    public impulses ``mag``."""
    sc = model.scene
    K = f.K
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
                nx, ny = f.rot(info.a, info.normal)
                # N: the force on the slider along the line's left normal (the groove's
                # normal, whichever body carries the groove)
                N = val if info.b == info.slider else -val
                sign = 1.0 if jt.on_by[0] == info.slider else -1.0
                signed[label] = (sign * N * nx, sign * N * ny)
                signed[f"{label}:N"] = N
                # its moment about the slider point: the pin lies on the line, d along it
                px, py = f.world(info.b, info.anchor_b)
                sx, sy = f.world(info.slider, info.slider_point)
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


def _pair(index: dict, f, a, at_a: tuple, b, at_b: tuple, ux: float, uy: float) -> list:
    """A constraint's column: the unit force (ux, uy) on body b at ``at_b`` and its
    opposite on a at ``at_a``, as (unknown's index, fx, fy, moment about the body's
    centre of mass) for each body that moves."""
    ent = []
    if b in index:
        rx, ry = f.arm(b, *at_b)
        ent.append((index[b], ux, uy, rx * uy - ry * ux))
    if a in index:
        rx, ry = f.arm(a, *at_a)
        ent.append((index[a], -ux, -uy, -(rx * uy - ry * ux)))
    return ent
