"""A proven bound on how fast a mechanism's closeness to a dead centre can change: the
dead-point screen's intervals that cannot hold a dead point, known from their rows alone
(no probe; numpy, no numba: the compiled path's ``screen.cleared`` makes the same
verdicts in one compiled pass).

m^2 (the smallest over the dyads of sin^2 tau and, for RRR and RTR, (pivots' distance /
size)^2, ``deadpoints.measure2``) is, wherever the chain closes, a Lipschitz function of
the crank's angle theta: |d m^2 / d theta| <= L, L from the link lengths alone
(:func:`lipschitz`). Between rows x0 < x1 (h = x1 - x0, rad) it is then at least
(m0^2 + m1^2 - L h) / 2 (the lower of the two cones from the rows' values; one row's
value alone: m^2 - L h). Where that is above :data:`CLEAR` no probe can find m^2 <= 1e-6
(``SINGULAR_WARN^2``: no dead point), and none can find a dyad that does not close: a
dyad's m^2 falls to 0 at the edge of its closure (sin tau -> 0, or the RTR's pivots'
distance -> 0 or -> |c|), and m^2 cannot fall there from the row's value inside the
interval. So the screen's verdicts on such an interval (not dead, not unassembled) are
the ones its probes would give, and its probes are left out
(``deadpoints.dead_points_stacked``, ``at.clear``).

The bounds, per dyad (theta in rad; a point's speed |dP / d theta| <= v, its body
turning at |omega| <= w about its outer pivot):

* RTR whose outer pivots are on the ground or the crank: D = G + R(theta) q (G, q from
  the pivots' points), so |D| lies in [| |G| - |q| |, |G| + |q|] and |d|D| / d theta|,
  |dD / d theta| <= |q|. sin^2 tau = 1 - c^2 / |D|^2 (c the slot's offset from the
  guide's pivot, ``rtr_guide_angle``): |d/d theta| <= 2 c^2 |q| / |D|min^3;
  (|D| / size)^2: <= 2 |D|max |q| / size^2. Both its bodies turn with the guide:
  omega = d delta / d theta + d side / d theta, |omega| <= |q| / |D| + |c| |q| /
  (|D| sqrt(|D|^2 - c^2)).
* RRT or TRR whose slider slides on a ground guide (it translates along u): the rod's
  length a = |Q - P| (its points of the inner and outer joints), n = u x (X - P) the
  rod's offset across the guide, sin^2 tau = (u . (X - P))^2 / a^2 = 1 - n^2 / a^2,
  |dn / d theta| <= v(P), |n| <= a where it closes: |d/d theta| <= 2 v(P) / a.
* RRR whose outer pivots are on the ground or the crank (the four-bar): D = P2 - P1 =
  G + R(theta) q as for RTR, d = |D|, a and b its links (outer to inner joint, each
  body's local points). Where it closes, the triangle P1 X P2 has the angle tau at X
  (c1, c2 = J(X - P1), J(X - P2): sin^2 tau = det^2 / (|c1| |c2|)^2, its sine), so
  cos tau = (a^2 + b^2 - d^2) / (2 a b) (the cosine rule) and
  sin^2 tau = 1 - cos^2 tau, a function of d^2 alone:
  d sin^2 tau / d theta = cos tau (d^2)' / (a b). With D' = J R(theta) q,
  (d^2)' = 2 D . D' = 2 (G + R q) . J R q = 2 G . J R q (R q . J R q = 0), so
  |(d^2)'| <= 2 |G| |q| and, |cos tau| <= 1,
  |d sin^2 tau / d theta| <= 2 |G| |q| / (a b); (d / size)^2: <= 2 |G| |q| / size^2.
  (The bound suggested for it, 2 |D|max |q| / (a b), holds too: |G| <= |D|max; both its
  outer pivots on one body, G = 0 or q = 0: d constant, L = 0.) Its edge of closure is
  d = a + b or |a - b|, where sin tau = 0: m^2 falls to 0 there, as the notes above ask.
  Its bodies' turning is not bounded (omega grows as 1 / sin tau near a dead centre):
  a later dyad on them gets no bound.
* anything else: no bound (every interval probed, as before).

:func:`sweep_clear` gives the numpy path's probe of one sweep its ``clear`` (the
geometry from :mod:`~kinetostatics.solver.fast.geometry`, numpy only), told to
:mod:`~kinetostatics.solver.deadpoints` in its ``SWEEP_BOUNDS``.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

import numpy as np

from ...model.scene import GROUND, Scene
from ...model.units import DEG
from ..deadpoints import SWEEP_BOUNDS
from ..memo import record_of
from .geometry import driver_geometry, dyad_geometry
from .layout import (
    D_LX,
    D_LY,
    D_PX,
    D_PY,
    DYAD_GEOMETRY,
    I_RTR,
    P_BX,
    P_BY,
    P_KX,
    P_KY,
    PARAM,
    Q1X,
    Q1Y,
    Q2X,
    Q2Y,
    SIZE,
)

# the lower bound of m^2 above which an interval is clear: 4 SINGULAR_WARN^2 (a dead point
# is m^2 <= 1e-6; the factor 4 leaves the rows' and the probes' rounding, some 1e-16 of
# m^2, far behind)
CLEAR = 4e-6


def lipschitz(crank: bool, gd: np.ndarray, known: np.ndarray, gy: np.ndarray,
              kinds: tuple[str, ...]) -> np.ndarray | None:
    """L per scene (a column of the tables) with |d m^2 / d theta| <= L wherever the chain
    closes, theta the crank's angle (rad); None where no bound is known (a sliding
    driver, a chain of other dyads, an RTR whose slot can reach its pivot's offset:
    every interval probed). ``gd``: the driver's geometry table, ``known``: each dyad's
    outer joints' known bodies (0 the ground, 1 the crank, ``2 + 2 i``, ``3 + 2 i`` dyad
    i's), ``gy``: the dyads' tables (:func:`~.screen.chain_probe`'s)."""
    if not crank:
        return None
    cols = gy.shape[2]
    if cols == 1 and gd.shape[-1] == 1:     # (one column of both: its numbers as floats,
        # numpy's scalars after them, the same doubles: measured 2026-11-30, the
        # shaper's L in some 100 us, not 270 on arrays of one; a stack whose driver
        # alone differs keeps its arrays)
        gd = gd[:, 0].tolist()
        gy = gy[:, :, 0].tolist()
    lx, ly = gd[D_LX], gd[D_LY]
    # each body's turning: its pivot's speed, its omega's bound, its pivot's local point
    turn: dict[int, tuple] = {0: (0.0, 0.0, 0.0, 0.0), 1: (0.0, 1.0, lx, ly)}

    def speed(b: int, px, py):
        v, w, ox, oy = turn[b]
        return v + w * np.hypot(px - ox, py - oy)

    bound = np.zeros(cols)
    with np.errstate(divide="ignore", invalid="ignore"):
        for i, kind in enumerate(kinds):
            g = gy[i]
            if kind == "RTR" and all(int(k) in (0, 1) for k in known[i]):
                here, w = _rtr(g, known[i], gd)
                turn[2 + 2 * i] = (speed(int(known[i][0]), g[P_KX], g[P_KY]), w,
                                   g[P_BX], g[P_BY])
                turn[3 + 2 * i] = (speed(int(known[i][1]), g[PARAM + P_KX], g[PARAM + P_KY]),
                                   w, g[PARAM + P_BX], g[PARAM + P_BY])
            elif kind == "RRR" and all(int(k) in (0, 1) for k in known[i]):
                here = _rrr(g, known[i], gd)
            elif kind in ("RRT", "TRR"):
                r, t = (0, 1) if kind == "RRT" else (1, 0)
                kr = int(known[i][r])
                if int(known[i][t]) != 0 or kr not in turn:
                    return None
                b = PARAM * r
                qx, qy = (g[Q1X], g[Q1Y]) if r == 0 else (g[Q2X], g[Q2Y])
                a = np.hypot(qx - g[b + P_BX], qy - g[b + P_BY])
                here = 2.0 * speed(kr, g[b + P_KX], g[b + P_KY]) / a
            else:
                return None
            bound = np.maximum(bound, here)     # (NaN kept: no bound)
    return np.where(np.isfinite(bound), bound, np.inf)


def known_bodies(drv, chain) -> list | None:
    """Each dyad's outer joints' known bodies (0 the ground, 1 the driver, ``2 + 2 i``,
    ``3 + 2 i`` dyad i's: :func:`lipschitz`'s ``known``) of a driver ``drv`` and the
    dyads ``chain``, or None where one is on a body not yet known."""
    names = {GROUND: 0, drv.body: 1}
    known = []
    for i, d in enumerate(chain):
        pair = [names.get(j.other(b)) for j, b in zip(d.outer, d.bodies, strict=True)]
        if None in pair:
            return None
        known.append(pair)
        names.update({d.bodies[0]: 2 + 2 * i, d.bodies[1]: 3 + 2 * i})
    return known


def _pivots(g: np.ndarray, known: np.ndarray, gd: np.ndarray) -> tuple:
    """A dyad's outer pivots' vector D = P2 - P1 = G + R(theta) q (on the ground (0) or
    the crank (1)): |G| and |q|."""
    ends = []
    for j in (0, 1):
        px, py = g[PARAM * j + P_KX], g[PARAM * j + P_KY]
        if int(known[j]) == 0:      # a ground point: G, no turning part
            ends.append((px, py, 0.0, 0.0))
        else:                       # the crank's pivot + R(theta) (P - l)
            ends.append((gd[D_PX], gd[D_PY], px - gd[D_LX], py - gd[D_LY]))
    (g1x, g1y, q1x, q1y), (g2x, g2y, q2x, q2y) = ends
    return np.hypot(g1x - g2x, g1y - g2y), np.hypot(q1x - q2x, q1y - q2y)


def _rrr(g: np.ndarray, known: np.ndarray, gd: np.ndarray) -> np.ndarray:
    """An RRR dyad's bound on |d m^2 / d theta|, its outer pivots on the ground (0) or
    the crank (1): max(2 |G| |q| / (a b), 2 |G| |q| / size^2) (the module's notes)."""
    big, q = _pivots(g, known, gd)
    a = np.hypot(g[Q1X] - g[P_BX], g[Q1Y] - g[P_BY])
    b = np.hypot(g[Q2X] - g[PARAM + P_BX], g[Q2Y] - g[PARAM + P_BY])
    size = g[SIZE]
    return np.fmax(2.0 * big * q / (a * b), 2.0 * big * q / (size * size))


def _rtr(g: np.ndarray, known: np.ndarray, gd: np.ndarray) -> tuple:
    """An RTR dyad's bound on |d m^2 / d theta| and on its bodies' |omega|, its outer
    pivots on the ground (0) or the crank (1) (see the module's notes)."""
    big, q = _pivots(g, known, gd)
    low, high = np.abs(big - q), big + q
    c = np.abs(g[I_RTR])
    size = g[SIZE]
    reach = np.sqrt(low * low - c * c)          # (NaN where the slot can reach |c|)
    # (a slot through the guide's pivot, c = 0: sin^2 tau = 1 wherever it closes, |D| > 0)
    sin2 = np.where(low > c, 2.0 * c * c * q / (low * low * low), np.inf)
    sin2 = np.where(c == 0.0, 0.0, sin2)
    dist = 2.0 * high * q / (size * size)
    w = np.where(low > c, q / low + c * q / (low * reach), np.inf)
    w = np.where(c == 0.0, q / low, w)
    return np.fmax(sin2, dist), w


def cleared(bound: np.ndarray, stride: int, lo: np.ndarray, hi: np.ndarray,
            owner: np.ndarray, m_lo: np.ndarray, m_hi: np.ndarray) -> np.ndarray:
    """Which intervals (``lo``, ``hi``: crank positions, deg; scene ``owner``) cannot hold
    a dead point nor a probe that does not close: the lower bound of m^2 over each from
    its rows' ``m_lo``, ``m_hi`` (-inf: no row there, an end's probe beyond the sweep)
    and L (``bound`` per column, ``stride`` 0 for one column) above :data:`CLEAR`. The
    reference of the compiled pass the probes use
    (:func:`~kinetostatics.solver.fast.screen.cleared`, the same verdicts)."""
    a, b = np.isfinite(m_lo), np.isfinite(m_hi)
    told = (a | (m_lo == -np.inf)) & (b | (m_hi == -np.inf))    # (a NaN or +inf row: not)
    with np.errstate(invalid="ignore"):     # (inf 0, inf - inf: NaN, not clear)
        slope = bound[np.asarray(owner, dtype=np.intp) * stride] * ((hi - lo) * DEG)
        least = np.where(a & b, 0.5 * (m_lo + m_hi - slope), np.maximum(m_lo, m_hi) - slope)
    return told & (least > CLEAR)       # (a NaN bound: not clear)


def sweep_clear(scene: Scene, structure) -> Callable | None:
    """``clear(lo, hi, owner, m_lo, m_hi)`` of a sweep of ``scene`` solved with
    ``structure`` on the numpy path (:func:`cleared` with the scene's L, one column), or
    None where no bound is known. The geometry is the compiled path's tables
    (:func:`~.geometry.driver_geometry`, :func:`~.geometry.dyad_geometry`: numpy, no
    numba), the assembly left out (L does not depend on it). Kept in the scene's record
    (:func:`~kinetostatics.solver.memo.record_of`) for the structure's dyads (a solve's
    structure is its assemblies' copy of them): what follows from the scene alone, as its
    structure (measured 2026-11-30, the shaper's L took some 90-180 us a solve, 9 % of
    its 2001 rows' solve, at a load of 6)."""
    record = record_of(scene)
    kept = record.get("bound")
    if kept is not None and kept[0] is structure.dyads:
        return kept[1]
    clear = _sweep_clear(scene, structure)
    record["bound"] = (structure.dyads, clear)
    return clear


def _sweep_clear(scene: Scene, structure) -> Callable | None:
    """:func:`sweep_clear` worked out."""
    drv = scene.driver
    known = known_bodies(drv, structure.dyads) if drv.kind == "R" else None
    if known is None:
        return None
    gy = np.empty((len(known), DYAD_GEOMETRY, 1))
    for i, d in enumerate(structure.dyads):
        gy[i] = dyad_geometry(scene, d, 1.0)[0]
    kinds = tuple(d.kind for d in structure.dyads)
    bound = lipschitz(True, driver_geometry(scene)[0], np.array(known), gy, kinds)
    return None if bound is None else partial(cleared, bound, 0)


# (deadpoints cannot import the compiled path's package, which imports it: the numpy
# sweep's bound is told to it here)
SWEEP_BOUNDS.append(sweep_clear)
