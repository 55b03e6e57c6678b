"""The classic pictures of kinetostatics, drawn from computed data.

Every function takes a :class:`~kinetostatics.results.Solution` (or tables), an
optional ``ax``, and returns the matplotlib Axes (or Figure, or animation); none calls
``plt.show``. Units are in every axis label; geometry and vector diagrams use equal
aspect.

- the mechanism at a position, with the joint reactions and the loads as arrows:
  :func:`draw_mechanism`; its motion over the cycle: :func:`animate`;
- the graphical method of the course (seed 001): the velocity and acceleration plans
  (planul vitezelor, planul accelerațiilor) :func:`velocity_plan`,
  :func:`acceleration_plan`;
- the force polygon of a dyad or of the driver (poligonul forțelor, seed 002 figs 2.9,
  2.11, 2.13, 2.15, 2.17, 2.19, 2.38, 2.42): :func:`force_polygon`;
- curves over the cycle: :func:`plot_driver` (Me), :func:`plot_polar` (polar diagram
  of the reactions), :func:`plot_transmission`, :func:`plot_trajectories`,
  :func:`plot_speeds`, :func:`plot_accelerations`, :func:`plot_angular`;
- :func:`overview`: four panels at once.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes
from matplotlib.colors import to_hex
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon
from matplotlib.ticker import MaxNLocator, MultipleLocator

from ..model.errors import WorkbenchError
from ..model.scene import GROUND
from ..results import Solution
from ..solver.structure import Dyad

__all__ = [
    "acceleration_plan", "animate", "draw_mechanism", "force_polygon", "overview",
    "plot_accelerations", "plot_angular", "plot_driver", "plot_polar", "plot_speeds",
    "plot_trajectories", "plot_transmission", "velocity_plan",
]

LOAD_COLORS = {"applied": "tab:blue", "gravity": "tab:brown", "inertia": "tab:purple"}
REACTION_COLOR = "tab:red"
PATH_COLORS = ("#1b9e77", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666")


def _body_colors() -> list[str]:
    """The colour cycle without its red, which marks the joint reactions."""
    cycle = plt.rcParams["axes.prop_cycle"].by_key().get("color", ["C0"])
    keep = [c for c in cycle if to_hex(c) not in ("#d62728", "#ff0000")]
    return keep or list(cycle)


def _ax(ax: Axes | None, figsize=(6, 4.5)) -> Axes:
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax


def _pos_label(sol: Solution) -> str:
    return "crank angle φ [deg]" if sol.scene.driver.kind == "R" else "driver position s [m]"


def _pos_text(sol: Solution, i: int) -> str:
    p = float(sol.positions[i])
    return f"φ = {p:g}°" if sol.scene.driver.kind == "R" else f"s = {p:g} m"


def _vector_axes(ax: Axes) -> None:
    """Few ticks, large numbers as powers of ten: legible tick labels on vector diagrams."""
    for a in (ax.xaxis, ax.yaxis):
        a.set_major_locator(MaxNLocator(nbins=6, steps=[1, 2, 2.5, 5, 10]))
    ax.ticklabel_format(style="sci", axis="both", scilimits=(-3, 4), useMathText=True)


def _cycle_axis(ax: Axes, sol: Solution) -> None:
    """Ticks every 45 deg (90 deg beyond a turn) on a crank-angle axis."""
    if sol.scene.driver.kind == "R" and sol.positions.size > 1:
        span = float(np.ptp(sol.positions))
        if span >= 180.0:
            ax.xaxis.set_major_locator(MultipleLocator(45.0 if span <= 360.0 else 90.0))


def _row(sol: Solution, position: float | None, row: int | None) -> int:
    if row is not None:
        return int(row)
    if position is None:
        return 0
    return int(np.argmin(np.abs(sol.positions - position)))


def _at(x, i: int, n: int) -> float:
    """Row ``i`` of an array over positions, or the scalar."""
    return float(np.broadcast_to(x, (n,))[i])


def _global(sol: Solution, body: str, point: str, row: int) -> tuple[float, float]:
    if body == GROUND:
        return sol.scene.ground[point]
    m = sol.kin.bodies[body]
    x, y = m.point(sol.scene.bodies[body].local(point))
    n = sol.positions.size
    return _at(x, row, n), _at(y, row, n)


def _num(x: float) -> str:
    """A magnitude for a legend: 31770 rather than 3.177e+04."""
    return f"{x:.0f}" if 1e3 <= abs(x) < 1e7 else f"{x:.4g}"


def _mtext(name: str) -> str:
    """A name safe inside mathtext ``\\mathrm{}``."""
    return name.replace("_", r"\_").replace("$", "")


def _legend_outside(ax: Axes, **kw) -> None:
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
              **kw)


# ----------------------------------------------------------------------------- drawing
def _guide_angle(sol: Solution, j, i: int) -> float:
    th = np.deg2rad(j.line_angle)
    if j.guide != GROUND:
        th += _at(sol.kin.bodies[j.guide].theta, i, sol.positions.size)
    return float(th)


def _guide_extent(sol: Solution, j, i: int, size: float) -> tuple[float, float]:
    """Where to draw a guide line, along it from its line point: over the slider
    point's whole travel for a ground guide, around the line point and the slider point
    now for a moving guide."""
    n = sol.positions.size
    th = _guide_angle(sol, j, i)
    gx, gy = _global(sol, j.guide, j.points[0], i)
    if j.guide == GROUND and j.slider != GROUND:
        m = sol.kin.bodies[j.slider]
        x, y = m.point(sol.scene.bodies[j.slider].local(j.points[1]))
        s = (np.broadcast_to(x, (n,)) - gx) * np.cos(th) + \
            (np.broadcast_to(y, (n,)) - gy) * np.sin(th)
    else:
        sx, sy = _global(sol, j.slider, j.points[1], i)
        s = np.array([0.0, (sx - gx) * np.cos(th) + (sy - gy) * np.sin(th)])
    return float(min(s.min(), 0.0) - 0.15 * size), float(max(s.max(), 0.0) + 0.15 * size)


def draw_mechanism(sol: Solution, position: float | None = None, *, row: int | None = None,
                   ax: Axes | None = None, forces: bool = False, labels: bool = True,
                   force_scale: float | None = None, loads: bool = False) -> Axes:
    """Draw the mechanism at one position: links between their joint points, pins,
    slider blocks and guides, the ground.

    Parameters
    ----------
    sol : Solution
        A solved scene.
    position : float, optional
        Driver position (deg or m); the nearest row is drawn (default: the first row).
    row : int, optional
        Row index instead of ``position``.
    ax : Axes, optional
        Where to draw; a new figure when None.
    forces : bool
        Draw the joint reactions on each joint's ``on`` body as red arrows.
    labels : bool
        Write the point names.
    force_scale : float, optional
        Metres of drawing per newton; default: the largest arrow is 1/4 of the size.
    loads : bool
        Draw the applied loads (blue), weights (brown) and inertia forces (purple) at
        their points (d'Alembert, seed 002 eq. 2.1).

    Returns
    -------
    Axes
    """
    ax = _ax(ax)
    i = _row(sol, position, row)
    n = sol.positions.size
    scene = sol.scene
    colors = _body_colors()
    allpts = [xy for xy in scene.ground.values()]
    for k, (name, body) in enumerate(scene.bodies.items()):
        pts = [_global(sol, name, p, i) for p in body.points]
        allpts += pts
        c = colors[k % len(colors)]
        if len(pts) >= 3:
            ax.add_patch(Polygon(pts, closed=True, alpha=0.25, color=c))
            ax.plot(*zip(*(pts + pts[:1]), strict=True), color=c, lw=2.5, label=name)
        elif len(pts) == 2:
            ax.plot(*zip(*pts, strict=True), color=c, lw=3.5, solid_capstyle="round",
                    label=name)
        else:
            ax.plot(*zip(*pts, strict=True), "s", color=c, ms=14, alpha=0.6, label=name)
        if body.cog is not None and body.mass > 0:
            g = _global(sol, name, "cog", i)
            ax.plot(*g, "o", mfc="white", mec=c, ms=6)
        if labels:
            for p, xy in zip(body.points, pts, strict=True):
                ax.annotate(p, xy, xytext=(4, 4), textcoords="offset points", fontsize=9)
    arr = np.array(allpts)
    size = float(np.ptp(arr, axis=0).max()) if len(arr) > 1 else 1.0
    size = size or 1.0
    for j in scene.joints.values():
        if j.kind == "R":
            b = j.bodies[1] if j.bodies[0] == GROUND else j.bodies[0]
            xy = _global(sol, b, j.point_on(b), i)
            ax.plot(*xy, "o", color="k", mfc="white", ms=7, zorder=5)
            if GROUND in j.bodies:
                ax.plot(*xy, "^", color="k", ms=12, zorder=4, mfc="0.8")
        else:
            lo, hi = _guide_extent(sol, j, i, size)
            gx, gy = _global(sol, j.guide, j.points[0], i)
            th = _guide_angle(sol, j, i)
            u = np.array([np.cos(th), np.sin(th)])
            ends = np.array([gx, gy]) + np.outer([lo, hi], u)
            ax.plot(ends[:, 0], ends[:, 1], "--", color="0.4", lw=1)
    arrows = []     # (label, x, y, fx, fy, color)
    if forces:
        for name in scene.joints:
            r = sol.joint_reactions[name]
            fx, fy = sol.reaction(name)
            arrows.append((f"F[{name}]", _at(r.x, i, n), _at(r.y, i, n), float(fx[i]),
                           float(fy[i]), REACTION_COLOR))
    if loads:
        for ld in sol.loads:
            fx, fy = _at(ld.fx, i, n), _at(ld.fy, i, n)
            if fx == 0.0 and fy == 0.0:
                continue
            x, y = ld.position(sol.kin)
            short = {"applied": "F", "gravity": "G", "inertia": "Fi"}[ld.kind]
            arrows.append((f"{short} {ld.body}", _at(x, i, n), _at(y, i, n), fx, fy,
                           LOAD_COLORS[ld.kind]))
    handles = []
    if arrows:
        fmax = max(np.hypot(a[3], a[4]) for a in arrows) or 1.0
        sc = force_scale or 0.25 * size / fmax
        for lab, x, y, fx, fy, col in arrows:
            tip = (x + sc * fx, y + sc * fy)
            ax.annotate("", tip, (x, y),
                        arrowprops={"arrowstyle": "-|>", "color": col, "lw": 1.5,
                                    "shrinkA": 0, "shrinkB": 0})
            ax.update_datalim([(x, y), tip])
            mag = float(np.hypot(fx, fy)) or 1.0
            ax.annotate(lab, tip, xytext=(4 * fx / mag, 4 * fy / mag),
                        textcoords="offset points", fontsize=9, color=col,
                        ha="left" if fx >= 0 else "right", va="bottom" if fy >= 0 else "top",
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.6})
        kinds = [("joint reactions", REACTION_COLOR)] if forces else []
        if loads:
            kinds += [(f"{k} forces", c) for k, c in LOAD_COLORS.items()
                      if any(a[5] == c for a in arrows)]
        handles = [Line2D([], [], color=c, lw=1.5, label=k) for k, c in kinds]
        ref = 10.0 ** np.floor(np.log10(0.1 * size))
        ax.text(0.99, 0.01, f"arrows: {ref:g} m ≙ {ref / sc:.3g} N", transform=ax.transAxes,
                ha="right", va="bottom", fontsize=8, color="0.3")
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.08)
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{scene.title or 'mechanism'} at {_pos_text(sol, i)}", fontsize=10)
    ax.grid(True, alpha=0.3)
    h, _ = ax.get_legend_handles_labels()
    ax.legend(handles=h + handles, fontsize=8, loc="best")
    return ax


def _trace_points(sol: Solution) -> list[tuple[str, str]]:
    """(body, point) of every named point of the moving bodies, one per location name."""
    seen, out = set(), []
    for name, body in sol.scene.bodies.items():
        for p in body.points:
            if p not in seen:
                seen.add(p)
                out.append((name, p))
    return out


def animate(sol: Solution, frames: int = 24, *, ax: Axes | None = None,
            interval: float = 120.0, trace: bool = True) -> FuncAnimation:
    """An animation of the mechanism over the sweep.

    Parameters
    ----------
    sol : Solution
        A solved scene.
    frames : int
        Number of frames, taken evenly over the sweep's rows (few frames keep
        ``anim.to_jshtml()`` fast in a notebook).
    ax : Axes, optional
        Where to draw; a new figure when None.
    interval : float
        Milliseconds between frames.
    trace : bool
        Draw the trajectories of the named points as faint lines.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Display it in a notebook with ``HTML(anim.to_jshtml())``; close its figure
        afterwards (``plt.close(anim._fig)``) to avoid a second, static picture.
    """
    if frames < 1:
        raise WorkbenchError(f"animate: frames must be >= 1, not {frames}")
    ax = _ax(ax)
    fig = ax.figure
    scene = sol.scene
    n = sol.positions.size
    rows = np.unique(np.linspace(0, n - 1, min(frames, n)).round().astype(int))
    colors = _body_colors()
    # coordinates of every body's points at every row: (rows, points, 2)
    geo = {}
    for name, body in scene.bodies.items():
        m = sol.kin.bodies[name]
        xy = [tuple(np.broadcast_to(c, (n,)) for c in m.point(loc))
              for loc in body.points.values()]
        geo[name] = np.stack([np.stack(p, axis=-1) for p in xy], axis=1)
    allxy = np.concatenate([g.reshape(-1, 2) for g in geo.values()]
                           + [np.array(list(scene.ground.values())).reshape(-1, 2)])
    lo, hi = allxy.min(axis=0), allxy.max(axis=0)
    pad = 0.08 * float(max(hi - lo)) + 1e-9
    if trace:
        for b, p in _trace_points(sol):
            k = list(scene.bodies[b].points).index(p)
            ax.plot(geo[b][:, k, 0], geo[b][:, k, 1], lw=0.8, color="0.6", alpha=0.7)
    for gxy in scene.ground.values():
        ax.plot(*gxy, "^", color="k", ms=10, mfc="0.8", zorder=4)
    artists = {}
    for k, (name, body) in enumerate(scene.bodies.items()):
        c = colors[k % len(colors)]
        npts = len(body.points)
        style = {"color": c, "label": name}
        if npts == 1:
            (ln,) = ax.plot([], [], "s", ms=13, alpha=0.7, **style)
        else:
            (ln,) = ax.plot([], [], "-o", lw=3, ms=5, mfc="white", **style)
        artists[name] = ln
    guides = [(j, ax.plot([], [], "--", color="0.4", lw=1)[0])
              for j in scene.joints.values() if j.kind == "T"]
    span = float(max(hi - lo)) or 1.0
    title = ax.set_title("", fontsize=10)

    def update(f: int):
        i = int(rows[f])
        for name, body in scene.bodies.items():
            pts = geo[name][i]
            if len(body.points) >= 3:
                pts = np.vstack([pts, pts[:1]])
            artists[name].set_data(pts[:, 0], pts[:, 1])
        for j, ln in guides:
            gx, gy = _global(sol, j.guide, j.points[0], i)
            th = _guide_angle(sol, j, i)
            t = np.array(_guide_extent(sol, j, i, span))
            ln.set_data(gx + t * np.cos(th), gy + t * np.sin(th))
        title.set_text(f"{scene.title or 'mechanism'}: {_pos_text(sol, i)}")
        return [*artists.values(), *(g[1] for g in guides), title]

    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    update(0)
    return FuncAnimation(fig, update, frames=len(rows), interval=interval, blit=False)


# ------------------------------------------------------------------ velocity plans
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
    ax = _ax(ax, figsize=(7.5, 5.0))
    i = _row(sol, position, row)
    pts, slides = _plan_points(sol, i, cog)
    attr = "v" if kind == "v" else "a"
    unit = "m/s" if kind == "v" else "m/s²"
    colors = _body_colors()
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
        own = [q for q in pts if b in q.bodies and id(q) not in at_pole]
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
            arrow(t0, t1, "0.35", lw=1.0)
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
    _vector_axes(ax)
    ax.set_xlabel(f"{attr}x [{unit}]")
    ax.set_ylabel(f"{attr}y [{unit}]")
    what = "velocity plan (planul vitezelor)" if kind == "v" else \
        "acceleration plan (planul accelerațiilor)"
    drv = sol.scene.driver
    speed = f"ω = {drv.speed:g} rad/s" if drv.kind == "R" else f"v = {drv.speed:g} m/s"
    ax.set_title(f"{what} at {_pos_text(sol, i)}, {speed}", fontsize=10)
    ax.grid(True, alpha=0.3)
    _legend_outside(ax, handles=handles)
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


# ------------------------------------------------------------------- force polygon
def _find_dyad(sol: Solution, dyad) -> Dyad | None:
    """A dyad by 1-based index, label/kind/body name or bodies tuple; None for the
    driver."""
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


def _force_on(sol: Solution, joint: str, body: str, i: int) -> np.ndarray:
    """The reaction of ``joint`` on ``body`` at row i."""
    r = sol.joint_reactions[joint]
    fx, fy = sol.reaction(joint)
    f = np.array([fx[i], fy[i]], dtype=float)
    return f if r.on == body else -f


def _polygon_forces(sol: Solution, dyad: Dyad | None, i: int, components: bool):
    """The forces of the polygon in drawing order: (label, vector, color, group)."""
    scene = sol.scene
    n = sol.positions.size
    out = []

    def loads_of(b):
        kind_label = {"applied": "F", "gravity": "G", "inertia": "F^{i}"}
        for ld in sol.loads:
            if ld.body != b:
                continue
            f = np.array([_at(ld.fx, i, n), _at(ld.fy, i, n)])
            if not f.any():
                continue
            k = kind_label[ld.kind]
            sub = _mtext(b)
            lab = f"${k}_{{\\mathrm{{{sub}}}}}$" if ld.kind != "inertia" else \
                f"$F^{{i}}_{{\\mathrm{{{sub}}}}}$"
            if ld.kind == "applied" and ld.label:
                lab += f" ({ld.label.split(' at ')[-1]})" if " at " in ld.label else ""
            out.append((lab, f, LOAD_COLORS[ld.kind], "load"))

    def reaction(j, b, other_point, color=REACTION_COLOR):
        f = _force_on(sol, j.name, b, i)
        name = _mtext(j.name)
        if j.kind == "R" and components and other_point is not None:
            p = np.array(_global(sol, b, j.point_on(b), i))
            d = np.asarray(other_point) - p
            if np.hypot(*d) > 1e-9:
                u = d / np.hypot(*d)
                fn = np.dot(f, u) * u
                out.append((f"$F_{{\\mathrm{{{name}}}}}^{{t}}$", f - fn, REACTION_COLOR,
                            "outer"))
                out.append((f"$F_{{\\mathrm{{{name}}}}}^{{n}}$", fn, "tab:orange", "outer"))
                return
        out.append((f"$F_{{\\mathrm{{{name}}}}}$", f, color, "outer"))

    if dyad is None:
        b = scene.driver.body
        loads_of(b)
        dj = scene.joints[scene.driver.joint]
        for j in scene.joints.values():
            if b in j.bodies and j is not dj:
                reaction(j, b, None, "darkred")
        if sol.drive.kind == "T":
            beta = np.deg2rad(dj.line_angle)
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
                f = _force_on(sol, j.name, b, i)
                out.append((f"$F_{{\\mathrm{{{_mtext(j.name)}}}}}$ ({j.other(b)})", f,
                            "darkred", "load"))

    if inner.kind == "R":
        x1 = np.array(_global(sol, b1, inner.point_on(b1), i))
        x2 = np.array(_global(sol, b2, inner.point_on(b2), i))
    else:
        x1 = x2 = np.array(_global(sol, inner.slider, inner.points[1], i))
    reaction(dyad.outer[0], b1, x1)
    loads_of(b1)
    later(b1)
    split = len(out)
    loads_of(b2)
    later(b2)
    reaction(dyad.outer[1], b2, x2)
    return out, split


def _place_labels(ax: Axes, labels: list, gap: float = 20.0) -> None:
    """Write each label beside its vector's middle, on the side (and at the distance)
    that keeps it at least ``gap`` pixels from the labels already placed."""
    ax.apply_aspect()
    placed: list[np.ndarray] = []
    dpi = ax.figure.dpi / 72.0
    for text, anchor, nrm, col in labels:
        base = ax.transData.transform(anchor)
        best, score = 9.0, -1.0
        for off in (9.0, -9.0, 18.0, -18.0, 28.0, -28.0):
            pos = base + off * dpi * np.array([nrm[0], nrm[1]])
            d = min((float(np.hypot(*(pos - q))) for q in placed), default=np.inf)
            if d >= gap * dpi:
                best, score = off, d
                break
            if d > score:
                best, score = off, d
        placed.append(base + best * dpi * np.asarray(nrm))
        ax.annotate(text, tuple(anchor), xytext=tuple(best * np.asarray(nrm)),
                    textcoords="offset points", fontsize=10, color=col, ha="center",
                    va="center")


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
        closure error |sum F|.
    """
    d = _find_dyad(sol, dyad)
    ax = _ax(ax, figsize=(7.5, 5.0))
    i = _row(sol, position, row)
    forces, split = _polygon_forces(sol, d, i, components)
    big = max((np.hypot(*f[1]) for f in forces), default=1.0) or 1.0
    tail = np.zeros(2)
    corners = [tail.copy()]
    handles = []
    labels = []         # (text, anchor, unit normal, colour): placed at the end
    for lab, f, col, _ in forces:
        tip = tail + f
        mag = float(np.hypot(*f))
        if mag > 1e-12 * big:
            ax.annotate("", tuple(tip), tuple(tail),
                        arrowprops={"arrowstyle": "-|>", "color": col, "lw": 1.8,
                                    "shrinkA": 0, "shrinkB": 0, "mutation_scale": 13})
            if mag > 0.04 * big:
                labels.append((lab, tail + 0.5 * f, np.array([-f[1], f[0]]) / mag, col))
        handles.append(Line2D([], [], color=col, lw=1.8, label=f"{lab} = {_num(mag)} N"))
        tail = tip
        corners.append(tail.copy())
    if d is not None and split is not None:
        s = corners[split]
        fin = -s
        mag = float(np.hypot(*fin))
        ax.annotate("", (0.0, 0.0), tuple(s),
                    arrowprops={"arrowstyle": "-|>", "color": "k", "lw": 1.4, "ls": "--",
                                "shrinkA": 0, "shrinkB": 0, "mutation_scale": 13})
        name = _mtext(d.inner.name)
        lab = f"$F_{{\\mathrm{{{name}}}}}$ on {d.bodies[0]}"
        if mag > 0.04 * big:
            labels.append((f"$F_{{\\mathrm{{{name}}}}}$", s + 0.5 * fin,
                           np.array([-fin[1], fin[0]]) / mag, "k"))
        handles.append(Line2D([], [], color="k", ls="--", lw=1.4,
                              label=f"{lab} = {_num(mag)} N (inner joint)"))
    ax.update_datalim(np.array(corners))
    ax.plot(0, 0, "ko", ms=4)
    closure = float(np.hypot(*tail))
    ax.text(0.01, 0.01, f"closure |ΣF| = {closure:.1e} N", transform=ax.transAxes,
            fontsize=8, color="0.3")
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.margins(0.12)
    _vector_axes(ax)
    _place_labels(ax, labels)
    ax.set_xlabel("Fx [N]")
    ax.set_ylabel("Fy [N]")
    what = f"dyad {d.index + 1} {d.kind} ({d.bodies[0]}, {d.bodies[1]})" if d is not None \
        else f"driver {sol.scene.driver.body}"
    extra = ""
    if d is None and sol.drive.kind == "R":
        extra = f", Me = {float(sol.Me[i]):.4g} N m"
    ax.set_title(f"force polygon (poligonul forțelor): {what}\nat {_pos_text(sol, i)}{extra}",
                 fontsize=10)
    ax.grid(True, alpha=0.3)
    _legend_outside(ax, handles=handles)
    return ax


