"""The classic balancing pictures, drawn from result objects.

Every function takes an optional ``ax`` (a new figure is made when it is None),
never calls ``plt.show()``, labels its axes with units, keeps an equal aspect for
vector diagrams and returns the Axes (or the Figure, for several panels).

- :func:`plot_unbalance_polygon`: the unbalance vectors tip to tail, closed by the
  correction(s) (seed 002 figs 3.2, 3.4, 3.7);
- :func:`plot_moment_polygon`: the moments of the unbalances about correction plane
  I, closed by plane II's correction (fig. 3.6);
- :func:`plot_parallelogram`: the amplitude parallelogram (fig. 3.14) with both
  candidate positions of the unbalance and of the correction (fig. 3.15);
- :func:`plot_amplitude_circles` and :func:`plot_run_comparison`: each run's
  amplitude as a circle; three runs (0 and 180 deg) meet in two mirror points,
  the four-run method's circles in one.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Circle
from matplotlib.text import Annotation

from kinetostatics.plot.collide import GUIDE
from kinetostatics.plot.place import declutter

from .common import polar
from .errors import BalanceError
from .resonance.methods import ResonanceResult
from .rotor.design import RotorResult

__all__ = [
    "candidate_marks",
    "plot_amplitude_circles",
    "plot_moment_polygon",
    "plot_parallelogram",
    "plot_run_comparison",
    "plot_unbalance_polygon",
]

_COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink",
           "tab:olive", "tab:cyan")
_CORRECTION = "tab:red"


def _new_axes(ax: Axes | None) -> Axes:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots(figsize=(6.4, 6.0), layout="constrained")
    return ax


def _arrow(ax: Axes, tail: complex, tip: complex, label: str | None, color: str,
           ls: str = "-", lw: float = 1.8, text_offset: float = 0.0, frac: float = 0.5) -> None:
    """A vector from tail to tip, labelled at ``frac`` of its length."""
    ax.annotate("", xy=(tip.real, tip.imag), xytext=(tail.real, tail.imag),
                arrowprops={"arrowstyle": "-|>", "color": color, "lw": lw, "ls": ls,
                            "shrinkA": 0, "shrinkB": 0, "mutation_scale": 14})
    ax.update_datalim([(tail.real, tail.imag), (tip.real, tip.imag)])
    if label:
        mid = tail + frac * (tip - tail)
        d = tip - tail
        n = 1j * d / abs(d) if abs(d) > 0 else 0j
        pos = mid + n * text_offset
        ax.annotate(label, (pos.real, pos.imag), color=color, fontsize=10, ha="center",
                    va="center", xytext=(0, 0), textcoords="offset points",
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                          "alpha": 0.8})


def _finish(ax: Axes, xlabel: str, ylabel: str, title: str) -> Axes:
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.margins(0.12)
    ax.axhline(0.0, color="0.85", lw=0.8, zorder=0, gid=GUIDE)     # guides, as grid lines
    ax.axvline(0.0, color="0.85", lw=0.8, zorder=0, gid=GUIDE)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10, pad=14)
    ax.grid(True, color="0.93")
    ax.ticklabel_format(style="sci", axis="both", scilimits=(-3, 4), useMathText=True)
    # the vectors' labels placed clear of the vectors and of each other (as the
    # mechanism pictures' labels: kinetostatics.plot.declutter; settle() at the end)
    declutter(ax, [t for t in ax.texts if isinstance(t, Annotation) and t.get_text()])
    return ax


def _rotor_scale(result: RotorResult, force: bool | None) -> tuple[float, str, str]:
    use = result.speed_rpm is not None if force is None else force
    if use and result.speed_rpm is None:
        raise BalanceError("plot: forces need the rotor's speed_rpm; use force=False")
    return (result.scale, "N", "N m") if use else (1.0, "kg m", "kg m$^2$")


def plot_unbalance_polygon(result: RotorResult, ax: Axes | None = None, *,
                           force: bool | None = None) -> Axes:
    """The unbalance vector polygon closed by the correction(s) (figs 3.2, 3.4, 3.7).

    The vectors U_j = m_j r_j follow tip to tail from the origin; the correction
    vectors (one plane: U_e, eq. 3.6; two planes: U_e1 and U_e2, eq. 3.10) bring the
    polygon back to the origin. The dashed vector (two planes) is the resultant U_d
    (eq. 3.3).

    Parameters
    ----------
    result : RotorResult
        From :func:`balance.balance_rotor`.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure when None.
    force : bool, optional
        Draw inertia forces U omega^2 (N) rather than unbalances (kg m). Default:
        forces when the rotor has a speed.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _new_axes(ax)
    k, unit, _ = _rotor_scale(result, force)
    vecs = result.unbalances * k
    size = float(np.abs(vecs).sum()) or 1.0
    p = 0j
    for j, u in enumerate(vecs):
        _arrow(ax, p, p + u, f"U{j + 1}", _COLORS[j % len(_COLORS)], text_offset=0.04 * size)
        p += u
    many = len(result.corrections) > 1
    if abs(p) > 0 and many:  # with one plane U_d is -U_e, drawn below
        _arrow(ax, 0j, p, "Ud", "0.45", ls="--", lw=1.2, text_offset=-0.04 * size)
    for c in result.corrections:
        u = c.vector * k
        if abs(u) > 0:
            _arrow(ax, p, p + u, f"Ue{c.plane}" if many else "Ue", _CORRECTION,
                   text_offset=0.04 * size)
        p += u
    ax.plot([0.0], [0.0], "ko", ms=4)
    what = r"inertia forces $U\omega^2$" if k != 1.0 else "unbalance vectors $U = m r$"
    return _finish(ax, f"x component ({unit})", f"y component ({unit})",
                   f"Polygon of the {what}, closed by the correction")


