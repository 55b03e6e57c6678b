"""A crank and one RTR dyad (the slotted lever's structure), or a crank, one RTR dyad and
a second dyad of another kind (the shaper's), fused: what a long sweep keeps (Me, each
dyad's closeness to a dead centre, the undefined rows) in one kernel call over the
sweep, each tile working out the crank's cos and sin (the compiled path's,
``trig_kernels.sincos_rows``), the guide's angle's cos and sin, then the rest, as the
composed kernels work them out (:mod:`~kinetostatics.solver.fast.kernels`: the crank's
cos and sin in a pass of their own, then the RTR guide's angle's cos and sin in a pass
of their own, ``closure_kernels.rtr_guide_angle``, then the rest)."""

from __future__ import annotations

import numpy as np

from .closure_kernels import rtr_guide_angle
from .jitbase import (
    TILE,
    body,
    jit,
    jit_as,
    nonfinite,
    not_literal,
    scratch,
    tile_geometry,
    tile_rows,
)
from .kernels import crank_row, dyad_row, outer_param
from .layout import (
    ASSEMBLY,
    C1X,
    C1Y,
    CL2,
    DRIVER_GEOMETRY,
    G1,
    G2,
    I_SFIRST,
    INNER_R,
    KINDS,
    OM,
    P_GROUND,
    PARAM,
    ROT1,
    ROT2,
    VX,
    VY,
    XX,
    C,
    S,
    padded_width,
)
from .layout import MOTION as BODY_ROWS
from .load_kernels import swept_force, swept_stats
from .reaction_kernels import reaction_row, tile_loads
from .scratch_views import DYAD_ROWS, LOAD_ROWS, dyad_views, resultant_views
from .tail_kernels import (
    add_rows,
    copy_rows,
    known_loads,
    tile_moment,
    tile_reactions,
    tile_swept,
)
from .trig_kernels import sincos_rows

RTR = KINDS["RTR"]      # outer joints revolute, inner prismatic


@body
def _guide_row(wk1, wk2, t, gy, k):
    """The RTR guide's angle's cos and sin, the pivots' distance and the gap at row ``t``
    of a tile (:func:`rtr_guide_angle`, seed 000 ch. 6-7: the composed RTR kernel's stage 0) from
    the outer joints' known bodies' motions ``wk1``, ``wk2`` (``gy``: the dyad's
    geometry, its column 0; ``k``: its assembly). (A pivot on the ground from its
    geometry alone, ``kernels.ground_param`` as the dyad's row takes it, changed the
    slotted lever's machine code: its kernel 55-61 ns a row against 46-59, measured
    2026-11-30 in alternating pairs; not kept.)"""
    p1 = outer_param(True, wk1, t, gy, 0, 0)
    p2 = outer_param(True, wk2, t, gy, 0, PARAM)
    return rtr_guide_angle(p1, p2, gy, 0, k)


