"""The free-body diagram of a dyad (seed 002 figs 2.37, 2.41) beside its force polygon.

The dyad is cut from the mechanism: its two bodies carry their loads (applied forces,
weights, d'Alembert inertia forces and couples, seed 002 eq. 2.1), the reactions of the
outer joints (from the bodies the dyad is cut from) and of the dyads solved before it;
the inner joint's reaction acts on each body, equal and opposite (action and reaction,
seed 002 eq. 2.19).
"""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Arc

from ..common.angles import radian_column
from ..model.scene import GROUND
from ..results import Solution
from .base import (
    LOAD_COLORS,
    REACTION_COLOR,
    SINGULAR_NOTE,
    at_row,
    body_colors,
    global_point,
    magnitude_text,
    position_text,
    row_index,
    singular_row,
    vector_axes,
)
from .mechanism import draw_body
from .notation import (
    couple_subscript,
    force_symbol,
    load_symbol,
    reading,
    round_scale,
    signed_text,
    titled,
)
from .place import declutter, settle
from .polygons import find_dyad, force_on, force_polygon

__all__ = ["dyad_free_body", "free_body_forces"]



def free_body_forces(sol: Solution, dyad, position: float | None = None, *,
                     row: int | None = None) -> list[dict]:
    """The forces and couples on a dyad's bodies at one position, with where they act.

    Parameters
    ----------
    sol : Solution
    dyad : int, str or tuple
        As for :func:`~kinetostatics.plot.force_polygon` (``0``: the driving element).
    position : float, optional
        Driver position (nearest row); ``row`` picks a row by index instead.

    Returns
    -------
    list of dict
        One per force: ``label`` (a reaction's also says which body acts on which),
        ``symbol`` (as the force polygon writes it, mathtext), ``body`` (the body it
        acts on), ``kind`` (``applied``, ``gravity``, ``inertia``, ``friction``,
        ``reaction`` for outer joints and the dyads solved before, ``inner`` for the
        inner joint), ``x``, ``y`` [m] (point of application), ``fx``, ``fy`` [N],
        ``m`` [N m] (a couple, ccw positive). On each body the forces and couples
        balance (the ``m`` of a prismatic joint's reaction included).
    """
    i = row_index(sol, position, row)
    n = sol.positions.size
    d = find_dyad(sol, dyad)
    bodies = (sol.scene.driver.body,) if d is None else d.bodies
    inner = None if d is None else d.inner.name
    out = []
    for ld in sol.loads:
        if ld.body not in bodies:
            continue
        fx, fy, m = at_row(ld.fx, i, n), at_row(ld.fy, i, n), at_row(ld.m, i, n)
        if fx == 0.0 and fy == 0.0 and m == 0.0:
            continue
        x, y = ld.position(sol.kin)
        sym = load_symbol(ld.kind, ld.body)
        out.append({"label": sym, "symbol": sym, "body": ld.body,
                    "kind": ld.kind, "x": at_row(x, i, n), "y": at_row(y, i, n),
                    "fx": fx, "fy": fy, "m": m})
    for j in sol.scene.joints.values():
        for b in bodies:
            if b not in j.bodies:
                continue
            r = sol.joint_reactions[j.name]
            f = force_on(sol, j.name, b, i)
            m = 0.0 if r.M is None else at_row(r.M, i, n) * (1.0 if r.on == b else -1.0)
            other = j.other(b)
            out.append({"label": f"{force_symbol(j.name)} {other}→{b}",
                        "symbol": force_symbol(j.name), "body": b,
                        "joint": j.name,
                        "kind": "inner" if j.name == inner else "reaction",
                        "x": at_row(r.x, i, n), "y": at_row(r.y, i, n),
                        "fx": float(f[0]), "fy": float(f[1]), "m": m})
    if d is None:
        dj = sol.scene.joints[sol.scene.driver.joint]
        me = float(sol.Me[i])
        if sol.drive.kind == "R":
            x, y = global_point(sol, bodies[0], dj.point_on(bodies[0]), i)
            out.append({"label": "Me", "symbol": "Me", "body": bodies[0], "kind": "applied",
                        "x": x, "y": y,
                        "fx": 0.0, "fy": 0.0, "m": me})
        else:       # Fe along the driving guide, at the slider point (as in the polygon)
            beta = dj.beta if dj.guide == GROUND else 0.0
            r = sol.joint_reactions[dj.name]
            out.append({"label": "Fe", "symbol": "Fe", "body": bodies[0], "kind": "applied",
                        "x": at_row(r.x, i, n), "y": at_row(r.y, i, n),
                        "fx": me * np.cos(beta), "fy": me * np.sin(beta), "m": 0.0})
    return out


