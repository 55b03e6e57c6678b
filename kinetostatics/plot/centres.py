"""Instantaneous centres of velocity (centre instantanee de rotație, CIR) of a mechanism
at one position, with the three-centre theorem (Kennedy) of the course (seed 001 eqs
1-5, figs 2-3; seed 004 fig. 2 for the slider-crank).
"""

from __future__ import annotations

import re
from itertools import combinations

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.lines import Line2D

from ..model.scene import GROUND
from ..results import Solution
from .base import at_row, axes_or_new, global_point, legend_outside, position_text, row_index
from .mechanism import draw_mechanism
from .notation import reading
from .place import declutter

__all__ = ["element_numbers", "instant_centres", "plot_instant_centres"]

_NUMBERED_PIVOT = re.compile(r"^O(\d+)$")


def element_numbers(scene) -> dict[str, int]:
    """The course's number of every element, the ground (``GROUND``) included.

    One rule for every scene (docs/notation.md): the ground is 0 and the moving bodies
    1, 2, ... in the scene's order (the numbering of the course's four-bar and
    slider-crank: crank 1, F01, I13), unless the scene numbers its ground pivots
    ``O<k>``: then the element pivoted at ``Ok`` is element k (the shaper's crank at O2
    is element 2, its lever at O4 element 4), the ground is 1 and the other bodies take
    the free numbers in the scene's order.

    Returns
    -------
    dict of str to int
    """
    pinned: dict[str, int] = {}
    for j in scene.joints.values():
        m = _NUMBERED_PIVOT.match(j.name)
        if m is not None and j.kind == "R" and GROUND in j.bodies:
            pinned.setdefault(j.other(GROUND), int(m.group(1)))
    if not pinned or len(set(pinned.values())) < len(pinned) or 1 in pinned.values():
        return {GROUND: 0, **{b: k for k, b in enumerate(scene.bodies, start=1)}}
    out = {GROUND: 1, **pinned}
    free = (k for k in range(2, 2 + 2 * len(scene.bodies)) if k not in pinned.values())
    for b in scene.bodies:
        if b not in out:
            out[b] = next(free)
    return out


def _fields(sol: Solution, i: int) -> dict[str, tuple[np.ndarray, float]]:
    """Per body (the ground first): the velocity at the global origin of
    its rigid velocity field and its angular velocity, at row i."""
    out = {GROUND: (np.zeros(2), 0.0)}
    for b in sol.scene.bodies:
        m = sol.kin.bodies[b].take(i)
        out[b] = (np.array(m.vel_at(0.0, 0.0), dtype=float), float(m.omega))
    return out


def _name(numbers: dict, a: str, b: str) -> str:
    """``I`` and the two elements' numbers (:func:`element_numbers`), smaller first."""
    ka, kb = sorted((numbers[a], numbers[b]))
    return f"I{ka}{kb}" if kb < 10 else f"I{ka},{kb}"


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
        ``name`` (``I13``: the two elements' numbers of :func:`element_numbers`),
        ``j``, ``k`` (the bodies), ``x``, ``y`` [m] (empty at infinity), ``at_infinity``,
        ``dir_x``, ``dir_y`` (unit direction towards the centre at infinity, else empty),
        ``omega_rel`` [rad/s] (omega_j - omega_k).
    """
    i = row_index(sol, position, row)
    f = _fields(sol, i)
    numbers = element_numbers(sol.scene)
    wmax = max(abs(w) for _, w in f.values()) or 1.0
    rows = []
    for (a, (ua, wa)), (b, (ub, wb)) in combinations(f.items(), 2):
        u, w = ua - ub, wa - wb
        rec = {"name": _name(numbers, a, b), "j": a, "k": b,
               "x": np.nan, "y": np.nan, "at_infinity": False, "dir_x": np.nan,
               "dir_y": np.nan, "omega_rel": w}
        if abs(w) <= 1e-12 * wmax:
            n = np.array([-u[1], u[0]]) / (np.hypot(*u) or 1.0)
            rec.update(at_infinity=True, dir_x=n[0], dir_y=n[1])
        else:
            rec.update(x=-u[1] / w, y=u[0] / w)
        rows.append(rec)
    return pd.DataFrame(rows)


def _kennedy_lines(ax: Axes, r, p: np.ndarray, names: list, numbers: dict, xy: dict,
                   toward: dict, shown: set, size: float) -> int:
    """Draw at most two three-centre lines through the centre ``r`` (at ``p``): for a
    third element m, I_jm - I_km passes through I_jk (Kennedy, seed 001 eq. 2). Returns
    how many were drawn."""
    lines = 0
    for m in names:             # Kennedy: I_jm - I_km passes through I_jk
        if m in (r.j, r.k) or lines == 2:
            continue
        a, b = (_name(numbers, x, m) for x in (r.j, r.k))
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
    return lines


def _rays(ax: Axes, sol: Solution, i: int, numbers: dict, xy: dict, near) -> None:
    """Dotted rays from each body's centre relative to the ground (I0k, in view) to its
    points: every velocity is perpendicular to its ray (seed 004 fig. 2)."""
    for b in sol.scene.bodies:
        key = _name(numbers, GROUND, b)
        if key not in xy or key not in near.name.values:
            continue
        for p in sol.scene.bodies[b].points:
            q = np.array(global_point(sol, b, p, i))
            ax.plot([xy[key][0], q[0]], [xy[key][1], q[1]], ":", color="0.45", lw=0.9)


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
        A solved scene.
    position, row : float or int, optional
        The driver position (the nearest row is drawn), or a row index instead.
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
    numbers = element_numbers(sol.scene)
    names = sorted(numbers, key=numbers.get)
    frame = numbers[GROUND]
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
        lines = _kennedy_lines(ax, r, p, names, numbers, xy, toward, shown, size)
        if lines:
            crossed.append(r.name)
    _rays(ax, sol, i, numbers, xy, near)
    for r in far.itertuples():
        txt = (f"{r.name} at infinity, towards ({r.dir_x + 0.0:.3f}, {r.dir_y + 0.0:.3f})"
               if r.at_infinity else f"{r.name} far: ({reading(r.x)}, {reading(r.y)}) m")
        handles.append(Line2D([], [], color="none", label=txt))
    if crossed:
        handles.insert(0, Line2D([], [], color="tab:red", ls="-.", lw=0.8,
                                 label=f"three-centre lines crossing at {', '.join(crossed)}"))
    key = ", ".join(f"{numbers[n]} = {n}" for n in names)
    handles.insert(0, Line2D([], [], color="0.45", ls=":",
                             label=f"rays from I{frame}k: v perpendicular to the ray"))
    handles.insert(0, Line2D([], [], color="none", label=key))
    ax.relim()
    ax.autoscale_view()
    ax.set_title(f"instantaneous centres of velocity\nat {position_text(sol, i)}",
                 fontsize=11)
    legend_outside(ax, handles=handles)
    declutter(ax, texts)
    return ax
