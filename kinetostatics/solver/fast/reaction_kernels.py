"""The compiled kernels of the reactions (seed 002 s. 2.3), row by row: the numpy path's
formulas, as :mod:`~kinetostatics.solver.fast.kernels` computes the motion (the same
conventions: rows ``lo`` to ``hi``, arrays at ``i - off``, geometry at ``i * gs``; each
kernel returns the count of rows the numpy path must judge). The loads' kernels are
:mod:`~kinetostatics.solver.fast.load_kernels`' (their names here too, as the fused
kernels import them)."""

from __future__ import annotations

from .jitbase import (
    TILE,
    body,
    jit,
    jit_as,
    nonfinite,
    not_literal,
    scratch,
    tile_add,
    tile_in,
    tile_next,
    tile_out,
)
from .layout import (
    C1X,
    C1Y,
    C2X,
    C2Y,
    D_LX,
    D_LY,
    DET,
    DYAD_GEOMETRY,
    DYAD_OUT,
    I_SFIRST,
    I_SX,
    I_SY,
    INNER_R,
    KINDS,
    NX,
    NY,
    O_WHERE,
    O_X,
    O_Y,
    OX,
    OY,
    P_BX,
    P_BY,
    P_GROUND,
    P_KX,
    P_KY,
    PARAM,
    Q1X,
    Q1Y,
    Q2X,
    Q2Y,
    R_FX,
    R_FY,
    R_M,
    R_N,
    R_SX,
    R_SY,
    ROT1,
    ROT2,
    T_ON,
    T_RUX,
    T_RUY,
    T_SX,
    T_SY,
    XX,
    XY,
    C,
    S,
)
from .layout import MOTION as BODY_ROWS
from .layout import REACTIONS as REACTION_ROWS
from .load_kernels import body_loads, swept_loads, swept_row, tile_loads, tile_loads_for


# -- reactions (seed 002 s. 2.3) ----------------------------------------------------------
@body
def _add(acc, j, fx, fy, rx, ry, mm, sign):
    """acc += sign (F, r x F + M) on a body's resultants."""
    acc[0, j] += sign * fx
    acc[1, j] += sign * fy
    acc[2, j] += sign * ((rx * fy - ry * fx) + mm)


@body
def _generalised(rot, m, a, d, g, j, r, t):
    """The generalised force of a dyad body's loads along its freedom: the moment about
    its outer pivot P (rot) or the force along its outer guide u (trans)."""
    if rot:
        lx, ly = g[PARAM * t + P_BX, r], g[PARAM * t + P_BY, r]
        px, py = m[C, j] * lx - m[S, j] * ly, m[S, j] * lx + m[C, j] * ly
        return a[2, j] - (px * a[1, j] - py * a[0, j])
    return a[0, j] * d[10 + 4 * t, j] + a[1, j] * d[11 + 4 * t, j]


