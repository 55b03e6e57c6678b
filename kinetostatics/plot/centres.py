"""Instantaneous centres of velocity (centre instantanee de rotație, CIR) of a mechanism
at one position, with the three-centre theorem (Kennedy) of the course (seed 001 eqs
1-5, figs 2-3; seed 004 fig. 2 for the slider-crank).
"""

from __future__ import annotations

from itertools import combinations

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.lines import Line2D

from ..model.scene import GROUND
from ..results import Solution
from .base import at_row, axes_or_new, global_point, legend_outside, position_text, row_index
from .mechanism import draw_mechanism
from .notation import gloss
from .place import declutter

__all__ = ["instant_centres", "plot_instant_centres"]


def _fields(sol: Solution, i: int) -> dict[str, tuple[np.ndarray, float]]:
    """Per body (the ground first, numbered 0): the velocity at the global origin of
    its rigid velocity field and its angular velocity, at row i."""
    out = {GROUND: (np.zeros(2), 0.0)}
    for b in sol.scene.bodies:
        m = sol.kin.bodies[b].take(i)
        out[b] = (np.array(m.vel_at(0.0, 0.0), dtype=float), float(m.omega))
    return out


def _name(names: list, a: str, b: str) -> str:
    """``I`` and the two elements' numbers, smaller first."""
    ka, kb = sorted((names.index(a), names.index(b)))
    return f"I{ka}{kb}"


def instant_centres(sol: Solution, position: float | None = None, *,
                    row: int | None = None) -> pd.DataFrame:
    """Every instantaneous centre of relative velocity I_jk at one position.

    The point where bodies j and k have the same velocity: with v_j(O) - v_k(O) = u
    and omega_j - omega_k = w, I_jk = (-u_y / w, u_x / w) (v = v(O) + omega x r, seed 001
    eq. 3); two bodies that translate relative to each other (w = 0) have it at infinity,
    perpendicular to their relative velocity (a prismatic joint, seed 001). A mechanism
    of n elements (the ground included) has n (n - 1) / 2 centres (seed 001 eq. 1).

    Parameters
    ----------
    sol : Solution
    position : float, optional
        Driver position (nearest row); ``row`` picks a row by index instead.

    Returns
    -------
    DataFrame
        ``name`` (``I02``: elements numbered 0 = ground, then the bodies in scene order),
        ``j``, ``k`` (the bodies), ``x``, ``y`` [m] (empty at infinity), ``at_infinity``,
        ``dir_x``, ``dir_y`` (unit direction towards the centre at infinity, else empty),
        ``omega_rel`` [rad/s] (omega_j - omega_k).
    """
    i = row_index(sol, position, row)
    f = _fields(sol, i)
    names = list(f)
    wmax = max(abs(w) for _, w in f.values()) or 1.0
    rows = []
    for (a, (ua, wa)), (b, (ub, wb)) in combinations(f.items(), 2):
        u, w = ua - ub, wa - wb
        rec = {"name": _name(names, a, b), "j": a, "k": b,
               "x": np.nan, "y": np.nan, "at_infinity": False, "dir_x": np.nan,
               "dir_y": np.nan, "omega_rel": w}
        if abs(w) <= 1e-12 * wmax:
            n = np.array([-u[1], u[0]]) / (np.hypot(*u) or 1.0)
            rec.update(at_infinity=True, dir_x=n[0], dir_y=n[1])
        else:
            rec.update(x=-u[1] / w, y=u[0] / w)
        rows.append(rec)
    return pd.DataFrame(rows)


