"""Curves over the cycle: Me (or Fe), the polar diagrams of the joint reactions, the
transmission angle, trajectories, speeds and accelerations of points, the angular motion
of the bodies, and the four-panel overview.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..model.errors import WorkbenchError
from ..results import Solution
from .base import (
    PATH_COLORS,
    axes_or_new,
    cycle_axis,
    legend_below,
    legend_outside,
    magnitude_text,
    position_label,
    trace_points,
    vector_axes,
)
from .mechanism import draw_mechanism
from .notation import direction_text, force_symbol, number, reading, titled
from .place import declutter, settle, settled_later

__all__ = [
    "overview", "plot_accelerations", "plot_angular", "plot_driver", "plot_polar",
    "plot_speeds", "plot_trajectories", "plot_transmission",
]


def plot_driver(sol: Solution, ax: Axes | None = None) -> Axes:
    """Me (or Fe) over the sweep, its mean (trapezoid rule) and the rows near a dead
    centre shaded (seed 002 eqs 2.44-2.51).

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        Position against Me [N m] (Fe [N] for a sliding driver).
    """
    ax = axes_or_new(ax, figsize=(8.5, 5.0))
    q = sol.driver_quantity
    sing = np.asarray(sol.singular, dtype=bool)
    me = np.where(sing, np.nan, sol.Me)     # a singular row has no value: a gap, shaded
    unit = "N m" if q == "Me" else "N"
    ax.plot(sol.positions, me, lw=2, label=q)
    mean = sol.summary()[f"{q}_mean"]
    if abs(mean) < 1e-9 * (np.nanmax(np.abs(me), initial=0.0) or 1.0):
        mean = 0.0
    mean_text = "0 (to rounding)" if mean == 0.0 else f"{number(mean)} {unit}"
    ax.axhline(mean, color="tab:orange", ls="--", label=f"mean {mean_text}")
    ax.axhline(0.0, color="0.5", lw=0.8)
    if sing.any():
        ax.fill_between(sol.positions, 0, 1, where=sing, transform=ax.get_xaxis_transform(),
                        color="tab:red", alpha=0.15,
                        label=f"near a dead point: {int(sing.sum())} rows, no value")
    ax.set_xlabel(position_label(sol))
    cycle_axis(ax, sol)
    ax.set_ylabel("equilibrating moment Me [N m]" if q == "Me"
                  else "equilibrating force Fe [N]")
    ax.set_title(f"{titled('equilibrating moment' if q == 'Me' else 'equilibrating force')} "
                 f"{q} over the cycle", fontsize=11)
    ax.grid(True, alpha=0.3)
    legend_outside(ax)
    return ax


def plot_polar(sol: Solution, joints: Sequence[str] | str | None = None,
               ax: Axes | None = None, numbers: int | None = None) -> Axes:
    """Polar diagram (hodograph) of joint reactions: the tip of the force vector over
    the cycle, drawn from the origin (seed 002: the polar diagram of F_ij), with the
    position numbers along each curve as in the course's drawings.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    joints : str or sequence of str, optional
        Joint names (default: every joint); the force is the one on the joint's ``on``
        body (the ``reactions`` table).
    ax : Axes, optional
        Where to draw; a new figure when None.
    numbers : int, optional
        How many numbered positions along each curve (0, 1, ... at evenly spaced rows
        of the sweep; the legend says where they are); 0 for none. Default: 12 for up
        to two joints, none for more (the numbers of many curves crowd each other).

    Returns
    -------
    Axes
        Fx [N] against Fy [N], equal aspect; a dot marks the first position.
    """
    ax = axes_or_new(ax, figsize=(8.5, 5.5))
    if joints is None:
        joints = list(sol.scene.joints)
    elif isinstance(joints, str):
        joints = [joints]
    if numbers is None:
        numbers = 12 if len(joints) <= 2 else 0
    rows = numbered_rows(sol, numbers)
    texts = []
    numbered = False
    for j in joints:
        fx, fy = sol.reaction(j)
        sing = np.asarray(sol.singular, dtype=bool)
        if sing.any() and not sing.all():       # a singular row has no value: a gap
            fx, fy = np.where(sing, np.nan, fx), np.where(sing, np.nan, fy)
        r = sol.joint_reactions[j]
        kind, u = _polar_kind(fx, fy)
        f0 = np.array([float(fx[0]), float(fy[0])])
        if kind == "constant":      # one point: say it, number nothing
            ax.plot(fx[:1], fy[:1], "o", ms=7, label=f"{force_symbol(j)} on {r.on}")
            c = ax.lines[-1].get_color()
            ax.annotate("", tuple(f0), (0.0, 0.0), arrowprops={
                "arrowstyle": "-|>", "color": c, "lw": 1.2, "shrinkA": 0, "shrinkB": 4})
            texts.append(ax.annotate(
                f"{force_symbol(j)} = {magnitude_text(float(np.hypot(*f0)))} N at "
                f"{direction_text(f0)}"
                "\nover the whole cycle", tuple(f0), xytext=(6, 6),
                textcoords="offset points", fontsize=10, color=c))
            continue
        numbered = True
        ax.plot(fx, fy, lw=1.8, label=f"{force_symbol(j)} on {r.on}")
        c = ax.lines[-1].get_color()
        if kind == "fixed direction":
            along = np.asarray(fx) * u[0] + np.asarray(fy) * u[1]
            ax.plot([], [], ls="none", label=f"{force_symbol(j)}: fixed direction "
                    f"{direction_text(u)}, "
                    f"{number(along.min(), '.4g')} to {number(along.max(), '.4g')} N along it")
            ax.annotate("", tuple(u * float(np.abs(along).max())), (0.0, 0.0),
                        arrowprops={"arrowstyle": "-|>", "color": c, "lw": 0.8, "ls": ":",
                                    "shrinkA": 0, "shrinkB": 0})
        ax.plot(fx[:1], fy[:1], "o", color=c, ms=5)
        ax.plot(fx[rows], fy[rows], ".", color=c, ms=4)
        for k, i in enumerate(rows):
            texts.append(ax.annotate(str(k), (float(fx[i]), float(fy[i])), xytext=(3, 3),
                                     textcoords="offset points", fontsize=10, color=c))
    ax.plot(0, 0, "k+", ms=10)
    if len(rows) and numbered:
        step = float(sol.positions[rows[1]] - sol.positions[rows[0]]) if len(rows) > 1 else 0.0
        unit = "°" if sol.scene.driver.kind == "R" else " m"
        ax.plot([], [], ".", color="0.3",
                label=f"k: position {float(sol.positions[0]):g}{unit} + k·{reading(step)}{unit}")
    ax.set_aspect("equal", adjustable="datalim")
    vector_axes(ax)
    ax.set_xlabel("Fx [N]")
    ax.set_ylabel("Fy [N]")
    ax.set_title(f"{titled('polar diagram')} of the joint reactions\n(dot: first position)",
                 fontsize=11)
    ax.grid(True, alpha=0.3)
    legend_outside(ax)
    declutter(ax, texts)
    return ax


def _polar_kind(fx, fy) -> tuple[str, np.ndarray]:
    """``"constant"`` (one vector over the cycle), ``"fixed direction"`` (every vector
    along one line, the unit vector returned) or ``"curve"``; to 1e-9 of the largest."""
    f = np.column_stack([np.broadcast_to(fx, np.shape(fy)), fy]).astype(float)
    big = float(np.hypot(f[:, 0], f[:, 1]).max()) if len(f) else 0.0
    if big == 0.0 or float(np.ptp(f, axis=0).max()) <= 1e-9 * big:
        return "constant", np.array([1.0, 0.0])
    k = int(np.argmax(np.hypot(f[:, 0], f[:, 1])))
    u = f[k] / np.hypot(*f[k])
    if float(np.abs(f[:, 0] * u[1] - f[:, 1] * u[0]).max()) <= 1e-9 * big:
        return "fixed direction", u
    return "curve", u


def numbered_rows(sol: Solution, numbers: int) -> np.ndarray:
    """``numbers`` rows evenly spaced over the sweep (a closed turn does not repeat its
    first position at the end)."""
    n = sol.positions.size
    if numbers <= 0 or n == 0:
        return np.array([], dtype=int)
    p = sol.positions
    closed = sol.scene.driver.kind == "R" and n > 1 and \
        abs(float(p[-1] - p[0]) - 360.0) < 1e-9 * 360.0
    return np.unique(np.linspace(0, n - 1, numbers, endpoint=not closed).round().astype(int))


def plot_transmission(sol: Solution, ax: Axes | None = None, admissible: float = 40.0) -> Axes:
    """Transmission angle of every dyad over the cycle (eqs 2.60-2.61), drawn as
    min(tau, 180 - tau) in [0, 90] deg, with the band below ``admissible`` shaded.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    ax : Axes, optional
        Where to draw (a new figure when None).
    admissible : float
        The smallest admissible transmission angle (deg); outside the band is shaded.

    Returns
    -------
    Axes
    """
    ax = axes_or_new(ax)
    t = getattr(sol, "transmission", None)
    if not isinstance(t, pd.DataFrame) or "transmission_angle" not in t:
        t = sol.dyads
    texts = []
    for d, g in t.groupby("dyad"):
        tau = g.transmission_angle.to_numpy()
        low = np.minimum(tau, 180.0 - tau)          # one definition, [0, 90]
        ax.plot(g.position, low, lw=2, label=f"dyad {d} {g.kind.iloc[0]} ({g.bodies.iloc[0]})")
        if len(low) and float(np.ptp(low)) <= 1e-9 * 90.0:      # constant: say it
            texts.append(ax.annotate(
                f"dyad {d}: τ = {number(float(low[0]), '.4g')}° over the whole cycle",
                (float(np.mean(g.position)), float(low[0])), xytext=(0, -6),
                textcoords="offset points", ha="center", va="top", fontsize=10,
                color=ax.lines[-1].get_color()))
    ax.axhspan(0, admissible, color="tab:red", alpha=0.1, label="not admissible")
    ax.set_ylim(0, 95)
    ax.set_xlabel(position_label(sol))
    cycle_axis(ax, sol)
    ax.set_ylabel("transmission angle min(τ, 180° − τ) [deg]")
    ax.set_title(titled("transmission angle"), fontsize=11)
    ax.grid(True, alpha=0.3)
    legend_outside(ax)
    declutter(ax, texts)
    return ax


def _points_arg(sol: Solution, points) -> list[tuple[str, str]]:
    if points is None:
        return trace_points(sol)
    if isinstance(points, str):
        points = [points]
    out = []
    for bp in points:
        if "." not in bp:
            raise WorkbenchError(f"point {bp!r}: write it as 'body.point', e.g. 'coupler.P'")
        b, p = bp.split(".", 1)
        if b not in sol.scene.bodies or (p != "cog" and p not in sol.scene.bodies[b].points):
            raise WorkbenchError(f"point {bp!r}: no such body point")
        out.append((b, p))
    return out


def plot_trajectories(sol: Solution, points: Sequence[str] | None = None,
                      ax: Axes | None = None) -> Axes:
    """Paths (traiectorii) of points over the sweep, dashed.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    points : sequence of str, optional
        ``"body.point"`` names (default: every named point and centre of mass).
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        x [m] against y [m], equal aspect.
    """
    ax = axes_or_new(ax)
    k = sol.kinematics
    if points is None:
        points = [f"{b}.{p}" for b, p in k[["body", "point"]].drop_duplicates().values]
    for c, bp in enumerate(points):
        b, p = bp.split(".", 1)
        g = k[(k.body == b) & (k.point == p)]
        ax.plot(g.x, g.y, lw=1.4, ls="--", color=PATH_COLORS[c % len(PATH_COLORS)],
                label=f"path of {bp}")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("trajectories", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=10, ncol=2)
    return ax


def _point_curves(sol: Solution, points, component: str, ax: Axes | None, kind: str) -> Axes:
    if component not in ("magnitude", "x", "y"):
        raise WorkbenchError(f"component must be 'magnitude', 'x' or 'y', not {component!r}")
    ax = axes_or_new(ax)
    n = sol.positions.size
    for b, p in _points_arg(sol, points):
        m = sol.kin.bodies[b]
        x, y = m.point(sol.scene.bodies[b].local(p))
        vx, vy = (m.vel_at if kind == "v" else m.acc_at)(x, y)
        vx, vy = np.broadcast_to(vx, (n,)), np.broadcast_to(vy, (n,))
        val = {"magnitude": np.hypot(vx, vy), "x": vx, "y": vy}[component]
        ax.plot(sol.positions, val, lw=1.8, label=f"{b}.{p}")
    sym = "v" if kind == "v" else "a"
    unit = "m/s" if kind == "v" else "m/s²"
    comp = {"magnitude": f"|{sym}|", "x": f"{sym}x", "y": f"{sym}y"}[component]
    ax.set_xlabel(position_label(sol))
    cycle_axis(ax, sol)
    ax.set_ylabel(f"{'speed' if kind == 'v' else 'acceleration'} {comp} [{unit}]")
    ax.set_title(f"{'velocities' if kind == 'v' else 'accelerations'} of points over the "
                 "cycle", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=10, ncol=2)
    return ax


def plot_speeds(sol: Solution, points: Sequence[str] | str | None = None, *,
                component: str = "magnitude", ax: Axes | None = None) -> Axes:
    """Velocity of points over the sweep.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    points : str or sequence of str, optional
        ``"body.point"`` names (default: every named point, once per name).
    component : str
        ``"magnitude"`` (the speed |v|), ``"x"`` or ``"y"`` (signed components).
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        Position against v [m/s].
    """
    return _point_curves(sol, points, component, ax, "v")


def plot_accelerations(sol: Solution, points: Sequence[str] | str | None = None, *,
                       component: str = "magnitude", ax: Axes | None = None) -> Axes:
    """Acceleration of points over the sweep: ``points``, ``component`` (``"magnitude"``,
    ``"x"`` or ``"y"``) and ``ax`` as in :func:`plot_speeds`.

    Returns
    -------
    Axes
        Position against a [m/s²].
    """
    return _point_curves(sol, points, component, ax, "a")


def plot_angular(sol: Solution, bodies: Sequence[str] | str | None = None) -> Figure:
    """Angle, angular velocity omega and angular acceleration eps of bodies over the
    sweep, three panels sharing the position axis.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    bodies : str or sequence of str, optional
        Body names (default: every body that turns).

    Returns
    -------
    Figure
    """
    t = sol.bodies
    if bodies is None:
        bodies = [b for b, g in t.groupby("body", sort=False)
                  if np.ptp(g.angle.to_numpy()) > 1e-9 or np.abs(g.omega).max() > 0]
    elif isinstance(bodies, str):
        bodies = [bodies]
    fig, axs = plt.subplots(3, 1, figsize=(6.5, 7.0), sharex=True, layout="constrained")
    for b in bodies:
        g = t[t.body == b]
        if g.empty:
            raise WorkbenchError(f"plot_angular: no body {b!r}")
        axs[0].plot(g.position, g.angle, lw=1.8, label=b)
        axs[1].plot(g.position, g.omega, lw=1.8, label=b)
        axs[2].plot(g.position, g.alpha, lw=1.8, label=b)
    for a, lab in zip(axs, ("angle θ [deg]", "ω [rad/s]", "ε [rad/s²]"), strict=True):
        a.set_ylabel(lab)
        a.grid(True, alpha=0.3)
        a.axhline(0.0, color="0.5", lw=0.6)
    axs[0].legend(fontsize=10, ncol=3)
    axs[0].set_title("angular motion of the bodies", fontsize=10)
    axs[-1].set_xlabel(position_label(sol))
    cycle_axis(axs[-1], sol)
    return fig


def overview(sol: Solution, position: float | None = None) -> Figure:
    """Four panels: the mechanism with its loads and reactions, Me(φ), the polar diagram of the
    reactions, the transmission angle (the trajectories when there is no dyad).

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    position : float, optional
        Driver position of the drawing (default: a twelfth into the sweep).

    Returns
    -------
    Figure
    """
    fig, axs = plt.subplots(2, 2, figsize=(14, 11.5), layout="constrained")
    if position is None:
        position = float(sol.positions[len(sol.positions) // 12])
    with settled_later():       # the labels placed once, by settle below
        draw_mechanism(sol, position, ax=axs[0, 0], forces=True, loads=True)
        plot_driver(sol, ax=axs[0, 1])
        plot_polar(sol, ax=axs[1, 0])
        if len(sol.kin.dyads):
            plot_transmission(sol, ax=axs[1, 1])
        else:
            plot_trajectories(sol, ax=axs[1, 1])
    for ax in axs.flat:         # four panels: each legend below its panel, not beside
        legend_below(ax)
    settle(fig)
    return fig

