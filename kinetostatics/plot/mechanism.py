"""The mechanism at a position (links, pins, sliders, guides, the ground, the joint
reactions and the loads as arrows) and its motion over the cycle.
"""

from __future__ import annotations

import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon

from ..model.errors import WorkbenchError
from ..model.scene import GROUND
from ..results import Solution
from .base import (
    LOAD_COLORS,
    REACTION_COLOR,
    SINGULAR_NOTE,
    at_row,
    axes_or_new,
    body_colors,
    global_point,
    legend_outside,
    position_text,
    row_index,
    singular_row,
    trace_points,
)
from .notation import force_symbol, load_symbol, reading, round_scale
from .place import declutter

__all__ = ["animate", "draw_body", "draw_mechanism"]


def _guide_angle(sol: Solution, j, i: int) -> float:
    th = j.beta
    if j.guide != GROUND:
        th += at_row(sol.kin.bodies[j.guide].theta, i, sol.positions.size)
    return float(th)


def _guide_extent(sol: Solution, j, i: int, size: float) -> tuple[float, float]:
    """Where to draw a guide line, along it from its line point: over the slider
    point's whole travel for a ground guide, around the line point and the slider point
    now for a moving guide."""
    n = sol.positions.size
    th = _guide_angle(sol, j, i)
    gx, gy = global_point(sol, j.guide, j.points[0], i)
    if j.guide == GROUND and j.slider != GROUND:
        m = sol.kin.bodies[j.slider]
        x, y = m.point(sol.scene.bodies[j.slider].local(j.points[1]))
        s = (np.broadcast_to(x, (n,)) - gx) * np.cos(th) + \
            (np.broadcast_to(y, (n,)) - gy) * np.sin(th)
    else:
        sx, sy = global_point(sol, j.slider, j.points[1], i)
        s = np.array([0.0, (sx - gx) * np.cos(th) + (sy - gy) * np.sin(th)])
    return float(min(s.min(), 0.0) - 0.15 * size), float(max(s.max(), 0.0) + 0.15 * size)


def draw_body(ax: Axes, sol: Solution, name: str, i: int, color: str,
              texts: list | None = None, named: set | None = None) -> list:
    """Draw one body at row ``i``: a bar between two points, a filled polygon through
    three or more, a block for one; its centre of mass as a ring.

    Parameters
    ----------
    ax : Axes
    sol : Solution
    name : str
        The body.
    i : int
        Row index.
    color : str
    texts : list, optional
        When given, the point names are written and their annotations appended here.
    named : set, optional
        (name, x, y) of the points already named (a shared point is named once).

    Returns
    -------
    list of (float, float)
        The body's points [m].
    """
    body = sol.scene.bodies[name]
    pts = [global_point(sol, name, p, i) for p in body.points]
    if len(pts) >= 3:
        ax.add_patch(Polygon(pts, closed=True, alpha=0.25, color=color))
        ax.plot(*zip(*(pts + pts[:1]), strict=True), color=color, lw=2.5, label=name)
    elif len(pts) == 2:
        ax.plot(*zip(*pts, strict=True), color=color, lw=3.5, solid_capstyle="round",
                label=name)
    else:
        ax.plot(*zip(*pts, strict=True), "s", color=color, ms=14, alpha=0.6, label=name)
    if body.cog is not None and body.mass > 0:
        g = global_point(sol, name, "cog", i)
        ax.plot(*g, "o", mfc="white", mec=color, ms=6)
    if texts is not None:
        named = set() if named is None else named
        for p, xy in zip(body.points, pts, strict=True):
            key = (p, round(xy[0], 9), round(xy[1], 9))
            if key not in named:
                named.add(key)
                texts.append(ax.annotate(p, xy, xytext=(4, 4), textcoords="offset points",
                                         fontsize=10))
    return pts


def _draw_joints(ax: Axes, sol: Solution, i: int, size: float) -> None:
    """The pins (a ground pin on its triangle) and the sliders' guides at row ``i``."""
    scene = sol.scene
    for j in scene.joints.values():
        if j.kind == "R":
            b = j.bodies[1] if j.bodies[0] == GROUND else j.bodies[0]
            xy = global_point(sol, b, j.point_on(b), i)
            ax.plot(*xy, "o", color="k", mfc="white", ms=7, zorder=5)
            if GROUND in j.bodies:
                ax.plot(*xy, "^", color="k", ms=12, zorder=4, mfc="0.8")
        else:
            lo, hi = _guide_extent(sol, j, i, size)
            gx, gy = global_point(sol, j.guide, j.points[0], i)
            th = _guide_angle(sol, j, i)
            u = np.array([np.cos(th), np.sin(th)])
            ends = np.array([gx, gy]) + np.outer([lo, hi], u)
            ax.plot(ends[:, 0], ends[:, 1], "--", color="0.4", lw=1)


