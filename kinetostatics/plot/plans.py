"""The graphical method of the course (seed 001): the velocity and acceleration plans
(planul vitezelor, planul accelerațiilor) at one position, both from one pole o.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.axes import Axes
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon
from matplotlib.text import Annotation

from ..model.scene import GROUND
from ..results import Solution
from .base import (
    axes_or_new,
    body_colors,
    math_name,
    position_text,
    row_index,
    vector_axes,
)
from .notation import POLE, reading, signed_text, titled
from .place import declutter

__all__ = ["acceleration_plan", "velocity_plan"]

#: The colours of the absolute vectors of a plan, one per point (none of them the
#: olive, cyan, pink and grey of the components and relative vectors, nor the red of
#: the reactions).
VECTOR_COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown",
                 "#1b9e77", "#7570b3", "#e7298a", "#a6761d", "#e6ab02", "#1f3b73", "#000000")


@dataclass
class _PlanPoint:
    name: str           # the point's name in the scene
    label: str          # tip letter(s), lowercase as in the plans of the course
    text: str           # what it is, for the legend
    bodies: list
    xy: np.ndarray
    v: np.ndarray
    a: np.ndarray


def _plan_points(sol: Solution, i: int, cog: bool) -> tuple[list[_PlanPoint], list]:
    """The points of a plan at row i, and per prismatic joint (joint, slider tip, guide
    tip) with the guide body's point that coincides with the slider point."""
    scene = sol.scene
    bodies = list(scene.bodies)
    pts: dict[str, _PlanPoint] = {}
    motions = {b: sol.kin.bodies[b].take(i) for b in bodies}
    vscale = ascale = 0.0
    raw = []
    for b in bodies:
        body = scene.bodies[b]
        names = list(body.points) + (["cog"] if cog and body.cog is not None else [])
        m = motions[b]
        for p in names:
            x, y = m.point(body.local(p))
            v = np.array(m.vel_at(x, y), dtype=float)
            a = np.array(m.acc_at(x, y), dtype=float)
            raw.append((b, p, np.array([x, y], dtype=float), v, a))
            vscale, ascale = max(vscale, np.hypot(*v)), max(ascale, np.hypot(*a))
    tol_v, tol_a = 1e-9 * (vscale or 1.0), 1e-9 * (ascale or 1.0)
    for b, p, xy, v, a in raw:
        key = p if p != "cog" else f"cog {b}"
        old = pts.get(key)
        if old is not None and np.allclose(old.v, v, atol=tol_v, rtol=0) and \
                np.allclose(old.a, a, atol=tol_a, rtol=0):
            old.bodies.append(b)
            continue
        if old is not None:
            key = f"{p}{bodies.index(b) + 1}"
        lab = f"g{bodies.index(b) + 1}" if p == "cog" else key.lower()
        pname = p if p != "cog" else "G"
        pts[key] = _PlanPoint(pname, lab, f"{pname} of {b}", [b], xy, v, a)
    slides = []
    for j in scene.joints.values():
        if j.kind != "T" or GROUND in j.bodies:
            continue
        sp = j.points[1]
        tip_s = next((q for q in pts.values() if q.name == sp and j.slider in q.bodies), None)
        if tip_s is None:
            continue
        g = motions[j.guide]
        x, y = tip_s.xy
        v = np.array(g.vel_at(x, y), dtype=float)
        a = np.array(g.acc_at(x, y), dtype=float)
        k = bodies.index(j.guide) + 1
        tip_g = _PlanPoint(f"{sp}{k}", f"{sp.lower()}{k}", f"point of {j.guide} at {sp}", [j.guide],
                           tip_s.xy.copy(), v, a)
        pts[f"{sp}@{j.guide}"] = tip_g
        slides.append((j, tip_s, tip_g))
    return list(pts.values()), slides


