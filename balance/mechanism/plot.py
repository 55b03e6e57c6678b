"""Pictures of a mechanism's static balancing (seed 002 s. 3.4), drawn from a
:class:`~balance.mechanism.MechanismBalancing`.

Every function takes an optional ``ax`` (or ``fig``), never calls ``plt.show()``,
labels its axes with units, keeps an equal aspect for hodographs and paths, and
returns the Axes (or the Figure, for several panels).

- :func:`plot_shaking_hodograph`: the tip of the shaking force vector over the
  cycle, before and after (a point at the origin after full balancing);
- :func:`plot_shaking_force`: |F| and the moment about the crank axis against the
  crank angle, before and after;
- :func:`plot_centre_of_mass`: the path of the mechanism's centre of mass, before
  and after (a fixed point after full balancing, eq. 3.41);
- :func:`plot_counterweights`: the mechanism at one position with its
  counterweights (and the counter-rotating pair);
- :func:`overview`: the four in one figure.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from kinetostatics.plot.collide import GUIDE
from kinetostatics.plot.notation import reading
from kinetostatics.plot.place import declutter

from .shaking import crank_axis, motion_at, pair_motion
from .solve import MechanismBalancing

__all__ = [
    "overview",
    "plot_centre_of_mass",
    "plot_counterweights",
    "plot_shaking_force",
    "plot_shaking_hodograph",
]

_BEFORE = "tab:blue"
_AFTER = "tab:red"


def _new_axes(ax: Axes | None, figsize: tuple[float, float] = (6.0, 5.6)) -> Axes:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax


def _position_label(result: MechanismBalancing) -> str:
    return "crank angle (deg)" if result.scene.driver.kind == "R" else "driver position (m)"


def _closed(a: np.ndarray) -> np.ndarray:
    return np.append(a, a[:1]) if a.size else a


def plot_shaking_hodograph(result: MechanismBalancing, ax: Axes | None = None, *,
                           before: bool = True, after: bool = True) -> Axes:
    """Hodograph of the shaking force (Fy against Fx over the sweep), before and after.

    Parameters
    ----------
    result : MechanismBalancing
    ax : matplotlib Axes, optional
    before, after : bool
        Which curves to draw.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _new_axes(ax)
    full_turn = result.before["position"].size > 1 and \
        abs(float(np.ptp(result.before["position"])) - 360.0) < 1e-9
    for show, tab, color, name in ((before, result.before, _BEFORE, "before"),
                                   (after, result.after, _AFTER, "after")):
        if not show:
            continue
        fx, fy = tab["Fx"].to_numpy(), tab["Fy"].to_numpy()
        if not full_turn:
            fx, fy = _closed(fx), _closed(fy)
        what = f"after {result.method} balancing" if name == "after" else "before"
        peak = float(tab["F"].max())
        scale = float(result.before["F"].max()) or 1.0
        peak_text = "0 (to rounding)" if peak <= 1e-9 * scale else f"{reading(peak)} N"
        ax.plot(fx, fy, color=color, lw=1.6, label=f"{what}: max |F| = {peak_text}")
        if fx.size:
            ax.plot(fx[0], fy[0], "o", color=color, ms=5)
    ax.plot(0.0, 0.0, "+", color="k", ms=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.axhline(0.0, color="0.85", lw=0.8, zorder=0, gid=GUIDE)
    ax.axvline(0.0, color="0.85", lw=0.8, zorder=0, gid=GUIDE)
    ax.set_xlabel("shaking force $F_x$ (N)")
    ax.set_ylabel("shaking force $F_y$ (N)")
    ax.set_title(f"Shaking-force hodograph, {result.kind}, method {result.method!r}\n"
                 "(dot: first position of the sweep)", fontsize=10)
    ax.grid(True, color="0.93")
    ax.legend(fontsize=10, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              borderaxespad=0.0)        # below the drawing, never over the curves
    return ax


def plot_shaking_force(result: MechanismBalancing, fig: Figure | None = None) -> Figure:
    """|F| and the shaking moment about the crank axis over the sweep, before and after.

    Returns
    -------
    matplotlib.figure.Figure
        Two panels sharing the position axis.
    """
    if fig is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(7.0, 6.0), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    for tab, color, name in ((result.before, _BEFORE, "before"), (result.after, _AFTER, "after")):
        pos = tab["position"].to_numpy()
        ax1.plot(pos, tab["F"], color=color, label=name)
        ax2.plot(pos, tab["M"], color=color, label=name)
    ax1.set_ylabel("|F| (N)")
    ax1.set_title(f"Shaking force and moment, {result.kind}, method {result.method!r}",
                  fontsize=10)
    ax2.set_ylabel("M about the crank axis (N m)")
    ax2.set_xlabel(_position_label(result))
    for ax in (ax1, ax2):
        ax.grid(True, color="0.9")
        ax.legend(fontsize=10)
    return fig


def plot_centre_of_mass(result: MechanismBalancing, ax: Axes | None = None) -> Axes:
    """Path of the mechanism's centre of mass over the sweep (eq. 3.32), before and after.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _new_axes(ax)
    for after, color, name in ((False, _BEFORE, "before"), (True, _AFTER, "after")):
        c = result.centre_of_mass(after=after)
        label = f"{name} (mass {c['mass'].iloc[0]:.4g} kg)" if len(c) else name
        ax.plot(c["x"], c["y"], color=color, lw=1.6, label=label)
        if len(c):
            ax.plot(c["x"].iloc[0], c["y"].iloc[0], "o", color=color, ms=5)
    ax.plot(*_axis(result), "^", color="k", ms=10, mfc="0.8", label="crank axis")
    if result.centre is not None:
        ax.plot(*result.centre, "x", color=_AFTER, ms=10, mew=2, label="fixed centre of mass")
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.15)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"Centre of mass of the mechanism, method {result.method!r}", fontsize=10)
    ax.grid(True, color="0.93")
    ax.legend(fontsize=10, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              borderaxespad=0.0)        # below the drawing, never over the curves
    return ax


def _axis(result: MechanismBalancing) -> tuple[float, float]:
    return crank_axis(result.scene)


def plot_counterweights(result: MechanismBalancing, position: float | None = None,
                        ax: Axes | None = None) -> Axes:
    """The mechanism at one position (``kinetostatics.plot.draw_mechanism``) with its
    counterweights as discs (area in proportion to mass) and the pair's masses.

    Parameters
    ----------
    result : MechanismBalancing
    position : float, optional
        Driver position (deg); default the sweep's first.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    import kinetostatics as ks
    from kinetostatics.plot import draw_mechanism

    ax = _new_axes(ax)
    sol = ks.solve(result.scene)
    pos = sol.positions
    i = 0 if position is None else int(np.argmin(np.abs(pos - position)))
    draw_mechanism(sol, row=i, ax=ax)
    masses = [c.mass for c in result.counterweights]
    if result.pair is not None:
        masses.append(result.pair.mass)
    top = max(masses, default=0.0) or 1.0
    texts: list = []            # the masses, placed clear of the links (declutter)
    for c in result.counterweights:
        bm = result.kin.bodies[c.body]
        x, y, *_ = motion_at(bm, c.position, result.kin.n)
        px, py, *_ = motion_at(bm, result.scene.bodies[c.body].points[c.about], result.kin.n)
        ax.plot([float(px[i]), float(x[i])], [float(py[i]), float(y[i])], "-", color="0.25",
                lw=2.0)
        ax.plot(float(x[i]), float(y[i]), "o", color="0.25", alpha=0.8,
                ms=6 + 18 * math.sqrt(c.mass / top))
        texts.append(ax.annotate(f"{reading(c.mass, 3)} kg", (float(x[i]), float(y[i])),
                                 xytext=(8, -12), textcoords="offset points", fontsize=10))
    if result.pair is not None:
        (xc, yc, _, _), (xr, yr, _, _) = pair_motion(result.kin, result.pair)
        ang = np.linspace(0.0, 2.0 * np.pi, 121)
        cx, cy = result.pair.axis
        ax.plot(cx + result.pair.radius * np.cos(ang), cy + result.pair.radius * np.sin(ang),
                ":", color="0.5", lw=1)
        for x, y, name in ((xc, yc, "+ω"), (xr, yr, "−ω")):
            ax.plot(float(x[i]), float(y[i]), "o", color="tab:purple", alpha=0.6,
                    ms=6 + 18 * math.sqrt(result.pair.mass / top))
            texts.append(ax.annotate(f"{reading(result.pair.mass, 3)} kg ({name})",
                                     (float(x[i]), float(y[i])), xytext=(8, 6),
                                     textcoords="offset points", fontsize=10,
                                     color="tab:purple"))
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.1)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    unit = "deg" if result.scene.driver.kind == "R" else "m"
    ax.set_title(f"Counterweights ({result.method}) at position {pos[i]:g} {unit}",
                 fontsize=10)
    declutter(ax, texts)
    return ax


def overview(result: MechanismBalancing, position: float | None = None) -> Figure:
    """The mechanism with its counterweights, the hodograph, the centre of mass path and
    |F| over the sweep, in one figure."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(12.0, 10.0), layout="constrained")
    plot_counterweights(result, position, ax=axes[0, 0])
    plot_shaking_hodograph(result, ax=axes[0, 1])
    plot_centre_of_mass(result, ax=axes[1, 0])
    ax = axes[1, 1]
    for tab, color, name in ((result.before, _BEFORE, "before"), (result.after, _AFTER, "after")):
        ax.plot(tab["position"], tab["F"], color=color, label=name)
    ax.set_xlabel(_position_label(result))
    ax.set_ylabel("|F| (N)")
    ax.set_title("Shaking force over the sweep", fontsize=10)
    ax.grid(True, color="0.9")
    ax.legend(fontsize=10)
    fig.suptitle(f"Static balancing of the {result.kind}: {result.method}")
    return fig
