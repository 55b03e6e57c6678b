"""The fused kernels of ``solve_many``: a crank and one dyad (every kind but RTR) in one
kernel per run, tile by tile (``jitbase.FUSED_TILE`` rows a tile): the driver's motion,
the dyad's, each body's loads, the dyad's reactions and Me, every value of a tile in one
scratch array, and only Me, the closeness to a dead centre and the undefined rows
written out (with each row's singular flag and the rows below the dead-point screen, told
in the same pass). The row helpers are the composed kernels'
(:mod:`~kinetostatics.solver.fast.kernels`), in the same order: the same numbers, bit
for bit.

Imported by :func:`~kinetostatics.solver.fast.stacked.fused_kept` once the compiled path
is loaded (the cache folder settled); the rules of the kernels module hold here.
"""

from __future__ import annotations

import numpy as np

from .jitbase import FUSED_TILE as TILE
from .jitbase import (
    body,
    jit_as,
    nonfinite,
    not_literal,
    scratch_for,
    tile_rows_for,
)
from .kernels import SINGULAR_WARN2, tile_motion_for
from .layout import CL2, DRIVER_GEOMETRY, G1, G2, INNER_R, KINDS, ROT1, ROT2, C, S
from .layout import MOTION as BODY_ROWS
from .reaction_kernels import crank_moment, reaction_row, tile_loads_for
from .scratch_views import DYAD_ROWS, LOAD_ROWS, dyad_views, load_views, resultant_views
from .tail_kernels import tile_swept
from .trig_kernels import sincos_rows

# tiles of FUSED_TILE rows (jitbase): the helpers of that width
scratch, tile_rows = scratch_for(TILE), tile_rows_for(TILE)
tile_loads = tile_loads_for(TILE)
tile_motion = tile_motion_for(TILE)


# -- a crank and one dyad, fused: what solve_many keeps of a run ---------------------------
# A tile holds TILE rows (16) of the run whatever their scenes (the last tile of a scene no
# longer partly worked out for nothing: measured 2026-11-30, 1000 four-bars x 361, the
# kernel alone 13.3-13.6 ms a call against 14.5-14.8 with a tile per scene's rest), each column
# its row's scene's geometry (the row helpers read column t of a tile for row t). A
# whole tile of one scene's cos and sin is copied in a loop of a constant count
# (vectorised; of nt rows it is not).
@body
def _fill(wg, g, c, a, b):
    """Columns ``a`` to ``b`` of a tile's geometry ``wg`` with column ``c`` of ``g`` (a
    slice per row: vectorised)."""
    for f in range(wg.shape[0]):
        wg[f, a:b] = g[f, c]


@body
def _fill_shared(wgd, gd, gds, wg, gy, gys, wl0, wl1, wl2, gl, gls):
    """Every column of each tile geometry whose table has one column (``gs`` 0: shared
    by the run's scenes) with it, once a call."""
    if gds == 0:
        _fill(wgd, gd, 0, 0, TILE)
    if gys == 0:
        _fill(wg, gy, 0, 0, TILE)
    if gls[0] == 0:
        _fill(wl0, gl[0], 0, 0, TILE)
    if gls[1] == 0:
        _fill(wl1, gl[1], 0, 0, TILE)
    if gls[2] == 0:
        _fill(wl2, gl[2], 0, 0, TILE)


@body
def _fill_scene(held, e, a, b, wgd, gd, gds, wg, gy, gys, wl0, wl1, wl2, gl, gls):
    """Columns ``a`` to ``b`` of each tile geometry whose table has a column per scene
    with scene ``e``'s, marked in ``held`` (each column's scene)."""
    if gds != 0:
        _fill(wgd, gd, e, a, b)
    if gys != 0:
        _fill(wg, gy, e, a, b)
    if gls[0] != 0:
        _fill(wl0, gl[0], e, a, b)
    if gls[1] != 0:
        _fill(wl1, gl[1], e, a, b)
    if gls[2] != 0:
        _fill(wl2, gl[2], e, a, b)
    held[a:b] = e


@body
def _tile_in(cs, sn, c0, a, nt, whole, wdrv):
    """The crank's cos and sin of ``nt`` rows of a tile (from row ``c0`` of ``cs``,
    ``sn``) into its columns ``a`` on; a whole tile (``whole``: ``a`` 0, ``nt`` TILE) in a
    loop of a constant count (vectorised)."""
    if whole:
        for t in range(TILE):
            wdrv[C, t] = cs[c0 + t]
            wdrv[S, t] = sn[c0 + t]
    else:
        for t in range(nt):
            wdrv[C, a + t] = cs[c0 + t]
            wdrv[S, a + t] = sn[c0 + t]


