"""Shaking force and moment, centre of mass and the seed's h vectors over the sweep
(seed 002 s. 3.4, eqs 3.32-3.37), with and without counterweights.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np
import pandas as pd

from kinetostatics.model.scene import GROUND, Scene
from kinetostatics.solver.arith import full
from kinetostatics.solver.kinematics import BodyMotion, Kinematics

from ..errors import BalanceError
from .counterweights import CounterRotatingPair, Counterweight
from .linkage import first_moment, recognise, vec

__all__ = [
    "as_kinematics",
    "centre_of_mass",
    "crank_axis",
    "h_vectors",
    "harmonic_amplitude",
    "motion_at",
    "pair_motion",
    "point_masses",
    "shaking_force",
]


# -- motion helpers ---------------------------------------------------------------------------

def as_kinematics(sol: Any) -> Kinematics:
    """A Kinematics from a Solution (``.kin``), a Kinematics or a MechanismBalancing."""
    kin = getattr(sol, "kin", sol)
    if not isinstance(kin, Kinematics):
        raise BalanceError(f"expected a kinetostatics Solution or Kinematics, not "
                           f"{type(sol).__name__}")
    return kin


def motion_at(bm: BodyMotion, local: Iterable[float], n: int) -> tuple[np.ndarray, ...]:
    """x, y, vx, vy, ax, ay (arrays) of a body's local point."""
    lx, ly = (float(t) for t in local)
    rx, ry = bm.rotate(lx, ly)
    x, y = bm.ox + rx, bm.oy + ry
    vx, vy = bm.vel_arm(rx, ry)
    ax, ay = bm.acc_arm(rx, ry)
    return tuple(full(t, n) for t in (x, y, vx, vy, ax, ay))


def point_masses(kin: Kinematics, counterweights: Iterable[Counterweight]):
    """(body, mass, local point, inertia) of every body cog and counterweight."""
    for name, body in kin.scene.bodies.items():
        if body.mass != 0.0 or body.inertia != 0.0:
            yield name, body.mass, body.local("cog"), body.inertia
    for cw in counterweights:
        if cw.mass != 0.0:
            yield cw.body, cw.mass, cw.position, 0.0


def crank_axis(scene: Scene) -> tuple[float, float]:
    drv = scene.driver
    if drv.kind != "R":
        return (0.0, 0.0)
    return scene.ground[scene.joints[drv.joint].point_on(GROUND)]


def pair_motion(kin: Kinematics, pair: CounterRotatingPair):
    """(x, y, ax, ay) arrays of the co- and counter-rotating masses."""
    n = kin.n
    crank = kin.bodies[kin.scene.driver.body]
    th = full(crank.theta, n)
    w = full(crank.omega, n)
    eps = full(crank.alpha, n)
    out = []
    for sign, phase in ((1.0, pair.co_angle), (-1.0, pair.counter_angle)):
        # degrees kept (10/10): the pair's phases are degrees (CounterRotatingPair)
        ang = sign * th + math.radians(phase)
        c, s = np.cos(ang), np.sin(ang)
        x = pair.axis[0] + pair.radius * c
        y = pair.axis[1] + pair.radius * s
        # a = r (theta'' J e - theta'^2 e), theta' = +-omega, theta'' = +-eps
        ax = pair.radius * (-sign * eps * s - w * w * c)
        ay = pair.radius * (sign * eps * c - w * w * s)
        out.append((x, y, ax, ay))
    return out


# -- public tables ----------------------------------------------------------------------------

def shaking_force(sol: Any, counterweights: Iterable[Counterweight] = (),
                  pair: CounterRotatingPair | None = None,
                  about: tuple[float, float] | None = None) -> pd.DataFrame:
    """Shaking force and moment over the sweep: the resultant of the inertia loads.

    F = sum -m_i a_Gi over the moving bodies and the counterweights (and the pair), the
    force the mechanism's inertia puts on the frame (s. 3.4: F_i = -m a_G); M its
    moment about ``about`` (default the crank axis), with the couples -I_Gi eps_i.

    Parameters
    ----------
    sol : kinetostatics.Solution or Kinematics
        The motion over the sweep.
    counterweights : iterable of Counterweight
        Point masses fixed to bodies.
    pair : CounterRotatingPair, optional
        The masses of eqs 3.52-3.53.
    about : (x, y), optional
        Reference point of the moment (m); default the crank axis.

    Returns
    -------
    pandas.DataFrame
        ``position, Fx, Fy, F, M`` (N, N m).
    """
    kin = as_kinematics(sol)
    n = kin.n
    x0, y0 = about if about is not None else crank_axis(kin.scene)
    fx, fy, mz = np.zeros(n), np.zeros(n), np.zeros(n)
    for name, m, local, inertia in point_masses(kin, counterweights):
        bm = kin.bodies[name]
        x, y, _, _, ax, ay = motion_at(bm, local, n)
        gx, gy = -m * ax, -m * ay
        fx += gx
        fy += gy
        mz += (x - x0) * gy - (y - y0) * gx - inertia * full(bm.alpha, n)
    if pair is not None and pair.mass != 0.0:
        for x, y, ax, ay in pair_motion(kin, pair):
            gx, gy = -pair.mass * ax, -pair.mass * ay
            fx += gx
            fy += gy
            mz += (x - x0) * gy - (y - y0) * gx
    return pd.DataFrame({"position": kin.positions, "Fx": fx, "Fy": fy, "F": np.hypot(fx, fy),
                         "M": mz})


