"""The fused table kernels: a crank and one dyad (every kind but RTR) solved again tile by
tile, as ``solve_many``'s fused kernel solves it
(:mod:`~kinetostatics.solver.fast.fused_kernels`: the same row helpers in the same
order, the same numbers bit for bit), and each tile's rows of the ``kinematics`` and
``reactions`` tables written straight into the tables' own columns while the tile is in
the first-level cache (:mod:`kinetostatics.results.fastpass`).

Per tile: every named point's ``x, y, vx, vy, ax, ay``
(:func:`~kinetostatics.solver.fast.table_kernels.point_row`, the numpy path's operations
in its order) and every joint's ``Fx, Fy`` (the reaction on its ``on`` body: the
solver's value or its negation, exact), ``F = hypot(Fx, Fy)`` (numpy's, bit for bit:
:func:`~kinetostatics.solver.fast.table_kernels.hypot_into`) and a prismatic joint's
``N, M``. The rows of a block are written a column or a few at a time, from the block's
motion and reactions kept in the caches (measured 2026-11-29: 54 columns written a tile
of 64 rows at a time ran at half the memory's speed for long runs of few columns).

Imported by :mod:`~kinetostatics.solver.fast.table_pass` once the compiled path is
loaded (the cache folder settled); the rules of the kernels module hold here.
"""

from __future__ import annotations

from .jitbase import (
    TILE,
    body,
    jit,
    nonfinite,
    scratch,
    tile_geometry,
    tile_out,
    tile_rows,
)
from .kernels import crank_row, dyad_row
from .layout import DRIVER_GEOMETRY, DYAD_GEOMETRY, DYAD_OUT, INNER_R, ROT1, ROT2, C, S
from .layout import MOTION as BODY_ROWS
from .layout import REACTIONS as REACTION_ROWS
from .reaction_kernels import tile_loads
from .table_kernels import hypot_into, point_row
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