@dataclass
class _Plan:
    """One plan being drawn: its Axes, its points, their vectors and the legend."""
    ax: Axes
    sol: Solution
    i: int
    kind: str           # "v" or "a"
    pts: list
    slides: list
    vec: dict
    big: float
    at_pole: set
    handles: list

    @property
    def unit(self) -> str:
        return "m/s" if self.kind == "v" else "m/s²"

    def arrow(self, tail, tip, color, lw=1.6, ls="-", alpha=1.0) -> None:
        self.ax.annotate("", tuple(tip), tuple(tail),
                         arrowprops={"arrowstyle": "-|>", "color": color, "lw": lw,
                                     "ls": ls, "shrinkA": 0, "shrinkB": 0, "alpha": alpha,
                                     "mutation_scale": 12})
        self.ax.update_datalim([tuple(tail), tuple(tip)])

    def legend(self, label: str, color, lw=1.6, ls="-") -> None:
        self.handles.append(Line2D([], [], color=color, lw=lw, ls=ls, label=label))


def _start(sol: Solution, position, row, ax, kind: str, cog: bool) -> _Plan:
    """The points of the plan, their vectors, and which of them sit on the pole."""
    ax = axes_or_new(ax, figsize=(8.0, 9.0))
    i = row_index(sol, position, row)
    pts, slides = _plan_points(sol, i, cog)
    vec = {id(q): (q.v if kind == "v" else q.a) for q in pts}
    big = max((np.hypot(*v) for v in vec.values()), default=0.0) or 1.0
    at_pole = {id(q) for q in pts if np.hypot(*vec[id(q)]) <= 1e-9 * big}
    return _Plan(ax, sol, i, kind, pts, slides, vec, big, at_pole, [])


def _absolute_vectors(pl: _Plan) -> None:
    """From the pole, the absolute vector of every point (tips at one place share one
    label "b = c"); the points on the pole are named beside it."""
    sym = "v" if pl.kind == "v" else "a"
    tips: list[list] = []
    moving = [q for q in pl.pts if id(q) not in pl.at_pole]
    for k, q in enumerate(moving):
        c = VECTOR_COLORS[k % len(VECTOR_COLORS)]     # every vector its own colour
        v = pl.vec[id(q)]
        pl.arrow((0.0, 0.0), v, c)
        same = next((t for t in tips if np.hypot(*(t[0] - v)) <= 1e-6 * pl.big), None)
        if same is None:
            tips.append([v, [q.label], c])
        else:
            same[1].append(q.label)
        pl.legend(f"{POLE}{q.label} = {sym}({q.text}): {reading(np.hypot(*v), 3)} {pl.unit}",
                  c)
    for v, labs, c in tips:
        off = 10.0 * v / np.hypot(*v)
        pl.ax.annotate(" = ".join(labs), tuple(v), xytext=tuple(off),
                       textcoords="offset points", fontsize=11, fontweight="bold", color=c,
                       ha="center", va="center")
    fixed = [q.label for q in pl.pts if id(q) in pl.at_pole]
    pl.ax.plot(0, 0, "ko", ms=5, zorder=5)
    pl.ax.annotate(" = ".join([POLE] + fixed), (0, 0), xytext=(-12, -12),
                   textcoords="offset points", fontsize=11, fontweight="bold")
    pl.handles.append(Line2D([], [], ls="none", marker="o", color="k", ms=5,
                             label=f"{POLE}: the pole" + (f" (= {', '.join(fixed)}: fixed "
                                                          "points)" if fixed else "")))


