"""Pictures of the cross-check and of its study (matplotlib Figures, never shown)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from .comparison import CrossCheck, _unit
from .studies import Study


def plot_comparison(cc: CrossCheck, quantities: list[str] | None = None, *, every: int = 1):
    """Simulated against computed values over the driver's positions, one panel each.

    Parameters
    ----------
    cc : CrossCheck
    quantities : list of str, optional
        Which (default every joint's ``F[...]``, the locked couples and ``Me``/``Fe``).
    every : int
        Plot every n-th simulated sample as a marker.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure
    qs = quantities or list(dict.fromkeys(cc.rows.quantity))
    ncol = min(3, len(qs))
    nrow = -(-len(qs) // ncol)
    fig = Figure(figsize=(4.2 * ncol, 3.0 * nrow), layout="constrained")
    axes = fig.subplots(nrow, ncol, squeeze=False).ravel()
    xlab = "driver angle (deg)" if cc.scene.driver.kind == "R" else "driver position (m)"
    for ax, q in zip(axes, qs, strict=False):
        g = cc.rows[cc.rows.quantity == q]
        ax.plot(g.position, g.computed, "-", lw=1.2, color="C0", label="kinetostatics")
        s = g.iloc[::max(1, every)]
        ax.plot(s.position, s.simulated, ".", ms=3, color="C1", label="pymunk")
        e = cc.errors.get(q, float("nan"))
        ax.set_title(f"{q}: error {e:.1e}", fontsize=9)
        ax.set_xlabel(xlab)
        ax.set_ylabel(f"{q} ({_unit(q, cc.scene)})")
        ax.grid(alpha=0.3)
    for ax in axes[len(qs):]:
        ax.set_visible(False)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{cc.scene.title}: pymunk (dt = {cc.settings.get('dt', 0):.3g} s, "
                 f"{cc.settings.get('iterations')} iterations) against kinetostatics",
                 fontsize=10)
    return fig


def plot_study(table: pd.DataFrame | Study):
    """Log-log pictures of a study: error against wall time per revolution, and error
    against dt with a dt^2 guide.

    Parameters
    ----------
    table : pandas.DataFrame or Study
        Rows as in :attr:`Study.table` (several cases may be concatenated).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure
    t = table.table if isinstance(table, Study) else table
    fig = Figure(figsize=(10, 4), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    for i, ((case, it), g) in enumerate(t.groupby(["case", "iterations"], sort=False)):
        g = g.sort_values("dt")
        style = dict(marker="o", ms=4, color=f"C{i % 10}", label=f"{case}, {it} it.")
        ax1.loglog(g.ms_per_revolution, g.max_error, **style)
        ax2.loglog(g.dt, g.max_error, **style)
    for thr, ms in ((1e-5, 20.0), (1e-6, 60.0)):
        ax1.plot([ms], [thr], marker="*", ms=12, color="k", ls="none")
    ax1.axhline(1e-5, color="0.6", lw=0.8, ls="--")
    ax1.axhline(1e-6, color="0.6", lw=0.8, ls="--")
    ax1.set_xlabel("wall time per simulated revolution (ms)")
    ax1.set_ylabel("max relative error")
    ax1.set_title("cost against error (stars: the targets)", fontsize=10)
    if len(t):
        h = np.array([t.dt.min(), t.dt.max()])
        e0 = float(t.max_error[t.dt == t.dt.max()].min())
        ax2.loglog(h, e0 * (h / h[1]) ** 2, "k--", lw=0.8, label="slope 2")
    ax2.set_xlabel("dt (s)")
    ax2.set_ylabel("max relative error")
    ax2.set_title("convergence", fontsize=10)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3, which="both")
    ax2.legend(fontsize=7)
    return fig
