"""The flywheel pictures (seed 002 ch. 4): the reduced moment of inertia I_r(phi), the
reduced moments M_r(phi), the energy Delta E(phi) over a cycle, and the Wittenbauer
(energy-inertia) diagram with the two tangents that size a flywheel for a degree of
irregularity delta (eq. 4.20).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from ..common.angles import degree_column, radian_column
from ..model.errors import WorkbenchError
from .base import axes_or_new
from .notation import reading

__all__ = ["plot_flywheel_curves", "plot_wittenbauer", "reduced_cycle", "wittenbauer_flywheel"]


def reduced_cycle(scene, n: int = 361, motor: float | np.ndarray | None = None
                  ) -> pd.DataFrame:
    """The reduced quantities of a scene's mechanism over one turn of the crank.

    Parameters
    ----------
    scene : Scene, path, TOML text or dict
        A mechanism with a crank driver.
    n : int
        Number of angles, from the sweep's first position over 360 deg (both ends).
    motor : float or array, optional
        The motor's moment on the crank [N m]: a constant or one value per angle.
        Default: the constant that does the cycle's work of the loads (the steady state
        of a position-only balance, eq. 4.8 over a cycle).

    Returns
    -------
    DataFrame
        ``phi`` [deg], ``I_r`` [kg m^2] (eq. 2.75, without a flywheel), ``dI_r`` [kg m^2
        /rad], ``M_loads`` [N m] (the loads reduced to the crank, eq. 2.72), ``M_motor``,
        ``M`` = M_motor + M_loads, ``delta_E`` [J] = integral of M dphi from the first
        angle (trapezoid rule; eq. 4.8).
    """
    from ..model.scene import load_scene
    from ..motion import ReducedMechanism

    sc = load_scene(scene)
    if sc.driver.kind != "R":
        raise WorkbenchError("reduced_cycle: the driver must be a crank")
    if n < 3:
        raise WorkbenchError(f"reduced_cycle: n must be >= 3, not {n}")
    start = float(sc.driver.positions[0])
    phi = radian_column(start + np.linspace(0.0, 360.0, n))
    i_r, di_r, m_r = ReducedMechanism(sc, phi[0]).evaluate(phi)
    if motor is None:
        motor = -np.trapezoid(m_r, phi) / (2.0 * np.pi)
    m_m = np.broadcast_to(np.asarray(motor, dtype=float), phi.shape)
    m = m_m + m_r
    de = np.concatenate(([0.0], np.cumsum(0.5 * (m[1:] + m[:-1]) * np.diff(phi))))
    return pd.DataFrame({"phi": degree_column(phi), "I_r": i_r, "dI_r": di_r, "M_loads": m_r,
                         "M_motor": m_m, "M": m, "delta_E": de})


def plot_flywheel_curves(data: pd.DataFrame) -> Figure:
    """I_r(phi), the reduced moments and Delta E(phi) over a cycle, three panels.

    Parameters
    ----------
    data : DataFrame
        :func:`reduced_cycle` (columns ``phi, I_r, M_loads, M_motor, M, delta_E``).

    Returns
    -------
    Figure
        Top: I_r [kg m^2]; middle: M_loads, M_motor and their sum M [N m]; bottom:
        Delta E [J] with its largest swing Delta E_max = max - min marked (the energy a
        flywheel must store, eq. 4.8).
    """
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(3, 1, figsize=(7.0, 8.0), sharex=True, layout="constrained")
    p = data["phi"].to_numpy()
    axs[0].plot(p, data["I_r"], lw=2, color="tab:blue")
    axs[0].set_ylabel("$I_r$ [kg m²]")
    axs[0].set_title("reduced moment of inertia, reduced moments\nand energy over a cycle",
                     fontsize=10)
    axs[1].plot(p, data["M_loads"], lw=1.8, label="loads $M_r$")
    axs[1].plot(p, data["M_motor"], lw=1.8, label="motor $M_m$")
    axs[1].plot(p, data["M"], lw=2.2, color="k", label="$M = M_m + M_r$")
    axs[1].axhline(0.0, color="0.5", lw=0.8)
    axs[1].set_ylabel("reduced moment [N m]")
    axs[1].legend(fontsize=10, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    de = data["delta_E"].to_numpy()
    k_hi, k_lo = int(np.argmax(de)), int(np.argmin(de))
    axs[2].plot(p, de, lw=2, color="tab:green")
    axs[2].plot(p[[k_hi, k_lo]], de[[k_hi, k_lo]], "o", color="tab:red")
    axs[2].axhline(0.0, color="0.5", lw=0.8)
    axs[2].annotate("", (p[k_hi], de[k_hi]), (p[k_hi], de[k_lo]),
                    arrowprops={"arrowstyle": "<->", "color": "tab:red"})
    axs[2].plot([], [], color="tab:red",
                label=f"$ΔE_{{max}}$ = {reading(de[k_hi] - de[k_lo])} J "
                      f"({p[k_lo]:.0f}° to {p[k_hi]:.0f}°)")
    axs[2].set_ylabel("ΔE [J]")
    axs[2].set_xlabel("crank angle φ [deg]")
    axs[2].legend(fontsize=10, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    for a in axs:
        a.grid(True, alpha=0.3)
    if np.ptp(p) >= 180.0:
        from matplotlib.ticker import MultipleLocator
        axs[2].xaxis.set_major_locator(MultipleLocator(45.0))
    return fig


def wittenbauer_flywheel(i_r, delta_e, omega_mean: float, delta: float) -> dict:
    """The flywheel from the Wittenbauer diagram for a degree of irregularity delta.

    The kinetic energy E0 + Delta E = (J + I_r) omega^2 / 2, so from the point (-J,
    -E0) every point of the curve (I_r, Delta E) is seen under a slope omega^2 / 2; the
    two tangents of slopes omega_max^2 / 2 and omega_min^2 / 2, with omega_max,min =
    omega_mean (1 +- delta / 2) (eq. 4.20: delta = (omega_max - omega_min) / omega_mean),
    cross at that point.

    Parameters
    ----------
    i_r, delta_e : array
        The curve: reduced moment of inertia [kg m^2] and energy [J] over a cycle.
    omega_mean : float
        Mean angular speed [rad/s].
    delta : float
        Degree of irregularity (0 < delta < 2).

    Returns
    -------
    dict
        ``J`` [kg m^2] (the flywheel's moment of inertia), ``E0`` [J] (the kinetic
        energy at Delta E = 0), ``k_max``, ``b_max``, ``k_min``, ``b_min`` (the tangents
        Delta E = k I + b), ``i_max``, ``i_min`` (the rows where they touch).
    """
    i_r, de = np.asarray(i_r, dtype=float), np.asarray(delta_e, dtype=float)
    if not 0.0 < delta < 2.0 or omega_mean <= 0.0:
        raise WorkbenchError("wittenbauer_flywheel: need omega_mean > 0 and 0 < delta < 2")
    k_max = 0.5 * (omega_mean * (1.0 + 0.5 * delta)) ** 2
    k_min = 0.5 * (omega_mean * (1.0 - 0.5 * delta)) ** 2
    up, lo = de - k_max * i_r, de - k_min * i_r
    i_max, i_min = int(np.argmax(up)), int(np.argmin(lo))
    b_max, b_min = float(up[i_max]), float(lo[i_min])
    x = (b_min - b_max) / (k_max - k_min)
    return {"J": -x, "E0": -(k_max * x + b_max), "k_max": k_max, "b_max": b_max,
            "k_min": k_min, "b_min": b_min, "i_max": i_max, "i_min": i_min}


def plot_wittenbauer(data: pd.DataFrame, omega_mean: float | None = None,
                     delta: float | None = None, ax: Axes | None = None,
                     numbers: int = 12) -> Axes:
    """The Wittenbauer diagram: Delta E against I_r over a cycle, numbered positions,
    and, given omega_mean and delta, the two tangents that size the flywheel
    (:func:`wittenbauer_flywheel`).

    Parameters
    ----------
    data : DataFrame
        :func:`reduced_cycle`.
    omega_mean : float, optional
        Mean angular speed [rad/s].
    delta : float, optional
        Degree of irregularity wanted (eq. 4.20).
    ax : Axes, optional
    numbers : int
        Positions numbered along the curve (evenly spaced angles).

    Returns
    -------
    Axes
        I_r [kg m^2] against Delta E [J]; the title gives J when the tangents are drawn.
    """
    from .notation import titled
    from .place import declutter

    ax = axes_or_new(ax, figsize=(8.5, 5.5))
    i_r, de, p = (data[c].to_numpy() for c in ("I_r", "delta_E", "phi"))
    closed = abs(p[-1] - p[0] - 360.0) < 1e-9
    rows = np.unique(np.linspace(0, len(p) - 1, numbers, endpoint=not closed).round()
                     .astype(int)) if numbers > 0 else np.array([], dtype=int)
    title = f"{titled('Wittenbauer diagram')}: energy against reduced inertia"
    curve = ax
    w = None
    if omega_mean is not None and delta is not None:
        w = wittenbauer_flywheel(i_r, de, omega_mean, delta)
        x0 = -w["J"]
        for k, b, r, lab in ((w["k_max"], w["b_max"], w["i_max"], "$ω_{max}^2/2$"),
                             (w["k_min"], w["b_min"], w["i_min"], "$ω_{min}^2/2$")):
            xs = np.array([x0, i_r[r]])
            ax.plot(xs, k * xs + b, "--", lw=1.2,
                    label=f"tangent, slope {lab} = {reading(k)} J/(kg m²)")
        ax.plot(x0, -w["E0"], "s", color="k",
                label=f"(−J, −E0) = ({reading(x0)} kg m², {reading(-w['E0'])} J)")
        title += (f"\n$ω_m$ = {reading(omega_mean)} rad/s, δ = {delta:g}: flywheel J = "
                  f"{reading(w['J'])} kg m²")
        # the curve is small beside the construction: zoomed in an inset
        curve = ax.inset_axes([0.08, 0.5, 0.45, 0.42])
        curve.set_title("the curve, zoomed", fontsize=10)
        curve.tick_params(labelsize=10)       # the lecture style's smallest text
        for axis in (curve.xaxis, curve.yaxis):
            axis.set_major_locator(MaxNLocator(nbins=3))
        curve.grid(True, alpha=0.3)
    for a in {ax, curve}:
        a.plot(i_r, de, lw=2, color="tab:blue", label="($I_r$(φ), ΔE(φ))" if a is ax else None)
    if w is not None:
        for k, b, r in ((w["k_max"], w["b_max"], w["i_max"]),
                        (w["k_min"], w["b_min"], w["i_min"])):
            xs = np.array([i_r.min(), i_r.max()])
            curve.plot(xs, k * xs + b, "--", lw=1.0)
            curve.plot(i_r[r], de[r], "o", color="tab:red", ms=5)
        pad_x, pad_y = 0.1 * np.ptp(i_r), 0.1 * np.ptp(de)
        curve.set_xlim(i_r.min() - pad_x, i_r.max() + pad_x)
        curve.set_ylim(de.min() - pad_y, de.max() + pad_y)
    texts = [curve.annotate(str(k), (i_r[r], de[r]), xytext=(3, 3),
                            textcoords="offset points", fontsize=10, color="tab:blue")
             for k, r in enumerate(rows)]
    curve.plot(i_r[rows], de[rows], ".", color="tab:blue")
    ax.set_xlabel("reduced moment of inertia $I_r$ [kg m²]")
    ax.set_ylabel("energy ΔE [J]")
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=10, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    declutter(curve, texts)
    return ax
