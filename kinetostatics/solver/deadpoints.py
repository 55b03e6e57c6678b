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
rows are flagged ``singular`` and the interval is reported. The same probe one row's
spacing beyond each end of the sweep flags an end row near a dead point just outside it
(for a whole turn that is the same state as the other end row).

Rows are taken in increasing driver position (:func:`~.continuity.sweep_order`), so a
``positions`` list in any order finds the same intervals.

A probe where some dyad cannot close (no closed form: the links do not reach) is not a
dead point: there is no motion from one row to the other at all, the two rows lie in
separate ranges of assembly. Such intervals are reported apart (``unassembled``;
``summary.json``: ``unassembled_between_rows``), their rows are not flagged
``singular`` for it, and no dead point is looked for in them. Beyond the ends of the
sweep such probes are left out.
"""

from __future__ import annotations

import numpy as np

from ..model.scene import Scene
from .continuity import open_rows, sweep_order
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


def _probe(scene: Scene, structure: Structure, lo: np.ndarray, hi: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray]:
    """The smallest m^2 found inside each interval (lo, hi), zooming ROUNDS times, and
    the intervals where some probe found a dyad that cannot close (no closed form)."""
    t = np.linspace(0.0, 1.0, PROBES + 2)
    rows = np.arange(lo.size)
    best = np.full(lo.size, np.inf)
    open_ = np.zeros(lo.size, dtype=bool)
    for _ in range(ROUNDS):
        grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
        probe = solve_kinematics(scene, structure, positions=grid[:, 1:-1].ravel(),
                                 strict=False)
        pm2 = _measure2(probe).reshape(lo.size, PROBES)
        nan = np.isnan(pm2) | open_rows(probe).reshape(lo.size, PROBES)
        open_ |= nan.any(axis=1)
        pm2 = np.where(nan, np.inf, pm2)        # no closed form there: not a dead point
        j = np.argmin(pm2, axis=1)
        best = np.minimum(best, pm2[rows, j])
        lo, hi = grid[rows, j], grid[rows, j + 2]
    return best, open_


def dead_points_between_rows(scene: Scene, structure: Structure, kin: Kinematics
                             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Dead points between rows, and just beyond the sweep's ends; intervals the
    mechanism cannot cross.

    Parameters
    ----------
    scene, structure, kin
        The mechanism and its kinematics over the sweep (rows in any order).

    Returns
    -------
    between : numpy.ndarray
        (k, 2) rows (i, j), neighbours in increasing driver position (i before j), with a
        dead point between them; in increasing position.
    ends : numpy.ndarray
        The end rows (smallest and/or largest position) with a dead point within one
        row's spacing beyond them (outside the sweep: for a whole turn, the same state as
        the other end).
    unassembled : numpy.ndarray
        (k, 2) rows (i, j) as in ``between`` where some dyad cannot close at a position
        probed between them: the two rows are not joined by any motion of the mechanism.
    """
    none, pairs = np.zeros(0, dtype=int), np.zeros((0, 2), dtype=int)
    m2u = _measure2(kin)
    n = m2u.size
    if n < 2:
        return pairs, none, pairs
    order = sweep_order(kin.positions)
    m2 = m2u[order]
    pos = np.asarray(kin.positions, dtype=float)[order]
    cand = _candidates(m2)
    # beyond the ends: an end row that is a dip of m, probed over one spacing outside
    outer = [(0, 2.0 * pos[0] - pos[1], pos[0]), (n - 1, pos[-1], 2.0 * pos[-1] - pos[-2])]
    outer = [o for o in outer
             if m2[o[0]] < SCREEN**2 and m2[o[0]] <= m2[1 if o[0] == 0 else n - 2]]
    lo = np.concatenate([pos[cand], [o[1] for o in outer]])
    hi = np.concatenate([pos[cand + 1], [o[2] for o in outer]])
    if lo.size == 0:
        return pairs, none, pairs
    best, open_ = _probe(scene, structure, lo, hi)
    k = cand.size
    ends_m2 = np.minimum(m2[cand], m2[cand + 1])
    dead = (best[:k] <= SINGULAR_WARN**2) & (best[:k] < ends_m2) & ~open_[:k]
    between = cand[dead]
    gaps = cand[open_[:k]]
    edge = np.array([order[o[0]] for o, b in zip(outer, best[k:], strict=True)
                     if b <= SINGULAR_WARN**2 and b < m2[o[0]]], dtype=int)
    return (np.stack([order[between], order[between + 1]], axis=1),
            edge, np.stack([order[gaps], order[gaps + 1]], axis=1))