@body
def _crank_dyad_tables(kind, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl,
                       gls, npt, slots, local, n, at, kout, src, sign, rout, mb, rb, mine):
    """A crank and one dyad (not RTR), rows ``lo`` to ``hi`` of its sweep (``own``,
    ``ts``, the geometry and the loads as ``solve_many``'s fused kernel takes them; no
    ``resist`` loads), solved tile by tile as that kernel solves them, each tile's
    bodies' motion kept in ``mb`` (ten rows a body: the driver's, the dyad's first,
    its second) and each joint's reaction in ``rb`` (four rows a joint), both in the
    caches; then the block's rows written into the tables' columns, at row
    ``at + i - lo`` of each block of ``n`` rows, a column or a few at a time (the
    memory takes long runs of one column faster than many columns a tile at a time):

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
    wdrv, wm1, wm2 = w_[R:2 * R], w_[2 * R:3 * R], w_[3 * R:4 * R]
    o1, o2 = R if k1d else 0, R if k2d else 0       # (the ground's motion: rows 0..R)
    wk1, wk2 = w_[o1:o1 + R], w_[o2:o2 + R]
    b = W_LOADS
    wad, wa1, wa2, wak1, wak2 = (w_[b:b + 3], w_[b + 3:b + 6], w_[b + 6:b + 9],
                                 w_[b + 9:b + 12], w_[b + 12:b + 15])
    wd = w_[W_DYAD:W_DYAD + DYAD_OUT]
    wr = w_[W_REACTIONS:W_REACTIONS + REACTION_ROWS]
    b = W_REACTIONS + REACTION_ROWS
    wg = w_[b:b + DYAD_GEOMETRY]
    wgd = w_[b + DYAD_GEOMETRY:]
    for t in range(TILE):
        w_[C, t] = 1.0                              # the ground: at rest
    n0, n1, n2 = gl[0].shape[0], gl[1].shape[0], gl[2].shape[0]
    wl = scratch(n0 + n1 + n2)
    wl0, wl1, wl2 = wl[:n0], wl[n0:n0 + n1], wl[n0 + n1:]
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
        for t in range(TILE):
            f = crank_row(t, t, wgd, w, eps, wdrv)
            bad += f if t < nt else 0
        for t in range(TILE):
            f = dyad_row(kind, rot1, rot2, inner_r, False, t, t, wg, wk1, wk2, wm1, wm2, wd)
            bad += f if t < nt else 0
        tile_out(mb, w_[R:4 * R], t0 - lo, nt)
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
            for q in range(src.shape[0]):
                for f in range(4):
                    row = src[q, f]
                    if row >= 0:
                        dst = rb[4 * q + f, t0 - lo:t0 - lo + nt]
                        for t in range(nt):
                            dst[t] = w_[row, t]
        t0 += nt
    _point_rows(mb, hi - lo, slots, local, n, at, kout)
    _reaction_rows(rb, hi - lo, src, sign, n, at, rout, mine)
    return bad


@body
def _point_rows(mb, m, slots, local, n, at, kout):
    """The block's ``m`` rows of every point into ``kout`` (:func:`_crank_dyad_tables`),
    point by point: six columns at a time."""
    R = BODY_ROWS
    for p in range(slots.shape[0]):
        s = R * (slots[p] - 1)
        lx, ly = local[p, 0], local[p, 1]
        origin = lx == 0.0 and ly == 0.0
        j = p * n + at
        for t in range(m):
            point_row(mb[s:s + R], t, lx, ly, origin, kout, j + t)


@body
def _reaction_rows(rb, m, src, sign, n, at, rout, mine):
    """The block's ``m`` rows of every joint's ``Fx, Fy, F`` (and ``N, M``) into
    ``rout`` (:func:`_crank_dyad_tables`), joint by joint."""
    for q in range(src.shape[0]):
        neg = sign[q, 0] < 0.0
        fxs, fys = rb[4 * q], rb[4 * q + 1]
        j = q * n + at
        fx_out, fy_out, f_out = rout[0, j:j + m], rout[1, j:j + m], rout[2, j:j + m]
        for t in range(m):
            fx, fy = fxs[t], fys[t]
            if neg:
                fx, fy = -fx, -fy
            fx_out[t] = fx
            fy_out[t] = fy
        hypot_into(fxs, fys, f_out, m, mine)     # (|Fx|, |Fy|: the sign is no matter)
        if src[q, 2] >= 0:
            flip = sign[q, 1] < 0.0
            ns, ms = rb[4 * q + 2], rb[4 * q + 3]
            n_out, m_out = rout[3, j:j + m], rout[4, j:j + m]
            for t in range(m):
                nn, mm = ns[t], ms[t]
                if flip:
                    nn, mm = -nn, -mm
                n_out[t] = nn
                m_out[t] = mm


@jit
def rrr_tables(lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
               slots, local, n, at, kout, src, sign, rout, mb, rb, mine):
    return _crank_dyad_tables(7, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d,
                              gl, gls, npt, slots, local, n, at, kout, src, sign, rout, mb, rb,
                              mine)


@jit
def rrt_tables(lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
               slots, local, n, at, kout, src, sign, rout, mb, rb, mine):
    return _crank_dyad_tables(5, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d,
                              gl, gls, npt, slots, local, n, at, kout, src, sign, rout, mb, rb,
                              mine)


@jit
def trr_tables(lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
               slots, local, n, at, kout, src, sign, rout, mb, rb, mine):
    return _crank_dyad_tables(6, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d,
                              gl, gls, npt, slots, local, n, at, kout, src, sign, rout, mb, rb,
                              mine)


@jit
def trt_tables(lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
               slots, local, n, at, kout, src, sign, rout, mb, rb, mine):
    return _crank_dyad_tables(4, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d,
                              gl, gls, npt, slots, local, n, at, kout, src, sign, rout, mb, rb,
                              mine)


@jit
def rtt_tables(lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
               slots, local, n, at, kout, src, sign, rout, mb, rb, mine):
    return _crank_dyad_tables(1, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d,
                              gl, gls, npt, slots, local, n, at, kout, src, sign, rout, mb, rb,
                              mine)


@jit
def ttr_tables(lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
               slots, local, n, at, kout, src, sign, rout, mb, rb, mine):
    return _crank_dyad_tables(2, lo, hi, own, cs, sn, ts, gd, gds, w, eps, gy, gys, k1d, k2d,
                              gl, gls, npt, slots, local, n, at, kout, src, sign, rout, mb, rb,
                              mine)


# a crank and one dyad, per dyad kind (RTR: the composed kernels, SolvedAgain)
TABLES = {"RRR": rrr_tables, "RRT": rrt_tables, "TRR": trr_tables, "TRT": trt_tables,
          "RTT": rtt_tables, "TTR": ttr_tables}

__all__ = ["TABLES", "W_DYAD", "W_LOADS", "W_MOTION", "W_REACTIONS", "W_ROWS"]
