"""The seed's split of each dyad's outer revolute reactions along and across its link
(eqs 2.17-2.18, 2.22, 2.26): the table behind :attr:`Solution.reaction_split`."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

if TYPE_CHECKING:
    from .solution import Solution


def reaction_split_table(sol: Solution) -> pd.DataFrame:
    """``position, dyad, joint, body, Fn, Ft``: ``Fn`` along the link from the outer joint
    to the inner joint, ``Ft`` perpendicular to it (the link direction turned +90 deg), on
    the dyad body."""
    n = sol.positions.size
    parts = []
    for dm in sol.kin.dyads:
        d = dm.dyad
        for i, (body, joint) in enumerate(zip(d.bodies, d.outer, strict=True)):
            if joint.kind != "R":
                continue
            p = dm.params[i]
            ex = np.broadcast_to(dm.xx - p.px, (n,))
            ey = np.broadcast_to(dm.xy - p.py, (n,))
            length = np.hypot(ex, ey)
            if length.min() <= 1e-12 * max(length.max(), 1e-300):
                continue            # the outer joint is the inner one: no link line
            with np.errstate(invalid="ignore", divide="ignore"):
                ex, ey = ex / length, ey / length
            fx, fy = sol.reaction(joint.name)
            if sol.joint_reactions[joint.name].on != body:
                fx, fy = -fx, -fy
            parts.append(pd.DataFrame({
                "position": sol.positions, "dyad": d.index + 1, "joint": joint.name,
                "body": body, "Fn": fx * ex + fy * ey, "Ft": -fx * ey + fy * ex}))
    if not parts:
        return pd.DataFrame(columns=["position", "dyad", "joint", "body", "Fn", "Ft"])
    return pd.concat(parts, ignore_index=True)
