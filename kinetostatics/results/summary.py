"""The contract's ``summary.json`` of a Solution: Me/Fe statistics, the largest joint
reactions, the smallest transmission angle and the rows flagged."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .solution import Solution


def solution_summary(sol: Solution) -> dict:
    """:meth:`Solution.summary <kinetostatics.results.Solution.summary>`: everything that
    depends on the order of the motion (the mean by the trapezoid rule, the position of
    an extreme when several rows tie, the intervals between rows) is taken along
    increasing driver position."""
    q = sol.driver_quantity
    order = sol.order
    me = np.asarray(sol.Me, dtype=float)[order]
    pos = sol.positions.astype(float)[order]
    locked = sol.self_locking
    # rows where the mechanism locks (friction) have no settled Me or reactions, and
    # rows flagged singular (at or near a dead point) no number to vouch for: the
    # extremes and the mean are over the other rows, the counts below say how many
    # were left out
    out_rows = np.asarray(sol.singular, dtype=bool).copy()
    if locked is not None:
        out_rows |= locked
    if out_rows.any() and not out_rows.all():
        keep = order[~out_rows[order]]
        me, pos = me[~out_rows[order]], pos[~out_rows[order]]
    else:
        keep = order
    if pos.size > 1 and pos[-1] != pos[0]:
        mean = float(np.trapezoid(me, pos) / (pos[-1] - pos[0]))
    else:
        mean = float(me.mean())
    out: dict = {"title": sol.scene.title, "positions": int(pos.size),
                 f"{q}_mean": mean, f"{q}_max": float(me.max()), f"{q}_min": float(me.min())}
    rmax = {}
    for name in sol.scene.joints:
        fx, fy = sol.reaction(name)
        f = np.broadcast_to(np.hypot(fx, fy), sol.positions.shape)[keep]
        i = int(np.argmax(f))
        rmax[name] = {"F": float(f[i]), "position": float(pos[i])}
    out["reaction_max"] = rmax
    if sol.kin.dyads:
        best = None
        for dm in sol.kin.dyads:
            t = np.broadcast_to(dm.transmission_angle, sol.positions.shape)[keep]
            i = int(np.argmin(t))
            if best is None or t[i] < best[0]:
                best = (float(t[i]), float(pos[i]), dm.dyad.index + 1)
        out["transmission_angle_min"] = best[0]
        out["transmission_angle_min_position"] = best[1]
        out["transmission_angle_min_dyad"] = best[2]
    else:
        out["transmission_angle_min"] = None
    out["singular_rows"] = int(np.count_nonzero(sol.singular))
    out["rows_left_out"] = int(np.count_nonzero(out_rows)) if not out_rows.all() else 0
    # a dead point between two rows (a change point passed, a lever through its
    # pivot): the pairs of positions around it, both rows flagged singular
    pos_all = sol.positions.astype(float)
    out["dead_points_between_rows"] = [[float(pos_all[i]), float(pos_all[j])]
                                       for i, j in sol.kin.between]
    # a dyad that cannot close somewhere between two rows: no motion joins them
    # (listed only when there is one)
    if len(sol.kin.unassembled):
        out["unassembled_between_rows"] = [[float(pos_all[i]), float(pos_all[j])]
                                           for i, j in sol.kin.unassembled]
    out["undefined_load_rows"] = int(np.count_nonzero(sol.undefined_load))
    if locked is not None:
        out["self_locking_rows"] = int(np.count_nonzero(locked))
    out["structure"] = sol.structure.describe()
    return out