@body
def _rtr_tile(rcode, lo, t0, nt, own, trig, wgd, w, eps, k1d, k2d, wg, wdrv, wk1, wk2, wm1,
              wm2, wd, wa, wl, npt, gw, gws, nw, undefined, st):
    """RTR over the tile that starts at row ``t0`` (``nt`` rows, one scene's) of rows from
    ``lo``: the crank's cos and sin (:func:`_crank_in`, ``trig``), the crank's motion
    (:func:`crank_row`), copied to the outer joints' known bodies where they are the
    crank (``k1d``, ``k2d``; ``rcode``: RTR's code and its ground bits, a constant of the
    entry), the guide's angle's cos and sin, the pivots' distance and
    the gap (:func:`_guide_row`), the dyad's motion (:func:`dyad_row`, RTR), then the
    loads of the crank and the dyad's
    bodies (:func:`tile_loads`, then :func:`tile_swept`: ``wa`` their resultants, ``wl``
    their geometry, the first three of ``npt``, ``gw``, ``nw``, ``st``); the count of
    the tile's rows that are not finite or that the numpy path refuses (the slider's
    flag pinned, :func:`_pin`): the operations of the composed kernels' passes on the
    same numbers."""
    rot1, rot2, inner_r = (RTR & ROT1) != 0, (RTR & ROT2) != 0, (RTR & INNER_R) != 0
    rtr = rot1 and rot2 and not inner_r
    _crank_in(t0, nt, own, trig, wdrv)
    bad = 0
    for t in range(TILE):
        f = crank_row(t, t, wgd, w, eps, wdrv)
        bad += f if t < nt else 0
    if k1d:
        copy_rows(wk1, wdrv)
    if k2d:
        copy_rows(wk2, wdrv)
    k = wg[ASSEMBLY, 0]                 # (the tile's scene's)
    # (every row of the tile, as the loops below: a loop of the tile's nt rows was
    # preceded by some 400 instructions of checks that its arrays do not overlap,
    # measured 2026-11-30, 1.5 % of the shaper's kernel's samples)
    for t in range(TILE):
        wd[C1X, t], wd[C1Y, t], wd[CL2, t], wd[XX, t] = _guide_row(wk1, wk2, t, wg, k)
    for t in range(TILE):
        _pin(wg, t)
        f = dyad_row(rcode, rot1, rot2, inner_r, rtr, t, t, wg, wk1, wk2, wm1, wm2, wd)
        bad += f if t < nt else 0
    bad += tile_loads(wdrv, wa[0], wl[0], npt[0], nt)
    bad += tile_loads(wm1, wa[1], wl[1], npt[1], nt)
    bad += tile_loads(wm2, wa[2], wl[2], npt[2], nt)
    if nw[0]:
        bad += tile_swept(lo, t0, nt, own, gws[0], _each(st[0]), gw[0], nw[0], wdrv,
                          wa[0], undefined, st[0])
    if nw[1]:
        bad += tile_swept(lo, t0, nt, own, gws[1], _each(st[1]), gw[1], nw[1], wm1,
                          wa[1], undefined, st[1])
    if nw[2]:
        bad += tile_swept(lo, t0, nt, own, gws[2], _each(st[2]), gw[2], nw[2], wm2,
                          wa[2], undefined, st[2])
    return bad


@body
def _swept(lo, t0, nt, own, gs, gw, nw, wm, wa, undefined, st, wq):
    """A body's swept loads over a tile (:func:`tile_swept`; none where ``nw`` is 0). One
    scene's (``gs`` 0, statistics in one column: a solve's) forces acting ``when =
    "resisting"`` (no ``resist`` load) each load's forces first, in a loop of their own
    (:func:`_swept_forces`), then its statistics row after row (:func:`_stats`) and its
    rows that stand still marked undefined: the tail's operations in its order, the same
    numbers."""
    es = _each(st)
    if nw == 0:
        return 0
    resist = False
    for q in range(nw):
        resist = resist or gw[7 * q + 2, 0] == 1.0
    if gs != 0 or es != 0 or resist:
        return tile_swept(lo, t0, nt, own, gs, es, gw, nw, wm, wa, undefined, st)
    xs, held = wq[7], undefined[t0 - lo:t0 - lo + nt]
    for q in range(nw):
        _swept_forces(gw, 7 * q, nt, wm, wa, wq)
        thr = gw[7 * q + 6, 0]
        st[q, 0, 0], st[q, 0, 1] = _stats(st[q, 0, 0], st[q, 0, 1], xs, thr, nt)
        for t in range(nt):
            held[t] = held[t] | (xs[t] <= thr)
    bad = 0
    for t in range(nt):
        bad += nonfinite((wa[0, t], wa[1, t], wa[2, t]))
    return bad


@body
def _stats(top, least, xs, thr, nt):
    """A swept load's statistics ``(top, least)`` after the speeds ``xs`` of a tile's
    first ``nt`` rows, row after row (:func:`swept_stats`, a row still where its speed
    is at most ``thr``)."""
    for t in range(nt):
        top, least = swept_stats(top, least, xs[t], xs[t] <= thr)
    return top, least


@body
def _swept_forces(gw, b, nt, wm, wa, wq):
    """A force acting ``when = "resisting"`` (:func:`swept_force`, its numbers rows ``b``
    to ``b + 7`` of ``gw``'s column 0) over the tile's first ``nt`` rows added to the
    resultants ``wa``, its speeds into row 7 of ``wq``. Its numbers in ``wq``, a column a
    row, its kind stored there just before each row reads it (as :func:`_pin`): LLVM
    folds ``resist``'s branch (``hypot``) away and the loop vectorises (measured
    2026-11-30: the shaper's ram, scalar, 5.5 % of its kernel's samples; vectorised
    1.6 %, its statistics 1.2)."""
    for f in range(7):
        wq[f, :] = gw[b + f, 0]
    for t in range(nt):
        _kind_in(wq, t, 2.0)
        _force_row(wq, t, wm, wa)