@body
def _outer(rot, t, g, r, j, m, mk, a, ak, d, rr):
    """Outer joint ``t``'s reaction, and what it loads the known body with (into ``ak``,
    a tile's scratch: added to the known body's resultants unless it is the ground)."""
    base = PARAM * t
    if rot:
        # eqs 2.19, 2.21, 2.28: the body's force balance gives the outer reaction
        lx, ly = g[base + P_KX, r], g[base + P_KY, r]
        kx, ky = mk[C, j] * lx - mk[S, j] * ly, mk[S, j] * lx + mk[C, j] * ly
        _add(ak, j, a[0, j], a[1, j], kx, ky, 0.0, 1.0)
        return
    # an outer prismatic joint: normal force through the slider point and a couple about
    # it (eqs 2.24-2.25, 2.36-2.37, 2.42-2.43); the slider point on the ground (where 0),
    # the dyad body (1) or the known body (2), chosen by value (no branch: it vectorises)
    where = g[O_WHERE + 3 * t, r]
    lx, ly = g[O_X + 3 * t, r], g[O_Y + 3 * t, r]
    sbx = m[OX, j] + (m[C, j] * lx - m[S, j] * ly)
    sby = m[OY, j] + (m[S, j] * lx + m[C, j] * ly)
    skx = mk[OX, j] + (mk[C, j] * lx - mk[S, j] * ly)
    sky = mk[OY, j] + (mk[S, j] * lx + mk[C, j] * ly)
    sx = lx if where == 0.0 else sbx if where == 1.0 else skx
    sy = ly if where == 0.0 else sby if where == 1.0 else sky
    ux, uy = d[10 + 4 * t, j], d[11 + 4 * t, j]
    nx, ny = -uy, ux
    fn = -(a[0, j] * nx + a[1, j] * ny)
    fx, fy = fn * nx, fn * ny
    cc = -(a[2, j] - ((sx - m[OX, j]) * a[1, j] - (sy - m[OY, j]) * a[0, j]))
    _add(ak, j, fx, fy, sx - mk[OX, j], sy - mk[OY, j], cc, -1.0)
    b = 4 + 6 * t
    rr[b + R_FX, j], rr[b + R_FY, j], rr[b + R_N, j] = fx, fy, fn
    rr[b + R_M, j], rr[b + R_SX, j], rr[b + R_SY, j] = cc, sx, sy


@body
def reaction_row(rot1, rot2, inner_r, j, r, g, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr):
    """A dyad's reactions at one row (:func:`_reactions_kernel`'s)."""
    sfirst = g[I_SFIRST, r] != 0.0
    # the generalised forces: moment about the outer pivot, or force along the guide
    q1 = _generalised(rot1, m1, a1, d, g, j, r, 0)
    q2 = _generalised(rot2, m2, a2, d, g, j, r, 1)
    c1x, c1y, c2x, c2y, det = d[C1X, j], d[C1Y, j], d[C2X, j], d[C2Y, j], d[DET, j]
    xx, xy = d[XX, j], d[XY, j]
    if inner_r:
        # c1 . R = Q1, c2 . R = -Q2 (eqs 2.17, 2.22, 2.26): R on body 2 from body 1
        rx = -((q1 * c2y + q2 * c1y) / det)
        ry = (c1x * q2 + c2x * q1) / det
        l1x, l1y, l2x, l2y = g[Q1X, r], g[Q1Y, r], g[Q2X, r], g[Q2Y, r]
        b1x, b1y = m1[C, j] * l1x - m1[S, j] * l1y, m1[S, j] * l1x + m1[C, j] * l1y
        b2x, b2y = m2[C, j] * l2x - m2[S, j] * l2y, m2[S, j] * l2x + m2[C, j] * l2y
        _add(a1, j, rx, ry, b1x, b1y, 0.0, -1.0)
        _add(a2, j, rx, ry, b2x, b2y, 0.0, 1.0)
        rr[R_FX, j], rr[R_FY, j] = rx, ry
    else:
        # [n.c_i, w_i] (N, M) = -sigma_i Q_i, sigma +1 on the slider, -1 on the guide
        nx, ny = d[NX, j], d[NY, j]
        e1, e2 = nx * c1x + ny * c1y, nx * c2x + ny * c2y
        w1 = 1.0 if rot1 else 0.0
        w2 = 1.0 if rot2 else 0.0
        s1, s2 = (1.0, -1.0) if sfirst else (-1.0, 1.0)
        dd = e1 * w2 - w1 * e2
        y1, y2 = -s1 * q1, -s2 * q2
        nn = (y1 * w2 - w1 * y2) / dd
        mm = (e1 * y2 - y1 * e2) / dd
        fx, fy = nn * nx, nn * ny
        ms, mg = (m1, m2) if sfirst else (m2, m1)
        as_, ag = (a1, a2) if sfirst else (a2, a1)
        lx, ly = g[I_SX, r], g[I_SY, r]
        sx, sy = ms[C, j] * lx - ms[S, j] * ly, ms[S, j] * lx + ms[C, j] * ly
        _add(as_, j, fx, fy, sx, sy, mm, 1.0)
        _add(ag, j, fx, fy, xx - mg[OX, j], xy - mg[OY, j], mm, -1.0)
        rr[R_FX, j], rr[R_FY, j], rr[R_N, j], rr[R_M, j] = fx, fy, nn, mm
    _outer(rot1, 0, g, r, j, m1, mk1, a1, ak1, d, rr)
    _outer(rot2, 1, g, r, j, m2, mk2, a2, ak2, d, rr)
    return nonfinite((rr[R_FX, j], rr[R_FY, j], rr[R_N, j], rr[R_M, j],
                a1[0, j], a1[1, j], a2[0, j], a2[1, j],
                rr[4, j], rr[5, j], rr[7, j], rr[10, j], rr[11, j], rr[13, j]))


