"""A crank and one RTR dyad (the slotted lever's structure), or a crank, one RTR dyad and
a second dyad of another kind (the shaper's), fused, per block of rows: what a long
sweep keeps (Me, each dyad's closeness to a dead centre, the undefined rows) in two
kernels with numpy's cos and sin of the guide's angle between them, as the composed
kernels work them out (:mod:`~kinetostatics.solver.fast.kernels`: the RTR guide's angle
in a pass of its own, its cos and sin numpy's, then the rest).

The row helpers are the composed kernels' (and those of ``solve_many``'s fused
kernels, :mod:`~kinetostatics.solver.fast.fused_kernels`; the tile's tail,
:mod:`~kinetostatics.solver.fast.tail_kernels`), called in the same order on the same
numbers: the same doubles, bit for bit. Imported once the compiled path is loaded (the
cache folder settled); the kernels module's rules hold here.
"""

from __future__ import annotations

from .closure_kernels import rtr_guide_angle
from .jitbase import TILE, body, jit, scratch, tile_geometry
from .kernels import crank_row, dyad_row, outer_param
from .layout import (
    ASSEMBLY,
    C1X,
    C1Y,
    CL2,
    DRIVER_GEOMETRY,
    DYAD_GEOMETRY,
    DYAD_OUT,
    INNER_R,
    KINDS,
    P_GROUND,
    PARAM,
    ROT1,
    ROT2,
    XX,
    C,
    S,
)
from .layout import MOTION as BODY_ROWS
from .layout import REACTIONS as REACTION_ROWS
from .reaction_kernels import tile_loads
from .tail_kernels import (
    add_rows,
    copy_rows,
    known_loads,
    tile_kept,
    tile_moment,
    tile_reactions,
    tile_swept,
)

RTR = KINDS["RTR"]      # outer joints revolute, inner prismatic


@jit
def rtr_guide(lo, hi, cs, sn, gd, w, eps, gy, k1d, k2d, th, reach, gap):
    """RTR's first pass over rows ``lo`` to ``hi`` of a block (``cs``, ``sn``: the
    crank's cos and sin over the block): the crank's motion (:func:`crank_row`), then
    each row's guide angle ``th``, the pivots' distance ``reach`` and the ``gap``
    (:func:`rtr_guide_angle`, seed 000 ch. 6-7: the composed RTR kernel's stage 0).
    ``k1d``, ``k2d``: whether each outer joint's known body is the crank (else the
    ground)."""
    R = BODY_ROWS
    w_ = scratch(2 * R)
    wdrv = w_[R:]
    for t in range(TILE):
        w_[C, t] = 1.0                          # the ground: at rest
    wk1 = wdrv if k1d else w_[:R]
    wk2 = wdrv if k2d else w_[:R]
    k = gy[ASSEMBLY, 0]
    for t0 in range(lo, hi, TILE):
        nt = min(TILE, hi - t0)
        for t in range(nt):
            wdrv[C, t] = cs[t0 + t]
            wdrv[S, t] = sn[t0 + t]
        for t in range(TILE):
            crank_row(t, 0, gd, w, eps, wdrv)   # (counted by the second pass)
        for t in range(nt):
            p1 = outer_param(True, wk1, t, gy, 0, 0)
            p2 = outer_param(True, wk2, t, gy, 0, PARAM)
            th[t0 + t], reach[t0 + t], gap[t0 + t] = rtr_guide_angle(p1, p2, gy, 0, k)
    return 0


@body
def _rtr_tile(t0, nt, cs, sn, ct, sg, reach, gap, wgd, w, eps, k1d, k2d, wg, wdrv, wk1, wk2,
              wm1, wm2, wd):
    """RTR's second pass over the tile that starts at row ``t0`` (``nt`` rows): the
    crank's cos and sin, the guide's (``ct``, ``sg``) and :func:`rtr_guide`'s ``reach``
    and ``gap`` in, the crank's motion (:func:`crank_row`), copied to the outer joints'
    known bodies where they are the crank (``k1d``, ``k2d``), and the dyad's
    (:func:`dyad_row`, RTR); the count of the tile's rows that are not finite or that
    the numpy path refuses."""
    rot1, rot2, inner_r = (RTR & ROT1) != 0, (RTR & ROT2) != 0, (RTR & INNER_R) != 0
    rtr = rot1 and rot2 and not inner_r
    for t in range(nt):
        wdrv[C, t] = cs[t0 + t]
        wdrv[S, t] = sn[t0 + t]
        wd[C1X, t] = ct[t0 + t]
        wd[C1Y, t] = sg[t0 + t]
        wd[CL2, t] = reach[t0 + t]
        wd[XX, t] = gap[t0 + t]
    bad = 0
    for t in range(TILE):
        f = crank_row(t, t, wgd, w, eps, wdrv)
        bad += f if t < nt else 0
    if k1d:
        copy_rows(wk1, wdrv)
    if k2d:
        copy_rows(wk2, wdrv)
    for t in range(TILE):
        f = dyad_row(RTR, rot1, rot2, inner_r, rtr, t, t, wg, wk1, wk2, wm1, wm2, wd)
        bad += f if t < nt else 0
    return bad