@body
def _kind_in(wq, t, kind):
    """A swept load's kind, a constant, into column ``t`` of its numbers ``wq`` (row 2)."""
    wq[2, t] = kind


@body
def _force_row(wq, t, wm, wa):
    """A swept load's force at row ``t`` (:func:`swept_force` of column ``t`` of ``wq``)
    added to the resultants ``wa``, its speed into ``wq[7, t]``."""
    rx, ry, fx, fy, wq[7, t], _ = swept_force(wq, 0, t, wm[C, t], wm[S, t], wm[OM, t],
                                              wm[VX, t], wm[VY, t])
    wa[0, t] += fx
    wa[1, t] += fy
    wa[2, t] += rx * fy - ry * fx


# a row of the kernels' scratch arrays: TILE values and some more, the rows an odd number
# of cache lines apart (layout.padded_width: 72 values, 9 lines). Rows of 64 values lie
# 512 bytes apart, and a loop reading some 90 rows at one column (a dyad's row: its known
# bodies, its geometry, its data, its bodies) fell in 8 of the first-level cache's 64
# sets, more lines than their 8 ways hold (measured 2026-11-30, the shaper's kernel alone
# at 2e5 rows, processor time, best of 61, alternating processes at a load of 6-7: 83.9-92
# ns a row against 80.6-81.5 padded; the loops read and write columns 0 to TILE - 1 only)
PAD = padded_width(TILE)


@body
def _padded(rows):
    """A tile's scratch array of ``rows`` rows of :data:`PAD` values (zeros; the tile's
    rows in columns 0 to ``TILE - 1``)."""
    return np.zeros((rows, PAD))


@body
def _loads_in(g):
    """A tile's scratch array of its own for a body's load geometry ``g`` (filled per
    tile: :func:`_scene_tile`)."""
    return scratch(g.shape[0])


@body
def _each(st):
    """1 when the statistics ``st`` of a body's swept loads have a column per scene
    (each row's at its scene's), else 0 (one scene's)."""
    return 1 if st.shape[1] > 1 else 0


@body
def _crank_in(t0, nt, own, trig, wdrv):
    """The crank's cos and sin of the ``nt`` rows of the tile that starts at row ``t0``
    (one scene's) into its columns: ``trig`` is ``(cs, sn, ts, angles)``; the compiled
    path's (:func:`~kinetostatics.solver.fast.trig_kernels.sincos_rows`) of the rows'
    ``angles`` (one scene, row ``i``'s at ``i``), or none given (an empty array) copied
    from ``cs``, ``sn`` (worked out by the same function before: row ``i`` of scene
    ``e`` at ``i - ts[e]``, a stack's, ``stacker.sweeps``)."""
    cs, sn, ts, angles = trig
    if angles.shape[0] > 0:
        sincos_rows(angles[t0:t0 + nt], wdrv[C, :nt], wdrv[S, :nt])
    else:
        c0 = t0 - ts[own[t0 * _stride(ts)]]
        for t in range(nt):
            wdrv[C, t] = cs[c0 + t]
            wdrv[S, t] = sn[c0 + t]


@body
def _stride(ts):
    """Each row's scene's stride in ``own``: 1 for a stack of scenes (``ts``, where each
    scene's rows begin in the crank's cos and sin, has more than one), 0 for one scene
    (its rows all scene 0: ``own`` may be shorter than the sweep, ``short.OWNERS``)."""
    return 1 if ts.shape[0] > 1 else 0


@body
def _scene_tile(t0, hi, own, ts, held, wgd, gd, gds, wg, gy, gys, wl, gl, gls):
    """The rows of the tile that starts at row ``t0`` (at most ``TILE``, all of one scene:
    :func:`~kinetostatics.solver.fast.jitbase.tile_rows`), the tile's geometry of the
    crank ``wgd``, the RTR dyad ``wg`` and each body's loads ``wl`` (the crank's, the
    dyad's first, its second) refilled with the scene's column where it changes
    (:func:`~kinetostatics.solver.fast.jitbase.tile_geometry`: ``held``, each table's
    scene filled last; a table of one column, ``gs`` 0, filled once)."""
    held[0] = tile_geometry(wgd, gd, gds, own, t0, held[0])
    held[1] = tile_geometry(wg, gy, gys, own, t0, held[1])
    held[2] = tile_geometry(wl[0], gl[0], gls[0], own, t0, held[2])
    held[3] = tile_geometry(wl[1], gl[1], gls[1], own, t0, held[3])
    held[4] = tile_geometry(wl[2], gl[2], gls[2], own, t0, held[4])
    return tile_rows(_stride(ts), own, t0, hi)


