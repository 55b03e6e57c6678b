"""Forces in cylindrical gear pairs with fixed axes (seed 002 s. 2.3.3, eqs 2.52-2.59).

The tooth force of gear 1 on gear 2, ``F12 = -F21``, acts along the line of action n-n
through the pitch point P, at the pressure angle ``alpha`` to the common tangent of the
pitch circles, so that its arm about each axis is ``r_w cos(alpha)`` (the base radius).
The seed's sentence puts alpha "between the normal n-n and the line of centres", but its
equations 2.52-2.58 (arm ``r_w2 cos alpha``) measure it from the tangent, as here.

Conventions (the workbench's: SI units, ccw positive, angles in degrees where a name ends
in ``_deg``):

- ``M2`` is the resisting moment of the driven gear 2, signed as the torque that gear 2
  delivers to the driven machine (ccw positive): the machine acts on gear 2 with ``-M2``.
  A resisting moment opposes the rotation, so ``M2`` has the sign of ``omega2`` when the
  pair works as a reducer or multiplier driven through gear 1. In the seed's figures
  (figs 2.22-2.23) every quantity is a magnitude; with this sign convention its results
  hold as signed identities.
- ``Me`` is the equilibrating moment that the actuator applies to gear 1, ccw positive.
- ``i12 = omega1 / omega2`` is the *signed* transmission ratio: ``-r_w2 / r_w1`` for an
  external pair (the gears turn in opposite senses), ``+r_w2 / r_w1`` for an internal one.
  The seed prints ``i12 = r_w2 / r_w1`` for both (a magnitude); then
  ``Me = M2 / i12`` (eqs 2.55, 2.59) holds with signs, and without friction the power
  balances: ``Me omega1 = M2 omega2``.
- Geometry: gear 1 turns about ``O1``; the line of centres points from ``O1`` to ``O2`` at
  ``centre_angle_deg``. External pair: ``O1O2 = r_w1 + r_w2`` and P between the axes.
  Internal pair: the larger gear is the ring (internal teeth), ``O1O2 = |r_w2 - r_w1|``.

Every function accepts arrays of ``M2`` (e.g. over the positions of a cycle) and
broadcasts them against the radii.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from ..common.angles import radian_column, radian_value
from ..model.errors import WorkbenchError

__all__ = [
    "GearError", "GearPair", "GearStage", "GearTrain", "equilibrating_moment", "gear_pair",
    "gear_ratio", "gear_train", "tooth_force", "tooth_force_components",
]


class GearError(WorkbenchError):
    """A gear pair or train that cannot be posed (bad radius, pressure angle, stages)."""


# --------------------------------------------------------------------------- checks

def _radii(r_w1: Any, r_w2: Any, internal: bool) -> tuple[np.ndarray, np.ndarray]:
    r1 = np.asarray(r_w1, dtype=float)
    r2 = np.asarray(r_w2, dtype=float)
    if not (np.all(np.isfinite(r1)) and np.all(np.isfinite(r2))):
        raise GearError("the working radii r_w1, r_w2 must be finite numbers")
    if np.any(r1 <= 0.0) or np.any(r2 <= 0.0):
        raise GearError(f"the working radii must be > 0 m (got r_w1 = {r_w1}, r_w2 = {r_w2})")
    if internal and np.any(r1 == r2):
        raise GearError("an internal pair needs different radii (the ring is the larger gear); "
                        f"r_w1 = r_w2 = {r_w1} m gives a zero centre distance")
    return r1, r2


def _alpha(alpha_deg: Any) -> np.ndarray:
    a = np.asarray(alpha_deg, dtype=float)
    if not np.all(np.isfinite(a)) or np.any(a < 0.0) or np.any(a >= 90.0):
        raise GearError(f"the pressure angle must lie in [0, 90) deg, not {alpha_deg} "
                        "(20 deg for standard gears)")
    return radian_column(a)


def _moment(M: Any, name: str) -> np.ndarray:
    m = np.asarray(M, dtype=float)
    if not np.all(np.isfinite(m)):
        raise GearError(f"{name} must be finite (N m)")
    return m


# --------------------------------------------------------------------------- scalar relations

def gear_ratio(r_w1: Any, r_w2: Any, internal: bool = False) -> np.ndarray | float:
    """Signed transmission ratio ``i12 = omega1 / omega2`` of a gear pair.

    Parameters
    ----------
    r_w1, r_w2 : float or array_like
        Working (rolling) radii of the driving gear 1 and the driven gear 2, m.
    internal : bool
        True for an internal pair (one of the gears is a ring with internal teeth).

    Returns
    -------
    float or ndarray
        ``-r_w2 / r_w1`` (external: opposite senses) or ``+r_w2 / r_w1`` (internal: the
        same sense). The seed's i12 (eqs 2.55, 2.59) is its magnitude.

    Examples
    --------
    >>> gear_ratio(0.05, 0.2), gear_ratio(0.05, 0.2, internal=True)
    (-4.0, 4.0)
    """
    r1, r2 = _radii(r_w1, r_w2, internal)
    i = (1.0 if internal else -1.0) * r2 / r1
    return float(i) if i.ndim == 0 else i


def tooth_force(M2: Any, r_w2: Any, alpha_deg: Any = 20.0) -> np.ndarray | float:
    """Magnitude of the tooth force ``|F12| = |M2| / (r_w2 cos alpha)`` (eqs 2.53, 2.57).

    Parameters
    ----------
    M2 : float or array_like
        Resisting moment on the driven gear 2, N m (its sign does not matter here).
    r_w2 : float or array_like
        Working radius of gear 2, m.
    alpha_deg : float
        Pressure angle, deg, in [0, 90).

    Returns
    -------
    float or ndarray
        ``|F12| = |F21|``, N; the same for external and internal pairs.
    """
    m = _moment(M2, "M2")
    _, r2 = _radii(1.0, r_w2, False)
    f = np.abs(m) / (r2 * np.cos(_alpha(alpha_deg)))
    return float(f) if f.ndim == 0 else f


def tooth_force_components(M2: Any, r_w2: Any,
                           alpha_deg: Any = 20.0) -> tuple[np.ndarray, np.ndarray]:
    """Tangential and radial components of the tooth force (magnitudes).

    ``Ft = |F12| cos alpha = |M2| / r_w2`` along the common tangent of the pitch circles
    (it carries the moment, eq. 2.52) and ``Fr = |F12| sin alpha = Ft tan alpha`` along
    the line of centres (it pushes the teeth apart and loads the bearings only).

    Returns
    -------
    (Ft, Fr) : ndarrays (or floats), N
    """
    m = _moment(M2, "M2")
    _, r2 = _radii(1.0, r_w2, False)
    ft = np.abs(m) / r2
    fr = ft * np.tan(_alpha(alpha_deg))
    if ft.ndim == 0 and fr.ndim == 0:
        return float(ft), float(fr)
    return ft, fr


def equilibrating_moment(M2: Any, r_w1: Any, r_w2: Any,
                         internal: bool = False) -> np.ndarray | float:
    """Equilibrating moment on the driving gear: ``Me = M2 r_w1 / r_w2 = M2 / i12``.

    Eqs 2.54-2.55 (external pair) and 2.58-2.59 (internal pair), with the signed ratio
    of :func:`gear_ratio`; the pressure angle cancels out. Without friction the power
    balances: ``Me omega1 = M2 omega2``.

    Parameters
    ----------
    M2 : float or array_like
        Resisting moment of gear 2 (N m; sign convention in the module docstring).
    r_w1, r_w2 : float or array_like
        Working radii, m.
    internal : bool
        True for an internal pair.

    Returns
    -------
    float or ndarray
        Me, N m, ccw positive, on gear 1.

    Examples
    --------
    >>> equilibrating_moment(120.0, 0.05, 0.2)       # external: gear 1 turns the other way
    -30.0
    """
    m = _moment(M2, "M2")
    i12 = np.asarray(gear_ratio(r_w1, r_w2, internal))
    me = m / i12
    return float(me) if me.ndim == 0 else me


# --------------------------------------------------------------------------- vector solution

@dataclass(frozen=True)
class GearPair:
    """Forces of a gear pair in equilibrium (arrays over the values of ``M2``).

    Attributes
    ----------
    i12 : float
        Signed transmission ratio omega1 / omega2.
    M2, Me : ndarray
        Resisting moment of gear 2 and equilibrating moment on gear 1 (N m, ccw positive).
    F : ndarray
        |F12| = |F21| (eqs 2.53, 2.57), N.
    Ft, Fr : ndarray
        Its tangential and radial components (magnitudes), N.
    F12x, F12y : ndarray
        Tooth force of gear 1 on gear 2 at the pitch point, global components, N.
    F01x, F01y, F02x, F02y : ndarray
        Bearing reactions of the ground on gears 1 and 2 (``F01 = -F21``, ``F02 = -F12``).
    O1, O2, P : tuple of float
        Axes of the gears and the pitch point, m.
    internal : bool
    alpha_deg : float
    """

    i12: float
    M2: np.ndarray
    Me: np.ndarray
    F: np.ndarray
    Ft: np.ndarray
    Fr: np.ndarray
    F12x: np.ndarray
    F12y: np.ndarray
    F01x: np.ndarray
    F01y: np.ndarray
    F02x: np.ndarray
    F02y: np.ndarray
    O1: tuple[float, float]
    O2: tuple[float, float]
    P: tuple[float, float]
    internal: bool
    alpha_deg: float

    @property
    def F21x(self) -> np.ndarray:
        """Tooth force of gear 2 on gear 1, x component (``-F12x``)."""
        return -self.F12x

    @property
    def F21y(self) -> np.ndarray:
        """Tooth force of gear 2 on gear 1, y component (``-F12y``)."""
        return -self.F12y

    def table(self) -> pd.DataFrame:
        """One row per value of M2: ``M2, Me, F, Ft, Fr, F12x, F12y, F01x, F01y, F02x, F02y``."""
        cols = ("M2", "Me", "F", "Ft", "Fr", "F12x", "F12y", "F01x", "F01y", "F02x", "F02y")
        return pd.DataFrame({c: np.atleast_1d(getattr(self, c)) for c in cols})


def _pair_geometry(r1: float, r2: float, internal: bool, theta: float,
                   o1: tuple[float, float]):
    """Unit vectors e1, e2 from each axis to the pitch point, O2 and P (see module doc)."""
    u = np.array([math.cos(theta), math.sin(theta)])
    if not internal:
        e1, e2, dist = u, -u, r1 + r2
    elif r2 > r1:                   # gear 2 is the ring: P beyond O1, away from O2
        e1, e2, dist = -u, -u, r2 - r1
    else:                           # gear 1 is the ring
        e1, e2, dist = u, u, r1 - r2
    O1 = np.asarray(o1, dtype=float)
    O2 = O1 + dist * u
    P = O1 + r1 * e1
    return e1, e2, O2, P


def gear_pair(M2: Any, r_w1: float, r_w2: float, alpha_deg: float = 20.0,
              internal: bool = False, centre_angle_deg: float = 0.0,
              O1: Sequence[float] = (0.0, 0.0)) -> GearPair:
    """Tooth force, equilibrating moment and bearing reactions of a gear pair.

    Gear 2 (eq. 2.52 / 2.56, moments about O2): the moment of F12 about O2 equals M2 (the
    machine acts with -M2), so the tangential component is ``M2 / r_w2`` and
    ``|F12| = |M2| / (r_w2 cos alpha)`` (eq. 2.53 / 2.57); its radial component
    ``|F12| sin alpha`` presses the teeth together (towards the centre of a gear with
    external teeth, outwards on a ring). Forces on gear 2: ``F02 = -F12``. Gear 1
    (eq. 2.54 / 2.58, moments about O1): ``Me = (P - O1) x F12 = M2 / i12`` (eq. 2.55 /
    2.59) and ``F01 = -F21 = F12``. Gravity and the gears' inertia are not included.

    Parameters
    ----------
    M2 : float or array_like
        Resisting moment of gear 2, N m (module docstring: the torque gear 2 delivers).
    r_w1, r_w2 : float
        Working radii of the driving gear 1 and the driven gear 2, m.
    alpha_deg : float
        Pressure angle (from the common tangent), deg, in [0, 90).
    internal : bool
        Internal pair: the larger gear is the ring.
    centre_angle_deg : float
        Direction of the line of centres O1 -> O2, deg from +x.
    O1 : (float, float)
        Axis of gear 1, m.

    Returns
    -------
    GearPair

    Raises
    ------
    GearError
        Radii not positive, equal radii of an internal pair, pressure angle out of range.

    Examples
    --------
    >>> g = gear_pair(120.0, 0.05, 0.15)
    >>> round(float(g.Me), 6), round(float(g.F), 3)
    (-40.0, 851.342)
    """
    m2 = _moment(M2, "M2")
    r1a, r2a = _radii(r_w1, r_w2, internal)
    if r1a.ndim or r2a.ndim:
        raise GearError("gear_pair takes one pair of radii (floats); M2 may be an array")
    r1, r2 = float(r1a), float(r2a)
    alpha = float(_alpha(alpha_deg))
    e1, e2, O2, P = _pair_geometry(r1, r2, internal, radian_value(float(centre_angle_deg)),
                                   tuple(O1))
    w2 = np.array([-e2[1], e2[0]])              # k x e2: ccw tangent of gear 2 at P
    ft = m2 / r2                                 # eq. 2.52: r_w2 * (F12 . w2) = M2
    fr_mag = np.abs(ft) * math.tan(alpha)
    fr = fr_mag if internal and r2 > r1 else -fr_mag   # along e2: out on a ring, in otherwise
    f12x = ft * w2[0] + fr * e2[0]
    f12y = ft * w2[1] + fr * e2[1]
    # eq. 2.54 / 2.58: moments about O1 of gear 1, (P - O1) x F21 + Me = 0
    me = r1 * (e1[0] * f12y - e1[1] * f12x)
    i12 = float(gear_ratio(r1, r2, internal))
    F = np.abs(m2) / (r2 * math.cos(alpha))      # eqs 2.53, 2.57
    o1 = np.asarray(O1, dtype=float)
    return GearPair(i12=i12, M2=m2, Me=me, F=F, Ft=np.abs(ft), Fr=fr_mag,
                    F12x=f12x, F12y=f12y, F01x=f12x, F01y=f12y, F02x=-f12x, F02y=-f12y,
                    O1=(float(o1[0]), float(o1[1])), O2=(float(O2[0]), float(O2[1])),
                    P=(float(P[0]), float(P[1])), internal=internal,
                    alpha_deg=float(alpha_deg))


# --------------------------------------------------------------------------- trains

@dataclass(frozen=True)
class GearStage:
    """One meshing pair of a train with fixed axes.

    ``r_w1`` is the driving gear on shaft k, ``r_w2`` the driven gear on shaft k + 1;
    ``centre_angle_deg`` the direction from shaft k to shaft k + 1. An idler gear is a
    shaft whose driving radius equals its driven radius.
    """

    r_w1: float
    r_w2: float
    internal: bool = False
    centre_angle_deg: float = 0.0


@dataclass(frozen=True)
class GearTrain:
    """A train of pairs with fixed axes in equilibrium.

    Attributes
    ----------
    i : float
        Overall signed ratio omega_1 / omega_last (product of the stages' i12).
    Me : ndarray
        Equilibrating moment on the first shaft, ``M_out / i`` (N m).
    pairs : list of GearPair
        Stage k's forces; its ``M2`` is the moment that shaft k + 1 receives through it.
    shafts : list of (float, float)
        Axes of the shafts, m.
    bearings : list of (ndarray, ndarray)
        (Fx, Fy) of the ground on each shaft: minus the sum of its tooth forces.
    """

    i: float
    Me: np.ndarray
    pairs: list[GearPair]
    shafts: list[tuple[float, float]]
    bearings: list[tuple[np.ndarray, np.ndarray]]

    def table(self) -> pd.DataFrame:
        """One row per stage for the first value of M_out: ratio, moments and forces."""
        rows = []
        for k, p in enumerate(self.pairs):
            rows.append({"stage": k + 1, "i12": p.i12, "M_in": float(np.ravel(p.Me)[0]),
                         "M_out": float(np.ravel(p.M2)[0]), "F": float(np.ravel(p.F)[0]),
                         "Ft": float(np.ravel(p.Ft)[0]), "Fr": float(np.ravel(p.Fr)[0])})
        return pd.DataFrame(rows)


def gear_train(M_out: Any, stages: Sequence[GearStage | tuple], alpha_deg: float = 20.0,
               O1: Sequence[float] = (0.0, 0.0)) -> GearTrain:
    """A train of gear pairs with fixed axes, solved pair by pair from the output.

    The seed (end of s. 2.3.3) says trains are solved "in the same way" as one pair: the
    last pair carries ``M_out`` (eqs 2.52-2.55 or 2.56-2.59); the moment its driving gear
    needs is the resisting moment the previous pair must deliver (shaft equilibrium), and
    so on to the first shaft, where ``Me = M_out / (i_1 i_2 ... i_k)``.

    Parameters
    ----------
    M_out : float or array_like
        Resisting moment on the last shaft, N m (the :func:`gear_pair` convention).
    stages : sequence of GearStage or (r_w1, r_w2[, internal[, centre_angle_deg]])
        From the driving shaft to the output shaft.
    alpha_deg : float
        Pressure angle of every pair, deg.
    O1 : (float, float)
        Axis of the first shaft, m.

    Returns
    -------
    GearTrain

    Examples
    --------
    >>> t = gear_train(90.0, [(0.02, 0.06), (0.03, 0.09)])
    >>> t.i, round(float(t.Me), 9)
    (9.0, 10.0)
    """
    if len(stages) == 0:
        raise GearError("a gear train needs at least one stage")
    st = [s if isinstance(s, GearStage) else GearStage(*s) for s in stages]
    m = _moment(M_out, "M_out")
    # positions of the shafts, from the first
    shafts = [tuple(float(v) for v in O1)]
    for s in st:
        r1, r2 = _radii(s.r_w1, s.r_w2, s.internal)
        dist = float(r1 + r2) if not s.internal else abs(float(r2 - r1))
        th = radian_value(float(s.centre_angle_deg))
        x, y = shafts[-1]
        shafts.append((x + dist * math.cos(th), y + dist * math.sin(th)))
    # moments from the output back to the input (shaft equilibrium: M2_(k-1) = Me_k)
    pairs: list[GearPair] = [None] * len(st)  # type: ignore[list-item]
    moment = m
    for k in range(len(st) - 1, -1, -1):
        s = st[k]
        pairs[k] = gear_pair(moment, s.r_w1, s.r_w2, alpha_deg, s.internal,
                             s.centre_angle_deg, shafts[k])
        moment = pairs[k].Me
    i_total = float(np.prod([p.i12 for p in pairs]))
    bearings = []
    for j in range(len(shafts)):
        fx = np.zeros_like(m)
        fy = np.zeros_like(m)
        if j > 0:                               # driven gear of stage j - 1: receives F12
            fx = fx + pairs[j - 1].F12x
            fy = fy + pairs[j - 1].F12y
        if j < len(pairs):                      # driving gear of stage j: receives F21
            fx = fx - pairs[j].F12x
            fy = fy - pairs[j].F12y
        bearings.append((-fx, -fy))
    return GearTrain(i=i_total, Me=pairs[0].Me, pairs=pairs, shafts=shafts, bearings=bearings)
