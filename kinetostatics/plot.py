"""The classic pictures of kinetostatics, drawn from computed data.

Every function takes a :class:`~kinetostatics.results.Solution` (or tables), an
optional ``ax``, and returns the matplotlib Axes (or Figure); none calls ``plt.show``.
Units are in every axis label; geometry and vector diagrams use equal aspect.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Polygon

from .results import Solution
from .scene import GROUND


def _ax(ax: Axes | None, figsize=(6, 4.5)) -> Axes:
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax


def _pos_label(sol: Solution) -> str:
    return "crank angle φ [deg]" if sol.scene.driver.kind == "R" else "driver position s [m]"


def _row(sol: Solution, position: float | None, row: int | None) -> int:
    if row is not None:
        return int(row)
    if position is None:
        return 0
    return int(np.argmin(np.abs(sol.positions - position)))


def _global(sol: Solution, body: str, point: str, row: int) -> tuple[float, float]:
    if body == GROUND:
        return sol.scene.ground[point]
    m = sol.kin.bodies[body]
    x, y = m.point(sol.scene.bodies[body].local(point))
    return float(np.broadcast_to(x, sol.positions.shape)[row]), \
        float(np.broadcast_to(y, sol.positions.shape)[row])


def draw_mechanism(sol: Solution, position: float | None = None, *, row: int | None = None,
                   ax: Axes | None = None, forces: bool = False, labels: bool = True,
                   force_scale: float | None = None) -> Axes:
    """Draw the mechanism at one position: links between their joint points, pins,
    slider blocks and guides, the ground; with ``forces=True`` the joint reactions on
    each joint's ``on`` body as arrows (scaled so the largest is 1/4 of the size)."""
    ax = _ax(ax)
    i = _row(sol, position, row)
    scene = sol.scene
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    allpts = []
    for k, (name, body) in enumerate(scene.bodies.items()):
        pts = [_global(sol, name, p, i) for p in body.points]
        allpts += pts
        c = colors[k % len(colors)]
        if len(pts) >= 3:
            ax.add_patch(Polygon(pts, closed=True, alpha=0.25, color=c))
            ax.plot(*zip(*(pts + pts[:1]), strict=True), color=c, lw=2.5, label=name)
        elif len(pts) == 2:
            ax.plot(*zip(*pts, strict=True), color=c, lw=3.5, solid_capstyle="round",
                    label=name)
        else:
            ax.plot(*zip(*pts, strict=True), "s", color=c, ms=14, alpha=0.6, label=name)
        if body.cog is not None and body.mass > 0:
            g = _global(sol, name, "cog", i)
            ax.plot(*g, "o", mfc="white", mec=c, ms=6)
        if labels:
            for p, xy in zip(body.points, pts, strict=True):
                ax.annotate(p, xy, xytext=(4, 4), textcoords="offset points", fontsize=9)
    size = np.ptp(np.array(allpts), axis=0).max() if allpts else 1.0
    for j in scene.joints.values():
        if j.kind == "R":
            b = j.bodies[1] if j.bodies[0] == GROUND else j.bodies[0]
            xy = _global(sol, b, j.point_on(b), i)
            ax.plot(*xy, "o", color="k", mfc="white", ms=7, zorder=5)
            if GROUND in j.bodies:
                ax.plot(*xy, "^", color="k", ms=12, zorder=4, mfc="0.8")
        else:
            gx, gy = _global(sol, j.guide, j.points[0], i) if j.guide != GROUND else \
                scene.ground[j.points[0]]
            th = np.deg2rad(j.line_angle)
            if j.guide != GROUND:
                th += float(np.broadcast_to(sol.kin.bodies[j.guide].theta,
                                            sol.positions.shape)[i])
            u = np.array([np.cos(th), np.sin(th)])
            ends = np.array([gx, gy]) + np.outer([-0.6 * size, 0.6 * size], u)
            ax.plot(ends[:, 0], ends[:, 1], "--", color="0.4", lw=1)
    if forces:
        vecs = []
        for name in scene.joints:
            r = sol.joint_reactions[name]
            fx, fy = sol.reaction(name)
            x = float(np.broadcast_to(r.x, sol.positions.shape)[i])
            y = float(np.broadcast_to(r.y, sol.positions.shape)[i])
            vecs.append((name, x, y, float(fx[i]), float(fy[i])))
        fmax = max((np.hypot(v[3], v[4]) for v in vecs), default=1.0) or 1.0
        sc = force_scale or 0.25 * size / fmax
        for name, x, y, fx, fy in vecs:
            ax.annotate("", (x + sc * fx, y + sc * fy), (x, y),
                        arrowprops={"arrowstyle": "-|>", "color": "tab:red", "lw": 1.5})
            ax.annotate(f"F[{name}]", (x + sc * fx, y + sc * fy), fontsize=8,
                        color="tab:red")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    unit = "deg" if scene.driver.kind == "R" else "m"
    ax.set_title(f"{scene.title or 'mechanism'} at {sol.positions[i]:g} {unit}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    return ax


def plot_driver(sol: Solution, ax: Axes | None = None) -> Axes:
    """Me (or Fe) over the sweep, its mean, and the singular rows shaded."""
    ax = _ax(ax)
    q = sol.driver_quantity
    me = sol.Me
    ax.plot(sol.positions, me, lw=2, label=q)
    mean = sol.summary()[f"{q}_mean"]
    ax.axhline(mean, color="tab:orange", ls="--", label=f"mean {mean:.4g}")
    ax.axhline(0.0, color="0.5", lw=0.8)
    sing = sol.singular
    if sing.any():
        ax.fill_between(sol.positions, 0, 1, where=sing, transform=ax.get_xaxis_transform(),
                        color="tab:red", alpha=0.15, label="near a dead centre")
    ax.set_xlabel(_pos_label(sol))
    ax.set_ylabel("equilibrating moment Me [N m]" if q == "Me"
                  else "equilibrating force Fe [N]")
    ax.set_title(f"{q} over the cycle")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_polar(sol: Solution, joints: Sequence[str] | str | None = None,
               ax: Axes | None = None) -> Axes:
    """Polar diagram (hodograph) of joint reactions: the tip of the force vector over
    the cycle, drawn from the origin (seed 002: the polar diagram of F_ij)."""
    ax = _ax(ax)
    if joints is None:
        joints = list(sol.scene.joints)
    elif isinstance(joints, str):
        joints = [joints]
    for j in joints:
        fx, fy = sol.reaction(j)
        r = sol.joint_reactions[j]
        ax.plot(fx, fy, lw=1.8, label=f"F[{j}] on {r.on}")
        ax.plot(fx[:1], fy[:1], "o", color=ax.lines[-1].get_color(), ms=5)
    ax.plot(0, 0, "k+", ms=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("Fx [N]")
    ax.set_ylabel("Fy [N]")
    ax.set_title("polar diagram of joint reactions (dot: first position)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_transmission(sol: Solution, ax: Axes | None = None, admissible: float = 40.0) -> Axes:
    """Transmission angle of every dyad over the cycle (eqs 2.60-2.61) with the
    admissible band [admissible, 180 - admissible]."""
    ax = _ax(ax)
    t = sol.dyads
    for d, g in t.groupby("dyad"):
        ax.plot(g.position, g.transmission_angle, lw=2,
                label=f"dyad {d} {g.kind.iloc[0]} ({g.bodies.iloc[0]})")
    ax.axhspan(0, admissible, color="tab:red", alpha=0.1)
    ax.axhspan(180 - admissible, 180, color="tab:red", alpha=0.1, label="not admissible")
    ax.set_ylim(0, 180)
    ax.set_xlabel(_pos_label(sol))
    ax.set_ylabel("transmission angle τ [deg]")
    ax.set_title("transmission angle")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_trajectories(sol: Solution, points: Sequence[str] | None = None,
                      ax: Axes | None = None) -> Axes:
    """Paths of points ``"body.point"`` over the sweep (default: every named point)."""
    ax = _ax(ax)
    k = sol.kinematics
    if points is None:
        points = [f"{b}.{p}" for b, p in k[["body", "point"]].drop_duplicates().values]
    for bp in points:
        b, p = bp.split(".", 1)
        g = k[(k.body == b) & (k.point == p)]
        ax.plot(g.x, g.y, lw=1.5, label=bp)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("trajectories")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return ax


def overview(sol: Solution, position: float | None = None) -> Figure:
    """Four panels: the mechanism with its reactions, Me(φ), the polar diagram of the
    reactions, the transmission angle."""
    fig, axs = plt.subplots(2, 2, figsize=(12, 9), layout="constrained")
    if position is None:
        position = float(sol.positions[len(sol.positions) // 12])
    draw_mechanism(sol, position, ax=axs[0, 0], forces=True)
    plot_driver(sol, ax=axs[0, 1])
    plot_polar(sol, ax=axs[1, 0])
    if len(sol.kin.dyads):
        plot_transmission(sol, ax=axs[1, 1])
    else:
        plot_trajectories(sol, ax=axs[1, 1])
    return fig
