"""What every picture shares: colours, a new Axes when none is given, the driver's
position as text, the row nearest a position, a body point's global coordinates at a
row, legible tick labels, legends outside, and labels placed clear of each other.

Helpers for the picture modules of :mod:`kinetostatics.plot`; not part of its public
picture API.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.colors import to_hex
from matplotlib.ticker import MaxNLocator, MultipleLocator

from ..model.scene import GROUND
from ..results import Solution
from .notation import reading

LOAD_COLORS = {"applied": "tab:blue", "gravity": "tab:brown", "inertia": "tab:purple"}
REACTION_COLOR = "tab:red"
PATH_COLORS = ("#1b9e77", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666")


def body_colors() -> list[str]:
    """The colour cycle without its red, which marks the joint reactions."""
    cycle = plt.rcParams["axes.prop_cycle"].by_key().get("color", ["C0"])
    keep = [c for c in cycle if to_hex(c) not in ("#d62728", "#ff0000")]
    return keep or list(cycle)


def axes_or_new(ax: Axes | None, figsize=(6, 4.5)) -> Axes:
    """``ax``, or the Axes of a new constrained-layout figure of ``figsize`` inches."""
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax


def position_label(sol: Solution) -> str:
    """The axis label of the driver's position (crank angle in deg or stroke in m)."""
    return "crank angle φ [deg]" if sol.scene.driver.kind == "R" else "driver position s [m]"


def position_text(sol: Solution, i: int) -> str:
    """The driver's position at row ``i`` with its unit, e.g. ``φ = 30°``."""
    p = float(sol.positions[i])
    return f"φ = {p:g}°" if sol.scene.driver.kind == "R" else f"s = {p:g} m"


#: What a picture of forces says at a row flagged singular, instead of drawing them.
SINGULAR_NOTE = "singular row (at or near a dead point): the forces are not drawn"


def singular_row(sol: Solution, i: int) -> bool:
    """Row ``i`` is flagged singular (at or near a dead point): its forces and Me have
    no value a picture can vouch for."""
    return bool(np.asarray(sol.singular)[i])


def vector_axes(ax: Axes) -> None:
    """Few ticks, large numbers as powers of ten: legible tick labels on vector diagrams."""
    for a in (ax.xaxis, ax.yaxis):
        a.set_major_locator(MaxNLocator(nbins=4, steps=[1, 2, 2.5, 5, 10]))
    ax.ticklabel_format(style="sci", axis="both", scilimits=(-3, 4), useMathText=True)


def cycle_axis(ax: Axes, sol: Solution) -> None:
    """Ticks every 45 deg (90 deg beyond half a turn) on a crank-angle axis."""
    if sol.scene.driver.kind == "R" and sol.positions.size > 1:
        span = float(np.ptp(sol.positions))
        if span >= 180.0:
            ax.xaxis.set_major_locator(MultipleLocator(45.0 if span <= 180.0 else 90.0))


def row_index(sol: Solution, position: float | None, row: int | None) -> int:
    """``row`` if given, else the row nearest ``position`` (deg or m), else the first."""
    if row is not None:
        return int(row)
    if position is None:
        return 0
    return int(np.argmin(np.abs(sol.positions - position)))


def at_row(x, i: int, n: int) -> float:
    """Row ``i`` of an array over positions, or the scalar."""
    return float(np.broadcast_to(x, (n,))[i])


def global_point(sol: Solution, body: str, point: str, row: int) -> tuple[float, float]:
    """The global (x, y) [m] of a named point of ``body`` (or of the ground) at ``row``."""
    if body == GROUND:
        return sol.scene.ground[point]
    m = sol.kin.bodies[body]
    x, y = m.point(sol.scene.bodies[body].local(point))
    n = sol.positions.size
    return at_row(x, row, n), at_row(y, row, n)


def magnitude_text(x: float) -> str:
    """A magnitude for a legend: 31770 rather than 3.177e+04, never in e-notation."""
    return f"{x:.0f}" if 1e3 <= abs(x) < 1e7 else reading(x)


def math_name(name: str) -> str:
    """A name safe inside mathtext ``\\mathrm{}``."""
    return name.replace("_", r"\_").replace("$", "")


def legend_outside(ax: Axes, **kw) -> None:
    """The legend to the right of the Axes, outside the drawing."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, **kw)


def legend_below(ax: Axes, ncol: int = 2) -> None:
    """Move an Axes' legend below it, in ``ncol`` columns (a panel of a grid)."""
    lg = ax.get_legend()
    if lg is None:
        return
    handles, labels = lg.legend_handles, [t.get_text() for t in lg.get_texts()]
    title = lg.get_title().get_text()
    lg.remove()
    ax.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              borderaxespad=0.0, ncol=ncol, title=title or None)


def trace_points(sol: Solution) -> list[tuple[str, str]]:
    """(body, point) of every named point of the moving bodies, one per location name."""
    seen, out = set(), []
    for name, body in sol.scene.bodies.items():
        for p in body.points:
            if p not in seen:
                seen.add(p)
                out.append((name, p))
    return out


def place_labels(ax: Axes, labels: list, gap: float = 20.0) -> list:
    """Write each label beside its vector's middle, on the side (and at the distance)
    that keeps it at least ``gap`` pixels from the labels already placed."""
    ax.apply_aspect()
    placed: list[np.ndarray] = []
    out = []
    dpi = ax.figure.dpi / 72.0
    for text, anchor, nrm, col in labels:
        base = ax.transData.transform(anchor)
        best, score = 9.0, -1.0
        for off in (9.0, -9.0, 18.0, -18.0, 28.0, -28.0):
            pos = base + off * dpi * np.array([nrm[0], nrm[1]])
            d = min((float(np.hypot(*(pos - q))) for q in placed), default=np.inf)
            if d >= gap * dpi:
                best, score = off, d
                break
            if d > score:
                best, score = off, d
        placed.append(base + best * dpi * np.asarray(nrm))
        out.append(ax.annotate(text, tuple(anchor), xytext=tuple(best * np.asarray(nrm)),
                               textcoords="offset points", fontsize=10, color=col,
                               ha="center", va="center"))
    return out