def _couple(ax: Axes, x: float, y: float, m: float, radius: float, color: str) -> None:
    """A curved arrow of a couple: counterclockwise for m > 0."""
    ax.add_patch(Arc((x, y), 2 * radius, 2 * radius, theta1=20, theta2=300, color=color,
                     lw=1.3))
    end = radian_column(300 if m > 0 else 20)
    tip = np.array([x + radius * np.cos(end), y + radius * np.sin(end)])
    tangent = np.array([-np.sin(end), np.cos(end)]) * (1 if m > 0 else -1)
    ax.annotate("", tuple(tip + 0.25 * radius * tangent), tuple(tip),
                arrowprops={"arrowstyle": "-|>", "color": color, "lw": 1.3,
                            "shrinkA": 0, "shrinkB": 0})


def _force_arrows(ax: Axes, forces: list, sc: float, fmax: float, mmax: float, size: float,
                  texts: list) -> tuple[dict, list]:
    """Draw ``forces`` on ``ax`` as arrows from their points (``sc`` m per N) and their
    couples as curved arrows; the inner reaction once, on the first body. Returns the
    colours of the kinds drawn and the couples' legend handles."""
    first_inner = True
    kinds = {}
    couples: list = []      # the couples: curved arrows, named in the legend
    for f in forces:
        col = {"reaction": REACTION_COLOR, "inner": "k"}.get(f["kind"],
                                                          LOAD_COLORS.get(f["kind"], "0.3"))
        if f["kind"] == "inner" and not first_inner:
            continue        # the same force, reversed, on the second body: drawn once
        mag = float(np.hypot(f["fx"], f["fy"]))
        x, y = f["x"], f["y"]
        if mag > 1e-12 * fmax:
            tip = (x + sc * f["fx"], y + sc * f["fy"])
            ax.annotate("", tip, (x, y), arrowprops={
                "arrowstyle": "-|>", "color": col, "lw": 1.6, "shrinkA": 0, "shrinkB": 0,
                "ls": "--" if f["kind"] == "inner" else "-"})
            ax.update_datalim([(x, y), tip])
            lab = f"{f['symbol']} {magnitude_text(mag)} N"
            if f["kind"] == "reaction":     # which body acts on which, under it
                lab += "\n" + f["label"].split(" ", 1)[1]
            texts.append(ax.annotate(lab, tip,
                                     xytext=(4 * f["fx"] / mag, 4 * f["fy"] / mag),
                                     textcoords="offset points", fontsize=10, color=col,
                                     ha="left" if f["fx"] >= 0 else "right",
                                     va="bottom" if f["fy"] >= 0 else "top"))
            kinds.setdefault(f["kind"], col)
        if abs(f["m"]) > 1e-9 * max(mmax, fmax * size):      # not a rounding-level couple
            r = 0.04 * size
            _couple(ax, x, y, f["m"], r, col)
            # each couple names its body (and a joint's couple its joint)
            name = {"inertia": f"Mi {f['body']}"}.get(
                f["kind"], "Me" if f["label"] == "Me" else
                f"$M{couple_subscript(f.get('joint', ''))}$ on {f['body']}")
            couples.append(Line2D([], [], color=col, lw=1.3, marker=r"$\circlearrowleft$"
                                  if f["m"] > 0 else r"$\circlearrowright$", ms=9,
                                  label=signed_text(name, f["m"], "N m")))
        if f["kind"] == "inner":
            first_inner = False
    return kinds, couples