@body
def _tile_turn(angles, c0, a, nt, wdrv):
    """The crank's cos and sin of ``nt`` rows of a tile worked out from their angles (row
    ``c0`` on of ``angles``) straight into its columns ``a`` on: the compiled path's
    (:func:`~kinetostatics.solver.fast.trig_kernels.sincos_rows`, vectorised).
    Measured 2026-11-30, 1e6 angles, processor time: 7 ns a row against 27 for the C
    library's cos and sin (one ``sincos``) and 37-46 for numpy's two passes. Not kept
    over the sweep: the tables' pass works them out again when a table asks
    (``table_pass``, the same doubles; measured 2026-11-30, the slider-crank at 2e5
    rows, the kernel alone 42-43 ns a row against 43-44 with the sweep's cos and sin
    written and copied, and two arrays of the sweep fewer to fault in)."""
    sincos_rows(angles[c0:c0 + nt], wdrv[C, a:a + nt], wdrv[S, a:a + nt])


@body
def _tile_kept(j0, nt, whole, wr, wd, drive, close, singular):
    """What a sweep keeps of a tile at ``j0`` on: Me (row 0 of ``wr``), the dyad's
    closeness to a dead centre (``wd``'s) and its singular flag, not above
    ``SINGULAR_WARN2`` (numpy's ``~(c > SINGULAR_WARN**2)``, ``compose.kept_sweep``: a NaN
    flagged); the whole tile where ``whole`` (the arrays reach past it: a loop of a
    constant count, vectorised), else ``nt`` rows. (The flags here, not in a pass of
    their own over the group's closeness: measured 2026-11-30, 1000 four-bars x 361,
    that pass 0.16 ms of a call, best of 200.)"""
    if whole:
        for t in range(TILE):
            c = wd[CL2, t]
            drive[j0 + t] = wr[0, t]
            close[j0 + t] = c
            singular[j0 + t] = not c > SINGULAR_WARN2
    else:
        for t in range(nt):
            c = wd[CL2, t]
            drive[j0 + t] = wr[0, t]
            close[j0 + t] = c
            singular[j0 + t] = not c > SINGULAR_WARN2


@body
def _tile_below(j0, nt, wd, screen2, below, k):
    """The tile's rows (from ``j0``) whose closeness is below ``screen2`` (the dead-point
    screen's, ``deadpoints.SCREEN**2``: a NaN never is), in order, written to ``below``
    from its ``k``-th place as far as it has room; returns the count ``k`` after them.
    (Told here, not in a pass of numpy over the group's closeness: measured 2026-11-30,
    1000 four-bars x 361 (3865 rows below), ``flatnonzero(m2 < SCREEN**2)`` 0.26 ms a
    call, best of 200.)"""
    for t in range(nt):
        if wd[CL2, t] < screen2:
            if k < below.size:
                below[k] = j0 + t
            k += 1
    return k


