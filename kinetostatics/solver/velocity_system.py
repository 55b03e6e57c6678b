"""The algebra of a dyad's velocity system (seed 000, ch. 5-12: ``G qdot = r``), shared
by the kinematics (:mod:`~kinetostatics.solver.kinematics`) and the dead-point probes,
which read only its positions: the columns c1, c2 (the velocity of the closing point X
per unit of each body's unknown), the matrix and Cramer's rule, the closing point and
the guide's line, and the closeness to a dead centre (min(sin^2 tau, (pivot distance /
size)^2)).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from . import arith as A

if TYPE_CHECKING:
    from .closure import DyadSolver, Param
    from .structure import Dyad


def velocity_column(pr: Param, xx, xy) -> tuple:
    """Velocity of the body's point at X per unit of its unknown (the column c_i)."""
    if pr.kind == "rot":
        return A.sub(pr.py, xy), A.sub(xx, pr.px)
    return pr.ux, pr.uy


def velocity_columns(pr: Param, xx, xy):
    """The column c_i (:func:`velocity_column`), the known part k_i of that velocity, and the
    weight of the unknown in the body's angular velocity (1 for rot, 0 for trans)."""
    if pr.kind == "rot":
        return velocity_column(pr, xx, xy), (pr.vpx, pr.vpy), 1.0
    return velocity_column(pr, xx, xy), pr.known.vel_at(xx, xy), 0.0


def velocity_matrix(revolute: bool, c1, c2, w1, w2, nx, ny):
    """The velocity system's matrix [[a11, -b12], [a21, -b22]] as (a11, b12, a21, b22)
    (:func:`cramer2`) and its determinant, from the columns (and, for a prismatic inner
    joint, the line's normal n and the angular weights w)."""
    if revolute:
        a11, b12, a21, b22 = c1[0], c2[0], c1[1], c2[1]
    else:
        a11, b12 = w1, w2
        a21 = A.mul_add(nx, c1[0], ny, c1[1])
        b22 = A.mul_add(nx, c2[0], ny, c2[1])
    # a11 a22 - a12 a21 with a12 = -b12, a22 = -b22 (the same numbers, exactly)
    return (a11, b12, a21, b22), A.mul_sub(b12, a21, a11, b22)


def cramer2(a11, b12, a21, b22, r1, r2, det):
    """Cramer's rule for [[a11, -b12], [a21, -b22]] x = [r1, r2].

    The second column is given negated (the velocity system's is -c2): the negations
    are never formed, and the numbers are exactly those of the plain rule, since
    r1 (-b22) - (-b12) r2 = b12 r2 - r1 b22 in floating point too."""
    return (A.mul_sub(b12, r2, r1, b22, den=det),
            A.mul_sub(a11, r2, r1, a21, den=det))


def guide_body(solver: DyadSolver) -> int:
    """The body (0 or 1) that carries a prismatic inner joint's guide (the other one
    carries the slider, whose point is the closing point X)."""
    return 1 if solver.dyad.inner.kind == "R" or solver.slider_first else 0


def closing_point(dyad: Dyad, solver: DyadSolver, cs, org, arm: list | None = None):
    """The closing point X (the inner joint's point; for a prismatic inner joint the
    slider point) from the first body (the slider) in its solved position. ``arm``: the
    body (0 or 1), the point's local coordinates (the Body's tuple) and its arm from the
    body's origin are put there (the reactions ask for that arm again:
    :meth:`~kinetostatics.solver.driver.BodyMotion.keep_arm`)."""
    ib = 1 - guide_body(solver)
    inner = dyad.inner
    loc = solver.q[0] if inner.kind == "R" else solver.b[ib].local(inner.points[1])
    rx, ry = A.rotate(cs[ib][0], cs[ib][1], *loc)
    if arm is not None:
        arm += (ib, loc, (rx, ry))
    return A.add(org[ib][0], rx), A.add(org[ib][1], ry)


def guide_line(solver: DyadSolver, cs):
    """The unit direction u of a prismatic inner joint's line, turned with its guide."""
    ig = guide_body(solver)
    return A.rotate(cs[ig][0], cs[ig][1], np.cos(solver.beta), np.sin(solver.beta))


