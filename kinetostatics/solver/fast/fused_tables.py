"""The fused table kernels: a crank and one dyad (every kind but RTR) solved again tile by
tile, as ``solve_many``'s fused kernel solves it
(:mod:`~kinetostatics.solver.fast.fused_kernels`: the same row helpers in the same
order, the same numbers bit for bit), and each block's rows of the ``kinematics`` and
``reactions`` tables written straight into the tables' own columns while the block's
motion is in the caches (:mod:`kinetostatics.results.fastpass`).

Per tile: every named point's ``x, y, vx, vy, ax, ay`` (the numpy path's operations
in its order, as :func:`~kinetostatics.solver.fast.table_kernels.point_row`) and every
joint's ``Fx, Fy`` (the reaction on its ``on`` body: the solver's value or its negation,
exact), ``F = hypot(Fx, Fy)`` (numpy's, bit for bit:
:func:`~kinetostatics.solver.fast.table_kernels.hypot_into`) and a prismatic joint's
``N, M``, written from the kernel's scratch, a column a loop, by non-temporal stores
(:mod:`~kinetostatics.solver.fast.streams`). Measured 2026-11-29 at 1e6 positions, the
four-bar's pass in pages already had, processor time: 0.066 s; with the tile's motion
and reactions first copied into a block of 4096 rows and the columns written from it
0.072 s (the copy alone 7 ms), and with ordinary stores six columns a loop 0.105 s
(0.084 s with the crank's cos and sin worked out again).

Imported by :mod:`~kinetostatics.solver.fast.table_pass` once the compiled path is
loaded (the cache folder settled); the rules of the kernels module hold here.
"""

from __future__ import annotations

from .jitbase import (
    TILE,
    body,
    jit_as,
    nonfinite,
    not_literal,
    scratch,
    tile_geometry,
    tile_rows,
)
from .kernels import tile_motion_for
from .layout import (
    AL,
    AX,
    AY,
    DRIVER_GEOMETRY,
    DYAD_GEOMETRY,
    DYAD_OUT,
    INNER_R,
    KINDS,
    OM,
    OX,
    OY,
    ROT1,
    ROT2,
    VX,
    VY,
    C,
    S,
)
from .layout import MOTION as BODY_ROWS
from .layout import REACTIONS as REACTION_ROWS
from .reaction_kernels import tile_loads
from .streams import drain, stream, stream_column
from .table_kernels import hypot_into
from .tail_kernels import known_loads, tile_reactions

# Where a tile's values lie in the kernel's scratch array (rows): the ground's motion,
# the driver's, the dyad's first and second body's, the load resultants of the driver
# and the dyad's bodies, what the outer joints load the known bodies with, the dyad's
# data, its reactions, then the geometry (as solve_many's fused kernel lays them out)
W_MOTION = 0                            # + BODY_ROWS * slot: ground 0, driver 1, dyad 2, 3
W_LOADS = 4 * BODY_ROWS                 # + 3 * (slot - 1): driver, dyad's first, second
W_DYAD = W_LOADS + 15
W_REACTIONS = W_DYAD + DYAD_OUT
W_ROWS = W_REACTIONS + REACTION_ROWS + DYAD_GEOMETRY + DRIVER_GEOMETRY
# the motion rows of a point's columns x, y, vx, vy, ax, ay (each its origin's)
POINT_FIELDS = (OX, OY, VX, VY, AX, AY)


@body
def _views(w, k1d, k2d):
    """The kernel's scratch ``w`` (``W_ROWS`` rows, the layout above) as the row
    helpers take it: the driver's motion, the dyad's bodies', each outer joint's known
    body's (the driver's where ``k1d``, ``k2d``, else the ground's), the load resultants
    of the driver, the dyad's bodies and the outer joints' known bodies, the dyad's data,
    its reactions, its geometry and the driver's."""
    R = BODY_ROWS
    o1, o2 = R if k1d else 0, R if k2d else 0       # (the ground's motion: rows 0..R)
    a, g = W_LOADS, W_REACTIONS + REACTION_ROWS
    return (w[R:2 * R], w[2 * R:3 * R], w[3 * R:4 * R], w[o1:o1 + R], w[o2:o2 + R],
            w[a:a + 3], w[a + 3:a + 6], w[a + 6:a + 9], w[a + 9:a + 12], w[a + 12:W_DYAD],
            w[W_DYAD:W_REACTIONS], w[W_REACTIONS:g], w[g:g + DYAD_GEOMETRY],
            w[g + DYAD_GEOMETRY:])


_tile_motion = tile_motion_for(TILE)


