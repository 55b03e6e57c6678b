"""Pictures of a design search: the front with the scene's own design marked
(:func:`plot_front`), and one design drawn beside its Me curve (:func:`draw_design`).
Both take data and return a matplotlib Figure; neither calls ``plt.show``."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..plot.base import axes_or_new


def _label(result, k: int) -> str:
    o = result.spec.objectives[k]
    return f"{o.quantity.name} [{o.quantity.unit}] ({'min' if o.sense > 0 else 'max'})"


def plot_front(result, ax: Axes | None = None, chosen: int | None = None) -> Axes:
    """The front's designs in the plane of the first two objectives (their values, a
    maximised one as its value), the scene's own design (a star, hollow when it is not
    feasible) and the ``chosen`` design (default: the compromise) marked."""
    ax = axes_or_new(ax, figsize=(6.4, 4.6))
    v = result.values
    chosen = result.compromise if chosen is None else chosen
    two = v.shape[1] > 1
    x = v[:, 0] if two else np.arange(len(v))
    y = v[:, 1] if two else v[:, 0]
    ax.plot(x, y, "o", ms=4, color="C0", label=f"front ({len(v)} designs)")
    ax.plot(x[chosen], y[chosen], "o", ms=11, mfc="none", mec="C3", mew=2,
            label=f"design {chosen} ({result.scene_file(chosen)})")
    own = result.bundled
    if own.solved[0]:
        ox, oy = (own.values[0, 0], own.values[0, 1]) if two else (-1, own.values[0, 0])
        ok = bool(own.feasible[0])
        ax.plot(ox, oy, "*", ms=15, color="C1", mfc="C1" if ok else "none", mew=1.5,
                label="the scene's own design" + ("" if ok else " (not feasible)"))
    ax.set_xlabel(_label(result, 0) if two else "design")
    ax.set_ylabel(_label(result, 1) if two else _label(result, 0))
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=9)
    ax.set_title(f"{result.spec.scene.title}: the front")
    return ax


def draw_design(result, i: int, fig: Figure | None = None, *, front: bool = False,
                own=None) -> Figure:
    """Design ``i`` of the front: its mechanism at the row of its largest |Me| (|Fe|),
    and its Me over the sweep beside the scene's own design's (``own``: that design's
    Solution, solved here when not given); with ``front``, the front first, design
    ``i`` circled."""
    from ..plot.mechanism import draw_mechanism
    from ..solver.pipeline import solve
    if fig is None:
        fig = Figure(figsize=(15.5 if front else 11, 4.4), layout="constrained")
        FigureCanvasAgg(fig)        # a canvas that renders (no pyplot)
    else:
        fig.clear()
    axes = fig.subplots(1, 3 if front else 2,
                        gridspec_kw={"width_ratios": [1, 1.1, 1] if front else [1.1, 1]})
    if front:
        plot_front(result, axes[0], chosen=i)
    a, b = axes[-2:]
    sol = result.solve(i)
    q = sol.driver_quantity
    me = np.asarray(sol.Me)
    draw_mechanism(sol, row=int(np.argmax(np.abs(me))), ax=a)
    a.set_title(f"design {i}: at the peak of |{q}|")
    order = sol.order
    b.plot(sol.positions[order], me[order], color="C3", lw=2, label=f"design {i}")
    if own is None and result.bundled.solved[0]:
        own = solve(result.spec.scene)
    if own is not None:
        b.plot(own.positions[own.order], np.asarray(own.Me)[own.order], color="C1", lw=1.2,
               ls="--", label="the scene's own design")
    b.axhline(0.0, color="0.5", lw=0.6)
    b.set_xlabel(f"driver position [{'deg' if sol.scene.driver.kind == 'R' else 'm'}]")
    b.set_ylabel(f"{q} [{'N m' if q == 'Me' else 'N'}]")
    b.grid(True, alpha=0.3)
    b.legend(loc="best", fontsize=9)
    names = ", ".join(f"{o.quantity.name} = {result.values[i, k]:.4g} {o.quantity.unit}"
                      for k, o in enumerate(result.spec.objectives))
    b.set_title(names, fontsize=9)
    return fig
