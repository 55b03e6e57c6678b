"""The graphical method of the course (seed 001): the velocity and acceleration plans
(planul vitezelor, planul accelerațiilor) at one position.
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
    legend_outside,
    position_text,
    row_index,
    vector_axes,
)
from .place import declutter

__all__ = ["acceleration_plan", "velocity_plan"]


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


def _plan(sol: Solution, position, row, ax, kind: str, cog: bool,
          components: bool) -> Axes:
    ax = axes_or_new(ax, figsize=(7.5, 5.0))
    i = row_index(sol, position, row)
    pts, slides = _plan_points(sol, i, cog)
    attr = "v" if kind == "v" else "a"
    unit = "m/s" if kind == "v" else "m/s²"
    colors = body_colors()
    bodies = list(sol.scene.bodies)
    vec = {id(q): getattr(q, attr) for q in pts}
    big = max((np.hypot(*v) for v in vec.values()), default=0.0) or 1.0
    at_pole = {id(q) for q in pts if np.hypot(*vec[id(q)]) <= 1e-9 * big}
    handles = []

    def arrow(tail, tip, color, lw=1.6, ls="-", alpha=1.0):
        ax.annotate("", tuple(tip), tuple(tail),
                    arrowprops={"arrowstyle": "-|>", "color": color, "lw": lw, "ls": ls,
                                "shrinkA": 0, "shrinkB": 0, "alpha": alpha,
                                "mutation_scale": 12})
        ax.update_datalim([tuple(tail), tuple(tip)])

    # absolute vectors from the pole
    pole = "p" if kind == "v" else "π"
    sym = "v" if kind == "v" else "a"
    for q in pts:
        if q.label == pole:
            q.label = pole + "′"
    tips: list[list] = []       # tips at one place share one label "y0 = k"
    for q in pts:
        if id(q) in at_pole:
            continue
        c = colors[bodies.index(q.bodies[0]) % len(colors)]
        v = vec[id(q)]
        arrow((0.0, 0.0), v, c)
        same = next((t for t in tips if np.hypot(*(t[0] - v)) <= 1e-6 * big), None)
        if same is None:
            tips.append([v, [q.label], c])
        else:
            same[1].append(q.label)
        handles.append(Line2D([], [], color=c, lw=1.6,
                              label=f"{pole}{q.label} = {sym}({q.text}): "
                                    f"{np.hypot(*v):.3g} {unit}"))
    for v, labs, c in tips:
        off = 10.0 * v / np.hypot(*v)
        ax.annotate(" = ".join(labs), tuple(v), xytext=tuple(off), textcoords="offset points",
                    fontsize=10, fontweight="bold", color=c, ha="center", va="center")
    # relative vectors between points of the same body
    rel_drawn = comp_drawn = False
    for b in bodies:
        # a point at the pole first: the side of the plan from the fixed pivot (a_C =
        # a_D + a_CD^n + a_CD^t from pi) is drawn as well as the side from b
        own = sorted((q for q in pts if b in q.bodies), key=lambda q: id(q) not in at_pole)
        if len(own) < 2:
            continue
        pairs = list(zip(own[:-1], own[1:], strict=True))
        if len(own) >= 3:
            pairs.append((own[-1], own[0]))
            ax.add_patch(Polygon([vec[id(q)] for q in own], closed=True, alpha=0.12,
                                 color=colors[bodies.index(b) % len(colors)]))
        m = sol.kin.bodies[b].take(i)
        omega, alpha = float(m.omega), float(m.alpha)
        for k, (q0, q1) in enumerate(pairs):
            t0, t1 = vec[id(q0)], vec[id(q1)]
            if np.hypot(*(t1 - t0)) <= 1e-9 * big:
                continue
            if id(q0) not in at_pole and id(q1) not in at_pole:
                arrow(t0, t1, "0.35", lw=1.0)   # from the pole: the absolute vector
                rel_drawn = True
            if k == 0:
                ln = float(np.hypot(*(q1.xy - q0.xy)))
                rel = float(np.hypot(*(t1 - t0)))
                rn, ln_name = f"{q1.name}{q0.name}", f"{q0.name}{q1.name}"
                if kind == "v":
                    txt = f"ω({b}) = v{rn}/{ln_name} = {omega:.4g} rad/s"
                else:
                    txt = f"ε({b}) = a{rn}ᵗ/{ln_name} = {alpha:.4g} rad/s²"
                handles.append(Line2D([], [], color="0.35", lw=1.0,
                                      label=f"{q0.label}{q1.label}: {rel:.3g} {unit}, {txt}"
                                      if ln > 0 else f"{q0.label}{q1.label}: {rel:.3g} {unit}"))
            if kind == "a" and components and k == 0:
                d = q1.xy - q0.xy
                an = -omega ** 2 * d                          # towards q0: omega^2 l
                at = alpha * np.array([-d[1], d[0]])         # eps x r
                mid = t0 + an
                arrow(t0, mid, "tab:olive", lw=1.0, ls="--")
                arrow(mid, mid + at, "tab:cyan", lw=1.0, ls="--")
                comp_drawn = True
    for j, ts, tg in slides:
        t0, t1 = vec[id(tg)], vec[id(ts)]
        if kind == "v":
            arrow(t0, t1, "tab:gray", lw=1.2, ls=":")
            rel_drawn = True
        else:
            g = sol.kin.bodies[j.guide].take(i)
            vrel = ts.v - tg.v
            cor = 2.0 * float(g.omega) * np.array([-vrel[1], vrel[0]])   # 2 omega x v_rel
            if np.hypot(*cor) > 1e-9 * big:
                arrow(t0, t0 + cor, "tab:pink", lw=1.2, ls="--")
                handles.append(Line2D([], [], color="tab:pink", ls="--",
                                      label=f"Coriolis 2ω×v_rel at {j.name} = "
                                            f"{np.hypot(*cor):.3g} {unit}"))
            arrow(t0 + cor, t1, "tab:gray", lw=1.2, ls=":")
            handles.append(Line2D([], [], color="tab:gray", ls=":",
                                  label=f"relative along {j.name} = "
                                        f"{np.hypot(*(t1 - t0 - cor)):.3g} {unit}"))
    if kind == "v" and slides:
        handles.append(Line2D([], [], color="tab:gray", ls=":",
                              label="relative velocity along the guide"))
    if rel_drawn:
        handles.append(Line2D([], [], color="0.35", lw=1.0,
                              label="relative, points of one body"))
    if comp_drawn:
        handles.append(Line2D([], [], color="tab:olive", ls="--",
                              label="normal component ω²l"))
        handles.append(Line2D([], [], color="tab:cyan", ls="--",
                              label="tangential component εl"))
    ax.plot(0, 0, "ko", ms=5, zorder=5)
    ax.annotate(pole, (0, 0), xytext=(-12, -12),
                textcoords="offset points", fontsize=11, fontweight="bold")
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.margins(0.1)
    vector_axes(ax)
    ax.set_xlabel(f"{attr}x [{unit}]")
    ax.set_ylabel(f"{attr}y [{unit}]")
    what = "velocity plan (planul vitezelor)" if kind == "v" else \
        "acceleration plan (planul accelerațiilor)"
    drv = sol.scene.driver
    speed = f"ω = {drv.speed:g} rad/s" if drv.kind == "R" else f"v = {drv.speed:g} m/s"
    ax.set_title(f"{what}\nat {position_text(sol, i)}, {speed}", fontsize=10)
    ax.grid(True, alpha=0.3)
    legend_outside(ax, handles=handles)
    declutter(ax, [t for t in ax.texts if isinstance(t, Annotation) and t.get_text()])
    return ax


def velocity_plan(sol: Solution, position: float | None = None, *, row: int | None = None,
                  ax: Axes | None = None, cog: bool = False) -> Axes:
    """The velocity plan of the graphical method at one position.

    From the pole p, the absolute velocity of every named point (tip labelled with the
    point's lowercase letter); between tips of points of one body, the relative
    velocities (v_CB from b to c; a body with three points gives a figure similar to
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

    From the pole π, the absolute acceleration of every named point; between tips of
    points of one body the relative accelerations, the first of each body split
    (``components``) into its normal part omega^2 l (towards the first point, dashed
    olive) and tangential part eps l (dashed cyan): a_C = a_B + a_CB^n + a_CB^t (seed
    001 eq. 9). At a prismatic joint on a moving guide, from the guide's coincident
    point: the Coriolis acceleration 2 omega x v_rel (dashed pink) and the relative
    acceleration along the guide (dotted).

    Parameters
    ----------
    sol : Solution
    position : float, optional
        Driver position (nearest row); ``row`` picks a row by index instead.
    ax : Axes, optional
    cog : bool
        Add the centres of mass.
    components : bool
        Draw the normal and tangential parts of each body's first relative
        acceleration.

    Returns
    -------
    Axes
        Axes in m/s^2.
    """
    return _plan(sol, position, row, ax, "a", cog, components)