@body
def _crank_dyad_tables(kind, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl,
                       gls, npt, slots, local, n, at, kout, src, sign, rout, mine):
    """A crank and one dyad (not RTR), rows ``lo`` to ``hi`` of its sweep (``own``,
    ``ts``, the geometry and the loads as ``solve_many``'s fused kernel takes them; no
    ``resist`` loads), solved tile by tile as that kernel solves them, and each tile's
    rows written into the tables' columns from the kernel's scratch (the tile's motion
    and reactions, in the first-level cache), at row ``at + i - lo`` of each block of
    ``n`` rows, a column a loop by non-temporal stores (drained before it returns):

    * ``kout`` (the ``kinematics`` table's six float columns, a row each): point ``p``
      of body ``slots[p]`` (1 the driver, 2 and 3 the dyad's bodies) at the local
      ``local[p]``, its block ``p`` (:func:`~kinetostatics.solver.fast.table_kernels.point_row`);
    * ``rout`` (the ``reactions`` table's ``Fx, Fy, F, N, M``): joint ``q``, its block
      ``q``: ``Fx, Fy`` the scratch rows ``src[q, 0]``, ``src[q, 1]`` times
      ``sign[q, 0]`` (+-1), F their hypot (``mine``: glibc's algorithm inlined, else
      the C library's, :func:`~kinetostatics.solver.fast.table_kernels.hypot`), and
      where ``src[q, 2] >= 0`` ``N, M`` the rows ``src[q, 2]``, ``src[q, 3]`` times
      ``sign[q, 1]``. No joint (``src`` of no rows): the loads and reactions are not
      solved.

    Returns the count of rows the numpy path must judge."""
    rot1, rot2, inner_r = (kind & ROT1) != 0, (kind & ROT2) != 0, (kind & INNER_R) != 0
    R = BODY_ROWS
    w_ = scratch(W_ROWS)
    wdrv, wm1, wm2, wk1, wk2, wad, wa1, wa2, wak1, wak2, wd, wr, wg, wgd = _views(w_, k1d,
                                                                                 k2d)
    for t in range(TILE):
        w_[C, t] = 1.0                              # the ground: at rest
    n0, n1, n2 = gl[0].shape[0], gl[1].shape[0], gl[2].shape[0]
    wl = scratch(n0 + n1 + n2)
    wl0, wl1, wl2 = wl[:n0], wl[n0:n0 + n1], wl[n0 + n1:]
    wf = scratch(1)[0]                    # (a reaction's F over the tile)
    ld = ly = l0 = l1 = l2 = -1           # (the scene whose geometry each tile holds)
    loads = src.shape[0] > 0
    bad = 0
    t0 = lo
    while t0 < hi:
        nt = tile_rows(1, own, t0, hi)
        ld = tile_geometry(wgd, gd, gds, own, t0, ld)
        ly = tile_geometry(wg, gy, gys, own, t0, ly)
        c0 = t0 - ts[own[t0]]
        for t in range(nt):
            wdrv[C, t] = cs[c0 + t]
            wdrv[S, t] = sn[c0 + t]
        bad += _tile_motion(kind, rot1, rot2, inner_r, nt, wgd, w, eps, wdrv, wg, wk1, wk2, wm1,
                            wm2, wd)
        j = at + t0 - lo                # (the tile's first row in each block of n)
        if loads:
            l0 = tile_geometry(wl0, gl[0], gls[0], own, t0, l0)
            l1 = tile_geometry(wl1, gl[1], gls[1], own, t0, l1)
            l2 = tile_geometry(wl2, gl[2], gls[2], own, t0, l2)
            bad += tile_loads(wdrv, wad, wl0, npt[0], nt)
            bad += tile_loads(wm1, wa1, wl1, npt[1], nt)
            bad += tile_loads(wm2, wa2, wl2, npt[2], nt)
            bad += tile_reactions(rot1, rot2, inner_r, nt, wg, wm1, wm2, wk1, wk2, wd, wa1,
                                  wa2, wak1, wak2, wr)
            known_loads(wg, wad, wad, wak1, wak2)
            for t in range(nt):
                bad += nonfinite((wad[0, t], wad[1, t]))
            _reaction_rows(w_, wf, nt, src, sign, n, j, rout, mine)
        _point_rows(w_[R:4 * R], nt, slots, local, n, j, kout)
        t0 += nt
    drain()                 # (the non-temporal stores in memory before the caller reads)
    return bad


