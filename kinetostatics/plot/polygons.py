"""The force polygon of a dyad or of the driver (poligonul forțelor, seed 002 figs 2.9,
2.11, 2.13, 2.15, 2.17, 2.19, 2.38, 2.42), and the forces that make it.
"""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.lines import Line2D

from ..model.errors import WorkbenchError
from ..model.scene import GROUND
from ..results import Solution
from ..solver.structure import Dyad
from .base import (
    LOAD_COLORS,
    REACTION_COLOR,
    SINGULAR_NOTE,
    at_row,
    axes_or_new,
    global_point,
    legend_outside,
    magnitude_text,
    math_name,
    place_labels,
    position_text,
    row_index,
    singular_row,
    vector_axes,
)
from .notation import direction_text, force_symbol, signed_text, titled
from .place import declutter
from .sidebyside import side_by_side

__all__ = ["find_dyad", "force_on", "force_polygon", "polygon_forces"]


def find_dyad(sol: Solution, dyad) -> Dyad | None:
    """A dyad of the solution by 1-based index, label, kind, one body's name or its two
    bodies; None for the driving element (``0``, ``"driver"`` or the driver's body).

    Raises
    ------
    WorkbenchError
        No such dyad (the message lists the dyads).
    """
    dyads = [d.dyad for d in sol.kin.dyads]
    if isinstance(dyad, str) and dyad in ("driver", sol.scene.driver.body):
        return None
    if isinstance(dyad, int | np.integer) and not isinstance(dyad, bool):
        if dyad == 0:
            return None
        if 1 <= dyad <= len(dyads):
            return dyads[dyad - 1]
    elif isinstance(dyad, str):
        hits = [d for d in dyads if dyad in (d.label, d.kind) or dyad in d.bodies]
        if len(hits) == 1:
            return hits[0]
    elif isinstance(dyad, tuple | list):
        hits = [d for d in dyads if set(d.bodies) == set(dyad)]
        if hits:
            return hits[0]
    known = ", ".join(f"{d.index + 1} = {d.label}" for d in dyads)
    raise WorkbenchError(f"force_polygon: no dyad {dyad!r}; the dyads are {known}, or "
                         "'driver' (0) for the driving element")


def force_on(sol: Solution, joint: str, body: str, i: int) -> np.ndarray:
    """The reaction of ``joint`` on ``body`` at row i."""
    r = sol.joint_reactions[joint]
    fx, fy = sol.reaction(joint)
    f = np.array([fx[i], fy[i]], dtype=float)
    return f if r.on == body else -f


def polygon_forces(sol: Solution, dyad: Dyad | None, i: int, components: bool):
    """The forces of a dyad's (or the driver's) force polygon at row ``i``, in drawing order.

    Parameters
    ----------
    sol : Solution
    dyad : Dyad or None
        The dyad (:func:`find_dyad`); None for the driving element.
    i : int
        Row index.
    components : bool
        Split the outer revolute reactions into t and n components.

    Returns
    -------
    forces : list of (str, ndarray, str, str)
        (mathtext label, force vector [N], colour, group ``"load"`` or ``"outer"``);
        head to tail they close to zero.
    split : int or None
        How many of ``forces`` act on the dyad's first body (None for the driver).
    """
    scene = sol.scene
    n = sol.positions.size
    out = []

    def loads_of(b):
        kind_label = {"applied": "F", "gravity": "G", "inertia": "F^{i}"}
        for ld in sol.loads:
            if ld.body != b:
                continue
            f = np.array([at_row(ld.fx, i, n), at_row(ld.fy, i, n)])
            if not f.any():
                continue
            k = kind_label[ld.kind]
            sub = math_name(b)
            lab = f"${k}_{{\\mathrm{{{sub}}}}}$" if ld.kind != "inertia" else \
                f"$F^{{i}}_{{\\mathrm{{{sub}}}}}$"
            if ld.kind == "applied" and ld.label:
                lab += f" ({ld.label.split(' at ')[-1]})" if " at " in ld.label else ""
            out.append((lab, f, LOAD_COLORS[ld.kind], "load"))

    def reaction(j, b, other_point, color=REACTION_COLOR):
        f = force_on(sol, j.name, b, i)
        name = math_name(j.name)
        if j.kind == "R" and components and other_point is not None:
            p = np.array(global_point(sol, b, j.point_on(b), i))
            d = np.asarray(other_point) - p
            if np.hypot(*d) > 1e-9:
                u = d / np.hypot(*d)
                fn = np.dot(f, u) * u
                out.append((f"$F_{{\\mathrm{{{name}}}}}^{{t}}$", f - fn, REACTION_COLOR,
                            "outer"))
                out.append((f"$F_{{\\mathrm{{{name}}}}}^{{n}}$", fn, "tab:orange", "outer"))
                return
        out.append((force_symbol(j.name), f, color, "outer"))

    if dyad is None:
        b = scene.driver.body
        loads_of(b)
        dj = scene.joints[scene.driver.joint]
        for j in scene.joints.values():
            if b in j.bodies and j is not dj:
                reaction(j, b, None, "darkred")
        if sol.drive.kind == "T":
            beta = dj.beta
            u = np.array([np.cos(beta), np.sin(beta)])
            if dj.guide != GROUND:
                u = np.array([1.0, 0.0])
            out.append(("$F_{e}$", float(sol.Me[i]) * u, "tab:green", "load"))
        reaction(dj, b, None)
        return out, None
    b1, b2 = dyad.bodies
    inner = dyad.inner
    own = {inner.name, dyad.outer[0].name, dyad.outer[1].name}

    def later(b):
        """Reactions of the dyads solved before this one (further out in the chain)."""
        for j in scene.joints.values():
            if b in j.bodies and j.name not in own:
                f = force_on(sol, j.name, b, i)
                out.append((f"{force_symbol(j.name)} ({j.other(b)})", f,
                            "darkred", "load"))

    if inner.kind == "R":
        x1 = np.array(global_point(sol, b1, inner.point_on(b1), i))
        x2 = np.array(global_point(sol, b2, inner.point_on(b2), i))
    else:
        x1 = x2 = np.array(global_point(sol, inner.slider, inner.points[1], i))
    reaction(dyad.outer[0], b1, x1)
    loads_of(b1)
    later(b1)
    split = len(out)
    loads_of(b2)
    later(b2)
    reaction(dyad.outer[1], b2, x2)
    return out, split