def column_norm2(solver: DyadSolver, pr) -> float:
    """|c1|^2 |c2|^2 of a revolute inner joint's velocity columns, a constant: a body
    turning about its outer pivot P has c = J (X - P), and X, P are two points of that
    body, so |c|^2 is their distance squared; a translating body has c = u, a unit vector.
    (Valid where the dyad closes: X lies on both bodies.)"""
    out = 1.0
    for i, p in enumerate(pr):
        if p.kind == "rot":
            qx, qy = solver.q[i]
            lx, ly = p.local
            dx, dy = A.less(qx, lx), A.less(qy, ly)
            # (an array's ** 2 is its x * x, a Python float's pow; a square is never
            # -0.0, so a stack's exact zeros cost no pass: the same bits)
            sx, sy = (d * d if type(d) is np.ndarray else d ** 2 for d in (dx, dy))
            if type(sy) is float and sy == 0.0 and type(sx) is np.ndarray:
                d2 = sx
            elif type(sx) is float and sx == 0.0 and type(sy) is np.ndarray:
                d2 = sy
            else:
                d2 = sx + sy
            out = d2 if type(out) is float and out == 1.0 else out * d2
    return out


def dead_centre_closeness2(vs, pr, reach, n: int, solver: DyadSolver | None = None):
    """Step 3, the closeness to a dead centre: min(sin^2 tau, (pivot distance / size)^2),
    with |det| <= 1e-12 |c1| |c2| exactly singular (for a prismatic inner joint the same
    test on the transmission measure of inner_t_tau). With ``solver`` (a sweep where the
    dyad closes at every row) |c1| |c2| is the rigid bodies' constant; without it (probes
    where the dyad may not close) it is measured row by row. ``vs``: a dyad's velocity
    system, or a probe's closing from the positions alone (what is read: ``revolute``,
    ``c1``, ``c2``, ``det``, ``ux``, ``uy``)."""
    if vs.revolute:
        c1, c2 = vs.c1, vs.c2
        if solver is not None:
            norm2 = column_norm2(solver, pr)
        else:
            norm2 = (c1[0] * c1[0] + c1[1] * c1[1]) * (c2[0] * c2[0] + c2[1] * c2[1])
        sin2 = A.full(vs.det * vs.det / norm2, n)
    else:
        piv = getattr(solver, "pivots", None)
        if piv is not None:
            # RTR (seed 000 ch. 6-7): u . D / |D| of inner_t_tau with the closing's own D
            # and |D| (DyadSolver.pivots): D = P_s - P_g there, P_1 - P_2 in inner_t_tau,
            # so this sin is the same number or exactly its negative (a - b = -(b - a),
            # products and quotients keep the sign), and only its square is read. Five
            # passes fewer a block (two differences, two squares, a root; measured
            # 2026-12-01, the bundled shaper)
            dx, dy, dn = piv
            sin_t = A.mul_add(vs.ux, dx, vs.uy, dy, den=dn)
        else:
            sin_t = inner_t_tau(pr, vs.ux, vs.uy, cos=False)[0]
        sin2 = A.full(sin_t, n) ** 2
    if reach is not None:
        sin2 = np.minimum(sin2, reach * reach)
    return sin2


def inner_t_tau(pr, ux, uy, cos: bool = True):
    """sin and cos of the transmission angle of a dyad with a prismatic inner joint:
    between the line and P_s - P_g (RTR: the velocity system's columns are J(P2 - P1)
    and u, so sin = u . D / |D|) or between the line and the other guide (RTT).
    ``cos`` False: the sin alone, and None (the closeness to a dead centre reads no
    more: four passes fewer of an RTR dyad, measured 2026-11-30)."""
    p1, p2 = pr
    if p1.kind == "rot" and p2.kind == "rot":
        dx, dy = A.sub(p1.px, p2.px), A.sub(p1.py, p2.py)
        dn = np.sqrt(dx * dx + dy * dy)
        return (A.mul_add(ux, dx, uy, dy, den=dn),
                A.mul_sub(ux, dy, uy, dx, den=dn) if cos else None)
    pt = p2 if p1.kind == "rot" else p1
    return (A.mul_sub(ux, pt.uy, uy, pt.ux),
            A.mul_add(ux, pt.ux, uy, pt.uy) if cos else None)
