"""The dead-point screen's probes of a driver and a chain of dyads in one compiled call:
each probe's closeness to a dead centre (m^2) from the positions alone and whether
some dyad cannot close there, every round of the screen's zoom
(``deadpoints._probe``) in one call. The numpy probe's operations
(:func:`~kinetostatics.solver.probes.probe_closeness`) on the compiled path's closures
(:mod:`~kinetostatics.solver.fast.closure_kernels`, called, not copied): a revolute
inner joint's and a sliding one's the numpy closure's numbers; the RTR guide's angle
is the compiled path's (its cos and sin from the pivots' direction, not atan2, asin,
cos and sin), within a few ulps of numpy's.

A probe's bodies' positions sit in one ``(10, 2 + 2 d)`` motion array (the rows of
:mod:`~kinetostatics.solver.fast.layout`, the speeds left at 0), a column per body:
0 the ground, 1 the driver, ``2 + 2 i`` and ``3 + 2 i`` dyad i's bodies; each dyad's
outer joints' known bodies are columns of it (``known``). Imported only once the
kernels are loaded (:func:`~kinetostatics.solver.fast.loader.kernels`).
"""

from __future__ import annotations

import math

import numpy as np

from .closure_kernels import close_prismatic, close_revolute, rtr_guide_angle
from .jitbase import body, jit, jit_as
from .kernels import crank_row, outer_param
from .layout import (
    ASSEMBLY,
    I_CB,
    I_SB,
    I_SFIRST,
    INNER_R,
    KINDS,
    MOTION,
    OX,
    OY,
    P_BX,
    P_BY,
    PARAM,
    Q1X,
    Q1Y,
    ROT1,
    ROT2,
    SIZE,
    T_C,
    T_LX,
    T_LY,
    T_RX,
    T_RY,
    T_S,
    T_SIGN,
    T_UX,
    T_UY,
    C,
    S,
)


@body
def narrow(n, p, t, m2, gone, lo, hi, best, opened):
    """One round of the screen's zoom over ``n`` intervals of ``p`` probes each (m^2 of
    probe j of interval i at ``m2[i p + j]``, ``gone`` where some dyad cannot close
    there): a probe that is NaN or gone counts +inf and marks its interval ``opened``;
    the interval's smallest value joins ``best`` and the interval shrinks to the two
    steps about its first smallest probe (``lo``, ``hi`` written over: numpy's argmin,
    ``lo + (hi - lo) t``)."""
    inf = np.inf
    for i in range(n):
        a, d = lo[i], hi[i] - lo[i]
        low, at = inf, 0
        for j in range(p):
            v = m2[i * p + j]
            if np.isnan(v) or gone[i * p + j]:
                opened[i] = True
                v = inf
            if v < low:
                low, at = v, j
        best[i] = best[i] if best[i] <= low else low
        lo[i], hi[i] = a + d * t[at], a + d * t[at + 2]


@body
def start_rounds(best, opened):
    """The rounds' results before the first: +inf, none opened."""
    for i in range(best.size):
        best[i] = np.inf
        opened[i] = False


@body
def slide_at(x, gd, r, w):
    """A sliding driver at position ``x`` into column 1 of ``w``: its angle's cos and
    sin, and its origin o = L + sign x u - R a (seed 000 ch. 4; the numpy path's
    ``_sliding``, its positions alone)."""
    sign = gd[T_SIGN, r]
    w[C, 1], w[S, 1] = gd[T_C, r], gd[T_S, r]
    w[OX, 1] = sign * gd[T_UX, r] * x + (gd[T_LX, r] - gd[T_RX, r])
    w[OY, 1] = sign * gd[T_UY, r] * x + (gd[T_LY, r] - gd[T_RY, r])


@body
def origin_of(rot, p, c, s, lx, ly, q):
    """A dyad body's origin (``closure.body_origin``): P - R l (turning about its outer
    pivot P) or b + q u (sliding along its outer guide)."""
    if rot:
        return p[0] - (c * lx - s * ly), p[1] - (s * lx + c * ly)
    return p[4] + q * p[2], p[5] + q * p[3]


@body
def column_of(rot, p, xx, xy):
    """The velocity system's column c_i at the closing point X: J (X - P) for a body
    turning about P, the guide's direction u for a sliding one
    (``velocity_system.velocity_column``)."""
    if rot:
        return p[1] - xy, xx - p[0]
    return p[2], p[3]


