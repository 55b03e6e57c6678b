"""Arrows of a vector polygon that would lie on top of each other, drawn side by side.

A force polygon of nearly collinear forces (an RTR dyad, a yoke on its guide) closes,
but its arrows run along one line and hide each other. Each arrow that would overlap
one already drawn is moved sideways, across its own direction, by a multiple of one
offset, and joined to the chain by two short dotted connectors (from its true tail, to
its true tip): the chain of arrows still runs from the pole back to the pole, and the
offset, a drawing aid only, is named in the legend with its length in newtons.
"""

from __future__ import annotations

import numpy as np

from ..common.angles import radian_column

__all__ = ["side_by_side"]

_PARALLEL = np.sin(radian_column(6.0))     # arrows within 6 deg count as parallel
_NEAR = 0.02                            # ... and as on one line within 2 % of the span


def _overlaps(t0, h0, t1, h1, span: float) -> bool:
    """Two arrows that run along one line over a common stretch."""
    d0, d1 = h0 - t0, h1 - t1
    l0, l1 = float(np.hypot(*d0)), float(np.hypot(*d1))
    if l0 == 0.0 or l1 == 0.0:
        return False
    if abs(d0[0] * d1[1] - d0[1] * d1[0]) > _PARALLEL * l0 * l1:
        return False
    u = d0 / l0
    n = np.array([-u[1], u[0]])
    if max(abs((t1 - t0) @ n), abs((h1 - t0) @ n)) > _NEAR * span:
        return False
    a0, a1 = sorted((0.0, l0))
    b0, b1 = sorted(((t1 - t0) @ u, (h1 - t0) @ u))
    return min(a1, b1) - max(a0, b0) > 0.05 * min(l0, l1)


def side_by_side(segs: list[tuple[np.ndarray, np.ndarray]], offset: float,
                 span: float) -> list[tuple[np.ndarray, np.ndarray, int]]:
    """Where to draw each arrow so that none lies on another.

    Parameters
    ----------
    segs : list of (tail, tip)
        The arrows in drawing order [N].
    offset : float
        One step sideways [N].
    span : float
        The size of the whole polygon [N] (what "on one line" is measured against).

    Returns
    -------
    list of (tail, tip, level)
        The drawn tail and tip of each arrow; ``level`` 0: where it is, k: moved by
        ``k * offset`` across its direction (left of it for k > 0, right for k < 0).
    """
    drawn: list[tuple[np.ndarray, np.ndarray]] = []
    out = []
    for t, h in segs:
        t, h = np.asarray(t, float), np.asarray(h, float)
        d = h - t
        ln = float(np.hypot(*d))
        n = np.array([-d[1], d[0]]) / ln if ln > 0 else np.zeros(2)
        for level in (0, 1, -1, 2, -2, 3, -3, 4, -4):
            a, b = t + level * offset * n, h + level * offset * n
            if not any(_overlaps(a, b, p, q, span) for p, q in drawn):
                break
        drawn.append((a, b))
        out.append((a, b, level))
    return out
