"""The contract's ``summary.json`` of a Solution: Me/Fe statistics, the largest joint
reactions, the smallest transmission angle and the rows flagged."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .solution import Solution


def solution_summary(sol: Solution, extremes: Extremes | None = None) -> dict:
    """:meth:`Solution.summary <kinetostatics.results.Solution.summary>`: everything that
    depends on the order of the motion (the mean by the trapezoid rule, the position of
    an extreme when several rows tie, the intervals between rows) is taken along
    increasing driver position.

    ``extremes``: the largest reactions and smallest transmission angles gathered block
    by block (:class:`Extremes`, a streamed write whose solution does not hold the
    reactions and dyads over the sweep); default: taken from ``sol``'s arrays."""
    q = sol.driver_quantity
    order = sol.order
    me = np.asarray(sol.Me, dtype=float)[order]
    pos = sol.positions.astype(float)[order]
    locked = sol.self_locking
    out_rows = left_out(sol.singular, locked)
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
    if extremes is None:
        extremes = Extremes(sol.scene, sol.kin.dyads)
        extremes.add(sol, keep, pos)
    out["reaction_max"] = {name: {"F": float(e.value), "position": float(e.at)}
                           for name, e in extremes.reactions.items()}
    if extremes.dyads:
        best = None
        for e, index in extremes.dyads:
            if best is None or e.value < best[0]:
                best = (float(e.value), float(e.at), index)
        out["transmission_angle_min"] = best[0]
        out["transmission_angle_min_position"] = best[1]
        out["transmission_angle_min_dyad"] = best[2]
    else:
        out["transmission_angle_min"] = None
    out["singular_rows"] = int(np.count_nonzero(sol.singular))
    out["rows_left_out"] = int(np.count_nonzero(out_rows)) if not out_rows.all() else 0
    # a dead point between two rows (a change point passed, a lever through its
    # pivot): the pairs of positions around it, both rows flagged singular
    between, unassembled = extremes.dead if extremes.dead is not None else (
        sol.kin.between, sol.kin.unassembled)
    pos_all = sol.positions.astype(float)
    out["dead_points_between_rows"] = [[float(pos_all[i]), float(pos_all[j])]
                                       for i, j in between]
    # a dyad that cannot close somewhere between two rows: no motion joins them
    # (listed only when there is one)
    if len(unassembled):
        out["unassembled_between_rows"] = [[float(pos_all[i]), float(pos_all[j])]
                                           for i, j in unassembled]
    out["undefined_load_rows"] = int(np.count_nonzero(sol.undefined_load))
    if locked is not None:
        out["self_locking_rows"] = int(np.count_nonzero(locked))
    out["structure"] = sol.structure.describe()
    return out


def left_out(singular: np.ndarray, locked: np.ndarray | None) -> np.ndarray:
    """The rows the extremes and the mean leave out: rows where friction locks the
    mechanism have no settled Me or reactions, and rows flagged singular (at or near a
    dead point) no number to vouch for (the summary counts them)."""
    out_rows = np.asarray(singular, dtype=bool).copy()
    if locked is not None:
        out_rows |= locked
    return out_rows


#: Values within this share of an extreme's size tie with it (a few units in the last
#: place): a flat extreme (the slotted lever's transmission angle, 90 deg at every row to
#: one unit in the last place) is located at its first row, whichever rounding each path's
#: arithmetic gave each row (the two paths agree to 5e-16 of a column's scale).
TIE = 16 * np.finfo(float).eps


class Extreme:
    """The largest (``"max"``) or smallest (``"min"``) value along the kept rows,
    gathered from parts of them in order, and its position: the first row whose value
    ties with the extreme to rounding (:data:`TIE`), or the first NaN."""

    def __init__(self, kind: str):
        self.sign = 1.0 if kind == "max" else -1.0
        self.value: float | None = None
        self.at: float | None = None
        # the rows so far that lay beyond every row before them and still tie with the
        # extreme, in order: (how far short of the extreme, as the least; position)
        self._records: list[tuple[float, float]] = []

    def add(self, values: np.ndarray, positions: np.ndarray) -> None:
        """The next kept rows' values and driver positions."""
        if values.size == 0 or (self.value is not None and np.isnan(self.value)):
            return                  # (a NaN before these rows stays the extreme)
        nan = np.isnan(values)
        if nan.any():
            i = int(np.argmax(nan))
            self.value, self.at, self._records = values[i], positions[i], []
            return
        low = -self.sign * values                  # (the extreme as the least)
        least = np.minimum.accumulate(low)
        new = np.empty(low.size, dtype=bool)        # (beyond every row before)
        new[0] = not self._records or low[0] < self._records[-1][0]
        np.less(low[1:], least[:-1], out=new[1:])
        if self._records:
            new &= low < self._records[-1][0]
        best = least[-1] if not self._records else min(least[-1], self._records[-1][0])
        band = best + TIE * abs(best)
        records = [r for r in self._records if r[0] <= band]
        records += [(w, x) for w, x in zip(low[new].tolist(), positions[new].tolist(),
                                           strict=True) if w <= band]
        self._records = records
        self.value, self.at = -self.sign * best, records[0][1]


class Extremes:
    """The summary's largest joint reactions and smallest transmission angles, gathered
    over the kept rows of a solution, or of its blocks in order (:meth:`add`)."""

    def __init__(self, scene, dyads: list, dead: tuple | None = None):
        self.reactions = {name: Extreme("max") for name in scene.joints}
        self.dyads = [(Extreme("min"), dm.dyad.index + 1) for dm in dyads]
        self.dead = dead            # (between, unassembled) of a streamed sweep

    def add(self, sol: Solution, keep: np.ndarray, pos: np.ndarray) -> None:
        """``sol``'s rows ``keep`` (indices or a mask), at driver positions ``pos``."""
        n = sol.positions.shape
        for name, e in self.reactions.items():
            fx, fy = sol.reaction(name)
            e.add(np.broadcast_to(np.hypot(fx, fy), n)[keep], pos)
        for (e, _), dm in zip(self.dyads, sol.kin.dyads, strict=True):
            e.add(np.broadcast_to(dm.transmission_angle, n)[keep], pos)