def force_polygon(sol: Solution, dyad: int | str | tuple = 1, position: float | None = None,
                  *, row: int | None = None, ax: Axes | None = None,
                  components: bool = True) -> Axes:
    """The force polygon of a dyad (or of the driver) at one position, closing to zero.

    The seed's construction (002 eqs 2.16, 2.76, 2.82; figs 2.9, 2.38, 2.42): the
    reaction in the first outer joint (split into its components t, perpendicular to
    the body's line from the outer to the inner joint, and n, along it), every load of
    the first body (applied, weight G, inertia force F^i), every load of the second
    body, the reaction in the second outer joint: head to tail, they close. The
    dashed diagonal from the end of the first body's forces back to the start is the
    inner joint's reaction on the first body (eq. 2.19: F12 + F2 + F32 = 0). Couples
    (inertia moments, Me, the couple in a prismatic joint) do not enter a force
    polygon.

    Parameters
    ----------
    sol : Solution
    dyad : int, str or tuple
        1-based dyad index as in ``sol.dyads`` (``sol.structure.describe()``), its
        label (``"RRR(coupler, rocker)"``), kind, one of its bodies or its two bodies;
        ``0`` or ``"driver"``: the driving element (its loads, the reactions of the
        dyads on it, the ground reaction; a sliding driver's Fe).
    position : float, optional
        Driver position (nearest row); ``row`` picks a row by index instead.
    ax : Axes, optional
    components : bool
        Split the outer revolute reactions into t and n components.

    Returns
    -------
    Axes
        In newtons; the legend gives every vector's magnitude, the lower corner the
        closing error |sum F| is in the title, a scale bar in N in the lower right
        corner. Arrows that would lie on one another (nearly collinear forces, as in an
        RTR dyad) are drawn side by side, joined by dotted connectors, the offset named in
        the legend (:func:`~kinetostatics.plot.sidebyside.side_by_side`).
    """
    d = find_dyad(sol, dyad)
    ax = axes_or_new(ax, figsize=(7.5, 5.0))
    i = row_index(sol, position, row)
    if singular_row(sol, i):        # no force to vouch for: said, not drawn
        ax.set(xticks=[], yticks=[])
        for side in ax.spines.values():
            side.set_visible(False)
        ax.text(0.5, 0.5, f"{titled('force polygon')} at {position_text(sol, i)}:\n"
                + SINGULAR_NOTE.replace(": ", ":\n"), ha="center", va="center",
                transform=ax.transAxes, color="tab:red")
        return ax
    forces, split = polygon_forces(sol, d, i, components)
    big = max((np.hypot(*f[1]) for f in forces), default=1.0) or 1.0
    chain = _chain(forces, d, split, big)
    corners = np.array([p for t, h, *_ in chain for p in (t, h)] or [[0.0, 0.0]])
    span = float(np.ptp(corners, axis=0).max()) or big
    offset = _OFFSET * span
    placed = side_by_side([(t, h) for t, h, *_ in chain], offset, span)
    handles, labels = [], []    # labels: (text, anchor, unit normal, colour), placed last
    moved = False
    for (t, h, lab, col, dashed, legend), (a, b, level) in zip(chain, placed, strict=True):
        f = h - t
        mag = float(np.hypot(*f))
        if level:
            moved = True
            ax.plot(*np.array([t, a]).T, ":", color="0.5", lw=1.0)
            ax.plot(*np.array([b, h]).T, ":", color="0.5", lw=1.0)
        ax.annotate("", tuple(b), tuple(a),
                    arrowprops={"arrowstyle": "-|>", "color": col, "lw": 1.4 if dashed else 1.8,
                                "ls": "--" if dashed else "-", "shrinkA": 0, "shrinkB": 0,
                                "mutation_scale": 13})
        ax.update_datalim([tuple(a), tuple(b)])
        if mag > 0.04 * big:
            labels.append((lab, a + 0.5 * f, np.array([-f[1], f[0]]) / mag, col))
        handles.append(Line2D([], [], color=col, ls="--" if dashed else "-",
                              lw=1.4 if dashed else 1.8, label=legend))
    for lab, f, col, _ in forces:       # forces too small to draw: in the legend only
        if np.hypot(*f) <= 1e-12 * big:
            handles.append(Line2D([], [], color=col, lw=1.8,
                                  label=f"{lab} = 0 N (to rounding)"))
    if moved:
        handles.append(Line2D([], [], ls=":", color="0.5", lw=1.0,
                              label=f"side-by-side offset {magnitude_text(offset)} N "
                                    "(drawing only)"))
    ax.plot(0, 0, "ko", ms=4)
    closure = float(np.hypot(*sum((f for _, f, _, _ in forces), np.zeros(2))))
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.margins(0.12)
    vector_axes(ax)
    texts = place_labels(ax, labels)
    texts.append(_scale_bar(ax, span))
    ax.set_xlabel("Fx [N]")
    ax.set_ylabel("Fy [N]")
    what = f"dyad {d.index + 1} {d.kind} ({d.bodies[0]}, {d.bodies[1]})" if d is not None \
        else f"driver {sol.scene.driver.body}"
    extra = ""
    if d is None and sol.drive.kind == "R":
        extra = ", " + signed_text("Me", float(sol.Me[i]), "N m")
    ax.set_title(f"{titled('force polygon')}\n{what} at "
                 f"{position_text(sol, i)}{extra}\nclosing error |ΣF| = {closure:.1e} N",
                 fontsize=11)
    ax.grid(True, alpha=0.3)
    legend_outside(ax, handles=handles)
    declutter(ax, texts)
    return ax


