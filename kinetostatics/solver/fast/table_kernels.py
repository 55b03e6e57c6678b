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

import math

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



# The C library's hypot as glibc (2.35 on) computes it without fused multiply-adds
# (sysdeps/ieee754/dbl-64/e_hypot.c: the inputs ordered and scaled, then one correction
# of sqrt(ax^2 + ay^2)), inlined where a loop calls it: the C library's own costs a call
# of some 16 ns a value (measured 2026-11-29, 1e6 values of the four-bar's size, 16 ms
# against 1 ms), the reactions table's F of four joints at 1e6 rows 63 ms of its pass.
# Used only where it gives numpy's ``hypot`` bit for bit on the probes of
# :func:`~kinetostatics.solver.fast.table_pass.own_hypot` (else the C library's).
HYPOT_SCALE = 2.0 ** -600
HYPOT_LARGE = 2.0 ** 511
HYPOT_TINY = 2.0 ** -511
HYPOT_EPS = 2.0 ** -54


@body
def _hypot_kernel(ax, ay):
    """hypot of ``ax >= ay >= 0`` whose squares neither overflow nor underflow."""
    h = math.sqrt(ax * ax + ay * ay)
    if h <= 2.0 * ay:
        delta = h - ay
        t1 = ax * (2.0 * delta - ax)
        t2 = (delta - 2.0 * (ax - ay)) * delta
    else:
        delta = h - ax
        t1 = 2.0 * delta * (ax - 2.0 * ay)
        t2 = (4.0 * delta - ay) * ay + delta * delta
    return h - (t1 + t2) / (2.0 * h)


@body
def hypot(x, y, own):
    """sqrt(x^2 + y^2): glibc's algorithm inlined (``own``), else the C library's."""
    if not own or not (math.isfinite(x) and math.isfinite(y)):
        return math.hypot(x, y)
    x, y = abs(x), abs(y)
    ax, ay = (y, x) if x < y else (x, y)
    if ax > HYPOT_LARGE:
        if ay <= ax * HYPOT_EPS:
            return ax + ay
        return _hypot_kernel(ax * HYPOT_SCALE, ay * HYPOT_SCALE) / HYPOT_SCALE
    if ay < HYPOT_TINY:
        if ax >= ay / HYPOT_EPS:
            return ax + ay
        return _hypot_kernel(ax / HYPOT_SCALE, ay / HYPOT_SCALE) * HYPOT_SCALE
    if ay <= ax * HYPOT_EPS:
        return ax + ay
    return _hypot_kernel(ax, ay)


@jit
def hypot_rows(x, y, out, own):
    """``out[i] = hypot(x[i], y[i])`` (:func:`hypot_into`)."""
    hypot_into(x, y, out, x.shape[0], own)


@body
def _hypot_usual(x, y):
    """:func:`hypot` of finite ``x, y`` neither huge nor tiny nor far apart (its usual
    road), without a branch: both of the kernel's corrections worked out, one taken."""
    x, y = abs(x), abs(y)
    ax = y if x < y else x
    ay = x if x < y else y
    h = math.sqrt(ax * ax + ay * ay)
    d1, d2 = h - ay, h - ax
    t1a, t2a = ax * (2.0 * d1 - ax), (d1 - 2.0 * (ax - ay)) * d1
    t1b, t2b = 2.0 * d2 * (ax - 2.0 * ay), (4.0 * d2 - ay) * ay + d2 * d2
    near = h <= 2.0 * ay
    t1 = t1a if near else t1b
    t2 = t2a if near else t2b
    return h - (t1 + t2) / (2.0 * h)


@body
def hypot_into(x, y, out, m, own):
    """``out[t] = hypot(x[t], y[t])`` for the first ``m`` values (:func:`hypot`): the
    usual road over all of them in one loop (it vectorises), then the rows off it
    again by the whole function."""
    if not own:
        for t in range(m):
            out[t] = math.hypot(x[t], y[t])
        return
    off = 0
    for t in range(m):
        off += 0 if _usual(x[t], y[t]) else 1
        out[t] = _hypot_usual(x[t], y[t])
    if off:
        for t in range(m):
            if not _usual(x[t], y[t]):
                out[t] = hypot(x[t], y[t], True)


@body
def _usual(x, y):
    """Whether ``x, y`` take :func:`hypot`'s usual road (finite, neither huge nor tiny
    nor far apart; NaN and infinities do not)."""
    ax, ay = abs(x), abs(y)
    big = ay if ax < ay else ax
    small = ax if ax < ay else ay
    return big <= HYPOT_LARGE and small >= HYPOT_TINY and small > big * HYPOT_EPS
