"""Cam pictures (seed 002 ch. 1): the follower's program over the cycle (s, v, a) with
its shocks, the cam and its follower at a cam angle, and the (ds/dphi, s) diagram of the
smallest base circle (fig. 1.11).
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from ..common.angles import degree_column, degree_value, radian_column, radian_value
from ..model.errors import WorkbenchError
from .base import axes_or_new, legend_outside, vector_axes
from .collide import GUIDE
from .notation import reading
from .place import declutter

__all__ = ["cam_shocks", "draw_cam", "plot_cam_diagram", "plot_cam_motion"]


def _boundaries(law) -> np.ndarray:
    """Cam angles (rad) where the program's segments meet, the start included."""
    return np.concatenate(([0.0], np.cumsum([seg.angle for seg in law.segments])[:-1]))


def cam_shocks(law, speed: float = 1.0, grid: int = 72000) -> list[dict]:
    """The jumps of the follower's velocity and acceleration over the cycle.

    A jump of the velocity is a hard (rigid) shock: in theory an infinite acceleration and
    force; a jump of the acceleration only (finite) is a soft shock: the inertia force
    jumps. Found on a grid of ``grid`` cam angles (a step where ds/dphi or d2s/dphi2
    changes by more than 1e-3 of its largest value), each located by bisection to 1e-10
    rad and measured from both sides (1e-9 rad; the angle is given to 1e-6 deg); the
    boundaries of the segments, the switch inside a constant-acceleration law and the
    cycle's closure (end to start) are found alike.

    Parameters
    ----------
    law : CamLaw
    speed : float
        The cam's angular speed omega [rad/s]: v = omega ds/dphi, a = omega^2 d2s/dphi2.
    grid : int
        Number of cam angles scanned over the cycle.

    Returns
    -------
    list of dict
        ``angle`` [deg], ``dv``, ``da`` (the jumps, in the follower's units per s and per
        s^2), ``kind`` (``"hard"``, ``"soft"``) in order of angle; empty for a
        shock-free program.
    """
    phi = np.linspace(0.0, 2.0 * np.pi, grid + 1)
    _, d1, d2 = law(phi)
    out = []
    scale1 = float(np.max(np.abs(d1))) or 1.0
    scale2 = float(np.max(np.abs(d2))) or 1.0
    jump = (np.abs(np.diff(d1)) > 1e-3 * scale1) | (np.abs(np.diff(d2)) > 1e-3 * scale2)
    for i in np.flatnonzero(jump):
        lo, hi = float(phi[i]), float(phi[i + 1])
        ref = law(np.array([lo]))
        for _ in range(60):                 # keep the jump between lo and hi
            mid = 0.5 * (lo + hi)
            m = law(np.array([mid]))
            if abs(m[1][0] - ref[1][0]) > 1e-3 * scale1 or \
                    abs(m[2][0] - ref[2][0]) > 1e-3 * scale2:
                hi = mid
            else:
                lo = mid
            if hi - lo < 1e-10:
                break
        a, b = law(np.array([lo - 1e-9])), law(np.array([hi + 1e-9]))
        dv = float(speed * (b[1][0] - a[1][0]))
        da = float(speed**2 * (b[2][0] - a[2][0]))
        kind = "hard" if abs(dv) > 1e-6 * speed * scale1 else "soft"
        out.append({"angle": round(degree_value(0.5 * (lo + hi)), 6) % 360.0, "dv": dv,
                    "da": da, "kind": kind})
    out.sort(key=lambda r: r["angle"])      # the jump at the cycle's end is at 0 deg
    return out


