"""A gear pair: pitch and base circles, the line of action and the tooth forces."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.lines import Line2D

from ..common.angles import radian_column
from ..model.errors import WorkbenchError
from .base import REACTION_COLOR, axes_or_new
from .notation import reading
from .place import declutter

__all__ = ["draw_gear_pair"]


def draw_gear_pair(pair, ax: Axes | None = None) -> Axes:
    """Draw a gear pair (seed 002 figs 2.22-2.23): the pitch circles (cercurile de
    rostogolire), the base circles, the line of action n-n through the pitch point P and
    the tooth forces F12 (on gear 2) and F21 = -F12 (on gear 1) along it.

    Parameters
    ----------
    pair : GearPair
        A solved pair (:func:`kinetostatics.transmission.gears.gear_pair`); with an array of ``M2``
        the first value is drawn.
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        x [m] against y [m], equal aspect, the legend below the plot. The arrows have a
        fixed length (half the larger pitch radius); their labels give the force in N.
        The title gives i12 and the moments (ccw positive).

    Raises
    ------
    WorkbenchError
        ``pair`` is not a :class:`~kinetostatics.transmission.gears.GearPair`.
    """
    from ..transmission.gears import GearPair

    if not isinstance(pair, GearPair):
        raise WorkbenchError(
            "draw_gear_pair: give a GearPair (kinetostatics.transmission.gears.gear_pair)")
    ax = axes_or_new(ax, figsize=(6, 6))
    o1, o2, p = (np.asarray(v, dtype=float) for v in (pair.O1, pair.O2, pair.P))
    r1, r2 = float(np.hypot(*(p - o1))), float(np.hypot(*(p - o2)))
    cos_a = np.cos(radian_column(pair.alpha_deg))
    t = np.linspace(0.0, 2.0 * np.pi, 361)
    texts: list = []            # placed clear of the circles and arrows (declutter)
    for o, r, c, k in ((o1, r1, "tab:blue", 1), (o2, r2, "tab:green", 2)):
        ring = " (ring)" if pair.internal and r > min(r1, r2) else ""
        ax.plot(o[0] + r * np.cos(t), o[1] + r * np.sin(t), color=c, lw=2,
                label=f"gear {k}{ring}: $r_{{w{k}}}$ = {reading(r)} m")
        ax.plot(o[0] + r * cos_a * np.cos(t), o[1] + r * cos_a * np.sin(t), color=c, lw=1,
                ls="--")
        ax.plot(*o, "+", color=c, ms=12, mew=2)
        texts.append(ax.annotate(f"O{k}", o, xytext=(5, -12), textcoords="offset points",
                                 fontsize=10, color=c))
    span = max(r1, r2)
    centres = o2 - o1
    out = (p - (o1 if r1 >= r2 else o2)) / span          # from the larger gear's axis to P
    ax.plot(*p, "o", color="k", ms=5, zorder=7)
    texts.append(ax.annotate("P", p, xytext=(10 * out[0], 10 * out[1]),
                             textcoords="offset points", fontsize=10, ha="center",
                             va="center", fontweight="bold"))
    tangent = np.array([-centres[1], centres[0]]) / (np.hypot(*centres) or 1.0)
    ends = p + np.outer([-0.5 * span, 0.5 * span], tangent)
    handles = [Line2D([], [], color="0.4", lw=1, ls="--", label="base circles $r_w$ cos α")]
    ax.plot(ends[:, 0], ends[:, 1], ":", color="0.4", lw=1.2, label="common tangent at P")
    f = np.array([np.ravel(pair.F12x)[0], np.ravel(pair.F12y)[0]], dtype=float)
    fmag = float(np.hypot(*f))
    if fmag > 0.0:
        u = f / fmag
        s = [float(np.dot(o - p, u)) for o in (o1, o2)]     # feet of the normals from O1, O2
        size = 0.5 * span
        side = np.array([-u[1], u[0]])                     # labels beside the arrows,
        side = side if np.dot(side, out) <= 0.0 else -side  # towards the larger gear
        lo, hi = min(*s, -size) - 0.1 * span, max(*s, size) + 0.1 * span
        line = p + np.outer([lo, hi], u)
        ax.plot(line[:, 0], line[:, 1], color="0.3", lw=0.8,
                label=f"line of action n-n, α = {pair.alpha_deg:g}° to the tangent")
        feet = p + np.outer(s, u)
        ax.plot(feet[:, 0], feet[:, 1], "o", color="0.3", ms=3)
        for sign, lab, col, text in ((1.0, "$F_{12}$", REACTION_COLOR,
                                      "$F_{12}$: gear 1 on gear 2"),
                                     (-1.0, "$F_{21}$", "tab:orange",
                                      "$F_{21} = -F_{12}$: 2 on 1")):
            tip = p + sign * size * u
            ax.annotate("", tip, p, arrowprops={"arrowstyle": "-|>", "color": col, "lw": 2,
                                                 "shrinkA": 0, "shrinkB": 0}, zorder=6)
            texts.append(ax.annotate(f"{lab} = {reading(fmag)} N", p + 0.6 * sign * size * u,
                        xytext=(8 * side[0], 8 * side[1]), textcoords="offset points",
                        fontsize=10, color=col, ha="left" if side[0] >= 0 else "right",
                        va="bottom" if side[1] >= 0 else "top",
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.85}))
            ax.update_datalim([tip])
            handles.append(Line2D([], [], color=col, lw=2, marker=">", markevery=[-1],
                                  label=text))
    me, m2 = float(np.ravel(pair.Me)[0]), float(np.ravel(pair.M2)[0])
    kind = "internal" if pair.internal else "external"
    ax.set_title(f"{kind} pair: $i_{{12}}$ = {reading(pair.i12)}, $M_2$ = {reading(m2)} N m, "
                 f"Me = {reading(me)} N m",
                 fontsize=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.12)
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    h, _ = ax.get_legend_handles_labels()
    ax.legend(handles=h + handles, fontsize=10, loc="upper center", bbox_to_anchor=(0.5, -0.12),
              ncol=1, borderaxespad=0.0)      # one column: as wide as the drawing
    declutter(ax, texts)
    return ax