@body
def _pin(wg, t):
    """The RTR dyad's slider-first flag, 0 (the guide first: the structure's analysis
    puts an inner prismatic joint's guide first, and ``solve.guided_blocks`` leaves any
    other geometry to the composed kernels), stored into column ``t`` of the
    dyad's geometry just before a row helper reads it there: LLVM forwards the constant
    to the helper's read, folds its choices of the slider's and the guide's rows and
    vectorises the tile's loop (the reactions' loop was scalar code with the flag read
    per row: measured 2026-11-29, 22.7 ns a row against 6.3 pinned; the same numbers, bit
    for bit, the flag the geometry's own)."""
    wg[I_SFIRST, t] = 0.0


@body
def _rtr_last(nt, wg, wgd, wdrv, wm1, wm2, wk1, wk2, wd, wad, wa1, wa2, wak1, wak2, wr):
    """The RTR dyad's reactions over a tile (:func:`reaction_row`, seed 002 s. 2.3, as
    ``tail_kernels.tile_reactions`` with the slider-first flag pinned, :func:`_pin`),
    what its outer joints load the crank with added to the crank's resultants
    (:func:`known_loads`) and Me (:func:`tile_moment`, eqs 2.47-2.48) into row 0 of
    ``wr``; the count of the tile's first ``nt`` rows that are not finite."""
    rot1, rot2, inner_r = (RTR & ROT1) != 0, (RTR & ROT2) != 0, (RTR & INNER_R) != 0
    wak1[:] = 0.0
    wak2[:] = 0.0
    bad = 0
    for t in range(TILE):
        _pin(wg, t)
        f = reaction_row(rot1, rot2, inner_r, t, t, wg, wm1, wm2, wk1, wk2, wd, wa1, wa2, wak1,
                         wak2, wr)
        bad += f if t < nt else 0
    known_loads(wg, wad, wad, wak1, wak2)
    return bad + tile_moment(wgd, wdrv, wad, wr, nt)


@jit
def rtr_kept(lo, hi, own, cs, sn, ts, angles, gd, gds, w, eps, gy, gys, k1d, k2d, gl, gls, npt,
             gw, gws, nw, st, drive, close, undefined):
    """A crank and one RTR dyad over rows ``lo`` to ``hi`` of the sweep (the crank's
    ``angles``; every tile working out the crank's and the guide's cos and sin,
    :func:`_rtr_tile`): the crank's motion, the
    dyad's (:func:`dyad_row`, RTR), each body's loads (bodies in the order crank, the
    dyad's first, its second: ``gl``, ``npt``, their swept loads ``gw``, ``nw`` with
    their statistics ``st``; seed 002 s. 2.1-2.2), the dyad's reactions (s. 2.3) and Me
    (eqs 2.47-2.48), tile by tile in one scratch
    array, as the composed kernels compute them; only Me, the closeness to a dead centre
    and the undefined rows written. One scene (``own``: zeros; ``ts``: one start; the
    crank's ``angles``) or a stack of scenes (``own``: each row's scene; each table with
    its ``gs``, 1 for a column per scene; the rows' cos and sin ``cs``, ``sn`` from
    ``ts``, ``angles`` empty): each tile one scene's rows, its geometry refilled where
    the scene changes (:func:`_scene_tile`). Returns the count of rows the numpy path
    must judge."""
    R = BODY_ROWS
    w_ = scratch(5 * R + LOAD_ROWS + DYAD_ROWS + DRIVER_GEOMETRY)
    # the known bodies' motions in rows of their own, copied per tile (views of one
    # scratch array at fixed offsets: LLVM proves them apart from the dyad's and
    # vectorises the rows' loops; a view chosen at run time between the ground's and the
    # crank's kept it from vectorising the RTR row, measured 2026-11-29: 140 ns a row
    # against 109)
    wdrv, wm1, wm2 = w_[:R], w_[R:2 * R], w_[2 * R:3 * R]
    wk1, wk2 = w_[3 * R:4 * R], w_[4 * R:5 * R]
    wad, wa1, wa2, wak1, wak2 = resultant_views(w_, 5 * R)
    wd, wr, wg, b = dyad_views(w_, 5 * R + LOAD_ROWS)
    wgd = w_[b:]
    for t in range(TILE):
        wk1[C, t] = wk2[C, t] = 1.0             # the ground: at rest (unless the crank)
    wa = (wad, wa1, wa2)
    wl = (_loads_in(gl[0]), _loads_in(gl[1]), _loads_in(gl[2]))
    held = np.full(5, -1, dtype=np.int64)
    trig = (cs, sn, ts, angles)
    bad = 0
    t0 = lo
    while t0 < hi:
        nt = _scene_tile(t0, hi, own, ts, held, wgd, gd, gds, wg, gy, gys, wl, gl, gls)
        bad += _rtr_tile(not_literal(RTR), lo, t0, nt, own, trig, wgd, w, eps, k1d, k2d, wg,
                         wdrv, wk1, wk2, wm1, wm2, wd, wa, wl, npt, gw, gws, nw, undefined, st)
        bad += _rtr_last(nt, wg, wgd, wdrv, wm1, wm2, wk1, wk2, wd, wad, wa1, wa2, wak1, wak2,
                         wr)
        _row_out(drive, t0 - lo, nt, wr[0])
        _row_out(close, t0 - lo, nt, wd[CL2])
        t0 += nt
    return bad


