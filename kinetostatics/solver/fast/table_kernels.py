"""Compiled kernels that write rows of a result table straight into its columns (the
``kinematics`` table of a sweep solved again on the compiled path,
:mod:`kinetostatics.results.fastpass`).

A point's row is worked out by the numpy path's own operations, in its order
(:meth:`BodyMotion.point <kinetostatics.solver.driver.BodyMotion.point>`,
:meth:`~kinetostatics.solver.driver.BodyMotion.vel_arm`,
:meth:`~kinetostatics.solver.driver.BodyMotion.acc_arm` with the rules of
:mod:`kinetostatics.solver.arith` that skip an exact zero of the local point): the same
numbers, bit for bit (no ``fastmath``: nothing contracted or reordered). Imported only
by :mod:`~kinetostatics.solver.fast.kernels`, after the cache folder is settled.
"""

from __future__ import annotations

from .jitbase import body, jit
from .layout import AL, AX, AY, OM, OX, OY, VX, VY, C, S


@jit
def point_rows(m, rows, lx, ly, out, at):
    """``x, y, vx, vy, ax, ay`` of the body point at the local ``(lx, ly)`` over the
    first ``rows`` columns of the body's motion ``m`` (:mod:`~kinetostatics.solver.fast.layout`)
    into columns ``at`` to ``at + rows`` of the six rows of ``out`` (:func:`point_row`)."""
    origin = lx == 0.0 and ly == 0.0
    for t in range(rows):
        point_row(m, t, lx, ly, origin, out, at + t)


@body
def point_row(m, t, lx, ly, origin, out, j):
    """Column ``j`` of the six rows of ``out``: ``x, y, vx, vy, ax, ay`` of the body point
    at the local ``(lx, ly)`` from column ``t`` of the body's motion ``m`` (``origin``:
    ``l`` = 0).

    The arm r = R(theta) l (arith's ``rotate``: ``(c lx, s lx)`` when ``ly`` is 0,
    ``(-ly s, c ly)`` when ``lx`` is 0), then x = o + r, v = v_O + omega k x r,
    a = a_O + eps k x r - omega^2 r (seed 001 eq. 9); the body's origin itself (``l`` =
    0) is its motion as it is (arith adds no zero)."""
    if origin:
        out[0, j], out[1, j] = m[OX, t], m[OY, t]
        out[2, j], out[3, j] = m[VX, t], m[VY, t]
        out[4, j], out[5, j] = m[AX, t], m[AY, t]
        return
    c, s = m[C, t], m[S, t]
    if ly == 0.0:
        rx, ry = c * lx, s * lx
    elif lx == 0.0:
        rx, ry = -ly * s, c * ly
    else:
        rx, ry = c * lx - s * ly, s * lx + c * ly
    om, al = m[OM, t], m[AL, t]
    w2 = om * om
    out[0, j] = m[OX, t] + rx
    out[1, j] = m[OY, t] + ry
    out[2, j] = m[VX, t] - om * ry
    out[3, j] = m[VY, t] + om * rx
    out[4, j] = (m[AX, t] - al * ry) - w2 * rx
    out[5, j] = (m[AY, t] + al * rx) - w2 * ry