@body
def _crank_dyad_kept(kind, lo, hi, own, cs, sn, ts, angles, gd, gds, w, eps, gy, gys, k1d, k2d,
                     gl, gls, npt, gw, gws, nw, st, drive, close, singular, undefined,
                     screen2, below):
    """A crank and one dyad (not RTR: its guide's cos and sin are numpy's, in a pass of
    their own), rows ``lo`` to ``hi`` of a stack (``own``: each row's scene; a table per
    kernel, ``gd`` the driver's, ``gy`` the dyad's, ``gl`` each body's loads, ``gw`` its
    swept loads with their ``st``; bodies in the order driver, the dyad's first, its
    second): the driver's motion, the dyad's, each body's loads, the dyad's reactions
    and Me, tile by tile, each tile's values in one scratch array, as
    :func:`crank_motion`, :func:`dyad_row`, :func:`tile_loads`, :func:`swept_row`,
    :func:`reaction_row` and :func:`crank_moment` compute them over blocks (the same
    operations in the same order: the same numbers); only Me, the dyad's closeness to a
    dead centre, its singular flags and the undefined rows are written (``drive``,
    ``close``, ``singular``, ``undefined``), and the rows whose closeness is below
    ``screen2`` (the dead-point screen's) to ``below`` as far as it has room
    (:func:`_tile_below`). ``k1d``, ``k2d``: whether each outer joint's known body is the
    driver (else the ground). The crank's cos and sin (``cs``, ``sn``) are worked out
    before, in a pass of their own: row ``i`` of scene ``e`` at ``i - ts[e]`` (one
    sweep shared by the scenes, or the run's rows), or here from the crank's ``angles``
    (one scene, ``ts`` 0; none: an empty array) into the tile alone (:func:`_tile_turn`;
    ``cs``, ``sn`` then unread). ``kind``'s ground bits (``layout.G1``, ``G2``: a
    prismatic outer joint whose known body is the ground) take the ground's motion as
    the constants it is (:func:`~kinetostatics.solver.fast.kernels.dyad_row`). Returns
    the count of rows the numpy path must judge and the count of rows below
    ``screen2``."""
    rot1, rot2, inner_r = (kind & ROT1) != 0, (kind & ROT2) != 0, (kind & INNER_R) != 0
    R = BODY_ROWS
    w_ = scratch(4 * R + LOAD_ROWS + DYAD_ROWS + DRIVER_GEOMETRY)
    wdrv, wm1, wm2 = w_[R:2 * R], w_[2 * R:3 * R], w_[3 * R:4 * R]
    o1, o2 = R if k1d else 0, R if k2d else 0       # (the ground's motion: rows 0..R)
    wk1, wk2 = w_[o1:o1 + R], w_[o2:o2 + R]
    wad, wa1, wa2, wak1, wak2 = resultant_views(w_, 4 * R)
    wd, wr, wg, b = dyad_views(w_, 4 * R + LOAD_ROWS)
    wgd = w_[b:]
    for t in range(TILE):
        w_[C, t] = 1.0                              # the ground: at rest
    wl0, wl1, wl2 = load_views(scratch(gl[0].shape[0] + gl[1].shape[0] + gl[2].shape[0]), gl)
    e0 = 1 if st[0].shape[1] > 1 else 0
    e1 = 1 if st[1].shape[1] > 1 else 0
    e2 = 1 if st[2].shape[1] > 1 else 0
    # (each column's scene: its geometry's; a one-column table, shared, filled once)
    held = np.full(TILE, -1, dtype=np.int64)
    _fill_shared(wgd, gd, gds, wg, gy, gys, wl0, wl1, wl2, gl, gls)
    bad = 0
    nbelow = 0
    turn = angles.shape[0] > 0
    t0 = lo
    while t0 < hi:
        # a tile of TILE rows (the last one's fewer) whose columns may hold several
        # scenes' rows, each column its row's scene's geometry and its cos and sin
        nt = min(TILE, hi - t0)
        a = 0
        while a < nt:
            e = own[t0 + a]
            n = tile_rows(1, own, t0 + a, t0 + nt)      # (scene e's rows from column a)
            if held[a] != e or held[a + n - 1] != e:     # (held: a scene per run of columns)
                _fill_scene(held, e, a, a + n, wgd, gd, gds, wg, gy, gys, wl0, wl1, wl2, gl,
                            gls)
            c0 = t0 + a - ts[e]         # (the scene's row in its cos and sin)
            if turn:
                _tile_turn(angles, c0, a, n, wdrv)
            else:
                _tile_in(cs, sn, c0, a, n, n == TILE, wdrv)
            a += n
        bad += tile_motion(kind, rot1, rot2, inner_r, nt, wgd, w, eps, wdrv, wg, wk1, wk2,
                           wm1, wm2, wd)
        bad += tile_loads(wdrv, wad, wl0, npt[0], nt)
        bad += tile_loads(wm1, wa1, wl1, npt[1], nt)
        bad += tile_loads(wm2, wa2, wl2, npt[2], nt)
        # (each body's swept loads after every body's loads, as the composed kernels: in a
        # helper per body, loads then swept loads, the same numbers ran 5-10 % slower,
        # measured 2026-11-29)
        if nw[0]:
            bad += tile_swept(lo, t0, nt, own, gws[0], e0, gw[0], nw[0], wdrv, wad, undefined,
                              st[0])
        if nw[1]:
            bad += tile_swept(lo, t0, nt, own, gws[1], e1, gw[1], nw[1], wm1, wa1, undefined,
                              st[1])
        if nw[2]:
            bad += tile_swept(lo, t0, nt, own, gws[2], e2, gw[2], nw[2], wm2, wa2, undefined,
                              st[2])
        wak1[:] = 0.0
        wak2[:] = 0.0
        # the reactions, what the outer joints load the driver with added to its
        # resultants in order unless their known body is the ground (as the composed
        # reactions add them, tile_add) and Me, in one loop (measured 2026-11-29, 1000
        # four-bars x 361: 9.1 ms a call against 9.9 in three loops; the dyad's motion
        # in the crank's loop stops it vectorising: 24.5 ms). k1d, k2d are constants of
        # the entry (_kept_for): each add is there or not, not a masked store per row
        # (vmaskmovpd, slow on this AMD machine: measured 2026-11-30, 1000 four-bars x
        # 361, the kernel alone 11.7-12.1 ms a call against 12.8-13.0 with the known
        # bodies read from the geometry per tile)
        for t in range(TILE):
            f = reaction_row(rot1, rot2, inner_r, t, t, wg, wm1, wm2, wk1, wk2, wd, wa1, wa2,
                             wak1, wak2, wr)
            if k1d:
                for q in range(3):
                    wad[q, t] += wak1[q, t]
            if k2d:
                for q in range(3):
                    wad[q, t] += wak2[q, t]
            me = crank_moment(t, t, wgd, wdrv, wad)
            wr[0, t] = me
            f = nonfinite((me, wad[0, t], wad[1, t]))
            bad += f if t < nt else 0
        _tile_kept(t0 - lo, nt, t0 + TILE <= hi, wr, wd, drive, close, singular)
        nbelow = _tile_below(t0 - lo, nt, wd, screen2, below, nbelow)
        t0 += nt
    return bad, nbelow