def _reactions_kernel(kind: int, name: str):
    """The compiled reactions kernel of dyad kind ``kind`` (its code, layout.KINDS), the
    kind a constant of the kernel as in the motion's
    (:func:`~kinetostatics.solver.fast.kernels._motion_kernel`, its helper here
    :func:`reaction_tiles`: numba types and lowers it once for every kind)."""

    @jit_as(f"{name.lower()}_reactions")
    def dyad_reactions(lo, hi, off, g, gs, own, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr):
        """A dyad's joint reactions (seed 002 s. 2.3.1, eqs 2.16-2.43 in vector form,
        the numpy path's ``_solve_dyad``): the inner joint's from the two bodies'
        equations along their freedoms (a 2 x 2 system with the velocity system's
        columns), each outer joint's from its body's remaining equations; the outer
        reactions load the known bodies (``ak1``, ``ak2``) with opposite sign."""
        return reaction_tiles(not_literal(kind), lo, hi, off, g, gs, own, m1, m2, mk1, mk2, d,
                              a1, a2, ak1, ak2, rr)
    return dyad_reactions


@body
def reaction_tiles(kind, lo, hi, off, g, gs, own, m1, m2, mk1, mk2, d, a1, a2, ak1, ak2, rr):
    """A dyad kind's reactions kernel (:func:`_reactions_kernel`; ``kind`` its code, a
    constant of each kind's entry that LLVM folds, inlining this)."""
    rot1, rot2, inner_r = (kind & ROT1) != 0, (kind & ROT2) != 0, (kind & INNER_R) != 0
    # in tiles (jitbase.TILE), as the dyad's motion: the motions (their angle and
    # origin rows), the data and the dyad bodies' resultants in, the tile worked out
    # in the scratch array alone, the reactions and resultants out; what the outer
    # joints load the known bodies with is added to theirs after (in order: the same
    # array twice when both outer joints are on one body)
    w = scratch(4 * BODY_ROWS + DYAD_OUT + 12 + REACTION_ROWS + DYAD_GEOMETRY)
    wm1, wm2 = w[:BODY_ROWS], w[BODY_ROWS:2 * BODY_ROWS]
    wk1, wk2 = w[2 * BODY_ROWS:3 * BODY_ROWS], w[3 * BODY_ROWS:4 * BODY_ROWS]
    b = 4 * BODY_ROWS
    wd = w[b:b + DYAD_OUT]
    b += DYAD_OUT
    wa1, wa2, wak1, wak2 = w[b:b + 3], w[b + 3:b + 6], w[b + 6:b + 9], w[b + 9:b + 12]
    b += 12
    wr = w[b:b + REACTION_ROWS]
    wg = w[b + REACTION_ROWS:]
    bad, last, t0 = 0, -1, lo       # (last: the scene whose geometry the tile holds)
    while t0 < hi:
        nt, last = tile_next(wg, g, gs, own, t0, hi, last)     # (one scene's rows)
        j0, t0 = t0 - off, t0 + nt
        for wm, m in ((wm1, m1), (wm2, m2), (wk1, mk1), (wk2, mk2)):
            tile_in(wm[C:S + 1], m[C:S + 1], j0, nt)
            tile_in(wm[OX:OY + 1], m[OX:OY + 1], j0, nt)
        # (only the rows a kind reads: the closing point, the velocity system, the
        # normal; an outer prismatic joint's guide direction)
        tile_in(wd[:NY + 1], d[:NY + 1], j0, nt)
        if not rot1:
            tile_in(wd[10:12], d[10:12], j0, nt)
        if not rot2:
            tile_in(wd[14:16], d[14:16], j0, nt)
        tile_in(wa1, a1, j0, nt)
        tile_in(wa2, a2, j0, nt)
        wak1[:] = 0.0
        wak2[:] = 0.0
        for t in range(TILE):
            f = reaction_row(rot1, rot2, inner_r, t, t, wg, wm1, wm2, wk1, wk2, wd, wa1,
                             wa2, wak1, wak2, wr)
            bad += f if t < nt else 0
        tile_out(a1, wa1, j0, nt)
        tile_out(a2, wa2, j0, nt)
        if wg[P_GROUND, 0] == 0.0:
            tile_add(ak1, wak1, j0, nt)
        if wg[PARAM + P_GROUND, 0] == 0.0:
            tile_add(ak2, wak2, j0, nt)
        tile_out(rr[:4], wr[:4], j0, nt)
        if not rot1:
            tile_out(rr[4:10], wr[4:10], j0, nt)
        if not rot2:
            tile_out(rr[10:], wr[10:], j0, nt)
    return bad