def _force_legend(fig: Figure, ax: Axes, kinds: dict, couples: list) -> None:
    """The legend under the diagram: the kinds of forces, then the couples."""
    handles = [Line2D([], [], color=c, lw=1.6, ls="--" if k == "inner" else "-",
                      label={"reaction": "outer joint reactions", "inner": "inner joint "
                             "(on the first body; reversed on the other)"}.get(
                                 k, f"{k} forces"))
               for k, c in kinds.items()]
    h, _ = ax.get_legend_handles_labels()
    fig.legend(handles=h + handles + couples, fontsize=10, loc="outside lower left",
               ncol=3 if couples else 4)


def dyad_free_body(sol: Solution, dyad=1, position: float | None = None, *,
                   row: int | None = None) -> Figure:
    """The free-body diagram of a dyad (or of the driver) beside its force polygon.

    Left: the dyad's bodies as drawn in the mechanism, each force of
    :func:`free_body_forces` as an arrow from its point of application (one scale for
    all; loads in the load colours, outer reactions red, the inner joint's reaction
    dashed black on the first body: on the second it acts reversed), couples as curved
    arrows (inertia couples, a prismatic joint's couple, Me). Right: the force polygon of the same
    forces (:func:`~kinetostatics.plot.force_polygon`), closing to zero.

    Parameters
    ----------
    sol : Solution
    dyad : int, str or tuple
        1-based dyad index, label, kind, body name or bodies; ``0``: the driver.
    position : float, optional
        Driver position (nearest row); ``row`` picks a row by index instead.

    Returns
    -------
    Figure
        Two Axes: the free-body diagram (x, y [m]) and the force polygon (Fx, Fy [N]).
    """
    import matplotlib.pyplot as plt

    i = row_index(sol, position, row)
    d = find_dyad(sol, dyad)
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13.5, 5.6), layout="constrained",
                                  width_ratios=[1.0, 1.25])
    bodies = (sol.scene.driver.body,) if d is None else d.bodies
    colors = body_colors()
    names = list(sol.scene.bodies)
    texts: list = []
    named: set = set()          # a point shared by the two bodies is named once
    pts = []
    for b in bodies:
        pts += draw_body(ax, sol, b, i, colors[names.index(b) % len(colors)], texts, named)
    singular = singular_row(sol, i)     # no force to vouch for: said, not drawn
    forces = [] if singular else free_body_forces(sol, dyad, row=i)
    pts = np.array(pts + [(f["x"], f["y"]) for f in forces])
    size = float(np.ptp(pts, axis=0).max()) or 1.0
    fmax = max((np.hypot(f["fx"], f["fy"]) for f in forces), default=0.0) or 1.0
    mmax = max((abs(f["m"]) for f in forces), default=0.0) or 1.0
    sc = round_scale(0.45 * size / fmax)      # m per N: 1, 2 or 5 x 10^k
    ref = 10.0 ** np.floor(np.log10(0.2 * size))      # m: the scale's length
    kinds, couples = _force_arrows(ax, forces, sc, fmax, mmax, size, texts)
    _force_legend(fig, ax, kinds, couples)
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.25)            # room for the labels around the arrows
    ax.autoscale_view()
    vector_axes(ax)             # few ticks: the diagram is narrow beside its polygon
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    what = f"dyad {d.index + 1} {d.kind} ({', '.join(d.bodies)})" if d is not None else \
        f"driver {bodies[0]}"
    ax.set_title(f"{titled('free-body diagram')}\n{what} at {position_text(sol, i)}\n"
                 + (SINGULAR_NOTE if singular else
                    f"arrows: {ref:g} m ≙ {reading(ref / sc)} N"), fontsize=10)
    force_polygon(sol, 0 if d is None else d.index + 1, row=i, ax=ax2)
    declutter(ax, texts)
    settle(fig)
    return fig