def _kept_for(kind: str, k1d: bool, k2d: bool):
    """The compiled entry of dyad kind ``kind`` whose outer joints' known bodies are the
    driver (``k1d``, ``k2d``) or else the ground: :func:`_crank_dyad_kept` with the kind's
    code (:data:`~kinetostatics.solver.fast.layout.KINDS`), its ground bits (``G1``,
    ``G2``: which prismatic outer joints' known body is the ground) and ``k1d``, ``k2d``
    constants (numba freezes the closure's values: each compiled on its first call as if
    written out), named by them (:func:`~kinetostatics.solver.fast.jitbase.jit_as`: a
    cache index of its own). Measured 2026-11-29 against the kind passed at run time (one
    compile for every kind): the four-bar at 2e5 rows 23 ms a solve against 11, its
    dyad's row no longer vectorised."""
    ground = _ground(kind, k1d, k2d)
    code = KINDS[kind] | ground
    suffix = "".join(f"_g{i + 1}" for i, bit in enumerate((G1, G2)) if ground & bit)
    suffix += "".join(f"_d{i + 1}" for i, d in enumerate((k1d, k2d)) if d)

    @jit_as(f"{kind.lower()}_kept{suffix}")
    def kept(lo, hi, own, cs, sn, ts, angles, gd, gds, w, eps, gy, gys, k1d_, k2d_, gl, gls,
             npt, gw, gws, nw, st, drive, close, singular, undefined, screen2, below):
        value = not_literal(code)       # (the helpers typed once for every kind)
        return _crank_dyad_kept(value, lo, hi, own, cs, sn, ts, angles, gd, gds, w, eps, gy, gys,
                                k1d, k2d, gl, gls, npt, gw, gws, nw, st, drive, close,
                                singular, undefined, screen2, below)
    return kept


def _ground(kind: str, k1d: bool, k2d: bool) -> int:
    """The ground bits (``layout.G1``, ``G2``) of a kind's outer joints whose known bodies
    are the driver (``k1d``, ``k2d``) or else the ground: a prismatic joint's whose known
    body is the ground (a revolute one's none)."""
    code = KINDS[kind]
    return (G1 if not code & ROT1 and not k1d else 0) | (G2 if not code & ROT2 and not k2d else 0)


# a crank and one dyad, fused, per dyad kind (RTR: its composed kernels) and whether each
# outer joint's known body is the driver (else the ground; each compiled on its first
# call). Measured 2026-11-30, the slider-crank (its guide on the ground) at 1e6 rows, the
# kernel alone, processor time: see docs/solve-paths.md
KEPT_ON = {(kind, k1d, k2d): _kept_for(kind, k1d, k2d) for kind in KINDS if kind != "RTR"
           for k1d in (False, True) for k2d in (False, True)}


class Kept:
    """A kind's fused kernel as its callers call it (the arguments of
    :func:`_crank_dyad_kept` after ``kind``): the entry of :data:`KEPT_ON` whose known
    bodies the call's ``k1d``, ``k2d`` (each outer joint's known body the driver, else the
    ground) name."""

    def __init__(self, kind: str) -> None:
        self.kind = kind

    def entry(self, k1d: bool, k2d: bool):
        """The compiled entry of a call whose outer joints' known bodies are the driver
        (``k1d``, ``k2d``) or else the ground."""
        return KEPT_ON[self.kind, bool(k1d), bool(k2d)]

    def __call__(self, *args):
        return self.entry(args[13], args[14])(*args)


KEPT = {kind: Kept(kind) for kind in KINDS if kind != "RTR"}


__all__ = ["KEPT", "KEPT_ON", "Kept"]