@jit
def rtr_kept(lo, hi, own, cs, sn, gd, w, eps, gy, k1d, k2d, gl, npt, gw, nw, st, ct, sg,
             reach, gap, drive, close, undefined):
    """RTR's second pass (rows ``lo`` to ``hi`` of a block; ``ct``, ``sg``: the guide's
    cos and sin, numpy's, of :func:`rtr_guide`'s angles): the crank's motion, the
    dyad's (:func:`dyad_row`, RTR), each body's loads (bodies in the order crank, the
    dyad's first, its second: ``gl``, ``npt``, their swept loads ``gw``, ``nw`` with
    their statistics ``st``; seed 002 s. 2.1-2.2), the dyad's reactions (s. 2.3) and Me
    (eqs 2.47-2.48), tile by tile in one scratch
    array, as the composed kernels compute them; only Me, the closeness to a dead centre
    and the undefined rows written (``own``: zeros, the one scene's column of the loads'
    geometry). Returns the count of rows the numpy path must
    judge."""
    # (the kind's flags worked out as the composed kernels do, not given as literals:
    # numba types a literal apart, and the rows then compiled slower, measured
    # 2026-11-29: 109 against 84 ns a row)
    rot1, rot2, inner_r = (RTR & ROT1) != 0, (RTR & ROT2) != 0, (RTR & INNER_R) != 0
    R = BODY_ROWS
    w_ = scratch(5 * R + 15 + DYAD_OUT + REACTION_ROWS + DYAD_GEOMETRY + DRIVER_GEOMETRY)
    # the known bodies' motions in rows of their own, copied per tile (views of one
    # scratch array at fixed offsets: LLVM proves them apart from the dyad's and
    # vectorises the rows' loops; a view chosen at run time between the ground's and the
    # crank's kept it from vectorising the RTR row, measured 2026-11-29: 140 ns a row
    # against 109)
    wdrv, wm1, wm2 = w_[:R], w_[R:2 * R], w_[2 * R:3 * R]
    wk1, wk2 = w_[3 * R:4 * R], w_[4 * R:5 * R]
    b = 5 * R
    wad, wa1, wa2, wak1, wak2 = (w_[b:b + 3], w_[b + 3:b + 6], w_[b + 6:b + 9],
                                 w_[b + 9:b + 12], w_[b + 12:b + 15])
    b += 15
    wd = w_[b:b + DYAD_OUT]
    wr = w_[b + DYAD_OUT:b + DYAD_OUT + REACTION_ROWS]
    b += DYAD_OUT + REACTION_ROWS
    wg = w_[b:b + DYAD_GEOMETRY]
    wgd = w_[b + DYAD_GEOMETRY:]
    for t in range(TILE):
        wk1[C, t] = wk2[C, t] = 1.0             # the ground: at rest (unless the crank)
    tile_geometry(wg, gy, 0, own, 0, -1)
    tile_geometry(wgd, gd, 0, own, 0, -1)
    n0, n1, n2 = gl[0].shape[0], gl[1].shape[0], gl[2].shape[0]
    wl = scratch(n0 + n1 + n2)
    wl0, wl1, wl2 = wl[:n0], wl[n0:n0 + n1], wl[n0 + n1:]
    tile_geometry(wl0, gl[0], 0, own, 0, -1)
    tile_geometry(wl1, gl[1], 0, own, 0, -1)
    tile_geometry(wl2, gl[2], 0, own, 0, -1)
    bad = 0
    for t0 in range(lo, hi, TILE):
        nt = min(TILE, hi - t0)
        bad += _rtr_tile(t0, nt, cs, sn, ct, sg, reach, gap, wgd, w, eps, k1d, k2d, wg, wdrv,
                         wk1, wk2, wm1, wm2, wd)
        bad += tile_loads(wdrv, wad, wl0, npt[0], nt)
        bad += tile_loads(wm1, wa1, wl1, npt[1], nt)
        bad += tile_loads(wm2, wa2, wl2, npt[2], nt)
        if nw[0]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[0], nw[0], wdrv, wad, undefined, st[0])
        if nw[1]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[1], nw[1], wm1, wa1, undefined, st[1])
        if nw[2]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[2], nw[2], wm2, wa2, undefined, st[2])
        bad += tile_reactions(rot1, rot2, inner_r, nt, wg, wm1, wm2, wk1, wk2, wd, wa1, wa2,
                              wak1, wak2, wr)
        known_loads(wg, wad, wad, wak1, wak2)
        bad += tile_moment(wgd, wdrv, wad, wr, nt)
        tile_kept(t0 - lo, nt, wr, wd, drive, close)
    return bad


