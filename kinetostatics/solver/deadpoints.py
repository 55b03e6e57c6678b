"""Dead points that fall between two rows of the sweep.

A row is flagged ``singular`` where some dyad is near a dead centre: the sine of its
transmission angle (the velocity system's |det| / (|c1| |c2|), seed 002 eqs 2.60-2.61)
or the distance it divides by (its outer pivots' distance, against the mechanism's size)
is at most 1e-3. A dead point can also lie between two rows: a four-bar passing its
change point (a + b = c + d) or a slotted lever whose block passes through the lever's
pivot. Both rows then look regular, while the computed motion is not smooth across the
interval (the rocker's angular velocity changes sign, the lever turns by 180 deg).

Search: the measure m = min(|sin tau|, pivot distance / size) of every dyad dips to zero
at a dead point, so every interval next to a local minimum of m over the rows is probed
at 31 interior positions, three times zooming on the smallest value (resolution 1/29791
of the interval, one vectorised solve of the same mechanism per round). An interval whose
interior minimum is at most 1e-3 and below both its rows' values holds a dead point: both
rows are flagged ``singular`` and the interval is reported.
"""

from __future__ import annotations

import numpy as np

from ..model.scene import Scene
from .kinematics import SINGULAR_WARN, Kinematics, solve_kinematics
from .structure import Structure

PROBES = 31        # interior positions per interval and round
ROUNDS = 3         # zooms on the smallest value
SCREEN = 0.5       # local minima of m below this are probed


def _measure2(kin: Kinematics) -> np.ndarray:
    """m^2 per row: the smallest closeness to a dead centre over the dyads."""
    m2 = np.full(kin.n, np.inf)
    for d in kin.dyads:
        np.minimum(m2, np.broadcast_to(d.closeness2, (kin.n,)), out=m2)
    return m2


def _candidates(m2: np.ndarray) -> np.ndarray:
    """Intervals i (rows i, i + 1) next to a local minimum of m over the rows."""
    n = m2.size
    if n < 2:
        return np.zeros(0, dtype=int)
    left = np.concatenate([[np.inf], m2[:-1]])
    right = np.concatenate([m2[1:], [np.inf]])
    # a real dip (not rounding jitter on a constant measure), small enough to matter
    shrink = 1.0 - 1e-9
    dip = (((m2 < left * shrink) & (m2 <= right))
           | ((m2 <= left) & (m2 < right * shrink)))
    rows = np.flatnonzero(dip & (m2 < SCREEN**2))
    out = np.unique(np.concatenate([rows - 1, rows]))
    return out[(out >= 0) & (out < n - 1)]


def dead_points_between_rows(scene: Scene, structure: Structure, kin: Kinematics) -> np.ndarray:
    """Intervals i (between rows i and i + 1) that hold a dead point of some dyad.

    Parameters
    ----------
    scene, structure, kin
        The mechanism and its kinematics over the sweep.

    Returns
    -------
    numpy.ndarray
        The indices i, ascending.
    """
    m2 = _measure2(kin)
    cand = _candidates(m2)
    if cand.size == 0:
        return cand
    pos = np.asarray(kin.positions, dtype=float)
    lo, hi = pos[cand], pos[cand + 1]
    t = np.linspace(0.0, 1.0, PROBES + 2)
    best = np.full(cand.size, np.inf)
    for _ in range(ROUNDS):
        grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
        probe = solve_kinematics(scene, structure, positions=grid[:, 1:-1].ravel(),
                                 strict=False)
        pm2 = _measure2(probe).reshape(cand.size, PROBES)
        pm2 = np.where(np.isnan(pm2), 0.0, pm2)        # no closed form there: a dead point
        j = np.argmin(pm2, axis=1)
        best = np.minimum(best, pm2[np.arange(cand.size), j])
        lo, hi = grid[np.arange(cand.size), j], grid[np.arange(cand.size), j + 2]
    ends = np.minimum(m2[cand], m2[cand + 1])
    found = (best <= SINGULAR_WARN**2) & (best < ends)
    return cand[found]