@body
def _arm(c, s, lx, ly):
    """The arm r = R(theta) l of the local point ``(lx, ly)`` (seed 001 eq. 9), as arith's
    ``rotate`` and :func:`~kinetostatics.solver.fast.table_kernels.point_row` work it
    out: ``(c lx, s lx)`` when ``ly`` is 0, ``(-ly s, c ly)`` when ``lx`` is 0."""
    if ly == 0.0:
        return c * lx, s * lx
    if lx == 0.0:
        return -ly * s, c * ly
    return c * lx - s * ly, s * lx + c * ly


@body
def _point_column(mb, s, k, m, lx, ly, out):
    """Column ``k`` (``x, y, vx, vy, ax, ay``) of the body point at the local ``(lx, ly)``
    over the tile's ``m`` rows of the body's motion (``mb[s:s + 10]``) into ``out``, by
    non-temporal stores: x = o + r, v = v_O + omega k x r, a = a_O + eps k x r - omega^2
    r (seed 001 eq. 9), the operations of
    :func:`~kinetostatics.solver.fast.table_kernels.point_row` in its order (the same
    numbers, bit for bit); the body's origin (``l`` = 0) its motion as it is."""
    base = mb[s + POINT_FIELDS[k]]
    if lx == 0.0 and ly == 0.0:
        stream_column(base, m, False, out)
        return
    cs, sn, om, al = mb[s + C], mb[s + S], mb[s + OM], mb[s + AL]
    for t in range(m):
        rx, ry = _arm(cs[t], sn[t], lx, ly)
        if k == 0:
            v = base[t] + rx
        elif k == 1:
            v = base[t] + ry
        elif k == 2:
            v = base[t] - om[t] * ry
        elif k == 3:
            v = base[t] + om[t] * rx
        elif k == 4:
            v = (base[t] - al[t] * ry) - (om[t] * om[t]) * rx
        else:
            v = (base[t] + al[t] * rx) - (om[t] * om[t]) * ry
        stream(out, t, v)


@body
def _point_rows(mb, m, slots, local, n, at, kout):
    """The tile's ``m`` rows of every point (``mb``: the motion of the driver and the
    dyad's bodies, ten rows each) into ``kout`` at row ``at`` of each point's block
    (:func:`_crank_dyad_tables`),
    a column at a time (:mod:`~kinetostatics.solver.fast.streams`: a loop of
    non-temporal stores writes one column)."""
    for p in range(slots.shape[0]):
        s = BODY_ROWS * (slots[p] - 1)
        j = p * n + at
        for k in range(6):
            _point_column(mb, s, k, m, local[p, 0], local[p, 1], kout[k, j:j + m])


@body
def _reaction_rows(w_, f, m, src, sign, n, j, rout, mine):
    """The tile's ``m`` rows of every joint's ``Fx, Fy, F`` (and ``N, M``) from the
    kernel's scratch ``w_`` into ``rout`` (:func:`_crank_dyad_tables`) at row ``j`` of
    each joint's block, a column at a time; ``F`` worked out into ``f`` first."""
    for q in range(src.shape[0]):
        neg = sign[q, 0] < 0.0
        at = q * n + j
        fx, fy = w_[src[q, 0]], w_[src[q, 1]]
        stream_column(fx, m, neg, rout[0, at:at + m])
        stream_column(fy, m, neg, rout[1, at:at + m])
        hypot_into(fx, fy, f, m, mine)              # (|Fx|, |Fy|: no sign)
        stream_column(f, m, False, rout[2, at:at + m])
        if src[q, 2] >= 0:
            flip = sign[q, 1] < 0.0
            stream_column(w_[src[q, 2]], m, flip, rout[3, at:at + m])
            stream_column(w_[src[q, 3]], m, flip, rout[4, at:at + m])


def _tables_of(kind: str):
    """The compiled entry of dyad kind ``kind``: :func:`_crank_dyad_tables` with the
    kind's code (:data:`~kinetostatics.solver.fast.layout.KINDS`) a constant (numba
    freezes the closure's ``code``: each kind compiled as if written out), named by its
    kind (:func:`~kinetostatics.solver.fast.jitbase.jit_as`: a cache index of its own)."""
    code = KINDS[kind]

    @jit_as(f"{kind.lower()}_tables")
    def tables(lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
               slots, local, n, at, kout, src, sign, rout, mine):
        value = not_literal(code)       # (the helpers typed once for every kind)
        return _crank_dyad_tables(value, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys,
                                  k1d, k2d, gl, gls, npt, slots, local, n, at, kout, src, sign,
                                  rout, mine)
    return tables


# a crank and one dyad, per dyad kind (RTR: the composed kernels, SolvedAgain)
TABLES = {kind: _tables_of(kind) for kind in KINDS if kind != "RTR"}

__all__ = ["TABLES", "W_DYAD", "W_LOADS", "W_MOTION", "W_REACTIONS", "W_ROWS"]