@body
def sin2_of(inner_r, rot1, rot2, p1, p2, c1, s1, c2, s2, o1x, o1y, g, r):
    """sin^2 of a dyad's transmission angle from its positions, as a probe measures it
    (``velocity_system.dead_centre_closeness2`` with the columns measured row by row):
    a revolute inner joint's det^2 / (|c1|^2 |c2|^2) at its closing point X on the
    first body (seed 002 eqs 2.60-2.61); a prismatic one's between the line and the
    pivots' direction (RTR) or the other guide (RTT, TTR), ``inner_t_tau``."""
    both = rot1 and rot2
    if inner_r:
        qx, qy = g[Q1X, r], g[Q1Y, r]
        xx, xy = o1x + (c1 * qx - s1 * qy), o1y + (s1 * qx + c1 * qy)
        c1x, c1y = column_of(rot1, p1, xx, xy)
        c2x, c2y = column_of(rot2, p2, xx, xy)
        det = c2x * c1y - c1x * c2y
        return det * det / ((c1x * c1x + c1y * c1y) * (c2x * c2x + c2y * c2y))
    # the guide's line u, turned with the guide's body (the slider's other one)
    sfirst = g[I_SFIRST, r] != 0.0
    cg, sg = (c2, s2) if sfirst else (c1, s1)
    cb, sb = g[I_CB, r], g[I_SB, r]
    ux, uy = cg * cb - sg * sb, sg * cb + cg * sb
    if both:            # sin tau = u . D / |D|, D = P1 - P2
        dx, dy = p1[0] - p2[0], p1[1] - p2[1]
        st = (ux * dx + uy * dy) / math.sqrt(dx * dx + dy * dy)
    else:               # u x u_t, the other (sliding) body's guide u_t
        pt = p2 if rot1 else p1
        st = ux * pt[3] - uy * pt[2]
    return st * st


@body
def dyad_at(kind, g, r, w, a, b, out):
    """One dyad of a probe, kind code ``kind`` (:data:`~.layout.KINDS`; its geometry
    column ``r`` of ``g``, its assembly there): its outer joints' known bodies are
    columns ``a``, ``b`` of the motion array ``w``, its bodies' positions go to columns
    ``out``, ``out + 1``. Closed by the compiled path's closures (a revolute inner
    joint: circle-circle, circle-line or line-line; a prismatic one: the RTR guide's
    angle first); returns its m^2 = min(sin^2 tau, (pivots' distance / size)^2) (the
    distance for RRR and RTR alone; numpy's minimum: a NaN kept) and the closure's gap
    (> 0: the links do not reach; -1 where it closes)."""
    rot1, rot2, inner_r = (kind & ROT1) != 0, (kind & ROT2) != 0, (kind & INNER_R) != 0
    both = rot1 and rot2
    k = g[ASSEMBLY, r]
    p1 = outer_param(rot1, w, a, g, r, 0)
    p2 = outer_param(rot2, w, b, g, r, PARAM)
    reach, gap, th = -1.0, -1.0, (1.0, 0.0)
    if inner_r:
        c1, s1, c2, s2, q1, q2, reach, gap = close_revolute(kind, p1, p2, g, r, k)
    else:
        if both:        # RTR: the guide's angle (seed 000 ch. 6-7)
            cg, sg, reach, gap = rtr_guide_angle(p1, p2, g, r, k)
            th = (cg, sg)
        c1, s1, c2, s2, q1, q2 = close_prismatic(kind, p1, p2, g, r, k, th)
    o1x, o1y = origin_of(rot1, p1, c1, s1, g[P_BX, r], g[P_BY, r], q1)
    o2x, o2y = origin_of(rot2, p2, c2, s2, g[PARAM + P_BX, r], g[PARAM + P_BY, r], q2)
    w[C, out], w[S, out], w[OX, out], w[OY, out] = c1, s1, o1x, o1y
    w[C, out + 1], w[S, out + 1], w[OX, out + 1], w[OY, out + 1] = c2, s2, o2x, o2y
    sin2 = sin2_of(inner_r, rot1, rot2, p1, p2, c1, s1, c2, s2, o1x, o1y, g, r)
    if both:
        rr = reach / g[SIZE, r]
        rr = rr * rr
        sin2 = sin2 if (sin2 <= rr or np.isnan(sin2)) else rr
    return sin2, gap


@body
def probe_at(c, s, x, e, crank, gd, gds, kinds, known, gy, gs, w):
    """One probe of scene ``e`` (its geometry columns ``e gds`` of the driver's ``gd``,
    ``e gs`` of each dyad's ``gy[i]``): the driver at position ``x`` (a crank: its cos
    ``c`` and sin ``s``, :func:`~.kernels.crank_row`; else sliding, :func:`slide_at`),
    then each dyad in turn (:func:`dyad_at`, kind ``kinds[i]``, known bodies
    ``known[i]``). Returns the smallest m^2 over the dyads (numpy's minimum: a NaN
    kept, ``deadpoints.measure2``) and whether some dyad cannot close (its gap not
    within 1e-9 of the mechanism's size)."""
    rd, r = e * gds, e * gs
    if crank:
        w[C, 1], w[S, 1] = c, s
        crank_row(1, rd, gd, 0.0, 0.0, w)
    else:
        slide_at(x, gd, rd, w)
    m2, gone = np.inf, False
    for i in range(len(kinds)):
        g = gy[i]
        v, gap = dyad_at(kinds[i], g, r, w, known[i, 0], known[i, 1], 2 + 2 * i)
        m2 = v if (np.isnan(v) or v < m2) else m2
        gone = gone or not gap <= 1e-9 * g[SIZE, r]
    return m2, gone