@body
def _known(which, crank, first, second):
    """A known body's rows of a tile by its code ``which`` (1 the crank's, 2 the RTR
    dyad's first body's, 3 its second's; 0, the ground's, is never asked for)."""
    return crank if which == 1 else first if which == 2 else second


@body
def _known_rows(which, ground, crank, first, second):
    """A known body's motion over a tile by its code ``which`` (:func:`_known`; 0 the
    ground's rows ``ground``, set once): a constant of the entry, so that the view is one
    at a fixed offset of the scratch array (no copy per tile: the copies were 5.3 % of
    the shaper's kernel's samples, measured 2026-11-30; a view chosen at run time keeps
    LLVM from vectorising the rows, :func:`rtr_kept`)."""
    return ground if which == 0 else _known(which, crank, first, second)


@body
def _row_out(out, j0, nt, row):
    """A tile's ``row`` (its first ``nt`` values) into ``out`` at ``j0`` on, through a
    view (indices from 0: no check of a negative index a row, the loop vectorised; the
    tail's ``tile_kept`` indexed ``out[j0 + t]`` and ran scalar: measured 2026-11-30,
    the shaper's three writes 2.7 % of its kernel's samples)."""
    part = out[j0:j0 + nt]
    for t in range(nt):
        part[t] = row[t]