def plot_moment_polygon(result: RotorResult, ax: Axes | None = None, *,
                        force: bool | None = None) -> Axes:
    """The polygon of the unbalance moments about correction plane I (fig. 3.6).

    Each moment is k x ((z_j - z_I) U_j), i.e. (z_j - z_I) U_j turned +90 deg (the
    seed draws them turned clockwise, looking along the other direction of the
    axis); plane II's correction moment (z_II - z_I) U_e2 closes the polygon
    (eqs 3.11-3.13). With one plane the gap left open is the residual couple.

    Parameters
    ----------
    result : RotorResult
        From :func:`balance.balance_rotor`.
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    force : bool, optional
        Moments of forces (N m) rather than of unbalances (kg m^2).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _new_axes(ax)
    k, _, unit = _rotor_scale(result, force)
    z_ref = result.corrections[0].z
    moments = 1j * (result.z - z_ref) * result.unbalances * k        # eq. 3.12
    size = float(np.abs(moments).sum()) or 1.0
    p = 0j
    for j, m in enumerate(moments):
        if abs(m) > 0:
            _arrow(ax, p, p + m, f"M{j + 1}", _COLORS[j % len(_COLORS)], text_offset=0.04 * size)
        p += m
    for c in result.corrections[1:]:
        m = 1j * (c.z - z_ref) * c.vector * k                          # eq. 3.13
        if abs(m) > 0:
            _arrow(ax, p, p + m, f"Me{c.plane}", _CORRECTION, text_offset=0.04 * size)
        p += m
    if abs(p) > 1e-9 * size:
        _arrow(ax, p, 0j, "residual couple", "0.45", ls="--", lw=1.2, text_offset=0.04 * size)
    ax.plot([0.0], [0.0], "ko", ms=4)
    return _finish(ax, f"x component ({unit})", f"y component ({unit})",
                   f"Moments about correction plane I (z = {z_ref:g} m): "
                   r"$k \times (z - z_I)\,U$")


def plot_parallelogram(result: ResonanceResult, ax: Axes | None = None, *,
                       unit: str = "amplitude unit", selected: float | None = None) -> Axes:
    """The amplitude parallelogram (fig. 3.14) with the candidate correction positions.

    The trial amplitude A lies along the 0 deg mark, the unbalance's amplitude A1 at
    phi from it; A2 = |A1 + A| and A3 = |A1 - A| are the diagonals. The mirror
    parallelogram (A1 at -phi, dashed) fits the same three amplitudes, so the
    three-run method leaves two candidates (``angle``, the seed's eq. 3.31 reading, and
    ``mirror_angle``): both are marked as candidates, neither as "the" correction,
    unless ``selected`` names the one a further test chose (a run at a third mark, or
    a known unbalance), which is then marked as selected. A runs result has one
    position, marked as the correction.

    Parameters
    ----------
    result : ResonanceResult
        From :func:`balance.parallelogram` or :func:`balance.trial_runs`.
    ax : matplotlib.axes.Axes, optional
        Where to draw.
    unit : str
        The amplitudes' unit, for the axis labels (e.g. ``"um"``).
    selected : float, optional
        The candidate angle (deg) a further test selected; it must be one of the two.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if result.phi is None:
        raise BalanceError("plot_parallelogram: A1 = 0, the rotor is balanced; nothing to draw")
    ax = _new_axes(ax)
    A, A1 = result.A, result.A1
    Avec = complex(A, 0.0)
    corr = candidate_marks(result, selected)
    # the parallelogram of the selected candidate solid, the other dashed
    mirror_chosen = len(corr) == 2 and corr[1][2]
    phi = -result.phi if mirror_chosen else result.phi
    candidates = [(phi, "-", 1.0)]
    if result.mirror_angle is not None:
        candidates.append((-phi, "--", 0.55))
    scale = A + A1
    for n, (phi, ls, alpha) in enumerate(candidates):
        U = polar(A1, phi)
        tag = "" if n == 0 else "'"
        color = "tab:blue" if n == 0 else "tab:gray"
        _arrow(ax, 0j, U, f"A1{tag}", color, ls=ls, text_offset=0.04 * scale)
        _arrow(ax, U, U + Avec, None, "0.6", ls=ls, lw=1.0)
        _arrow(ax, Avec, U + Avec, None, "0.6", ls=ls, lw=1.0)
        _arrow(ax, 0j, U + Avec, f"A2{tag}", "tab:green" if n == 0 else "0.5", ls=ls,
               lw=1.4, text_offset=-0.03 * scale, frac=0.72)
        _arrow(ax, Avec, U, f"A3{tag}", "tab:purple" if n == 0 else "0.5", ls=ls, lw=1.4,
               text_offset=0.03 * scale, frac=0.3)
        ax.plot([U.real], [U.imag], "o", color=color, ms=5, alpha=alpha)
    _arrow(ax, 0j, Avec, "A", "tab:orange", text_offset=-0.05 * scale)   # the trial, at 0°
    R = 1.15 * max(A1, A)
    for ang, text, filled in corr:
        q = polar(R, ang)
        ax.plot([0.0, q.real], [0.0, q.imag], ":", color=_CORRECTION, lw=1.0)
        ax.plot([q.real], [q.imag], marker="s", color=_CORRECTION, ms=8,
                mfc=_CORRECTION if filled else "white")
        right = q.real > 0.0        # the label runs towards the inside of the picture
        ax.annotate(text, (q.real, q.imag), xytext=(-6 if right else 6,
                                                    -12 if q.imag < 0 else 6),
                    textcoords="offset points", color=_CORRECTION, fontsize=10,
                    ha="right" if right else "left")
        ax.update_datalim([(q.real, q.imag)])
    # the circle of the marks: a faint guide, as a grid line (a label may cross it)
    ax.add_patch(Circle((0.0, 0.0), R, fill=False, color="0.9", lw=0.8, zorder=0))
    return _finish(ax, f"amplitude along the 0° mark, the trial A's ({unit})",
                   f"amplitude, normal to it ({unit})",
                   f"Amplitude parallelogram, plane {result.plane}: φ = {result.phi:.2f}°"
                   + ("\nthree runs fit both: a run at a third mark decides"
                      if result.mirror_angle is not None and selected is None else ""))