def plot_cam_motion(res) -> Figure:
    """The follower's program over the cycle: lift, velocity and acceleration, three
    panels, the segments named, and the shocks marked (:func:`cam_shocks`).

    Parameters
    ----------
    res : CamResults
        :func:`kinetostatics.cams.solve_cam` of the scene.

    Returns
    -------
    Figure
        Cam angle [deg] against s [m], v [m/s], a [m/s^2] (translating follower) or
        beta [deg], omega2 [rad/s], eps2 [rad/s^2] (oscillating follower).
    """
    import matplotlib.pyplot as plt

    law, w = res.scene.law, res.scene.speed
    m = res.motion
    p = m["angle"].to_numpy()
    if "s" in m:
        cols = (("s", "lift s [m]", 1.0), ("v", "velocity v [m/s]", 1.0),
                ("a", "acceleration a [m/s²]", 1.0))
    else:
        cols = (("beta", "swing β [deg]", 1.0), ("omega2", "ω2 [rad/s]", 1.0),
                ("eps2", "ε2 [rad/s²]", 1.0))
    fig, axs = plt.subplots(3, 1, figsize=(8.0, 7.5), sharex=True, layout="constrained")
    for a, (c, lab, k) in zip(axs, cols, strict=True):
        a.plot(p, k * m[c].to_numpy(), lw=2)
        a.set_ylabel(lab)
        a.grid(True, alpha=0.3)
        a.axhline(0.0, color="0.5", lw=0.8)
    bounds = degree_column(_boundaries(law))
    lo, hi = axs[0].get_ylim()
    axs[0].set_ylim(lo, hi + 0.55 * (hi - lo))      # a band above the lift for the names
    texts = []
    for b, seg in zip(bounds, law.segments, strict=True):
        for a in axs:
            a.axvline(b, color="0.6", lw=0.8, ls=":", gid=GUIDE)   # a faint guide
        name = seg.kind if seg.law is None else f"{seg.kind}\n{seg.law}"
        texts.append(axs[0].annotate(name, (b + 0.5 * degree_value(seg.angle), 0.83),
                                     xycoords=("data", "axes fraction"), ha="center",
                                     va="center", fontsize=10, color="0.3",
                                     xytext=(0, 0), textcoords="offset points"))
    shocks = cam_shocks(law, w)
    kinds = set()
    for s in shocks:
        col = "tab:red" if s["kind"] == "hard" else "tab:orange"
        axs[2 if s["kind"] == "soft" else 1].axvline(s["angle"], color=col, lw=1.5, alpha=0.7)
        kinds.add(s["kind"])
    for kind, col, what, a in (("hard", "tab:red", "hard shock: v jumps", axs[1]),
                               ("soft", "tab:orange", "soft shock: a jumps", axs[2])):
        if kind in kinds:
            a.plot([], [], color=col, lw=1.5, label=what)
            legend_outside(a)
    axs[0].set_title(f"{res.scene.title or 'cam'}\nthe follower's program at "
                     f"ω = {w:g} rad/s" + ("" if shocks else " (no shocks)"), fontsize=10)
    axs[-1].set_xlabel("cam angle φ [deg]")
    from matplotlib.ticker import MultipleLocator
    axs[-1].xaxis.set_major_locator(MultipleLocator(45.0))
    declutter(axs[0], texts)
    return fig


def _rot(xy: np.ndarray, ang: float) -> np.ndarray:
    c, s = math.cos(ang), math.sin(ang)
    return np.array([[c, -s], [s, c]]) @ xy


