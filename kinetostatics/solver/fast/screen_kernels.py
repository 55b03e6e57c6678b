"""The dead-point screen's scan in one compiled pass: the intervals next to a local
minimum of the closeness to a dead centre (``deadpoints._candidates`` on the numpy
arithmetic, a dozen passes and gathers over the rows below the screen).

Only comparisons and one product by a constant are made, each the numpy scan's own
(IEEE doubles, no fastmath): the same intervals, in the same order. Imported only once
the kernels are loaded (:func:`~kinetostatics.solver.fast.loader.kernels`: numba's cache
folder settled first).
"""

from __future__ import annotations

import math

import numpy as np

from .jitbase import body, jit
from .probe_kernels import narrow, start_rounds

# a real dip is below a neighbour by more than rounding jitter (deadpoints._candidates)
SHRINK = 1.0 - 1e-9


@body
def dip(m2, r, a, b):
    """Whether row ``r`` of the segment of rows ``a`` to ``b`` (excluded) is a dip of m:
    (m_r < m_left (1 - 1e-9) and m_r <= m_right) or (m_r <= m_left and
    m_r < m_right (1 - 1e-9)), a segment's end having no neighbour beyond it (+inf)."""
    inf = np.inf
    v = m2[r]
    left = m2[r - 1] if r > a else inf
    right = m2[r + 1] if r + 1 < b else inf
    return (((v < left * SHRINK) and (v <= right))
            or ((v <= left) and (v < right * SHRINK)))


@body
def put_dip(out, k, prev, r, a, b):
    """The intervals (r - 1, r) unless ``r`` starts its segment (rows ``a`` to ``b``)
    and (r, r + 1) unless it ends it, each once (``prev``: the last interval written; the
    intervals never decrease), written to ``out`` while it has room; returns the count of
    intervals ``k`` and ``prev`` after them."""
    if r > a and r - 1 != prev:
        if k < out.size:
            out[k] = r - 1
        k += 1
        prev = r - 1
    if r + 1 < b and r != prev:
        if k < out.size:
            out[k] = r
        k += 1
        prev = r
    return k, prev


@jit
def scan_candidates(m2, starts, counts, screen2, out):
    """The intervals i (rows i, i + 1) next to a local minimum of m over each segment of
    rows alone (segment s: ``counts[s]`` rows from ``starts[s]``), in increasing order,
    written to ``out`` (as many as there are); returns how many.

    A row r below the screen (m^2 < ``screen2``: NaN never is) is a dip when
    (m_r < m_left (1 - 1e-9) and m_r <= m_right) or (m_r <= m_left and
    m_r < m_right (1 - 1e-9)), a segment's end having no neighbour beyond it (+inf); the
    intervals (r - 1, r) unless r starts its segment and (r, r + 1) unless it ends it,
    each once. Only the first ``out.size`` intervals are written (an empty ``out``:
    counted only); the count is of them all, so that an ``out`` too short is filled by a
    second call with one of that size (``deadpoints.scanned``: no array as long as the
    rows is taken, whose fresh pages, mapped and given back, cost the next solve's
    arrays their pages again: measured 2026-11-29, solve_many's fused kernel 1.5-2 ms
    slower a call after a scan with an ``out`` of the rows' length)."""
    k = 0
    prev = -1           # (the last interval written: the intervals never decrease)
    for s in range(starts.size):
        a = starts[s]
        b = a + counts[s]
        for r in range(a, b):
            if m2[r] < screen2 and dip(m2, r, a, b):
                k, prev = put_dip(out, k, prev, r, a, b)
    return k


@jit
def flags_and_measure(c0, c1, warn2, screen2, s0, s1, m2, out):
    """Two dyads' singular rows, their m^2 and its screen's intervals in one pass over
    their closeness to a dead centre ``c0``, ``c1``: ``s0``, ``s1`` the rows not above
    ``warn2`` (numpy's ``~(c > warn2)``: NaN flagged), ``m2`` the smaller of the two per
    row (numpy's ``minimum``: a NaN kept; -0.0 or 0.0 as may be, read by comparisons
    only; ``deadpoints.measure2``), and the intervals :func:`scan_candidates` finds over
    the rows as one segment (row r judged once row r + 1 is made), the same, written to
    ``out`` as far as it has room. Returns their count and whether some row's m^2 is
    below ``screen2`` (NaN never is)."""
    n = c0.size
    k, prev, below = 0, -1, False
    for i in range(n + 1):
        if i < n:
            a, b = c0[i], c1[i]
            s0[i] = not a > warn2
            s1[i] = not b > warn2
            m2[i] = a if (a <= b or np.isnan(a)) else b
        r = i - 1
        if r >= 0 and m2[r] < screen2:
            below = True
            if dip(m2, r, 0, n):
                k, prev = put_dip(out, k, prev, r, 0, n)
    return k, below