def candidate_marks(result: ResonanceResult, selected: float | None = None
                    ) -> list[tuple[float, str, bool]]:
    """The correction positions a parallelogram picture marks: (angle in deg, label,
    filled). Three runs: both candidates, hollow and labelled as candidates, unless
    ``selected`` (one of them, to 1e-6 deg modulo 360) was chosen by a further test:
    that one filled and labelled "selected". Runs: the unique correction, filled.

    Raises
    ------
    BalanceError
        ``selected`` is not one of the candidates.
    """
    if result.mirror_angle is None:
        return [(result.angle, f"correction {result.angle:.1f}°", True)]
    both = [result.angle, result.mirror_angle]
    # the result's keys angle and mirror_angle, as a student reads them
    names = ("candidate 1", "candidate 2 (mirror)")
    if selected is None:
        return [(a, f"{n}: {a:.1f}°", False) for a, n in zip(both, names, strict=True)]

    def gap(a):
        return abs((a - selected + 180.0) % 360.0 - 180.0)

    if min(gap(a) for a in both) > 1e-6:
        raise BalanceError(f"plot_parallelogram: selected = {selected:g} deg is neither "
                           f"candidate ({both[0]:.6g} or {both[1]:.6g} deg)")
    return [(a, f"correction = {n}: {a:.1f}° (selected)" if gap(a) <= 1e-6 else
             f"{n}: {a:.1f}° (rejected)", gap(a) <= 1e-6)
            for a, n in zip(both, names, strict=True)]