@body
def _known_copy(which, wk, wdrv, wm1, wm2):
    """A known body's motion copied into its rows of its own (``wk``) for a tile:
    ``which`` 1 the crank's, 2 the RTR dyad's first body's, 3 its second's (0: the
    ground's, set once and left)."""
    if which == 1:
        copy_rows(wk, wdrv)
    elif which == 2:
        copy_rows(wk, wm1)
    elif which == 3:
        copy_rows(wk, wm2)


@body
def _known_add(which, wad, wa1, wa2, wak):
    """What an outer joint loads its known body with (``wak``) added to that body's
    resultants (``which`` as :func:`_known_copy`; the ground's: nothing)."""
    if which == 1:
        add_rows(wad, wak)
    elif which == 2:
        add_rows(wa1, wak)
    elif which == 3:
        add_rows(wa2, wak)


@body
def _rtr_dyad_kept(kind, lo, hi, own, cs, sn, gd, w, eps, gy, k1d, k2d, gz, k3, k4, gl, npt,
                   gw, nw, st, ct, sg, reach, gap, drive, close1, close2, undefined):
    """A crank, one RTR dyad and a second dyad of kind ``kind`` (not RTR) whose outer
    joints' known bodies are the ground, the crank or the RTR dyad's bodies (``k3``,
    ``k4``: 0 the ground, 1 the crank, 2 the RTR dyad's first body, 3 its second): the
    shaper's structure. RTR's second pass as :func:`rtr_kept` (``ct``, ``sg``, ``reach``,
    ``gap`` from :func:`rtr_guide`), then the second dyad's motion (:func:`dyad_row`,
    ``gz`` its geometry), each body's loads (bodies in the order crank, the RTR dyad's
    first, its second, the second dyad's first, its second; seed 002 s. 2.1-2.2), the
    second dyad's reactions, then the RTR dyad's (s. 2.3: the dyads last to first, what
    each outer joint loads its known body with added in order) and Me (eqs 2.47-2.48),
    tile by tile in one scratch array, as the composed kernels compute them; only Me,
    each dyad's closeness to a dead centre and the undefined rows written. Returns the
    count of rows the numpy path must judge."""
    rot1, rot2, inner_r = (RTR & ROT1) != 0, (RTR & ROT2) != 0, (RTR & INNER_R) != 0
    rot3, rot4, inner_z = (kind & ROT1) != 0, (kind & ROT2) != 0, (kind & INNER_R) != 0
    R = BODY_ROWS
    w_ = scratch(9 * R + 27 + 2 * (DYAD_OUT + REACTION_ROWS + DYAD_GEOMETRY)
                 + DRIVER_GEOMETRY)
    # every body's motion and every known body's copy at fixed offsets of one scratch
    # array (views chosen at run time keep LLVM from vectorising the rows: rtr_kept)
    wdrv, wm1, wm2 = w_[:R], w_[R:2 * R], w_[2 * R:3 * R]
    wm3, wm4 = w_[3 * R:4 * R], w_[4 * R:5 * R]
    wk1, wk2, wk3, wk4 = w_[5 * R:6 * R], w_[6 * R:7 * R], w_[7 * R:8 * R], w_[8 * R:9 * R]
    b = 9 * R
    wad, wa1, wa2, wa3, wa4 = (w_[b:b + 3], w_[b + 3:b + 6], w_[b + 6:b + 9],
                               w_[b + 9:b + 12], w_[b + 12:b + 15])
    wak1, wak2, wak3, wak4 = (w_[b + 15:b + 18], w_[b + 18:b + 21], w_[b + 21:b + 24],
                              w_[b + 24:b + 27])
    b += 27
    wd, wdz = w_[b:b + DYAD_OUT], w_[b + DYAD_OUT:b + 2 * DYAD_OUT]
    b += 2 * DYAD_OUT
    wr, wrz = w_[b:b + REACTION_ROWS], w_[b + REACTION_ROWS:b + 2 * REACTION_ROWS]
    b += 2 * REACTION_ROWS
    wg, wgz = w_[b:b + DYAD_GEOMETRY], w_[b + DYAD_GEOMETRY:b + 2 * DYAD_GEOMETRY]
    wgd = w_[b + 2 * DYAD_GEOMETRY:]
    for t in range(TILE):                       # the ground: at rest (unless a body's)
        wk1[C, t] = wk2[C, t] = wk3[C, t] = wk4[C, t] = 1.0
    tile_geometry(wg, gy, 0, own, 0, -1)
    tile_geometry(wgz, gz, 0, own, 0, -1)
    tile_geometry(wgd, gd, 0, own, 0, -1)
    n0, n1, n2, n3 = gl[0].shape[0], gl[1].shape[0], gl[2].shape[0], gl[3].shape[0]
    wl = scratch(n0 + n1 + n2 + n3 + gl[4].shape[0])
    b1, b2, b3 = n0 + n1, n0 + n1 + n2, n0 + n1 + n2 + n3
    wl0, wl1, wl2, wl3, wl4 = wl[:n0], wl[n0:b1], wl[b1:b2], wl[b2:b3], wl[b3:]
    tile_geometry(wl0, gl[0], 0, own, 0, -1)
    tile_geometry(wl1, gl[1], 0, own, 0, -1)
    tile_geometry(wl2, gl[2], 0, own, 0, -1)
    tile_geometry(wl3, gl[3], 0, own, 0, -1)
    tile_geometry(wl4, gl[4], 0, own, 0, -1)
    bad = 0
    for t0 in range(lo, hi, TILE):
        nt = min(TILE, hi - t0)
        bad += _rtr_tile(t0, nt, cs, sn, ct, sg, reach, gap, wgd, w, eps, k1d, k2d, wg, wdrv,
                         wk1, wk2, wm1, wm2, wd)
        _known_copy(k3, wk3, wdrv, wm1, wm2)
        _known_copy(k4, wk4, wdrv, wm1, wm2)
        for t in range(TILE):
            f = dyad_row(kind, rot3, rot4, inner_z, False, t, t, wgz, wk3, wk4, wm3, wm4, wdz)
            bad += f if t < nt else 0
        bad += tile_loads(wdrv, wad, wl0, npt[0], nt)
        bad += tile_loads(wm1, wa1, wl1, npt[1], nt)
        bad += tile_loads(wm2, wa2, wl2, npt[2], nt)
        bad += tile_loads(wm3, wa3, wl3, npt[3], nt)
        bad += tile_loads(wm4, wa4, wl4, npt[4], nt)
        if nw[0]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[0], nw[0], wdrv, wad, undefined, st[0])
        if nw[1]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[1], nw[1], wm1, wa1, undefined, st[1])
        if nw[2]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[2], nw[2], wm2, wa2, undefined, st[2])
        if nw[3]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[3], nw[3], wm3, wa3, undefined, st[3])
        if nw[4]:
            bad += tile_swept(lo, t0, nt, own, 0, 0, gw[4], nw[4], wm4, wa4, undefined, st[4])
        # the reactions, the dyads last to first (seed 002 s. 2.3)
        bad += tile_reactions(rot3, rot4, inner_z, nt, wgz, wm3, wm4, wk3, wk4, wdz, wa3, wa4,
                              wak3, wak4, wrz)
        if wgz[P_GROUND, 0] == 0.0:
            _known_add(k3, wad, wa1, wa2, wak3)
        if wgz[PARAM + P_GROUND, 0] == 0.0:
            _known_add(k4, wad, wa1, wa2, wak4)
        bad += tile_reactions(rot1, rot2, inner_r, nt, wg, wm1, wm2, wk1, wk2, wd, wa1, wa2,
                              wak1, wak2, wr)
        known_loads(wg, wad, wad, wak1, wak2)
        bad += tile_moment(wgd, wdrv, wad, wr, nt)
        tile_kept(t0 - lo, nt, wr, wd, drive, close1)
        for t in range(nt):
            close2[t0 + t - lo] = wdz[CL2, t]
    return bad


def _after_rtr_for(code: int):
    """The entry point of :func:`_rtr_dyad_kept` for a second dyad of kind ``code``
    (:data:`~kinetostatics.solver.fast.layout.KINDS`), its arguments but the kind's: one
    source, compiled once per kind on its first call and cached, the kind a constant of
    the compiled code (as :mod:`~kinetostatics.solver.fast.fused_kernels`' ``KEPT``)."""
    @jit
    def kept(*args):
        return _rtr_dyad_kept(code, *args)
    return kept


# a crank, one RTR dyad and a second dyad, fused, per the second dyad's kind (compiled on
# its first call: the shaper's RRT alone, unless a scene asks for another)
AFTER_RTR = {name: _after_rtr_for(code) for name, code in KINDS.items() if name != "RTR"}

__all__ = ["AFTER_RTR", "rtr_guide", "rtr_kept"]