def _arrows(sol: Solution, i: int, forces: bool, loads: bool) -> list[tuple]:
    """The arrows to draw at row ``i``: (label, x, y, fx, fy, colour) of the joint
    reactions (``forces``) and of the nonzero loads (``loads``)."""
    scene = sol.scene
    n = sol.positions.size
    arrows = []     # (label, x, y, fx, fy, color)
    if forces:
        for name in scene.joints:
            r = sol.joint_reactions[name]
            fx, fy = sol.reaction(name)
            arrows.append((force_symbol(name), at_row(r.x, i, n), at_row(r.y, i, n), float(fx[i]),
                           float(fy[i]), REACTION_COLOR))
    if loads:
        for ld in sol.loads:
            fx, fy = at_row(ld.fx, i, n), at_row(ld.fy, i, n)
            if fx == 0.0 and fy == 0.0:
                continue
            x, y = ld.position(sol.kin)
            arrows.append((load_symbol(ld.kind, ld.body), at_row(x, i, n), at_row(y, i, n), fx, fy,
                           LOAD_COLORS[ld.kind]))
    return arrows


def draw_mechanism(sol: Solution, position: float | None = None, *, row: int | None = None,
                   ax: Axes | None = None, forces: bool = False, labels: bool = True,
                   force_scale: float | None = None, loads: bool = False) -> Axes:
    """Draw the mechanism at one position: links between their joint points, pins,
    slider blocks and guides, the ground.

    Parameters
    ----------
    sol : Solution
        A solved scene.
    position : float, optional
        Driver position (deg or m); the nearest row is drawn (default: the first row).
    row : int, optional
        Row index instead of ``position``.
    ax : Axes, optional
        Where to draw; a new figure when None.
    forces : bool
        Draw the joint reactions on each joint's ``on`` body as red arrows.
    labels : bool
        Write the point names.
    force_scale : float, optional
        Metres of drawing per newton; default: the largest arrow is 1/4 of the size.
    loads : bool
        Draw the applied loads (blue), weights (brown) and inertia forces (purple) at
        their points (d'Alembert, seed 002 eq. 2.1).

    Returns
    -------
    Axes
    """
    ax = axes_or_new(ax, figsize=(8.0, 6.0))
    i = row_index(sol, position, row)
    scene = sol.scene
    colors = body_colors()
    allpts = [xy for xy in scene.ground.values()]
    texts: list = []            # labels to keep clear of each other (declutter)
    named: set = set()          # a point shared by two bodies is named once
    for k, name in enumerate(scene.bodies):
        allpts += draw_body(ax, sol, name, i, colors[k % len(colors)],
                            texts if labels else None, named)
    arr = np.array(allpts)
    size = float(np.ptp(arr, axis=0).max()) if len(arr) > 1 else 1.0
    size = size or 1.0
    _draw_joints(ax, sol, i, size)
    arrows = _arrows(sol, i, forces, loads)
    handles = []
    note = ""
    if arrows and singular_row(sol, i):
        arrows, note = [], "\n" + SINGULAR_NOTE      # no number to vouch for
    if arrows:
        fmax = max(np.hypot(a[3], a[4]) for a in arrows) or 1.0
        # a round scale (1, 2 or 5 x 10^k m per N): the arrow legend reads round numbers
        sc = force_scale or round_scale(0.25 * size / fmax)
        for lab, x, y, fx, fy, col in arrows:
            tip = (x + sc * fx, y + sc * fy)
            ax.annotate("", tip, (x, y),
                        arrowprops={"arrowstyle": "-|>", "color": col, "lw": 1.5,
                                    "shrinkA": 0, "shrinkB": 0})
            ax.update_datalim([(x, y), tip])
            mag = float(np.hypot(fx, fy)) or 1.0
            texts.append(ax.annotate(lab, tip, xytext=(4 * fx / mag, 4 * fy / mag),
                        textcoords="offset points", fontsize=10, color=col,
                        ha="left" if fx >= 0 else "right", va="bottom" if fy >= 0 else "top",
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.6}))
        kinds = [("joint reactions", REACTION_COLOR)] if forces else []
        if loads:
            kinds += [(f"{k} forces", c) for k, c in LOAD_COLORS.items()
                      if any(a[5] == c for a in arrows)]
        handles = [Line2D([], [], color=c, lw=1.5, label=k) for k, c in kinds]
        ref = 10.0 ** np.floor(np.log10(0.1 * size))
        handles.append(Line2D([], [], ls="none",
                              label=f"arrows: {ref:g} m ≙ {reading(ref / sc)} N"))
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.08)
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{scene.title or 'mechanism'}\nat {position_text(sol, i)}{note}",
                 fontsize=11)
    ax.grid(True, alpha=0.3)
    h, _ = ax.get_legend_handles_labels()
    ax.legend(handles=h + handles, fontsize=10, loc="best")
    declutter(ax, texts)
    return ax