@body
def motions_for(kinds):
    """A probe's motion array (:func:`probe_at`): the ground's column at rest, cos 1."""
    w = np.zeros((MOTION, 2 + 2 * len(kinds)))
    w[C, 0] = 1.0
    return w


@jit
def probe_chain(c, s, x, own, kinds, crank, gd, gds, known, gy, gs, m2, gone):
    """:func:`probe_at` at each row i (scene ``own[i]``, driver position ``x[i]``; a
    crank's cos ``c[i]`` and sin ``s[i]``, numpy's), the dyads' kind codes ``kinds`` an
    array (one kernel for every chain: a round at a time, where the C library's cos and
    sin are not numpy's): m^2 to ``m2``, whether some dyad cannot close to ``gone``."""
    w = motions_for(kinds)
    for i in range(x.size):
        m2[i], gone[i] = probe_at(c[i], s[i], x[i], own[i], crank, gd, gds, kinds, known, gy,
                                  gs, w)


@jit
def clear_rows(bound, stride, lo, hi, owner, m_lo, m_hi, deg, clear, out):
    """:func:`~kinetostatics.solver.fast.screen_bound.cleared` in one compiled pass (the
    same comparisons on the same doubles: interval i clear where the lower bound of m^2
    over it, from its rows' ``m_lo[i]``, ``m_hi[i]`` (-inf: no row) and L
    ``bound[owner[i] stride]``, is above ``clear``; a NaN or +inf row or bound: not).
    Measured 2026-11-30, a shaper's sweep's 2 intervals: the numpy form 34-58 us a call,
    about what probing them costs, at a load of 10."""
    for i in range(lo.size):
        a, b = m_lo[i], m_hi[i]
        fa, fb = np.isfinite(a), np.isfinite(b)
        if not (fa or a == -np.inf) or not (fb or b == -np.inf):
            out[i] = False
            continue
        slope = bound[owner[i] * stride] * ((hi[i] - lo[i]) * deg)
        least = 0.5 * (a + b - slope) if fa and fb else max(a, b) - slope
        out[i] = least > clear


def chain_rounds_for(kinds: tuple[str, ...]):
    """The compiled entry of the screen's rounds (:func:`rounds_of` gives it) for a chain
    of dyads of kinds ``kinds`` (their codes constants of the kernel, named by them: LLVM
    folds each dyad's other kinds' branches away; measured 2026-11-30, 1000 shapers'
    2626 intervals, 244 218 probes: 91 ns a probe against 166 with the codes an array,
    the same numbers)."""
    codes = tuple(KINDS[k] for k in kinds)

    @jit_as("chain_rounds_" + "_".join(k.lower() for k in kinds))
    def chain_rounds(lo, hi, owner, t, deg, crank, gd, gds, known, gy, gs, rounds, best,
                     opened, m2, gone):
        """The dead-point screen's probes of a driver and a chain of dyads, every round
        in one call (``deadpoints._probe``'s zoom, as numpy works it out): each interval
        ``(lo[i], hi[i])`` of scene ``owner[i]`` probed at its interior points
        ``lo + (hi - lo) t[1:-1]`` (:func:`probe_at`, the dyads' kinds the factory's; a
        crank's angles ``x deg``, their cos and sin the C library's, which
        :func:`~kinetostatics.solver.fast.solve.kernel_trig` finds numpy's), then
        :func:`narrow`, ``rounds`` times. The smallest m^2 found per interval goes to
        ``best``, whether some probe could not close to ``opened``; ``lo`` and ``hi``
        are written over; ``m2`` and ``gone``: scratch of ``lo.size * (t.size - 2)``
        values."""
        n, p = lo.size, t.size - 2
        w = motions_for(codes)
        start_rounds(best, opened)
        for _ in range(rounds):
            for i in range(n):
                a, d, e = lo[i], hi[i] - lo[i], owner[i]
                for j in range(p):
                    x = a + d * t[j + 1]
                    c, s = (math.cos(x * deg), math.sin(x * deg)) if crank else (1.0, 0.0)
                    m2[i * p + j], gone[i * p + j] = probe_at(c, s, x, e, crank, gd, gds, codes,
                                                              known, gy, gs, w)
            narrow(n, p, t, m2, gone, lo, hi, best, opened)
    return chain_rounds


# the rounds' kernels made so far, by the chain's dyads' kinds (each compiled on its first
# call, cached on disk apart: the shaper's ("RTR", "RRT"), the slotted lever's ("RTR",)...)
CHAIN_ROUNDS: dict[tuple[str, ...], object] = {}


def rounds_of(kinds: tuple[str, ...]):
    """The rounds' kernel of a chain of dyads of kinds ``kinds`` (:func:`chain_rounds_for`,
    made once a process)."""
    kernel = CHAIN_ROUNDS.get(kinds)
    if kernel is None:
        kernel = CHAIN_ROUNDS[kinds] = chain_rounds_for(kinds)
    return kernel