# the columns of probe_rrr's table, one row per scene: the driver joint's ground point
# and its point on the crank, per outer pivot j (0, 1) its point on the ground or on the
# crank and its point on the dyad's body, the inner joint's point on each dyad body, size
PA, CA, PIVOT, LOCAL, INNER, SIZE = 0, 2, (4, 8), (6, 10), 12, 16
COLUMNS = 17


@body
def rrr_pivots(ci, si, g, e, on_crank):
    """The outer pivots P1, P2 of scene ``e`` (row ``e`` of ``g``) at the crank's cos
    ``ci`` and sin ``si``: a point of the ground, or of the crank about its origin
    o = P - R a (seed 000 ch. 4), as the numpy probe computes them."""
    ox = g[e, PA] - (ci * g[e, CA] - si * g[e, CA + 1])
    oy = g[e, PA + 1] - (si * g[e, CA] + ci * g[e, CA + 1])
    b1, b2 = PIVOT
    if on_crank[0]:
        p1x = ox + (ci * g[e, b1] - si * g[e, b1 + 1])
        p1y = oy + (si * g[e, b1] + ci * g[e, b1 + 1])
    else:
        p1x, p1y = g[e, b1], g[e, b1 + 1]
    if on_crank[1]:
        p2x = ox + (ci * g[e, b2] - si * g[e, b2 + 1])
        p2y = oy + (si * g[e, b2] + ci * g[e, b2 + 1])
    else:
        p2x, p2y = g[e, b2], g[e, b2 + 1]
    return p1x, p1y, p2x, p2y


@body
def rrr_arms(g, e):
    """The dyad's links from its outer joints' points to its inner joint's, in each
    body (the numpy closure's a1, a2: A.less, the same subtractions)."""
    return (g[e, INNER] - g[e, LOCAL[0]], g[e, INNER + 1] - g[e, LOCAL[0] + 1],
            g[e, INNER + 2] - g[e, LOCAL[1]], g[e, INNER + 3] - g[e, LOCAL[1] + 1])


@body
def rrr_span(ci, si, g, e, on_crank):
    """A row's outer pivots P1, P2 (:func:`rrr_pivots`), the first link a1
    (:func:`rrr_arms`), both links' squared lengths and P2 - P1: what the probe and the
    gaps both start from, in the numpy closure's order."""
    p1x, p1y, p2x, p2y = rrr_pivots(ci, si, g, e, on_crank)
    a1x, a1y, a2x, a2y = rrr_arms(g, e)
    r1s = a1x * a1x + a1y * a1y
    r2s = a2x * a2x + a2y * a2y
    return p1x, p1y, p2x, p2y, a1x, a1y, r1s, r2s, p2x - p1x, p2y - p1y


@body
def rrr_close(ci, si, g, e, ke, on_crank):
    """The closeness to a dead centre (m^2) of scene ``e`` (row ``e`` of ``g``) in
    assembly ``ke`` (+-1.0) at the crank's cos ``ci`` and sin ``si``, and 1 where h^2 is
    negative or not finite (else 0): the operations of
    :func:`~kinetostatics.solver.probes.probe_closeness` in their order (IEEE doubles, no
    fastmath; numpy's minimum: a NaN kept)."""
    # circle-circle (seed 000 eq. 5.1): Q = P1 + x e + k h J e
    p1x, p1y, p2x, p2y, a1x, a1y, r1s, r2s, ex, ey = rrr_span(ci, si, g, e, on_crank)
    d2 = ex * ex + ey * ey
    reach = np.sqrt(d2)
    inv = 1.0 / reach
    x = (d2 + (r1s - r2s)) * (0.5 * inv)
    h2 = r1s - x * x
    bad = 1 if (h2 < 0.0 or not np.isfinite(h2)) else 0
    root = np.sqrt(h2 if not h2 < 0.0 else 0.0)     # (numpy's maximum(h2, 0))
    xi = x * inv
    kh = (ke * inv) * root
    tx = xi * ex - kh * ey                      # X - P1
    ty = xi * ey + kh * ex
    u, v = a1x / r1s, a1y / r1s               # the first body's cos, sin
    c1, s1 = tx * u + ty * v, ty * u - tx * v
    # (the second body's angle: not read by the closeness)
    # the first body's origin, then the closing point X on it
    lx, ly = g[e, LOCAL[0]], g[e, LOCAL[0] + 1]
    o1x = p1x - (c1 * lx - s1 * ly)
    o1y = p1y - (s1 * lx + c1 * ly)
    qx, qy = g[e, INNER], g[e, INNER + 1]
    xx = o1x + (c1 * qx - s1 * qy)
    xy = o1y + (s1 * qx + c1 * qy)
    # the velocity system's columns c_i = J (X - P_i) and determinant; sin^2 tau
    # = det^2 / (|c1|^2 |c2|^2) (seed 002 eqs 2.60-2.61)
    c1x, c1y = p1y - xy, xx - p1x
    c2x, c2y = p2y - xy, xx - p2x
    det = c2x * c1y - c1x * c2y
    norm2 = (c1x * c1x + c1y * c1y) * (c2x * c2x + c2y * c2y)
    sin2 = det * det / norm2
    rr = reach / g[e, SIZE]
    rr = rr * rr
    return (sin2 if (sin2 <= rr or np.isnan(sin2)) else rr), bad     # (numpy's minimum)


