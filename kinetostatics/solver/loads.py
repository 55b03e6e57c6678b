"""Loads on the bodies: applied forces and moments, gravity, and the inertia forces.

Seed 002 s. 2.1: the inertia torsor of a body in plane motion, F_i = -m a_G,
M_i = -I_G eps (eq. 2.1), added to the applied loads (d'Alembert). Seed 002 s. 2.2:
mass concentration, which replaces the torsor by point forces -m_k a_k (eq. 2.8):
static in two points (eqs 2.9-2.11) and dynamic in two points (eqs 2.12-2.15).

Every load is kept as a :class:`PointLoad` (a force at a moving point and/or a
couple) so that the resultants, the virtual power and the pictures use one list.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.scene import Body, Scene
from . import arith as A
from .kinematics import Kinematics

RESIST_STILL = 1e-9     # a resist point slower than this fraction of its top speed: undefined


@dataclass
class PointLoad:
    """A force (fx, fy) on ``body`` at the arm (rx, ry) from the body's local origin
    (global axes), plus a couple ``m``; arrays over positions or scalars.

    ``kind`` is ``"applied"``, ``"gravity"``, ``"inertia"`` or ``"friction"`` (added by
    :mod:`kinetostatics.friction`).
    """

    body: str
    kind: str
    rx: object
    ry: object
    fx: object
    fy: object
    m: object = 0.0
    label: str = ""
    scratch: tuple[str, ...] = ()
    """The fields (``fx``, ``fy``, ``m``) whose arrays this load alone holds, made for
    :func:`resultants` alone (``arms`` given): it may write its sums into them."""

    def position(self, kin: Kinematics):
        """Global position of the point of application."""
        b = kin.bodies[self.body]
        return A.add(b.ox, self.rx), A.add(b.oy, self.ry)

    def velocity(self, kin: Kinematics):
        """Velocity of the point of application."""
        return kin.bodies[self.body].vel_arm(self.rx, self.ry)

    def power(self, kin: Kinematics) -> np.ndarray:
        """Power of the load: F . v + M omega."""
        vx, vy = self.velocity(kin)
        om = kin.bodies[self.body].omega
        return A.add(A.mul_add(self.fx, vx, self.fy, vy), A.mul(self.m, om))


def concentrated_masses(body: Body) -> list[tuple[tuple[float, float], float]]:
    """Local positions and values of the concentrated masses of a body's mass model.

    Static, two points B, C with the cog G = B + t (C - B) on their line (eq. 2.11):
    m_B = m (1 - t), m_C = m t. Dynamic, point B and its conjugate K on the line BG
    beyond G with |GK| = I_G / (m |GB|) (eqs 2.13-2.14): m_B = m |GK| / (|GB| + |GK|),
    m_K = m |GB| / (|GB| + |GK|). Both keep the mass and the centre of mass; the dynamic
    pair keeps I_G too, the static pair does not.
    """
    model = body.mass_model
    m = body.mass
    g = np.asarray(body.cog, dtype=float)
    if model is None:
        return [(tuple(g), m)]
    if model.kind == "static":
        b = np.asarray(body.points[model.points[0]], dtype=float)
        c = np.asarray(body.points[model.points[1]], dtype=float)
        t = float(np.dot(g - b, c - b) / np.dot(c - b, c - b))
        return [(tuple(b), m * (1.0 - t)), (tuple(c), m * t)]
    b = np.asarray(body.points[model.points[0]], dtype=float)
    gb = float(np.hypot(*(g - b)))
    gk = body.inertia / (m * gb)
    k = g + (g - b) / gb * gk
    return [(tuple(b), m * gk / (gb + gk)), (tuple(k), m * gb / (gb + gk))]


def inertia_loads(scene: Scene, kin: Kinematics, arms: dict | None = None
                  ) -> list[PointLoad]:
    """Inertia loads of every body with mass: the exact torsor (eq. 2.1) or the point
    forces of its mass model (eq. 2.8 with 2.11 or 2.13-2.15). ``arms``: each body's
    arm of its cog is put there (:func:`applied_loads` takes its weight's from it)."""
    out = []
    for name, body in scene.bodies.items():
        if body.mass == 0.0 and body.inertia == 0.0:
            continue
        m = kin.bodies[name]
        if body.mass_model is None:
            rx, ry = m.rotate(*(body.cog or (0.0, 0.0)))
            if arms is not None:
                arms[name] = (rx, ry)
            ax, ay = m.acc_arm(rx, ry)
            neg = -body.mass
            # (a body turning at a constant rate: the couple is 0.0 whatever the sign of
            # the inertia, so not negated; a NaN or an infinity gives NaN either way)
            alpha = m.alpha
            inertia = body.inertia if A.zero(alpha) else -body.inertia
            fx, fy, mi = A.mul(neg, ax), A.mul(neg, ay), A.mul(inertia, alpha)
            out.append(PointLoad(name, "inertia", rx, ry, fx, fy, mi, "inertia torsor",
                                 _scratch(arms, fx=(fx, ax), fy=(fy, ay), m=(mi, alpha))))
            continue
        for loc, mk in concentrated_masses(body):
            rx, ry = m.rotate(*loc)
            ax, ay = m.acc_arm(rx, ry)
            fx, fy = A.mul(-mk, ax), A.mul(-mk, ay)
            out.append(PointLoad(name, "inertia", rx, ry, fx, fy, 0.0,
                                 f"concentrated mass {mk:.6g} kg",
                                 _scratch(arms, fx=(fx, ax), fy=(fy, ay))))
    return out


def _scratch(arms: dict | None, **made) -> tuple[str, ...]:
    """The fields of a load for the resultants alone (``arms`` given) whose arrays were
    just made (``made``: each field's value and the operand it was made from)."""
    if arms is None:
        return ()
    fresh = A.fresh
    return tuple([k for k, (x, src) in made.items() if fresh(x, src)])


def motion_scales(scene: Scene) -> tuple[float, float, float, float]:
    """The mechanism's own scales of motion: (linear speed, angular speed, linear
    acceleration, angular acceleration) of a point at the mechanism's size from a pivot
    turning with the driver (for a sliding driver: of the driver, and that over the
    size). "Standing still" is measured against the larger of these and the largest
    value over the sweep, so that a sweep whose rows all lie at dead centres (every
    speed rounding noise) still sees them stand still."""
    drv = scene.driver
    size = scene.size
    w, eps = abs(float(drv.speed)), abs(float(drv.acceleration))
    if drv.kind == "R":
        return w * size, w, (eps + w * w) * size, eps + w * w
    acc = eps + w * w / size
    return w, w / size, acc, acc / size


def applied_loads(scene: Scene, kin: Kinematics, arms: dict | None = None
                  ) -> tuple[list[PointLoad], np.ndarray]:
    """Gravity (at every cog) and the scene's ``[[loads]]``.

    Returns the loads and the ``undefined_load`` mask: rows where a ``resist`` point
    stands still (its speed at most 1e-9 of its top speed, or of the mechanism's speed
    scale if larger: :func:`motion_scales`), where that force is zero, and rows where a
    ``when = "resisting"`` force's power is at most 1e-9 of its top (the force switches
    there; it is taken as zero).

    ``arms``: the arms of the cogs :func:`inertia_loads` put there, and the loads for
    :func:`resultants` alone: a weight's component along an axis without gravity is
    the number 0.0 (a stack's masses times 0.0 are zeros over its rows: what the sums
    skip, :func:`resultants`), not an array.
    """
    n = kin.n
    undefined = np.zeros(n, dtype=bool)
    out = []
    vscale = motion_scales(scene)[0]
    gx, gy = scene.gravity
    if gx or gy:
        for name, body in scene.bodies.items():
            if body.mass > 0.0:
                arm = arms.get(name) if arms is not None else None
                rx, ry = arm or kin.bodies[name].rotate(*body.cog)
                mass = body.mass
                fx, fy = (0.0 if arms is not None and gg == 0.0 else mass * gg
                          for gg in (gx, gy))
                out.append(PointLoad(name, "gravity", rx, ry, fx, fy, 0.0, "weight"))
    for i, load in enumerate(scene.loads):
        m = kin.bodies[load.body]
        body = scene.bodies[load.body]
        if load.point is None:
            out.append(PointLoad(load.body, "applied", 0.0, 0.0, 0.0, 0.0, load.moment,
                                 f"load {i}"))
            continue
        rx, ry = m.rotate(*body.local(load.point))
        if load.resist is not None:
            vx, vy = m.vel_arm(rx, ry)
            vx, vy = np.broadcast_to(vx, (n,)), np.broadcast_to(vy, (n,))
            speed = np.hypot(vx, vy)
            still = _still(speed, scene, vscale, i)
            undefined |= still
            # (divided by 1 where the point stands still, not by 0: no 0/0 to ignore,
            # the same numbers elsewhere)
            moving = np.where(still, 1.0, speed)
            fx = np.where(still, 0.0, -load.resist * vx / moving)
            fy = np.where(still, 0.0, -load.resist * vy / moving)
        elif load.force is not None and load.when == "resisting":
            # on the working stroke only: the force acts where its power is negative;
            # where the point stands still (|power| <= 1e-9 of its top) it is undefined
            fx, fy = float(load.force[0]), float(load.force[1])
            vx, vy = m.vel_arm(rx, ry)
            power = np.broadcast_to(fx * vx + fy * vy, (n,))
            still = _still(np.abs(power), scene, math.hypot(fx, fy) * vscale, i)
            undefined |= still
            on = (power < 0.0) & ~still
            fx, fy = np.where(on, fx, 0.0), np.where(on, fy, 0.0)
        elif load.force is not None:
            fx, fy = float(load.force[0]), float(load.force[1])
        else:                                   # a moment given with a point
            fx = fy = 0.0
        out.append(PointLoad(load.body, "applied", rx, ry, fx, fy, load.moment,
                             f"load {i} at {load.point}"))
    return out, undefined


def _still(x: np.ndarray, scene: Scene, floor, key: int) -> np.ndarray:
    """Rows where ``x`` (a point's speed, a force's |power|) is at most RESIST_STILL of
    its top over the sweep (at least ``floor``): a block of a long sweep
    (``scene.__dict__["tops"]``, :class:`SweepTops`) measures against the top so far."""
    tops = scene.__dict__.get("tops")
    if tops is not None:
        return tops.still(key, x, floor)
    return x <= RESIST_STILL * _top(x, scene, floor)


class SweepTops:
    """The tops of a long sweep's ``resist`` and ``when = "resisting"`` loads, met block
    by block (:mod:`~kinetostatics.solver.blocks`): each block measures its rows
    against the largest value so far, its own included (at least the floor), a top no
    larger than the sweep's; once every block is solved, :meth:`settle` says whether any
    row of an earlier block lies above its block's threshold and at or below the sweep's
    (its flag would differ: the sweep is then solved in one pass), and from then on
    every block measures against the sweep's top (a block solved again, the same
    numbers as one pass: max is exact). (Measured 2026-11-30, the bundled shaper at 2e5
    rows, numpy path: 150 -> 98 ms a solve in one pass -> in blocks.)"""

    def __init__(self) -> None:
        self.top: dict[int, float] = {}
        self.seen: list[tuple[int, float]] = []    # (key, least x above its threshold)
        self.settled = False

    def still(self, key: int, x: np.ndarray, floor) -> np.ndarray:
        # the order of one pass's max(x.max(), floor): the same double, for finite values
        top = max(x.max() if x.size else 0.0, self.top.get(key, floor))
        self.top[key] = top
        still = x <= RESIST_STILL * top
        if not self.settled:
            self.seen.append((key, float(np.where(still, np.inf, x).min(initial=np.inf))))
        return still

    def settle(self) -> bool:
        """True when every block's flags are the sweep's (none to solve again); from now
        on the sweep's tops are used."""
        self.settled = True
        return all(math.isfinite(t) for t in self.top.values()) and all(
            least > RESIST_STILL * self.top[key] for key, least in self.seen)


def _top(x: np.ndarray, scene: Scene, floor):
    """The largest of ``x`` over the sweep, at least ``floor``; over each scene's own
    rows for a run of stacked scenes (``scene.__dict__["segments"]``: the rows of each,
    one after another, :meth:`~kinetostatics.solver.stack.Stacker.runs`), per row."""
    segments = scene.__dict__.get("segments")
    if segments is None:
        return max(x.max() if x.size else 0.0, floor)
    starts = np.cumsum(segments) - segments
    return np.maximum(np.repeat(np.maximum.reduceat(x, starts), segments), floor)


def resultants(loads: list[PointLoad], names, n: int) -> dict[str, list]:
    """Per body [Fx, Fy, M_O]: the resultant force and its moment about the body's local
    origin O. The three are arrays of their own (accumulated in place: at large sizes a
    fresh array per operation costs more than the arithmetic), each summed from 0.0 in
    the order of ``loads``: a sum of numbers stays a number until its first array term
    (0.0 + x, the same double), and the array is then made by that term's own pass (no
    pass of zeros before it); a sum still a number at the end is laid over the rows.
    (A sum from +0.0 is never -0.0, so the terms the arithmetic skips, exact zeros, leave
    it as it is: :func:`~kinetostatics.solver.arith.iadd`.)"""
    acc = {b: [0.0, 0.0, 0.0] for b in names}
    tmp = None
    iadd, zero, arr = A.iadd, A.zero, np.ndarray
    for ld in loads:
        r = acc[ld.body]
        fx, fy = ld.fx, ld.fy
        # (the moment first: a force's array may then take its sum, _add_term)
        for a, b, sign in ((ld.rx, fy, 1.0), (ld.ry, fx, -1.0)):    # M_O += rx fy - ry fx
            # (zero() of an array is False: not asked, measured 2026-12-01, 10-30 calls
            # a solve fewer)
            if type(a) is not arr and zero(a) or type(b) is not arr and zero(b):
                continue
            if tmp is None:
                tmp = np.empty(n)
            np.multiply(a, b, out=tmp)
            if type(r[2]) is arr:
                iadd(r[2], tmp, sign)
            else:
                _add_term(r, 2, tmp, sign, n, True)
                tmp = None                      # (the scratch array is the sum's now)
        for i, x, name in ((2, ld.m, "m"), (0, fx, "fx"), (1, fy, "fy")):
            if type(r[i]) is arr:
                iadd(r[i], x)
            else:
                _add_term(r, i, x, 1.0, n, name in ld.scratch)
    return {b: [x if type(x) is arr else np.full(n, x) for x in r] for b, r in acc.items()}


def _add_term(r: list, i: int, x, sign: float, n: int, spare: bool = False) -> None:
    """r[i] += sign * x while r[i] is a number: a number plus an array x becomes an array
    (the same operation, elementwise: written into x itself when ``spare``, x a plain
    float array of n values no one else holds, else a new one); two numbers, a number."""
    a = r[i]
    if type(x) is np.ndarray or isinstance(x, np.ndarray):
        # (into a plain array: x may be a stack's Rows, whose type is not wanted here)
        own = spare and A.fresh(x) and x.shape == (n,)
        r[i] = (np.add if sign > 0 else np.subtract)(a, x, out=x if own else np.empty(n))
    elif not A.zero(x):
        r[i] = a + x if sign > 0 else a - x
