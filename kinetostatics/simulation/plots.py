"""Pictures of the cross-check and of its study (matplotlib Figures, never shown)."""

from __future__ import annotations

import math
import re

import numpy as np
import pandas as pd

from ..plot.notation import couple_subscript, force_symbol, reading
from .comparison import CrossCheck, quantity_unit
from .runner import BUDGET, TARGET_ERROR
from .studies import Study

__all__ = ["display_name", "plot_comparison", "plot_study"]

_BRACKETED = re.compile(r"^([A-Za-z|]+)\[([^\]]+)\](\|?)$")


def display_name(quantity: str) -> str:
    """A compared quantity as the pictures write it: ``F[A]`` is the reaction
    :math:`F_A` (the notation of the free-body diagrams and polygons), ``M[slot]`` the
    couple in a prismatic joint; ``Me``, ``Fe`` stay."""
    m = _BRACKETED.match(quantity)
    if m is None:
        return quantity
    head, joint, bar = m.groups()
    sym = force_symbol(joint) if head.strip("|") == "F" else \
        f"${head.strip('|')}{couple_subscript(joint)}$"
    return f"|{sym}|" if head.startswith("|") or bar else sym


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
    # by default the driver's signed Me (Fe) stands for its magnitude |Me| as well
    qs = quantities or [q for q in dict.fromkeys(cc.rows.quantity)
                        if q not in ("|Me|", "|Fe|")]
    ncol = min(3, len(qs))
    nrow = -(-len(qs) // ncol)
    fig = Figure(figsize=(4.2 * ncol, 3.0 * nrow), layout="constrained")
    axes = fig.subplots(nrow, ncol, squeeze=False).ravel()
    xlab = "crank angle φ (deg)" if cc.scene.driver.kind == "R" else "driver position s (m)"
    for ax, q in zip(axes, qs, strict=False):
        g = cc.rows[cc.rows.quantity == q]
        ax.plot(g.position, g.computed, "-", lw=1.2, color="C0", label="kinetostatics")
        s = g.iloc[::max(1, every)]
        ax.plot(s.position, s.simulated, ".", ms=3, color="C1", label="pymunk")
        e = cc.errors.get(q, cc.derived_errors.get(q, float("nan")))
        src = "" if q in cc.errors else " (momentum balance)"
        name = display_name(q)
        ax.set_title(f"{name}: error {e:.1e}{src}", fontsize=10)
        ax.set_xlabel(xlab)
        ax.set_ylabel(f"{name} ({quantity_unit(q, cc.scene)})")
        ax.grid(alpha=0.3)
    for ax in axes[len(qs):]:
        ax.set_visible(False)
    # one legend for all panels, below them: never over a curve
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncol=2,
               fontsize=10, frameon=False)
    fig.suptitle(f"{cc.scene.title}: pymunk (dt = {reading(cc.settings.get('dt', 0), 3)} s, "
                 f"{cc.settings.get('iterations')} iterations) against kinetostatics",
                 fontsize=10)
    return fig