def animate(sol: Solution, frames: int = 24, *, ax: Axes | None = None,
            interval: float = 120.0, trace: bool = True) -> FuncAnimation:
    """An animation of the mechanism over the sweep.

    Parameters
    ----------
    sol : Solution
        A solved scene.
    frames : int
        Number of frames, taken evenly over the sweep's rows (few frames keep
        ``anim.to_jshtml()`` fast in a notebook).
    ax : Axes, optional
        Where to draw; a new figure when None.
    interval : float
        Milliseconds between frames.
    trace : bool
        Draw the trajectories of the named points as faint lines.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Display it in a notebook with ``HTML(anim.to_jshtml())``; close its figure
        afterwards (``plt.close(anim._fig)``) to avoid a second, static picture.
    """
    if frames < 1:
        raise WorkbenchError(f"animate: frames must be >= 1, not {frames}")
    ax = axes_or_new(ax)
    fig = ax.figure
    scene = sol.scene
    n = sol.positions.size
    rows = np.unique(np.linspace(0, n - 1, min(frames, n)).round().astype(int))
    colors = body_colors()
    # coordinates of every body's points at every row: (rows, points, 2)
    geo = {}
    for name, body in scene.bodies.items():
        m = sol.kin.bodies[name]
        xy = [tuple(np.broadcast_to(c, (n,)) for c in m.point(loc))
              for loc in body.points.values()]
        geo[name] = np.stack([np.stack(p, axis=-1) for p in xy], axis=1)
    allxy = np.concatenate([g.reshape(-1, 2) for g in geo.values()]
                           + [np.array(list(scene.ground.values())).reshape(-1, 2)])
    lo, hi = allxy.min(axis=0), allxy.max(axis=0)
    pad = 0.08 * float(max(hi - lo)) + 1e-9
    if trace:
        for b, p in trace_points(sol):
            k = list(scene.bodies[b].points).index(p)
            ax.plot(geo[b][:, k, 0], geo[b][:, k, 1], lw=0.8, color="0.6", alpha=0.7)
    for gxy in scene.ground.values():
        ax.plot(*gxy, "^", color="k", ms=10, mfc="0.8", zorder=4)
    artists = {}
    for k, (name, body) in enumerate(scene.bodies.items()):
        c = colors[k % len(colors)]
        npts = len(body.points)
        style = {"color": c, "label": name}
        if npts == 1:
            (ln,) = ax.plot([], [], "s", ms=13, alpha=0.7, **style)
        else:
            (ln,) = ax.plot([], [], "-o", lw=3, ms=5, mfc="white", **style)
        artists[name] = ln
    guides = [(j, ax.plot([], [], "--", color="0.4", lw=1)[0])
              for j in scene.joints.values() if j.kind == "T"]
    span = float(max(hi - lo)) or 1.0
    title = ax.set_title("", fontsize=10)

    def update(f: int):
        i = int(rows[f])
        for name, body in scene.bodies.items():
            pts = geo[name][i]
            if len(body.points) >= 3:
                pts = np.vstack([pts, pts[:1]])
            artists[name].set_data(pts[:, 0], pts[:, 1])
        for j, ln in guides:
            gx, gy = global_point(sol, j.guide, j.points[0], i)
            th = _guide_angle(sol, j, i)
            t = np.array(_guide_extent(sol, j, i, span))
            ln.set_data(gx + t * np.cos(th), gy + t * np.sin(th))
        title.set_text(f"{scene.title or 'mechanism'}: {position_text(sol, i)}")
        return [*artists.values(), *(g[1] for g in guides), title]

    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    legend_outside(ax, fontsize=10)     # never over the moving links
    update(0)
    return FuncAnimation(fig, update, frames=len(rows), interval=interval, blit=False)