@body
def _rtr_dyad_kept(kind, rcode, lo, hi, own, cs, sn, ts, angles, gd, gds, w, eps, gy, gys, k1d,
                   k2d, gz, gzs, k3, k4, gl, gls, npt, gw, gws, nw, st, drive, close1, close2,
                   undefined):
    """A crank, one RTR dyad and a second dyad of kind ``kind`` (not RTR) whose outer
    joints' known bodies are the ground, the crank or the RTR dyad's bodies (``k3``,
    ``k4``: 0 the ground, 1 the crank, 2 the RTR dyad's first body, 3 its second): the
    shaper's structure. The crank and the RTR dyad as :func:`rtr_kept`, then the
    second dyad's motion (:func:`dyad_row`, ``gz`` its geometry), each body's loads
    (bodies in the order crank, the RTR dyad's first, its second, the second dyad's
    first, its second; seed 002 s. 2.1-2.2), the
    second dyad's reactions, then the RTR dyad's (s. 2.3: the dyads last to first, what
    each outer joint loads its known body with added in order) and Me (eqs 2.47-2.48),
    tile by tile in one scratch array, as the composed kernels compute them; only Me,
    each dyad's closeness to a dead centre and the undefined rows written; one scene or a
    stack, each tile one scene's rows, as :func:`rtr_kept` (``gzs``: the second dyad's
    table's). The known bodies (``k1d``, ``k2d``: the RTR dyad's, 1 the crank, 0 the
    ground; ``k3``, ``k4``) are constants of the entry: each dyad reads its known bodies'
    rows where they are worked out (:func:`_known_rows`), and ``kind``, ``rcode`` (RTR's
    code) carry the ground bits of the outer joints on the ground (``layout.G1``,
    ``G2``: :func:`~kinetostatics.solver.fast.kernels.ground_param`). Returns the count
    of rows the numpy path must judge."""
    rot3, rot4, inner_z = (kind & ROT1) != 0, (kind & ROT2) != 0, (kind & INNER_R) != 0
    R = BODY_ROWS
    w_ = _padded(7 * R + LOAD_ROWS + 12 + 2 * DYAD_ROWS + DRIVER_GEOMETRY)
    # every body's motion and the ground's at fixed offsets of one scratch array (views
    # chosen at run time keep LLVM from vectorising the rows: rtr_kept)
    wdrv, wm1, wm2 = w_[:R], w_[R:2 * R], w_[2 * R:3 * R]
    wm3, wm4 = w_[3 * R:4 * R], w_[4 * R:5 * R]
    w0 = w_[5 * R:6 * R]
    for t in range(TILE):                       # the ground: at rest
        w0[C, t] = 1.0
    wk1, wk2 = _known_rows(k1d, w0, wdrv, wm1, wm2), _known_rows(k2d, w0, wdrv, wm1, wm2)
    wk3, wk4 = _known_rows(k3, w0, wdrv, wm1, wm2), _known_rows(k4, w0, wdrv, wm1, wm2)
    wad, wa1, wa2, wak1, wak2 = resultant_views(w_, 7 * R)
    b = 7 * R + LOAD_ROWS       # (the second dyad's: its bodies' resultants, its loads)
    wa3, wa4, wak3, wak4 = w_[b:b + 3], w_[b + 3:b + 6], w_[b + 6:b + 9], w_[b + 9:b + 12]
    wd, wr, wg, b = dyad_views(w_, b + 12)
    wdz, wrz, wgz, b = dyad_views(w_, b)
    wgd = w_[b:]
    wa = (wad, wa1, wa2)
    wl = (_loads_in(gl[0]), _loads_in(gl[1]), _loads_in(gl[2]))
    wl3, wl4 = _loads_in(gl[3]), _loads_in(gl[4])
    held = np.full(8, -1, dtype=np.int64)
    wq = scratch(8)                     # (a swept load's numbers and speeds: _swept)
    trig = (cs, sn, ts, angles)
    # the crank's and the RTR dyad's bodies' tables as rtr_kept passes them (tuples of
    # three: _scene_tile and _rtr_tile then typed and compiled once a process for both
    # entries, not again for tuples of five; measured 2026-12-01, an empty cache: the
    # shaper's first solve after the slotted lever's 1.5-2.5 s of compiling less, its
    # entry's machine code 4.6 % smaller, bit for bit, as fast within a load of 10's
    # noise: docs/testing.md)
    gl3, gls3, npt3, gw3, gws3, nw3, st3 = gl[:3], gls[:3], npt[:3], gw[:3], gws[:3], nw[:3], st[:3]
    bad = 0
    t0 = lo
    while t0 < hi:
        nt = _scene_tile(t0, hi, own, ts, held, wgd, gd, gds, wg, gy, gys, wl, gl3, gls3)
        held[5] = tile_geometry(wgz, gz, gzs, own, t0, held[5])
        held[6] = tile_geometry(wl3, gl[3], gls[3], own, t0, held[6])
        held[7] = tile_geometry(wl4, gl[4], gls[4], own, t0, held[7])
        bad += _rtr_tile(rcode, lo, t0, nt, own, trig, wgd, w, eps, False, False, wg, wdrv, wk1,
                         wk2, wm1, wm2, wd, wa, wl, npt3, gw3, gws3, nw3, undefined, st3)
        for t in range(TILE):
            f = dyad_row(kind, rot3, rot4, inner_z, False, t, t, wgz, wk3, wk4, wm3, wm4, wdz)
            bad += f if t < nt else 0
        bad += tile_loads(wm3, wa3, wl3, npt[3], nt)
        bad += tile_loads(wm4, wa4, wl4, npt[4], nt)
        bad += _swept(lo, t0, nt, own, gws[3], gw[3], nw[3], wm3, wa3, undefined, st[3], wq)
        bad += _swept(lo, t0, nt, own, gws[4], gw[4], nw[4], wm4, wa4, undefined, st[4], wq)
        # the reactions, the dyads last to first (seed 002 s. 2.3)
        bad += tile_reactions(rot3, rot4, inner_z, nt, wgz, wm3, wm4, wk3, wk4, wdz, wa3, wa4,
                              wak3, wak4, wrz)
        if k3 and wgz[P_GROUND, 0] == 0.0:
            add_rows(_known(k3, wad, wa1, wa2), wak3)
        if k4 and wgz[PARAM + P_GROUND, 0] == 0.0:
            add_rows(_known(k4, wad, wa1, wa2), wak4)
        bad += _rtr_last(nt, wg, wgd, wdrv, wm1, wm2, wk1, wk2, wd, wad, wa1, wa2, wak1, wak2,
                         wr)
        _row_out(drive, t0 - lo, nt, wr[0])
        _row_out(close1, t0 - lo, nt, wd[CL2])
        _row_out(close2, t0 - lo, nt, wdz[CL2])
        t0 += nt
    return bad