def plot_instant_centres(sol: Solution, position: float | None = None, *,
                         row: int | None = None, ax: Axes | None = None,
                         reach: float = 2.5) -> Axes:
    """The mechanism with its instantaneous centres of velocity at one position.

    Each centre I_jk is a marked point (joints are centres of the bodies they join);
    from each body's centre relative to the ground (I0k), dotted rays to its points
    show that every velocity is perpendicular to the ray (seed 004 fig. 2); each
    centre not at a joint is drawn with the two lines of the three-centre theorem that
    cross at it (Kennedy: I_jm, I_km and I_jk are collinear, seed 001 eq. 2). Centres
    farther than ``reach`` mechanism sizes, or at infinity, are listed in the legend.

    Parameters
    ----------
    sol : Solution
    position : float, optional
        Driver position (nearest row); ``row`` picks a row by index instead.
    ax : Axes, optional
    reach : float
        How far (in sizes of the mechanism) the view may grow to show a centre.

    Returns
    -------
    Axes
        x [m] against y [m], equal aspect.
    """
    ax = axes_or_new(ax, figsize=(9.0, 6.5))
    i = row_index(sol, position, row)
    draw_mechanism(sol, row=i, ax=ax)
    ax.get_legend().remove()
    tab = instant_centres(sol, row=i)
    allpts = np.vstack([ln.get_xydata() for ln in ax.lines if len(ln.get_xydata())])
    centre = 0.5 * (allpts.min(axis=0) + allpts.max(axis=0))
    size = float(np.ptp(allpts, axis=0).max()) or 1.0
    names = [GROUND, *sol.scene.bodies]
    near = tab[~tab.at_infinity & (np.hypot(tab.x - centre[0], tab.y - centre[1])
                                   <= reach * size)]
    far = tab[~tab.index.isin(near.index)]
    xy = {r.name: np.array([r.x, r.y]) for r in tab.itertuples() if not r.at_infinity}
    toward = {r.name: np.array([r.dir_x, r.dir_y]) for r in tab.itertuples() if r.at_infinity}
    shown = set(near.name)          # the three-centre lines use the centres in view
    texts = []
    handles = []
    n = sol.positions.size
    joints = [(at_row(r.x, i, n), at_row(r.y, i, n)) for r in sol.joint_reactions.values()
              if r.joint.kind == "R"]
    crossed = []
    for r in near.itertuples():
        p = xy[r.name]
        at_joint = any(np.hypot(p[0] - jx, p[1] - jy) <= 1e-9 * size for jx, jy in joints)
        ax.plot(*p, "D", color="tab:red" if not at_joint else "k", ms=6, mfc="white",
                mew=1.6, zorder=6)
        texts.append(ax.annotate(r.name, tuple(p), xytext=(6, -10),
                                 textcoords="offset points", fontsize=10, color="tab:red",
                                 fontweight="bold"))
        if at_joint:
            continue
        lines = 0
        for m in names:             # Kennedy: I_jm - I_km passes through I_jk
            if m in (r.j, r.k) or lines == 2:
                continue
            a, b = (_name(names, x, m) for x in (r.j, r.k))
            if b in shown and a not in shown:
                a, b = b, a
            if a not in shown or np.hypot(*(xy[a] - p)) <= 1e-9 * size:
                continue
            if b in shown:
                seg = np.array([xy[a], xy[b], p])
                step = xy[b] - xy[a]
            elif b in toward:       # the line through I_jm towards a centre at infinity
                seg = np.array([xy[a], p])
                step = toward[b] * size
            else:
                continue
            t = (seg - xy[a]) @ step / (np.hypot(*step) ** 2 or 1.0)
            ends = xy[a] + np.outer([min(t.min(), 0.0), max(t.max(), 0.0)], step)
            ax.plot(ends[:, 0], ends[:, 1], "-.", color="tab:red", lw=0.8, alpha=0.7)
            lines += 1
        if lines:
            crossed.append(r.name)
    for k, b in enumerate(sol.scene.bodies, start=1):
        key = f"I0{k}"
        if key not in xy or key not in near.name.values:
            continue
        for p in sol.scene.bodies[b].points:
            q = np.array(global_point(sol, b, p, i))
            ax.plot([xy[key][0], q[0]], [xy[key][1], q[1]], ":", color="0.45", lw=0.9)
    for r in far.itertuples():
        txt = (f"{r.name} at infinity, towards ({r.dir_x + 0.0:.3f}, {r.dir_y + 0.0:.3f})"
               if r.at_infinity else f"{r.name} far: ({r.x:.4g}, {r.y:.4g}) m")
        handles.append(Line2D([], [], color="none", label=txt))
    if crossed:
        handles.insert(0, Line2D([], [], color="tab:red", ls="-.", lw=0.8,
                                 label=f"three-centre lines crossing at {', '.join(crossed)}"))
    key = ", ".join(f"{k} = {n}" for k, n in enumerate(names))
    handles.insert(0, Line2D([], [], color="0.45", ls=":",
                             label="rays from I0k: v perpendicular to the ray"))
    handles.insert(0, Line2D([], [], color="none", label=key))
    ax.relim()
    ax.autoscale_view()
    ax.set_title(f"instantaneous centres of velocity\n({gloss('instantaneous centres')}) "
                 f"at {position_text(sol, i)}", fontsize=11)
    legend_outside(ax, handles=handles)
    declutter(ax, texts)
    return ax