def plot_study(table: pd.DataFrame | Study, *, repeats: int | None = None):
    """Log-log pictures of a study: error against wall time per revolution, and error
    against dt with a dt^2 guide.

    Converged settings are joined by lines; a setting whose cost fell although its
    steps grew is drawn hollow and grey (timing noise, not a result) and kept off the
    line; diverged settings have no error: they are marked along the top of the
    convergence panel. Legends sit below the panels, off the data.

    Parameters
    ----------
    table : pandas.DataFrame or Study
        Rows as in :attr:`Study.table` (several cases may be concatenated).
    repeats : int, optional
        Runs per setting whose best wall time is shown (default the study's).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure
    from matplotlib.transforms import blended_transform_factory
    t = table.table if isinstance(table, Study) else table
    if repeats is None:
        repeats = table.repeats if isinstance(table, Study) else 1
    blown_col = t["diverged"] if "diverged" in t else pd.Series(False, index=t.index)
    noise_col = t["timing_noise"] if "timing_noise" in t else pd.Series(False, index=t.index)
    fig = Figure(figsize=(11, 5.5), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    top = blended_transform_factory(ax2.transData, ax2.transAxes)
    row = 0                         # each series with diverged settings: its own row of x
    for i, ((case, it), g) in enumerate(t.groupby(["case", "iterations"], sort=False)):
        g = g.sort_values("dt")
        blown, noise = blown_col[g.index], noise_col[g.index]
        ok = g[~blown]
        color = f"C{i % 10}"
        label = f"{case}, {it} it."
        clean = ok[~noise[ok.index]]
        ax1.loglog(clean.ms_per_revolution, clean.max_error, "o-", ms=4, color=color,
                   label=label)
        noisy = ok[noise[ok.index]]
        if len(noisy):
            ax1.loglog(noisy.ms_per_revolution, noisy.max_error, "o", ms=6, mfc="none",
                       color="0.5", label="timing noise (cost fell as steps grew)")
        ax2.loglog(ok.dt, ok.max_error, "o-", ms=4, color=color, label=label)
        if blown.any():
            ax2.plot(g.dt[blown], np.full(int(blown.sum()), 0.965 - 0.045 * row), "x", ms=7,
                     mew=2, color=color, transform=top, clip_on=False,
                     label="diverged (no error)")
            row += 1
    ax1.plot([1e3 * BUDGET], [TARGET_ERROR], marker="*", ms=12, color="k", ls="none",
             label=f"target: {TARGET_ERROR:g} within {1e3 * BUDGET:g} ms")
    ax1.axhline(1e-5, color="0.6", lw=0.8, ls="--")
    ax1.axhline(1e-6, color="0.6", lw=0.8, ls="--")
    ax1.set_xlabel("wall time per simulated revolution (ms)")
    ax1.set_ylabel("max relative error")
    ax1.set_title(f"cost against error (wall time: best of {repeats} run"
                  f"{'s' if repeats != 1 else ''})", fontsize=10)
    ok = t[~blown_col]
    if len(ok):
        h = np.array([ok.dt.min(), ok.dt.max()])
        e0 = float(ok.max_error[ok.dt == ok.dt.max()].min())
        ax2.loglog(h, e0 * (h / h[1]) ** 2, "k--", lw=0.8, label="slope 2")
    ax2.set_xlabel("dt (s)")
    ax2.set_ylabel("max relative error")
    ax2.set_title("convergence" + (" (x along the top: diverged)" if blown_col.any() else ""),
                  fontsize=10)
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter
    if not len(ok):
        ax2.set_yticks([])
        for ax in (ax1, ax2):
            ax.text(0.5, 0.3, "every setting diverged: no error to show", ha="center",
                    va="center", transform=ax.transAxes, fontsize=10, color="0.3")
    elif blown_col.any():
        # an empty band along the top for the diverged marks, clear of the data
        lo, hi = ax2.get_ylim()
        ax2.set_ylim(lo, hi * (hi / lo) ** (0.06 + 0.07 * row))
    handles: dict = {}
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3, which="both")
        # ticks at 1, 2 and 5 of each decade, labelled as plain numbers: never crowded
        ax.xaxis.set_major_locator(FixedLocator(_log_ticks(*ax.get_xlim())))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _: reading(x)))
        ax.xaxis.set_minor_formatter(NullFormatter())
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(lab, h)
    fig.legend(handles.values(), handles.keys(), loc="outside lower center", ncol=3,
               fontsize=10, frameon=False)
    return fig


def _log_ticks(lo: float, hi: float) -> list[float]:
    """Tick values 1, 2 and 5 times a power of ten within [lo, hi]; where fewer than two
    fall inside (a range under a factor of 5), the ends rounded to two figures."""
    k0, k1 = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
    ticks = [m * 10.0 ** k for k in range(k0, k1 + 1) for m in (1.0, 2.0, 5.0)
             if lo <= m * 10.0 ** k <= hi]
    if len(ticks) < 2:
        ticks = sorted({*ticks, float(f"{lo * 1.05:.2g}"), float(f"{hi / 1.05:.2g}")})
    return ticks