def _grounded(code: int, first: bool, second: bool) -> int:
    """A dyad's ``code`` with the ground bits (``layout.G1``, ``G2``) of the outer joints
    whose known body is the ground (``first``, ``second``)."""
    return code | (G1 if first else 0) | (G2 if second else 0)


def _after_rtr_for(kind: str, known: tuple):
    """The compiled entry of :func:`_rtr_dyad_kept` for a second dyad of kind ``kind``
    and the known bodies ``known`` (``k1d``, ``k2d``, ``k3``, ``k4`` as integers), its
    codes (:data:`~kinetostatics.solver.fast.layout.KINDS`, the ground bits) and
    ``known`` constants (numba freezes the closure's cells: each cached apart), named by
    both (as :mod:`~kinetostatics.solver.fast.fused_kernels`' ``KEPT_ON``). Measured
    2026-11-30, the shaper's kernel alone (1e6 rows): see docs/solve-paths.md."""
    k1d, k2d, k3, k4 = known
    code = _grounded(KINDS[kind], k3 == 0, k4 == 0)
    rcode = _grounded(RTR, k1d == 0, k2d == 0)

    @jit_as(f"rtr_{kind.lower()}_kept_{k1d}{k2d}{k3}{k4}")
    def kept(lo, hi, own, cs, sn, ts, angles, gd, gds, w, eps, gy, gys, _k1d, _k2d, gz, gzs,
             _k3, _k4, gl, gls, npt, gw, gws, nw, st, drive, close1, close2, undefined):
        value = not_literal(code)       # (the helpers typed once for every kind)
        return _rtr_dyad_kept(value, not_literal(rcode), lo, hi, own, cs, sn, ts, angles, gd,
                              gds, w, eps, gy, gys, not_literal(k1d), not_literal(k2d), gz, gzs,
                              not_literal(k3), not_literal(k4), gl, gls, npt, gw, gws, nw, st,
                              drive, close1, close2, undefined)
    return kept


# a crank, one RTR dyad and a second dyad, fused, per the second dyad's kind and the known
# bodies of both dyads' outer joints: (kind, (k1d, k2d, k3, k4)) -> its entry, made on a
# call's first need (AfterRtr) and compiled then (the shaper's alone, unless a scene asks
# for another)
AFTER_RTR_ON: dict = {}


class AfterRtr:
    """A second dyad's kind's kernel as its callers call it (the arguments of
    :func:`_rtr_dyad_kept` after ``kind`` and ``rcode``): the entry of
    :data:`AFTER_RTR_ON` for the call's known bodies (``k1d``, ``k2d``, ``k3``, ``k4``)."""

    def __init__(self, kind: str) -> None:
        self.kind = kind

    def entry(self, k1d: bool, k2d: bool, k3: int, k4: int):
        """The compiled entry of a call whose outer joints' known bodies are ``k1d``,
        ``k2d`` (the RTR dyad's: the driver, else the ground), ``k3``, ``k4`` (the
        second dyad's codes)."""
        key = (self.kind, (int(k1d), int(k2d), int(k3), int(k4)))
        found = AFTER_RTR_ON.get(key)
        if found is None:
            found = AFTER_RTR_ON[key] = _after_rtr_for(*key)
        return found

    def __call__(self, *args):
        return self.entry(args[13], args[14], args[17], args[18])(*args)


AFTER_RTR = {kind: AfterRtr(kind) for kind in KINDS if kind != "RTR"}

__all__ = ["AFTER_RTR", "AFTER_RTR_ON", "AfterRtr", "rtr_kept"]