def draw_cam(res, angle: float = 0.0, ax: Axes | None = None) -> Axes:
    """The cam turned by ``angle`` with its follower in place: the working profile, the
    pitch curve and the base circle, the roller (or knife edge) at B on the pitch curve,
    the follower's stem (translating) or arm from its pivot C (oscillating).

    Parameters
    ----------
    res : CamResults
        :func:`kinetostatics.cams.solve_cam` of the scene.
    angle : float
        Cam angle [deg] from the start of the program (the nearest row is drawn).
    ax : Axes, optional

    Returns
    -------
    Axes
        x [m] against y [m], equal aspect, the cam's axis A at the origin.
    """
    from ..cams import TranslatingFollower, follower_points

    ax = axes_or_new(ax, figsize=(9.0, 6.5))
    sc, g = res.scene, res.geometry
    ang = g["angle"].to_numpy()
    k = int(np.argmin(np.abs(((ang - angle) + 180.0) % 360.0 - 180.0)))
    phi = radian_value(float(ang[k]))
    s, ds, dds = sc.law(radian_column(ang))
    b = follower_points(sc.follower, s, ds, dds)[0]
    pitch = g[["x_pitch", "y_pitch"]].to_numpy().T
    mirror = np.array([[-1.0], [1.0]]) if sc.rotation == "cw" else np.ones((2, 1))
    b = mirror * b
    # the turn that carries the cam-frame pitch point of row k onto B (ccw: +phi)
    sign = min((1.0, -1.0), key=lambda sg: float(np.hypot(*(_rot(pitch[:, [k]], sg * phi)
                                                           - b[:, [k]]).ravel())))
    turn = sign * phi
    prof = _rot(g[["x_profile", "y_profile"]].to_numpy().T, turn)
    pit = _rot(pitch, turn)
    ax.fill(prof[0], prof[1], color="tab:blue", alpha=0.18)
    ax.plot(prof[0], prof[1], color="tab:blue", lw=2, label="cam profile")
    ax.plot(pit[0], pit[1], color="tab:blue", lw=0.9, ls="--", label="pitch curve")
    fol = sc.follower
    r0 = fol.base_radius
    t = np.linspace(0.0, 2.0 * np.pi, 241)
    ax.plot(r0 * np.cos(t), r0 * np.sin(t), color="0.5", lw=0.8, ls=":",
            label=f"base circle $r_0$ = {reading(r0 * 1e3)} mm")
    ax.plot(0.0, 0.0, "+", color="k", ms=12, mew=2)
    mark = _rot(np.array([[0.0], [0.8 * r0]]), turn).ravel()      # the cam's own radius
    ax.plot([0.0, mark[0]], [0.0, mark[1]], color="tab:blue", lw=1.2)
    bx, by = b[:, k]
    rr = fol.roller_radius
    if rr > 0.0:
        ax.add_patch(Circle((bx, by), rr, fc="white", ec="k", lw=1.5, zorder=5))
    ax.plot(bx, by, "o", color="k", ms=3, zorder=6)
    if isinstance(fol, TranslatingFollower):
        top = by + 1.2 * r0
        ax.plot([bx, bx], [by, top], color="tab:green", lw=4, solid_capstyle="butt",
                label="follower")
        for side in (-1.0, 1.0):                      # the guide
            ax.plot([bx + side * 0.12 * r0] * 2, [by + 0.5 * r0, top], color="0.3", lw=1)
        rise = f"s = {s[k] * 1e3:.4g} mm"
    else:
        cx = mirror[0, 0] * fol.pivot_distance
        ax.plot([cx, bx], [0.0, by], color="tab:green", lw=4, label="follower arm")
        ax.plot(cx, 0.0, "^", color="k", ms=12, mfc="0.8")
        rise = f"β = {degree_value(s[k]):.4g}°"
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.1)
    vector_axes(ax)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    tau = float(g["tau"].iloc[k])
    ax.set_title(f"{sc.title or 'cam'}\nat φ = {ang[k]:g}°: {rise}, τ = {reading(tau, 3)}°",
                 fontsize=10, pad=10)      # clear of a tick label at the top
    legend_outside(ax)
    return ax


