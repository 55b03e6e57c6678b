"""The assembly a dyad takes, chosen at the scene's first row from the ``[near]`` hints.

A dyad with two assemblies (the seed's indicator k = +-1, seed 000 eqs 6.1, 8.1) takes the
one whose hinted points lie closest at the first row (scene-format section 1); where no
hint tells them apart the scene is refused, naming the point and the hint to add. The
refusals of a first row that cannot close are said here too.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..model.errors import AssemblyError
from ..model.scene import Scene
from . import arith as A
from .closure import DyadSolver, Param, body_origin, take_rows

if TYPE_CHECKING:
    from .structure import Dyad

SINGULAR_FAIL = 1e-12   # below this the velocity system cannot be solved: refused


def fmt_positions(scene: Scene, rows: np.ndarray, values: np.ndarray | None = None,
                   unit: str = "length") -> str:
    # said in the scene's own units (a mm scene's gap in mm): the user reads what they typed
    pos, units = scene.driver.positions, scene.units
    quantity = "angle" if scene.driver.kind == "R" else "length"
    items = []
    for i, r in enumerate(rows[:6]):
        s = units.quote(float(pos[r]), quantity, file=True)
        if values is not None:
            s += f" (by {units.quote(float(values[i]), unit, '.3g')})"
        items.append(s)
    more = f" and {rows.size - 6} more" if rows.size > 6 else ""
    return ", ".join(items) + more


def hint_points(scene: Scene, dyad: Dyad):
    """Hints that concern the dyad: (hint name, body, local point, target)."""
    out = []
    for key, target in scene.near.items():
        if "." in key:
            b, p = key.split(".", 1)
            if b in dyad.bodies:
                out.append((key, b, scene.bodies[b].local(p), target))
        else:
            j = scene.joints[key]
            for b in dyad.bodies:
                if b in j.bodies:
                    out.append((key, b, scene.bodies[b].local(j.point_on(b)), target))
                    break
    return out


def refuse_coincident_pivots(scene: Scene, dyad: Dyad, reach: np.ndarray) -> None:
    """Refuse rows where the dyad's outer pivots coincide (its closure divides by their
    distance: closer than 1e-12 of the mechanism's size)."""
    if not reach.size or reach.min() > SINGULAR_FAIL:   # (usual: one pass; NaN is not above)
        return
    tiny = np.flatnonzero(~(reach > SINGULAR_FAIL))
    if tiny.size:
        o1, o2 = dyad.outer
        raise AssemblyError(
            f"dyad {dyad.label}: the pivots of its joints {o1.name!r} and {o2.name!r} "
            f"coincide at driver position(s) {fmt_positions(scene, tiny)} (closer than "
            f"1e-12 of the mechanism's size {scene.units.quote(scene.size, 'length', '.4g')}); "
            "the dyad's angles are undefined there: leave those positions out of the sweep")


def first_row_assembly(scene: Scene, dyad: Dyad, solver: DyadSolver, pr, two: dict,
                       margin: float = 1e-12) -> int | None:
    """:func:`choose_branch` from ``two`` (per k, the first row's (cos, sin) and
    displacement of each body, :meth:`DyadSolver.positions`); None where the pivots
    coincide there (refused by :func:`choose_branch`). ``margin``: as for
    :func:`decide_assembly`."""
    if solver.reach is not None and not _at(solver.reach, 0) / scene.size > SINGULAR_FAIL:
        return None
    # (the parameters' first row, as the closure's numbers are: the fields an origin reads)
    pr = [Param(p.kind, p.known, p.local, _first(p.px), _first(p.py), ux=_first(p.ux),
                uy=_first(p.uy), bx=_first(p.bx), by=_first(p.by)) for p in pr]
    return decide_assembly(scene, dyad, {k: [[*cs[i], *body_origin(pr[i], cs[i], ss[i])]
                                             for i in range(2)] for k, (cs, ss) in two.items()},
                           margin)