_OFFSET = 0.05      # one side-by-side step, as a fraction of the polygon's size


def _chain(forces: list, d, split: int | None, big: float) -> list:
    """(tail, tip, label, colour, dashed, legend text) of every arrow drawn: the forces
    head to tail from the pole, then the inner joint's reaction (dashed) from the end
    of the first body's forces back to the pole."""
    tail = np.zeros(2)
    corners = [tail.copy()]
    out = []
    for lab, f, col, _ in forces:
        tip = tail + f
        mag = float(np.hypot(*f))
        if mag > 1e-12 * big:
            out.append((tail.copy(), tip.copy(), lab, col, False,
                        f"{lab} = {magnitude_text(mag)} N at {direction_text(f)}"))
        tail = tip
        corners.append(tail.copy())
    if d is not None and split is not None:
        s = corners[split]
        mag = float(np.hypot(*s))
        name = force_symbol(d.inner.name)
        if mag > 1e-12 * big:
            out.append((s.copy(), np.zeros(2), name, "k", True,
                        f"{name} on {d.bodies[0]} = {magnitude_text(mag)} N (inner joint)"))
    return out


def _scale_bar(ax: Axes, span: float):
    """A bar of a round number of newtons in the lower right corner, named."""
    step = 10.0 ** np.floor(np.log10(0.25 * span))
    length = max(m * step for m in (1.0, 2.0, 5.0) if m * step <= 0.3 * span)
    ax.apply_aspect()
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    xr = x1 - 0.04 * (x1 - x0)
    yb = y0 + 0.06 * (y1 - y0)
    ax.plot([xr - length, xr], [yb, yb], "-", color="0.2", lw=3, solid_capstyle="butt",
            label="_scale")
    return ax.annotate(f"{magnitude_text(length)} N", (xr - 0.5 * length, yb), xytext=(0, 4),
                       textcoords="offset points", ha="center", va="bottom", fontsize=10,
                       color="0.2")
