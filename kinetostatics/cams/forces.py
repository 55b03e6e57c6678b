"""Forces on the follower and the critical transmission angle (seed 002 s. 1.5, eqs
1.39-1.43), and the cam's table over the cycle.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd

from ..common.angles import degree_column, degree_value
from .followers import (
    Follower,
    TranslatingFollower,
    profile,
    transmission_angle,
)
from .laws import (
    CamError,
    CamLaw,
)

# --------------------------------------------------------------------------- forces

def critical_transmission_angle(mu: float, a: Any, b: float) -> np.ndarray:
    """Critical transmission angle of a translating follower, tan tau_cr = mu (2a + b)/b (1.44).

    ``a``: distance from the contact point to the guide (m), ``b``: guide length (m).
    """
    return np.arctan(mu * (2.0 * np.asarray(a, dtype=float) + b) / b)


def translating_follower_forces(load: Any, tau: Any, mu: float = 0.0, a: Any = 0.0,
                                b: float = 1.0, direction: Any = 1.0,
                                angles: Any = None) -> tuple[np.ndarray, ...]:
    """Contact force F12 and guide reactions N1, N2 of a translating follower (eqs 1.39-1.43).

    Equilibrium along the axis, F12 sin tau - F - sgn(v) mu (N1 + N2) = 0 (eq. 1.39, the seed
    writes the rise, sgn(v) = +1; friction opposes the follower's velocity, and vanishes in
    a dwell), and moments about the guide ends (eq. 1.40, friction moments neglected as in
    the seed): N1 = (a + b)/b F12 cos tau (1.41), N2 = a/b F12 cos tau (1.42), hence
    F12 = F / (sin tau - sgn(v) mu (2a + b)/b cos tau) (1.43).

    Parameters
    ----------
    load : array_like
        F, N: the axial load on the follower, positive towards the cam (it resists the rise).
    tau : array_like
        Transmission angle, rad.
    mu : float
        Friction coefficient in the guide.
    a : array_like
        Distance from the contact point to the near end of the guide, m.
    b : float
        Guide length, m.
    direction : array_like
        Sign of the follower's velocity (+1 rise, -1 return, 0 dwell).
    angles : array_like, optional
        Cam angles (rad) of the rows, only to name the row in an error.

    Returns
    -------
    F12, N1, N2 : numpy.ndarray
        N. F12 < 0 means the cam would have to pull: contact is lost.

    Raises
    ------
    CamError
        Where the denominator of eq. 1.43 is not positive: self-locking (tau <= tau_cr, 1.44).
    """
    load, tau, a, sgn = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                              for v in (load, tau, a, direction)))
    k = mu * (2.0 * a + b) / b
    den = np.sin(tau) - np.sign(sgn) * k * np.cos(tau)
    bad = den <= 1e-12
    if np.any(bad):
        i = int(np.argmax(bad.ravel()))
        raise CamError(f"the follower self-locks {_row(angles, i)}: transmission angle "
                       f"{degree_value(tau.ravel()[i]):.4g} deg <= critical "
                       f"{degree_value(math.atan(k.ravel()[i])):.4g} deg (eq. 1.44); enlarge "
                       "the base radius, shorten the overhang a or lower the friction")
    f12 = load / den
    ct = f12 * np.cos(tau)
    return f12, (a + b) / b * ct, a / b * ct


def _row(angles: Any, i: int) -> str:
    if angles is None:
        return f"at row {i}"
    return f"at cam angle {degree_value(float(np.ravel(angles)[i])):.6g} deg"


def critical_transmission_angle_oscillating(mu: float, pin_radius: float, arm: float) -> float:
    """Critical transmission angle of an oscillating follower, sin tau_cr = mu r / L (1.48)."""
    return math.asin(min(mu * pin_radius / arm, 1.0))


def oscillating_follower_force(moment: Any, tau: Any, arm: float, mu: float = 0.0,
                               pin_radius: float = 0.0, direction: Any = 1.0,
                               angles: Any = None) -> np.ndarray:
    """Contact force F12 on an oscillating follower (eqs 1.46-1.47).

    Moments about the pivot C: F12 L sin tau - M - sgn(dbeta) Mf = 0 with the pin friction
    moment Mf = mu r F02 and F02 = F12 (eq. 1.46), so F12 = M / (L sin tau - sgn mu r)
    (eq. 1.47). ``moment``: M, N m, resisting the rise; ``direction``: sign of the swing
    velocity. Raises :class:`CamError` where the denominator is not positive (1.48).
    """
    moment, tau, sgn = np.broadcast_arrays(*(np.asarray(v, dtype=float)
                                             for v in (moment, tau, direction)))
    den = arm * np.sin(tau) - np.sign(sgn) * mu * pin_radius
    bad = den <= 1e-12 * arm
    if np.any(bad):
        i = int(np.argmax(bad.ravel()))
        cr = degree_value(critical_transmission_angle_oscillating(mu, pin_radius, arm))
        raise CamError(f"the follower self-locks {_row(angles, i)}: transmission angle "
                       f"{degree_value(tau.ravel()[i]):.4g} deg <= critical {cr:.4g} deg "
                       "(eq. 1.48)")
    return moment / den


# --------------------------------------------------------------------------- tables

def cam_angles(count: int) -> np.ndarray:
    """The cam angles of a table of ``count`` rows over one turn, rad (both ends included:
    the ``angle`` column is their value in degrees, 0 to 360)."""
    return np.linspace(0.0, 2.0 * np.pi, count)


def cam_table(law: CamLaw, follower: Follower, count: int = 361, speed: float = 1.0,
              rotation: str = "ccw") -> pd.DataFrame:
    """Motion, transmission angle and profile of a cam over one turn.

    Parameters
    ----------
    law : CamLaw
    follower : TranslatingFollower or OscillatingFollower
    count : int
        Rows at cam angles numpy.linspace(0, 360, count) deg.
    speed : float
        Cam speed omega, rad/s, for the follower's velocity and acceleration.
    rotation : {"ccw", "cw"}

    Returns
    -------
    pandas.DataFrame
        ``angle`` (deg); translating: ``s, ds, dds, v, a`` (m, m/rad, m/rad^2, m/s, m/s^2);
        oscillating: ``beta`` (deg), ``dbeta, ddbeta`` (rad/rad, rad/rad^2), ``omega2,
        eps2`` (rad/s, rad/s^2); then ``tau, pressure_angle`` (deg) and the columns of
        :func:`profile`.
    """
    if count < 2:
        raise CamError("count must be at least 2")
    phi = cam_angles(count)
    s, ds, dds = law(phi)
    tau = transmission_angle(law, follower, phi)
    if isinstance(follower, TranslatingFollower):
        cols = {"s": s, "ds": ds, "dds": dds, "v": speed * ds, "a": speed**2 * dds}
    else:
        cols = {"beta": degree_column(s), "dbeta": ds, "ddbeta": dds, "omega2": speed * ds,
                "eps2": speed**2 * dds}
    table = pd.DataFrame({"angle": degree_column(phi), **cols, "tau": degree_column(tau),
                          "pressure_angle": 90.0 - degree_column(tau)})
    prof = profile(law, follower, phi, rotation).drop(columns="angle")
    return pd.concat([table, prof], axis=1)