# --------------------------------------------------------------------------- curves
def plot_driver(sol: Solution, ax: Axes | None = None) -> Axes:
    """Me (or Fe) over the sweep, its mean (trapezoid rule) and the rows near a dead
    centre shaded (seed 002 eqs 2.44-2.51).

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        Position against Me [N m] (Fe [N] for a sliding driver).
    """
    ax = _ax(ax)
    q = sol.driver_quantity
    me = sol.Me
    unit = "N m" if q == "Me" else "N"
    ax.plot(sol.positions, me, lw=2, label=q)
    mean = sol.summary()[f"{q}_mean"]
    if abs(mean) < 1e-9 * (np.abs(me).max() or 1.0):
        mean = 0.0
    ax.axhline(mean, color="tab:orange", ls="--", label=f"mean {mean:.4g} {unit}")
    ax.axhline(0.0, color="0.5", lw=0.8)
    sing = sol.singular
    if sing.any():
        ax.fill_between(sol.positions, 0, 1, where=sing, transform=ax.get_xaxis_transform(),
                        color="tab:red", alpha=0.15, label="near a dead centre")
    ax.set_xlabel(_pos_label(sol))
    _cycle_axis(ax, sol)
    ax.set_ylabel("equilibrating moment Me [N m]" if q == "Me"
                  else "equilibrating force Fe [N]")
    ax.set_title(f"{q} over the cycle", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_polar(sol: Solution, joints: Sequence[str] | str | None = None,
               ax: Axes | None = None) -> Axes:
    """Polar diagram (hodograph) of joint reactions: the tip of the force vector over
    the cycle, drawn from the origin (seed 002: the polar diagram of F_ij).

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    joints : str or sequence of str, optional
        Joint names (default: every joint); the force is the one on the joint's ``on``
        body (the ``reactions`` table).
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        Fx [N] against Fy [N], equal aspect; a dot marks the first position.
    """
    ax = _ax(ax)
    if joints is None:
        joints = list(sol.scene.joints)
    elif isinstance(joints, str):
        joints = [joints]
    for j in joints:
        fx, fy = sol.reaction(j)
        r = sol.joint_reactions[j]
        ax.plot(fx, fy, lw=1.8, label=f"F[{j}] on {r.on}")
        ax.plot(fx[:1], fy[:1], "o", color=ax.lines[-1].get_color(), ms=5)
    ax.plot(0, 0, "k+", ms=10)
    ax.set_aspect("equal", adjustable="datalim")
    _vector_axes(ax)
    ax.set_xlabel("Fx [N]")
    ax.set_ylabel("Fy [N]")
    ax.set_title("polar diagram of joint reactions (dot: first position)", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def plot_transmission(sol: Solution, ax: Axes | None = None, admissible: float = 40.0) -> Axes:
    """Transmission angle of every dyad over the cycle (eqs 2.60-2.61) with the
    admissible band [admissible, 180 - admissible].

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    ax : Axes, optional
        Where to draw; a new figure when None.
    admissible : float
        The smallest admissible transmission angle (deg); outside the band is shaded.

    Returns
    -------
    Axes
    """
    ax = _ax(ax)
    t = sol.dyads
    for d, g in t.groupby("dyad"):
        ax.plot(g.position, g.transmission_angle, lw=2,
                label=f"dyad {d} {g.kind.iloc[0]} ({g.bodies.iloc[0]})")
    ax.axhspan(0, admissible, color="tab:red", alpha=0.1)
    ax.axhspan(180 - admissible, 180, color="tab:red", alpha=0.1, label="not admissible")
    ax.set_ylim(0, 180)
    ax.set_xlabel(_pos_label(sol))
    _cycle_axis(ax, sol)
    ax.set_ylabel("transmission angle τ [deg]")
    ax.set_title("transmission angle", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def _points_arg(sol: Solution, points) -> list[tuple[str, str]]:
    if points is None:
        return _trace_points(sol)
    if isinstance(points, str):
        points = [points]
    out = []
    for bp in points:
        if "." not in bp:
            raise WorkbenchError(f"point {bp!r}: write it as 'body.point', e.g. 'coupler.P'")
        b, p = bp.split(".", 1)
        if b not in sol.scene.bodies or (p != "cog" and p not in sol.scene.bodies[b].points):
            raise WorkbenchError(f"point {bp!r}: no such body point")
        out.append((b, p))
    return out


def plot_trajectories(sol: Solution, points: Sequence[str] | None = None,
                      ax: Axes | None = None) -> Axes:
    """Paths (traiectorii) of points over the sweep, dashed.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    points : sequence of str, optional
        ``"body.point"`` names (default: every named point and centre of mass).
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        x [m] against y [m], equal aspect.
    """
    ax = _ax(ax)
    k = sol.kinematics
    if points is None:
        points = [f"{b}.{p}" for b, p in k[["body", "point"]].drop_duplicates().values]
    for c, bp in enumerate(points):
        b, p = bp.split(".", 1)
        g = k[(k.body == b) & (k.point == p)]
        ax.plot(g.x, g.y, lw=1.4, ls="--", color=PATH_COLORS[c % len(PATH_COLORS)],
                label=f"path of {bp}")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("trajectories", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return ax


def _point_curves(sol: Solution, points, component: str, ax: Axes | None, kind: str) -> Axes:
    if component not in ("magnitude", "x", "y"):
        raise WorkbenchError(f"component must be 'magnitude', 'x' or 'y', not {component!r}")
    ax = _ax(ax)
    n = sol.positions.size
    for b, p in _points_arg(sol, points):
        m = sol.kin.bodies[b]
        x, y = m.point(sol.scene.bodies[b].local(p))
        vx, vy = (m.vel_at if kind == "v" else m.acc_at)(x, y)
        vx, vy = np.broadcast_to(vx, (n,)), np.broadcast_to(vy, (n,))
        val = {"magnitude": np.hypot(vx, vy), "x": vx, "y": vy}[component]
        ax.plot(sol.positions, val, lw=1.8, label=f"{b}.{p}")
    sym = "v" if kind == "v" else "a"
    unit = "m/s" if kind == "v" else "m/s²"
    comp = {"magnitude": f"|{sym}|", "x": f"{sym}x", "y": f"{sym}y"}[component]
    ax.set_xlabel(_pos_label(sol))
    _cycle_axis(ax, sol)
    ax.set_ylabel(f"{'speed' if kind == 'v' else 'acceleration'} {comp} [{unit}]")
    ax.set_title(f"{'velocities' if kind == 'v' else 'accelerations'} of points over the "
                 "cycle", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    return ax


def plot_speeds(sol: Solution, points: Sequence[str] | str | None = None, *,
                component: str = "magnitude", ax: Axes | None = None) -> Axes:
    """Velocity of points over the sweep.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    points : str or sequence of str, optional
        ``"body.point"`` names (default: every named point, once per name).
    component : str
        ``"magnitude"`` (the speed |v|), ``"x"`` or ``"y"`` (signed components).
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        Position against v [m/s].
    """
    return _point_curves(sol, points, component, ax, "v")


def plot_accelerations(sol: Solution, points: Sequence[str] | str | None = None, *,
                       component: str = "magnitude", ax: Axes | None = None) -> Axes:
    """Acceleration of points over the sweep.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    points : str or sequence of str, optional
        ``"body.point"`` names (default: every named point, once per name).
    component : str
        ``"magnitude"``, ``"x"`` or ``"y"``.
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        Position against a [m/s²].
    """
    return _point_curves(sol, points, component, ax, "a")


def plot_angular(sol: Solution, bodies: Sequence[str] | str | None = None) -> Figure:
    """Angle, angular velocity omega and angular acceleration eps of bodies over the
    sweep, three panels sharing the position axis.

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    bodies : str or sequence of str, optional
        Body names (default: every body that turns).

    Returns
    -------
    Figure
    """
    t = sol.bodies
    if bodies is None:
        bodies = [b for b, g in t.groupby("body", sort=False)
                  if np.ptp(g.angle.to_numpy()) > 1e-9 or np.abs(g.omega).max() > 0]
    elif isinstance(bodies, str):
        bodies = [bodies]
    fig, axs = plt.subplots(3, 1, figsize=(6.5, 7.0), sharex=True, layout="constrained")
    for b in bodies:
        g = t[t.body == b]
        if g.empty:
            raise WorkbenchError(f"plot_angular: no body {b!r}")
        axs[0].plot(g.position, g.angle, lw=1.8, label=b)
        axs[1].plot(g.position, g.omega, lw=1.8, label=b)
        axs[2].plot(g.position, g.alpha, lw=1.8, label=b)
    for a, lab in zip(axs, ("angle θ [deg]", "ω [rad/s]", "ε [rad/s²]"), strict=True):
        a.set_ylabel(lab)
        a.grid(True, alpha=0.3)
        a.axhline(0.0, color="0.5", lw=0.6)
    axs[0].legend(fontsize=8, ncol=3)
    axs[0].set_title("angular motion of the bodies", fontsize=10)
    axs[-1].set_xlabel(_pos_label(sol))
    _cycle_axis(axs[-1], sol)
    return fig


def overview(sol: Solution, position: float | None = None) -> Figure:
    """Four panels: the mechanism with its reactions, Me(φ), the polar diagram of the
    reactions, the transmission angle (the trajectories when there is no dyad).

    Parameters
    ----------
    sol : Solution
        A solved scene (:func:`kinetostatics.solve`).
    position : float, optional
        Driver position of the drawing (default: a twelfth into the sweep).

    Returns
    -------
    Figure
    """
    fig, axs = plt.subplots(2, 2, figsize=(12, 9), layout="constrained")
    if position is None:
        position = float(sol.positions[len(sol.positions) // 12])
    draw_mechanism(sol, position, ax=axs[0, 0], forces=True)
    plot_driver(sol, ax=axs[0, 1])
    plot_polar(sol, ax=axs[1, 0])
    if len(sol.kin.dyads):
        plot_transmission(sol, ax=axs[1, 1])
    else:
        plot_trajectories(sol, ax=axs[1, 1])
    return fig


def draw_gear_pair(pair, ax: Axes | None = None) -> Axes:
    """Draw a gear pair (seed 002 figs 2.22-2.23): the pitch circles (cercurile de
    rostogolire), the base circles, the line of action n-n through the pitch point P and
    the tooth forces F12 (on gear 2) and F21 = -F12 (on gear 1) along it.

    Parameters
    ----------
    pair : GearPair
        A solved pair (:func:`kinetostatics.gears.gear_pair`); with an array of ``M2``
        the first value is drawn.
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
        x [m] against y [m], equal aspect, the legend below the plot. The arrows have a
        fixed length (half the larger pitch radius); their labels give the force in N.
        The title gives i12 and the moments (ccw positive).

    Raises
    ------
    WorkbenchError
        ``pair`` is not a :class:`~kinetostatics.gears.GearPair`.
    """
    from ..topics.gears import GearPair

    if not isinstance(pair, GearPair):
        raise WorkbenchError("draw_gear_pair: give a GearPair (kinetostatics.gears.gear_pair)")
    ax = _ax(ax, figsize=(6, 6))
    o1, o2, p = (np.asarray(v, dtype=float) for v in (pair.O1, pair.O2, pair.P))
    r1, r2 = float(np.hypot(*(p - o1))), float(np.hypot(*(p - o2)))
    cos_a = np.cos(np.deg2rad(pair.alpha_deg))
    t = np.linspace(0.0, 2.0 * np.pi, 361)
    for o, r, c, k in ((o1, r1, "tab:blue", 1), (o2, r2, "tab:green", 2)):
        ring = " (ring)" if pair.internal and r > min(r1, r2) else ""
        ax.plot(o[0] + r * np.cos(t), o[1] + r * np.sin(t), color=c, lw=2,
                label=f"gear {k}{ring}: r_w{k} = {r:.4g} m")
        ax.plot(o[0] + r * cos_a * np.cos(t), o[1] + r * cos_a * np.sin(t), color=c, lw=1,
                ls="--")
        ax.plot(*o, "+", color=c, ms=12, mew=2)
        ax.annotate(f"O{k}", o, xytext=(5, -12), textcoords="offset points", fontsize=9,
                    color=c)
    span = max(r1, r2)
    centres = o2 - o1
    out = (p - (o1 if r1 >= r2 else o2)) / span          # from the larger gear's axis to P
    ax.plot(*p, "o", color="k", ms=5, zorder=7)
    ax.annotate("P", p, xytext=(10 * out[0], 10 * out[1]), textcoords="offset points",
                fontsize=10, ha="center", va="center", fontweight="bold")
    tangent = np.array([-centres[1], centres[0]]) / (np.hypot(*centres) or 1.0)
    ends = p + np.outer([-0.5 * span, 0.5 * span], tangent)
    handles = [Line2D([], [], color="0.4", lw=1, ls="--", label="base circles r_w cos α")]
    ax.plot(ends[:, 0], ends[:, 1], ":", color="0.4", lw=1.2, label="common tangent at P")
    f = np.array([np.ravel(pair.F12x)[0], np.ravel(pair.F12y)[0]], dtype=float)
    fmag = float(np.hypot(*f))
    if fmag > 0.0:
        u = f / fmag
        s = [float(np.dot(o - p, u)) for o in (o1, o2)]     # feet of the normals from O1, O2
        size = 0.5 * span
        side = np.array([-u[1], u[0]])                     # labels beside the arrows,
        side = side if np.dot(side, out) <= 0.0 else -side  # towards the larger gear
        lo, hi = min(*s, -size) - 0.1 * span, max(*s, size) + 0.1 * span
        line = p + np.outer([lo, hi], u)
        ax.plot(line[:, 0], line[:, 1], color="0.3", lw=0.8,
                label=f"line of action n-n, α = {pair.alpha_deg:g}° to the tangent")
        feet = p + np.outer(s, u)
        ax.plot(feet[:, 0], feet[:, 1], "o", color="0.3", ms=3)
        for sign, lab, col, text in ((1.0, "F12", REACTION_COLOR, "F12: gear 1 on gear 2"),
                                     (-1.0, "F21", "tab:orange", "F21 = -F12: 2 on 1")):
            tip = p + sign * size * u
            ax.annotate("", tip, p, arrowprops={"arrowstyle": "-|>", "color": col, "lw": 2,
                                                 "shrinkA": 0, "shrinkB": 0}, zorder=6)
            ax.annotate(f"{lab} = {fmag:.4g} N", p + 0.6 * sign * size * u,
                        xytext=(8 * side[0], 8 * side[1]), textcoords="offset points",
                        fontsize=9, color=col, ha="left" if side[0] >= 0 else "right",
                        va="bottom" if side[1] >= 0 else "top",
                        bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                              "alpha": 0.85})
            ax.update_datalim([tip])
            handles.append(Line2D([], [], color=col, lw=2, marker=">", markevery=[-1],
                                  label=text))
    me, m2 = float(np.ravel(pair.Me)[0]), float(np.ravel(pair.M2)[0])
    kind = "internal" if pair.internal else "external"
    ax.set_title(f"{kind} pair: i12 = {pair.i12:.4g}, M2 = {m2:.4g} N m, Me = {me:.4g} N m",
                 fontsize=10)
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.12)
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    h, _ = ax.get_legend_handles_labels()
    ax.legend(handles=h + handles, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12),
              ncol=2, borderaxespad=0.0)
    return ax