def _relative_vectors(pl: _Plan, components: bool) -> tuple[bool, bool]:
    """Between the tips of points of one body, the relative vectors (the first of each
    body named with the body's angular speed or acceleration, and split into its
    normal and tangential parts in the acceleration plan). Returns (relative drawn,
    components drawn)."""
    colors, bodies = body_colors(), list(pl.sol.scene.bodies)
    vec = pl.vec
    rel_drawn = comp_drawn = False
    for b in bodies:
        # a point at the pole first: the side of the plan from the fixed pivot (a_C =
        # a_D + a_CD^n + a_CD^t from the pole) is drawn as well as the side from b
        own = sorted((q for q in pl.pts if b in q.bodies), key=lambda q: id(q) not in
                     pl.at_pole)
        if len(own) < 2:
            continue
        pairs = list(zip(own[:-1], own[1:], strict=True))
        if len(own) >= 3:
            pairs.append((own[-1], own[0]))
            pl.ax.add_patch(Polygon([vec[id(q)] for q in own], closed=True, alpha=0.12,
                                    color=colors[bodies.index(b) % len(colors)]))
        m = pl.sol.kin.bodies[b].take(pl.i)
        omega, alpha = float(m.omega), float(m.alpha)
        for k, (q0, q1) in enumerate(pairs):
            t0, t1 = vec[id(q0)], vec[id(q1)]
            if np.hypot(*(t1 - t0)) <= 1e-9 * pl.big:
                continue
            if id(q0) not in pl.at_pole and id(q1) not in pl.at_pole:
                pl.arrow(t0, t1, "0.35", lw=1.0)   # from the pole: the absolute vector
                rel_drawn = True
            if k == 0:
                pl.legend(_relative_text(pl, b, q0, q1, omega, alpha), "0.35", lw=1.0)
            if pl.kind == "a" and components and k == 0:
                d = q1.xy - q0.xy
                an = -omega ** 2 * d                          # towards q0: omega^2 l
                at = alpha * np.array([-d[1], d[0]])         # eps x r
                mid = t0 + an
                # from the pole with no tangential part the normal part is the absolute
                # vector itself (a crank at constant speed): drawn once, as the absolute
                lies_on = id(q0) in pl.at_pole and np.hypot(*at) <= 1e-9 * pl.big
                if not lies_on:
                    pl.arrow(t0, mid, "tab:olive", lw=1.0, ls="--")
                if np.hypot(*at) > 1e-9 * pl.big:
                    pl.arrow(mid, mid + at, "tab:cyan", lw=1.0, ls="--")
                comp_drawn = comp_drawn or not lies_on
    return rel_drawn, comp_drawn


def _relative_text(pl: _Plan, b: str, q0, q1, omega: float, alpha: float) -> str:
    """``bc: 0.183 m/s, ω(coupler) = v_CB/BC = 0.787 rad/s, clockwise``."""
    rel = float(np.hypot(*(pl.vec[id(q1)] - pl.vec[id(q0)])))
    head = f"{q0.label}{q1.label}: {reading(rel, 3)} {pl.unit}"
    if float(np.hypot(*(q1.xy - q0.xy))) == 0.0:
        return head
    rn, ln = q1.name + q0.name, q0.name + q1.name
    if pl.kind == "v":
        return head + ", " + signed_text(
            f"ω({b}) = $v_{{\\mathrm{{{math_name(rn)}}}}}$/{ln}", omega, "rad/s")
    return head + ", " + signed_text(
        f"ε({b}) = $a^{{t}}_{{\\mathrm{{{math_name(rn)}}}}}$/{ln}", alpha, "rad/s²")


def _sliding_vectors(pl: _Plan) -> bool:
    """At a prismatic joint on a moving guide: the relative vector along the guide
    (and the Coriolis acceleration 2ω×v_rel before it). Returns: relative drawn."""
    drawn = False
    for j, ts, tg in pl.slides:
        t0, t1 = pl.vec[id(tg)], pl.vec[id(ts)]
        if pl.kind == "v":
            pl.arrow(t0, t1, "tab:gray", lw=1.2, ls=":")
            drawn = True
            continue
        g = pl.sol.kin.bodies[j.guide].take(pl.i)
        vrel = ts.v - tg.v
        cor = 2.0 * float(g.omega) * np.array([-vrel[1], vrel[0]])   # 2 omega x v_rel
        if np.hypot(*cor) > 1e-9 * pl.big:
            pl.arrow(t0, t0 + cor, "tab:pink", lw=1.2, ls="--")
            pl.legend(f"Coriolis 2ω × $v_{{\\mathrm{{rel}}}}$ at {j.name} = "
                      f"{reading(np.hypot(*cor), 3)} {pl.unit}", "tab:pink", ls="--")
        pl.arrow(t0 + cor, t1, "tab:gray", lw=1.2, ls=":")
        pl.legend(f"relative along {j.name} = {reading(np.hypot(*(t1 - t0 - cor)), 3)} "
                  f"{pl.unit}",
                  "tab:gray", ls=":")
    if pl.kind == "v" and pl.slides:
        pl.legend("relative velocity along the guide", "tab:gray", ls=":")
    return drawn