def plot_amplitude_circles(result: ResonanceResult, ax: Axes | None = None, *,
                           unit: str = "amplitude unit") -> Axes:
    """Each run as a circle: they meet at the tip of the unbalance's amplitude vector.

    A run with the trial mass at mark theta_k measured A_k = |A1 e^(i theta_u) +
    A e^(i theta_k)|: the tip of A1 e^(i theta_u) lies on the circle of radius A_k
    about -A e^(i theta_k), and on the circle of radius A1 about the origin. Runs at 0
    and 180 deg give circles meeting in two mirror points; a third mark settles it.

    Parameters
    ----------
    result, ax, unit
        As in :func:`plot_parallelogram`.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _new_axes(ax)
    t = np.linspace(0.0, 2.0 * math.pi, 361)
    circle = np.exp(1j * t)
    c0 = result.A1 * circle
    u = {"um": "µm"}.get(unit, unit)        # micrometres with the micro sign
    ax.plot(c0.real, c0.imag, color="k", lw=1.2, label=f"A1 = {result.A1:.4g} {u} about O")
    for k, (mark, amp) in enumerate(zip(result.marks, result.amplitudes, strict=True)):
        centre = -polar(result.A, float(mark))
        c = centre + amp * circle
        color = _COLORS[k % len(_COLORS)]
        ax.plot(c.real, c.imag, color=color, lw=1.2,
                label=f"trial at {mark:g} deg: A = {amp:.4g} {u}")
        ax.plot([centre.real], [centre.imag], "+", color=color, ms=8)
    if result.phi is not None:
        tips = [polar(result.A1, result.phi)]
        if result.mirror_angle is not None:
            tips.append(polar(result.A1, -result.phi))
        for n, tip in enumerate(tips):
            ax.plot([tip.real], [tip.imag], "o", ms=8, mfc="none", mec=_CORRECTION, mew=2,
                    label=("unbalance" if len(tips) == 1 else "candidate unbalances")
                    if n == 0 else None)
            ax.plot([0.0, tip.real], [0.0, tip.imag], color=_CORRECTION, lw=1.0)
    ax.legend(fontsize=10, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    kind = "three-run" if result.method == "three-run" else f"{result.marks.size + 1}-run"
    return _finish(ax, f"x ({u}), 0 deg mark along +x", f"y ({u})",
                   f"{kind} method, plane {result.plane}:\ncircles of the measured amplitudes")


def plot_run_comparison(three_run: ResonanceResult, runs: ResonanceResult,
                        *, unit: str = "amplitude unit") -> Figure:
    """Side by side: the three-run method's two mirror solutions, the runs' unique one.

    Parameters
    ----------
    three_run : ResonanceResult
        From :func:`balance.parallelogram`.
    runs : ResonanceResult
        From :func:`balance.four_run` or :func:`balance.trial_runs`.
    unit : str
        The amplitudes' unit.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12.0, 6.0), layout="constrained")
    plot_amplitude_circles(three_run, axes[0], unit=unit)
    plot_amplitude_circles(runs, axes[1], unit=unit)
    fig.suptitle("Three runs leave a mirror ambiguity; a run at a third mark removes it")
    return fig