@body
def rrr_open(ci, si, g, e, on_crank):
    """Whether the dyad of scene ``e`` cannot close at the crank's cos ``ci`` and sin
    ``si``: its gap max(d - (r1 + r2), |r1 - r2| - d) (numpy's maximum: a NaN kept) is
    not within 1e-9 of the mechanism's size."""
    _, _, _, _, _, _, r1s, r2s, ex, ey = rrr_span(ci, si, g, e, on_crank)
    d = np.sqrt(ex * ex + ey * ey)
    r1, r2 = np.sqrt(r1s), np.sqrt(r2s)
    gap = d - (r1 + r2)
    far = abs(r1 - r2) - d
    gap = gap if (gap >= far or np.isnan(gap)) else far
    return not gap <= 1e-9 * g[e, SIZE]


@jit
def probe_rrr(c, s, own, k, g, on_crank, m2):
    """The closeness to a dead centre of a crank and one RRR dyad at the rows' crank
    angles (cos ``c``, sin ``s``: numpy's), row i of scene ``own[i]`` in assembly
    ``k[own[i]]`` (+-1.0), its numbers row ``own[i]`` of ``g`` (the columns above;
    ``on_crank[j]``: outer pivot j on the crank, else on the ground): :func:`rrr_close`
    per row, m^2 written to ``m2``. Returns 1 when some row's h^2 is negative or not
    finite (then the rows' gaps count, :func:`rrr_gaps`, as numpy's probe measures them
    only then), else 0."""
    bad = 0
    for i in range(c.size):
        e = own[i]
        v, b = rrr_close(c[i], s[i], g, e, k[e], on_crank)
        m2[i] = v
        bad |= b
    return bad


@jit
def rrr_gaps(c, s, own, g, on_crank, opened):
    """Per row of :func:`probe_rrr`, whether the dyad cannot close (:func:`rrr_open`),
    written to ``opened``."""
    for i in range(c.size):
        opened[i] = rrr_open(c[i], s[i], g, own[i], on_crank)


@jit
def probe_rounds(lo, hi, owner, t, deg, k, g, on_crank, rounds, best, opened, m2, gone):
    """The dead-point screen's probes of a crank and one RRR dyad, every round in one
    call (:func:`~kinetostatics.solver.deadpoints._probe`'s zoom, as numpy works it
    out): each interval ``(lo[i], hi[i])`` of scene ``owner[i]`` probed at its interior
    points ``lo + (hi - lo) t[1:-1]`` (deg; their angles ``x deg``, their cos and sin
    the C library's, which :func:`~kinetostatics.solver.fast.solve.kernel_trig` finds
    numpy's), :func:`rrr_close` at each, and where some probe of the round has h^2
    negative or not finite, :func:`rrr_open` at each (as the numpy probe measures the
    gaps only then); then :func:`~.probe_kernels.narrow` (a probe that is NaN or open
    counts +inf; the interval shrinks to the two steps about its first smallest probe,
    numpy's argmin), ``rounds`` times. The
    smallest m^2 found per interval goes to ``best``, whether some probe was open to
    ``opened``; ``lo`` and ``hi`` are written over; ``m2`` and ``gone``: scratch of
    ``lo.size * (t.size - 2)`` values."""
    n = lo.size
    p = t.size - 2
    start_rounds(best, opened)
    for _ in range(rounds):
        bad = 0
        for i in range(n):
            a, d, e = lo[i], hi[i] - lo[i], owner[i]
            for j in range(p):
                x = (a + d * t[j + 1]) * deg
                v, b = rrr_close(math.cos(x), math.sin(x), g, e, k[e], on_crank)
                m2[i * p + j] = v
                bad |= b
        for i in range(n):
            a, d, e = lo[i], hi[i] - lo[i], owner[i]
            for j in range(p):
                gone[i * p + j] = False
                if bad:
                    x = (a + d * t[j + 1]) * deg
                    gone[i * p + j] = rrr_open(math.cos(x), math.sin(x), g, e, on_crank)
        narrow(n, p, t, m2, gone, lo, hi, best, opened)