def centre_of_mass(sol: Any, counterweights: Iterable[Counterweight] = ()) -> pd.DataFrame:
    """The mechanism's centre of mass over the sweep, eq. 3.32: m r_G = sum m_i r_i.

    Parameters
    ----------
    sol : kinetostatics.Solution or Kinematics
    counterweights : iterable of Counterweight
        Added point masses (a balanced mechanism).

    Returns
    -------
    pandas.DataFrame
        ``position, x, y, vx, vy, ax, ay, mass`` (m, m/s, m/s^2, kg) of the centre of
        mass of the moving bodies and counterweights.
    """
    kin = as_kinematics(sol)
    n = kin.n
    acc = np.zeros((6, n))
    total = 0.0
    for name, m, local, _ in point_masses(kin, counterweights):
        if m == 0.0:
            continue
        acc += m * np.array(motion_at(kin.bodies[name], local, n))
        total += m
    if total == 0.0:
        raise BalanceError("the mechanism has no mass: its centre of mass is undefined")
    x, y, vx, vy, ax, ay = acc / total
    return pd.DataFrame({"position": kin.positions, "x": x, "y": y, "vx": vx, "vy": vy,
                         "ax": ax, "ay": ay, "mass": total})


def h_vectors(sol: Any, counterweights: Iterable[Counterweight] = ()) -> pd.DataFrame:
    """The seed's h vectors over the sweep (eqs 3.33-3.37).

    Along the serial chain A-B-C(-D) of a four-bar or slider-crank (crank, coupler or
    rod, rocker or piston), body i with mass m_i (counterweights included), cog s_i and
    link l_i measured from its first joint gives

        h_i = (m_i s_i + (m_(i+1) + ... + m_n) l_i) / m          (3.36)

    and r_G = A + h_1 + ... + h_n (3.37), A the crank axis. Each h_i is fixed in its
    body: constant length, turning with it.

    Returns
    -------
    pandas.DataFrame
        ``position, body, hx, hy, h`` (m, global components), one row per body and
        position, in chain order.
    """
    kin = as_kinematics(sol)
    sc = kin.scene
    lk = recognise(sc)
    cws = list(counterweights)
    chain = lk.chain()
    mass, first = [], []
    for name, p, _ in chain:
        body = sc.bodies[name]
        ref = vec(body.points[p])
        m = body.mass + sum(c.mass for c in cws if c.body == name)
        s = first_moment(body, ref) + sum((c.mass * (vec(c.position) - ref) for c in cws
                                      if c.body == name), np.zeros(2))
        mass.append(m)
        first.append(s)
    total = sum(mass)
    if total == 0.0:
        raise BalanceError("the mechanism has no mass: the h vectors are undefined")
    parts = []
    n = kin.n
    for i, (name, p, q) in enumerate(chain):
        body = sc.bodies[name]
        link = vec(body.points[q]) - vec(body.points[p]) if q is not None else np.zeros(2)
        h = (first[i] + sum(mass[i + 1:]) * link) / total          # local, eq. 3.36
        hx, hy = kin.bodies[name].rotate(float(h[0]), float(h[1]))
        hx, hy = full(hx, n), full(hy, n)
        parts.append(pd.DataFrame({"position": kin.positions, "body": name, "hx": hx, "hy": hy,
                                   "h": np.hypot(hx, hy)}))
    return pd.concat(parts, ignore_index=True)


def harmonic_amplitude(values: Any, order: int = 1) -> float:
    """Amplitude of one harmonic of a periodic signal sampled at N uniformly spaced
    positions of one full cycle (the endpoint not repeated): 2 |FFT_k| / N.

    Parameters
    ----------
    values : array_like
        The samples.
    order : int
        The harmonic k >= 1 (k < N / 2).

    Examples
    --------
    >>> t = np.linspace(0.0, 2.0 * np.pi, 360, endpoint=False)
    >>> round(harmonic_amplitude(3.0 * np.cos(t) + np.sin(2 * t), 1), 12)
    3.0
    """
    v = np.asarray(values, dtype=float)
    if not 1 <= order < v.size / 2:
        raise BalanceError(f"harmonic {order} needs more than {2 * order} samples, "
                           f"got {v.size}")
    return float(2.0 * np.abs(np.fft.rfft(v)[order]) / v.size)