@jit
def crank_reaction(lo, hi, off, g, gs, own, m, a, out):
    """The equilibrating moment on a crank, from the moments about its ground joint
    (seed 002 eqs 2.47-2.48); the ground reaction is the crank's resultant force."""
    bad = 0
    for i in range(lo, hi):
        j = i - off
        out[0, j] = crank_moment(j, own[i * gs], g, m, a)
        bad += nonfinite((out[0, j], a[0, j], a[1, j]))
    return bad


@body
def crank_moment(j, r, g, m, a):
    """:func:`crank_reaction`'s Me at row ``j`` (geometry column ``r``)."""
    lx, ly = g[D_LX, r], g[D_LY, r]
    ax, ay = m[C, j] * lx - m[S, j] * ly, m[S, j] * lx + m[C, j] * ly
    return -(a[2, j] - (ax * a[1, j] - ay * a[0, j]))


@jit
def slider_reaction(lo, hi, off, g, gs, own, m, a, out):
    """The equilibrating force on a sliding driver along its line, the guide's normal
    force and couple about the slider point (seed 002 eqs 2.49-2.51): rows Fe, N, M,
    the slider point's x, y and the normal force's Fx, Fy."""
    bad = 0
    for i in range(lo, hi):
        j, r = i - off, own[i * gs]
        ux, uy = g[T_RUX, r], g[T_RUY, r]
        lx, ly = g[T_SX, r], g[T_SY, r]
        if g[T_ON, r] != 0.0:
            ax, ay = m[C, j] * lx - m[S, j] * ly, m[S, j] * lx + m[C, j] * ly
            sx, sy = m[OX, j] + ax, m[OY, j] + ay
        else:
            sx, sy = lx, ly
            ax, ay = sx - m[OX, j], sy - m[OY, j]
        nx, ny = -uy, ux
        out[0, j] = -(a[0, j] * ux + a[1, j] * uy)
        out[1, j] = -(a[0, j] * nx + a[1, j] * ny)
        out[2, j] = -(a[2, j] - (ax * a[1, j] - ay * a[0, j]))
        out[3, j], out[4, j] = sx, sy
        out[5, j], out[6, j] = out[1, j] * nx, out[1, j] * ny
        bad += nonfinite((out[0, j], out[1, j], out[2, j]))
    return bad


# one compiled kernel per dyad kind (layout.KINDS)
REACTIONS = {name: _reactions_kernel(code, name) for name, code in KINDS.items()}

__all__ = ["REACTIONS", "body_loads", "crank_moment", "crank_reaction", "reaction_row",
           "slider_reaction", "swept_loads", "swept_row", "tile_loads", "tile_loads_for"]