def _frame(pl: _Plan) -> None:
    """Equal axes in m/s or m/s², the title with the gloss, the legend outside."""
    ax, sol = pl.ax, pl.sol
    attr = "v" if pl.kind == "v" else "a"
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.margins(0.1)
    vector_axes(ax)
    ax.set_xlabel(f"${attr}_x$ [{pl.unit}]")
    ax.set_ylabel(f"${attr}_y$ [{pl.unit}]")
    term = "velocity plan" if pl.kind == "v" else "acceleration plan"
    what = titled(term)
    drv = sol.scene.driver
    speed = f"ω = {drv.speed:g} rad/s" if drv.kind == "R" else f"v = {drv.speed:g} m/s"
    ax.set_title(f"{what}\nat {position_text(sol, pl.i)}, {speed}", fontsize=11)
    ax.grid(True, alpha=0.3)
    # below the x label (3.4 font sizes under the Axes, whatever their size): the plan
    # keeps the figure's width
    ax.legend(handles=pl.handles, loc="upper center", bbox_to_anchor=(0.5, 0.0),
              borderaxespad=3.4)


def _plan(sol: Solution, position, row, ax, kind: str, cog: bool,
          components: bool) -> Axes:
    """A velocity (``kind="v"``) or acceleration (``"a"``) plan, in named steps."""
    pl = _start(sol, position, row, ax, kind, cog)
    _absolute_vectors(pl)
    rel_drawn, comp_drawn = _relative_vectors(pl, components)
    rel_drawn |= _sliding_vectors(pl)
    if rel_drawn:
        pl.legend("relative, points of one body", "0.35", lw=1.0)
    if comp_drawn:
        pl.legend("normal component ω²l", "tab:olive", lw=1.0, ls="--")
        pl.legend("tangential component εl", "tab:cyan", lw=1.0, ls="--")
    _frame(pl)
    declutter(pl.ax, [t for t in pl.ax.texts if isinstance(t, Annotation) and t.get_text()])
    return pl.ax


def velocity_plan(sol: Solution, position: float | None = None, *, row: int | None = None,
                  ax: Axes | None = None, cog: bool = False) -> Axes:
    """The velocity plan of the graphical method at one position.

    From the pole o (the fixed points sit on it), the absolute velocity of every named
    point (tip labelled with the point's lowercase letter); between tips of points of
    one body, the relative velocities (v_CB from b to c; a body with three points gives
    a figure similar to
    the body, turned by 90 deg); at a prismatic joint on a moving guide, the tip of the
    guide's coincident point (``a3``: point A of body 3) and the relative velocity along
    the guide (dotted). Seed 001: v_C = v_B + omega x BC.

    Parameters
    ----------
    sol : Solution
    position : float, optional
        Driver position (nearest row); ``row`` picks a row by index instead.
    ax : Axes, optional
    cog : bool
        Add the centres of mass (``g1``, ``g2``, ...).

    Returns
    -------
    Axes
        Axes in m/s; the legend gives every absolute speed.
    """
    return _plan(sol, position, row, ax, "v", cog, False)


def acceleration_plan(sol: Solution, position: float | None = None, *,
                      row: int | None = None, ax: Axes | None = None, cog: bool = False,
                      components: bool = True) -> Axes:
    """The acceleration plan of the graphical method at one position.

    From the pole o (as in the velocity plan), the absolute acceleration of every named
    point; between tips of points of one body the relative accelerations, the first of
    each body split (``components``) into its normal part omega^2 l (towards the first point, dashed
    olive) and tangential part eps l (dashed cyan): a_C = a_B + a_CB^n + a_CB^t (seed
    001 eq. 9). At a prismatic joint on a moving guide, from the guide's coincident
    point: the Coriolis acceleration 2 omega x v_rel (dashed pink) and the relative
    acceleration along the guide (dotted).

    Parameters
    ----------
    sol, position, row, ax, cog
        As in :func:`velocity_plan`.
    components : bool
        Draw the normal and tangential parts of each body's first relative
        acceleration.

    Returns
    -------
    Axes
        Axes in m/s^2.
    """
    return _plan(sol, position, row, ax, "a", cog, components)