def plot_cam_diagram(res, transmission_angle: float | None = None,
                     ax: Axes | None = None, numbers: int = 12) -> Axes:
    """The (ds/dphi, s) diagram of a translating follower and the smallest base circle
    for an admissible transmission angle (seed 002 fig. 1.11, eqs 1.27-1.29).

    The curve x = ds/dphi, y = s (both in m); a cam centre (e, -s0) keeps the
    transmission angle >= tau_adm while every point of the curve is seen from it at
    least tau_adm above the horizontal: below the line of slope +tan tau_adm tangent to
    the rise side and the line of slope -tan tau_adm tangent to the return side. The
    smallest cam is the admissible centre nearest the origin (B0, the follower on the
    base circle): r0 = sqrt(e^2 + s0^2) (:func:`kinetostatics.cams.optimal_offset`);
    the scene's own centre is marked too.

    Parameters
    ----------
    res : CamResults
        A translating-follower cam (:func:`kinetostatics.cams.solve_cam`).
    transmission_angle : float, optional
        tau_adm [deg]; default: the scene's (its summary's admissible angle).
    ax : Axes, optional
    numbers : int
        Positions numbered along the curve (evenly spaced cam angles).

    Returns
    -------
    Axes
        ds/dphi [m] against s [m], equal aspect.
    """
    from ..cams import TranslatingFollower, optimal_offset

    sc = res.scene
    if not isinstance(sc.follower, TranslatingFollower):
        raise WorkbenchError("plot_cam_diagram: the (ds/dphi, s) diagram is drawn for a "
                             "translating follower")
    tau_deg = transmission_angle if transmission_angle is not None else \
        res.summary.get("transmission_angle_admissible")
    if tau_deg is None:
        raise WorkbenchError("plot_cam_diagram: give the admissible transmission angle")
    tau = radian_value(float(tau_deg))
    ax = axes_or_new(ax, figsize=(8.0, 6.5))
    m = res.motion
    p, s, ds = (m[c].to_numpy() for c in ("angle", "s", "ds"))
    ax.plot(ds, s, lw=2, color="tab:blue", label="(ds/dφ, s) over the cycle")
    k = math.tan(tau)
    b_up = float(np.min(s - k * ds))          # y <= k x + b_up (rise side)
    b_dn = float(np.min(s + k * ds))          # y <= -k x + b_dn (return side)
    e_opt, r0_opt = optimal_offset(sc.law, tau)
    s0_opt = math.sqrt(max(r0_opt**2 - e_opt**2, 0.0))
    e, s0 = sc.follower.offset, sc.follower.s0
    lo_y = min(-s0_opt, -s0) - 0.15 * float(np.ptp(s))
    for slope, bb, side in ((k, b_up, "rise"), (-k, b_dn, "return")):
        x_at = np.array([(lo_y - bb) / slope, float(ds[np.argmin(s - slope * ds)])])
        ax.plot(x_at, slope * x_at + bb, "--", lw=1.2,
                label=f"tangent at $τ_{{adm}}$ = {tau_deg:g}° ({side} side)")
    ax.plot(e_opt, -s0_opt, "s", color="tab:red",
            label=f"smallest cam: e = {reading(e_opt * 1e3)} mm, $r_0$ = "
                  f"{reading(r0_opt * 1e3)} mm")
    ax.plot([0.0, e_opt], [0.0, -s0_opt], color="tab:red", lw=0.9)
    ax.plot(e, -s0, "o", color="k",
            label=f"this cam: e = {reading(e * 1e3)} mm, $r_0$ = "
                  f"{reading(sc.follower.base_radius * 1e3)} mm")
    closed = abs(p[-1] - p[0] - 360.0) < 1e-9
    rows = np.unique(np.linspace(0, len(p) - 1, numbers, endpoint=not closed).round()
                     .astype(int)) if numbers > 0 else np.array([], dtype=int)
    ax.plot(ds[rows], s[rows], ".", color="tab:blue")
    texts = [ax.annotate(str(i), (ds[r], s[r]), xytext=(3, 3), textcoords="offset points",
                         fontsize=10, color="tab:blue") for i, r in enumerate(rows)]
    ax.plot(0.0, 0.0, "k+", ms=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("ds/dφ [m]")
    ax.set_ylabel("lift s [m]")
    ax.grid(True, alpha=0.3)
    ax.set_title("smallest base circle from the (ds/dφ, s) diagram "
                 f"(numbers: every {360.0 / max(numbers, 1):g}°)", fontsize=10)
    legend_outside(ax)
    declutter(ax, texts)
    return ax