def choose_branch(scene: Scene, dyad: Dyad, solver: DyadSolver, pr,
                  margin: float = 1e-12) -> int:
    """The assembly k = +-1 whose hinted points lie closest at the first row (both
    assemblies closed at once: the first row twice, with k = 1 and k = -1); ``margin``:
    as for :func:`decide_assembly`."""
    two = np.zeros(2, dtype=np.intp)
    pr = (take_rows(pr[0], two), take_rows(pr[1], two))
    cs, ss, gap = solver.positions(pr, np.array([1.0, -1.0]))
    if solver.reach is not None and not _at(solver.reach / scene.size, 0) > SINGULAR_FAIL:
        refuse_coincident_pivots(scene, dyad, A.full(solver.reach / scene.size, 2)[:1])
    if gap is not None and float(np.ravel(gap)[0]) > 1e-9 * scene.size:
        raise AssemblyError(
            f"dyad {dyad.label} cannot be assembled at the first driver position "
            f"{fmt_positions(scene, np.array([0]))}: the links do not reach by "
            f"{scene.units.quote(float(np.ravel(gap)[0]), 'length', '.4g')}; change the "
            "lengths, the ground points or the sweep's start")
    org = [body_origin(pr[i], cs[i], ss[i]) for i in range(2)]
    # each body's cos, sin and origin in either assembly, as floats (read once)
    return decide_assembly(scene, dyad, {
        k: [[_at(v, r) for v in (*cs[i], *org[i])] for i in range(2)]
        for k, r in ((1, 0), (-1, 1))}, margin)


def decide_assembly(scene: Scene, dyad: Dyad, frames: dict, margin: float = 1e-12) -> int:
    """The assembly whose hinted points lie closest, from ``frames[k]``: each body's cos,
    sin and origin at the first row (floats) in assembly k; refused when no hint
    settles it: the two sums of squared distances differ by ``margin`` of the
    mechanism's size squared or less."""

    def where(k, b, loc):
        c, s, ox, oy = frames[k][dyad.bodies.index(b)]
        return ox + c * loc[0] - s * loc[1], oy + s * loc[0] + c * loc[1]

    def off2(p, t):
        return (p[0] - t[0]) ** 2 + (p[1] - t[1]) ** 2
    hints = hint_points(scene, dyad)
    if hints:
        dist = {k: sum(off2(where(k, b, loc), t) for _, b, loc, t in hints) for k in (1, -1)}
        if abs(dist[1] - dist[-1]) > margin * scene.size ** 2:
            return 1 if dist[1] < dist[-1] else -1
    # no hint settles it: name the point that tells the two assemblies apart best
    best = None
    for b in dyad.bodies:
        for pname, loc in scene.bodies[b].points.items():
            p1, p2 = where(1, b, loc), where(-1, b, loc)
            sep = math.hypot(p1[0] - p2[0], p1[1] - p2[1])
            if best is None or sep > best[0] * (1.0 + 1e-9):
                best = (sep, b, pname, p1, p2)
    sep, b, pname, p1, p2 = best
    inner = dyad.inner
    key = f'"{b}.{pname}"'
    if inner.kind == "R" and pname == inner.point_on(b):
        key = inner.name
    hinted = (f" (the hints {', '.join(h[0] for h in hints)} do not tell them apart)"
              if hints else "")
    raise AssemblyError(
        f"dyad {dyad.label} has two assemblies at the first driver position{hinted}: point "
        f"{b}.{pname} at ({p1[0]:.4g}, {p1[1]:.4g}) or ({p2[0]:.4g}, {p2[1]:.4g}); add a hint "
        f"for the one you mean, e.g. [near] {key} = [{p1[0]:.4g}, {p1[1]:.4g}]")


def _at(v, row: int) -> float:
    """A value at one row, as a Python float (the same double the array holds)."""
    return float(v[row]) if isinstance(v, np.ndarray) and v.ndim else float(v)


def _first(v):
    """The first row of a per-row array; a number as it is."""
    return float(v[0]) if type(v) is np.ndarray and v.ndim else v
