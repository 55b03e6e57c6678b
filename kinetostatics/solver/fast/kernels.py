"""The compiled kernels: the numpy path's formulas, row by row (numba).

Imported only by :func:`~kinetostatics.solver.fast.loader.kernels`, after the cache
folder is settled. Every kernel works on rows ``lo`` to ``hi`` of the sweep; the arrays
it reads and writes over the rows (motions, a dyad's data, load resultants) hold them at
``i - off`` (``off = 0``: arrays over the whole sweep; ``off = lo``: a block's scratch),
its geometry at ``i * gs`` (:mod:`~kinetostatics.solver.fast.layout`). Each returns the
number of rows where it wrote a value that is not finite, or where the numpy path would
refuse the row (the links do not reach, a dead centre, coincident pivots): the caller
then solves on the numpy path, whose message names the rows.

Rules (measured on a prototype): ``error_model="numpy"`` (a division by zero gives an
infinity, as numpy's, counted), sin and cos in a pass of their own, no ``fastmath`` (the
numbers stay IEEE), no ``prange`` (the executors spread scenes over processes).
A dyad's kernels have one entry point per kind (:data:`MOTION`, :data:`REACTIONS`), each
made from one source by a factory (:func:`_motion_kernel`): the kind a constant in each,
its other kinds' branches folded away.
"""

from __future__ import annotations

import math

from .closure_kernels import close_prismatic, close_revolute, rtr_guide_angle
from .jitbase import (
    TILE,
    body,
    fmin,
    jit,
    jit_as,
    nonfinite,
    not_literal,
    scratch,
    tile_in,
    tile_next,
    tile_out,
)
from .layout import (
    AL,
    ASSEMBLY,
    AX,
    AY,
    C1X,
    C1Y,
    C2X,
    C2Y,
    CL2,
    D_LX,
    D_LY,
    D_PX,
    D_PY,
    DET,
    DYAD_GEOMETRY,
    DYAD_OUT,
    G1,
    G2,
    I_CB,
    I_SB,
    I_SFIRST,
    I_SX,
    I_SY,
    INNER_R,
    KINDS,
    NORM2,
    NX,
    NY,
    OM,
    OX,
    OY,
    P_BX,
    P_BY,
    P_CB,
    P_GK,
    P_KX,
    P_KY,
    P_SB,
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
    VX,
    VY,
    XX,
    XY,
    C,
    S,
)
from .layout import MOTION as BODY_ROWS
from .load_kernels import body_loads, swept_loads
from .reaction_kernels import REACTIONS, crank_reaction, slider_reaction
from .table_kernels import point_rows
from .trig_kernels import turn_rows

SINGULAR_WARN2 = 1e-6       # (1e-3)^2: kinematics.SINGULAR_WARN squared
SINGULAR_FAIL2 = 1e-24      # (1e-12)^2
SINGULAR_FAIL = 1e-12


# -- the driver (seed 000 ch. 4) ---------------------------------------------------------
@jit
def crank_motion(theta, lo, hi, off, g, gs, own, w, eps, m):
    """A crank turning about its ground joint P: o = P - R a, v_o = omega k x (o - P),
    a_o = eps k x (o - P) - omega^2 (o - P) (seed 000 ch. 4; the numpy path's
    ``driver_motion``). Its cos and sin (rows C, S of ``m``) are worked out before, in a
    pass of their own (numpy's, vectorised: the numpy path's numbers)."""
    bad = 0
    for i in range(lo, hi):
        bad += crank_row(i - off, own[i * gs], g, w, eps, m)
    return bad


@body
def crank_row(j, r, g, w, eps, m):
    """:func:`crank_motion` at row ``j`` of ``m`` (geometry column ``r``); 1 if not
    finite."""
    w2 = w * w
    c, s = m[C, j], m[S, j]
    lx, ly = g[D_LX, r], g[D_LY, r]
    rax, ray = c * lx - s * ly, s * lx + c * ly
    m[OM, j] = w
    m[AL, j] = eps
    m[OX, j] = g[D_PX, r] - rax
    m[OY, j] = g[D_PY, r] - ray
    m[VX, j] = w * ray
    m[VY, j] = -w * rax
    m[AX, j] = eps * ray + w2 * rax
    m[AY, j] = -eps * rax + w2 * ray
    return nonfinite((c, s, m[OX, j], m[OY, j], m[AX, j], m[AY, j]))


@jit
def slider_motion(pos, lo, hi, off, g, gs, own, w, eps, m):
    """A slider on a ground guide (or carrying a guide along a ground point): its origin
    moves along the line, o = L + sign s u - R a (seed 000 ch. 4)."""
    bad = 0
    for i in range(lo, hi):
        j, r = i - off, own[i * gs]
        sign = g[T_SIGN, r]
        ux, uy = g[T_UX, r], g[T_UY, r]
        v, a = sign * w, sign * eps
        m[C, j] = g[T_C, r]
        m[S, j] = g[T_S, r]
        m[OM, j] = 0.0
        m[AL, j] = 0.0
        m[OX, j] = sign * ux * pos[i] + (g[T_LX, r] - g[T_RX, r])
        m[OY, j] = sign * uy * pos[i] + (g[T_LY, r] - g[T_RY, r])
        m[VX, j] = v * ux
        m[VY, j] = v * uy
        m[AX, j] = a * ux
        m[AY, j] = a * uy
        bad += nonfinite((m[OX, j], m[OY, j]))
    return bad


# -- a dyad's kinematics (seed 000 ch. 5-12) ---------------------------------------------
@body
def outer_param(rot, k, j, g, r, base):
    """A dyad body's parameter through its outer joint (the numpy path's ``dyad_param``):
    rot, the known body's point P with its velocity and acceleration; trans, the body's
    angle (c, s), the guide's direction u and the line's base point b."""
    kc, ks = k[C, j], k[S, j]
    lx, ly = g[base + P_KX, r], g[base + P_KY, r]
    rx, ry = kc * lx - ks * ly, ks * lx + kc * ly
    px, py = k[OX, j] + rx, k[OY, j] + ry
    if rot:
        om, al = k[OM, j], k[AL, j]
        w2 = om * om
        return (px, py, k[VX, j] - om * ry, k[VY, j] + om * rx,
                (k[AX, j] - al * ry) - w2 * rx, (k[AY, j] + al * rx) - w2 * ry)
    cb, sb = g[base + P_CB, r], g[base + P_SB, r]
    c, s = kc * cb - ks * sb, ks * cb + kc * sb
    bx, by = g[base + P_BX, r], g[base + P_BY, r]
    if g[base + P_GK, r] != 0.0:
        ux, uy = c, s
    else:
        ux, uy = kc, ks
    return c, s, ux, uy, px - (c * bx - s * by), py - (s * bx + c * by)


@body
def ground_param(rot, ground, k, j, g, r, base):
    """:func:`outer_param`, of an outer joint whose known body is the ground (``ground``)
    from its geometry alone: the ground's cos 1 and sin 0, origin 0 (0 + (1 lx - 0 ly) is
    0 + lx for a finite lx, and so on: the same doubles); a revolute one's pivot at rest
    (its velocity 0 - 0 ry and acceleration (0 - 0 ry) - 0 rx are +0 for finite rows)."""
    if not ground:
        return outer_param(rot, k, j, g, r, base)
    lx, ly = g[base + P_KX, r], g[base + P_KY, r]
    if rot:
        return 0.0 + lx, 0.0 + ly, 0.0, 0.0, 0.0, 0.0
    cb, sb = g[base + P_CB, r], g[base + P_SB, r]
    c, s = cb - 0.0 * sb, 0.0 * cb + sb
    bx, by = g[base + P_BX, r], g[base + P_BY, r]
    if g[base + P_GK, r] != 0.0:
        ux, uy = c, s
    else:
        ux, uy = 1.0, 0.0
    px, py = 0.0 + lx, 0.0 + ly
    return c, s, ux, uy, px - (c * bx - s * by), py - (s * bx + c * by)


@body
def _vel_at(k, j, x, y):
    """Velocity of the known body's point at the global (x, y)."""
    om = k[OM, j]
    return k[VX, j] - om * (y - k[OY, j]), k[VY, j] + om * (x - k[OX, j])


@body
def _vel_known(ground, k, j, x, y):
    """:func:`_vel_at`, 0 on the ground (``ground``: 0 - 0 (y - 0) is +0 for a finite y;
    a row that is not finite is counted)."""
    if ground:
        return 0.0, 0.0
    return _vel_at(k, j, x, y)


@body
def _acc_known(ground, k, j, x, y):
    """:func:`_acc_at`, 0 on the ground (as :func:`_vel_known`)."""
    if ground:
        return 0.0, 0.0
    return _acc_at(k, j, x, y)


@body
def _acc_at(k, j, x, y):
    """Acceleration of the known body's point at (x, y) (seed 001 eq. 9)."""
    rx, ry = x - k[OX, j], y - k[OY, j]
    om, al = k[OM, j], k[AL, j]
    w2 = om * om
    return (k[AX, j] - al * ry) - w2 * rx, (k[AY, j] + al * rx) - w2 * ry


@body
def _origin(rot, p, c, s, lx, ly, q):
    """A dyad body's origin (``body_origin``): P - R a (rot) or b + s u (trans)."""
    if rot:
        return p[0] - (c * lx - s * ly), p[1] - (s * lx + c * ly)
    return p[4] + q * p[2], p[5] + q * p[3]


@body
def _column(rot, ground, p, k1, j, xx, xy):
    """The column c_i of the velocity system, the known part k_i of the velocity of the
    body's point at X and the angular weight w_i."""
    if rot:
        return p[1] - xy, xx - p[0], p[2], p[3], 1.0
    kx, ky = _vel_known(ground, k1, j, xx, xy)
    return p[2], p[3], kx, ky, 0.0


@body
def _body(rot, ground, p, kb, j, c, s, lx, ly, ox, oy, qd, qdd, m, jo):
    """A dyad body's motion from its unknown's rate and acceleration (``_body_motion``)."""
    m[C, jo], m[S, jo], m[OX, jo], m[OY, jo] = c, s, ox, oy
    if rot:
        rax, ray = c * -lx - s * -ly, s * -lx + c * -ly
        w2 = qd * qd
        m[OM, jo], m[AL, jo] = qd, qdd
        m[VX, jo] = p[2] - qd * ray
        m[VY, jo] = p[3] + qd * rax
        m[AX, jo] = (p[4] - qdd * ray) - w2 * rax
        m[AY, jo] = (p[5] + qdd * rax) - w2 * ray
        return
    om = kb[OM, j]
    vkx, vky = _vel_known(ground, kb, j, ox, oy)
    akx, aky = _acc_known(ground, kb, j, ox, oy)
    f = 2.0 * om * qd
    m[OM, jo], m[AL, jo] = om, kb[AL, j]
    m[VX, jo], m[VY, jo] = vkx + qd * p[2], vky + qd * p[3]
    m[AX, jo] = (akx + qdd * p[2]) - f * p[3]
    m[AY, jo] = (aky + qdd * p[3]) + f * p[2]


def _motion_kernel(kind: int, name: str):
    """The compiled motion kernel of dyad kind ``kind`` (its code, layout.KINDS): the
    kind a constant of the kernel (a closure's cell, frozen by numba; each cached apart,
    its cell's value in the key), its other kinds' branches folded away. The kernel is
    :func:`motion_tiles` with the kind's code: that helper is typed and lowered by numba
    once for every kind, each kind's entry then costs little more than LLVM's work on it
    (numba's own typing and lowering was about half of an entry's compile: measured
    2026-11-30, an empty cache, the helpers compiled on the four-bar first, the six
    other kinds' entries compiled, processor time at a load of 8-10: motion 2.0-2.5 s
    an entry -> 0.65-0.92, reactions (:func:`reaction_tiles`, the same way) 3.3-4.4 s ->
    1.3-2.0; in all 36.1 s -> 13.5. The machine code alike: the RRR, RRT, RTR entries'
    vector multiplies as many, their instructions within 2 %; the solves' arrays bit
    for bit)."""

    @jit_as(f"{name.lower()}_motion")
    def dyad_motion(stage, lo, hi, off, g, gs, own, k1, k2, m1, m2, d):
        """Positions, velocities and accelerations of a dyad (seed 000 ch. 5-12, the numpy
        path's ``solve_dyad``): its bodies' motions into ``m1``, ``m2`` and its data
        (closing point, velocity system, closeness to a dead centre, parameters) into
        ``d``. Counts the rows that are not finite, cannot close, or are exactly
        singular. ``stage`` 0: RTR's guide angle only (nothing for the other kinds); 1:
        the rest."""
        return motion_tiles(not_literal(kind), stage, lo, hi, off, g, gs, own, k1, k2, m1, m2,
                            d)
    return dyad_motion


@body
def motion_tiles(kind, stage, lo, hi, off, g, gs, own, k1, k2, m1, m2, d):
    """A dyad kind's motion kernel (:func:`_motion_kernel`; ``kind`` its code, a constant
    of each kind's entry that LLVM folds, inlining this)."""
    rot1, rot2, inner_r = (kind & ROT1) != 0, (kind & ROT2) != 0, (kind & INNER_R) != 0
    rtr = rot1 and rot2 and not inner_r
    if stage == 0:
        return rtr_stage(rtr, lo, hi, off, g, gs, own, k1, k2, d)
    # in tiles (jitbase.TILE): the known bodies' motions (and RTR's guide) in,
    # the tile worked out in the scratch array alone, the bodies' motions and the
    # data out
    w = scratch(4 * BODY_ROWS + DYAD_OUT + DYAD_GEOMETRY)
    wk1, wk2 = w[:BODY_ROWS], w[BODY_ROWS:2 * BODY_ROWS]
    wm1, wm2 = w[2 * BODY_ROWS:3 * BODY_ROWS], w[3 * BODY_ROWS:4 * BODY_ROWS]
    wd = w[4 * BODY_ROWS:4 * BODY_ROWS + DYAD_OUT]
    wg = w[4 * BODY_ROWS + DYAD_OUT:]
    bad, last, t0 = 0, -1, lo       # (last: the scene whose geometry the tile holds)
    while t0 < hi:
        nt, last = tile_next(wg, g, gs, own, t0, hi, last)     # (one scene's rows)
        j0, t0 = t0 - off, t0 + nt
        tile_in(wk1, k1, j0, nt)
        tile_in(wk2, k2, j0, nt)
        if rtr:
            tile_in(wd[XX:XX + 1], d[XX:XX + 1], j0, nt)
            tile_in(wd[C1X:C1Y + 1], d[C1X:C1Y + 1], j0, nt)
            tile_in(wd[CL2:CL2 + 1], d[CL2:CL2 + 1], j0, nt)
        for t in range(TILE):
            b = dyad_row(kind, rot1, rot2, inner_r, rtr, t, t, wg, wk1, wk2, wm1, wm2, wd)
            bad += b if t < nt else 0
        tile_out(m1, wm1, j0, nt)
        tile_out(m2, wm2, j0, nt)
        tile_out(d[:CL2 + 1], wd[:CL2 + 1], j0, nt)
        # each side's parameter: P (rot), or the guide's u and the line's base point
        tile_out(d[10:12 if rot1 else 14], wd[10:12 if rot1 else 14], j0, nt)
        tile_out(d[14:16 if rot2 else 18], wd[14:16 if rot2 else 18], j0, nt)
    return bad


@body
def rtr_stage(rtr, lo, hi, off, g, gs, own, k1, k2, d):
    """A dyad's stage 0: RTR's guide angle's cos and sin (rows C1X, C1Y), the pivots'
    distance and the gap (rows CL2, XX: :func:`rtr_guide_angle`), read by stage 1; nothing
    for the other kinds."""
    if rtr:
        for i in range(lo, hi):
            j, r = i - off, own[i * gs]
            p1 = outer_param(True, k1, j, g, r, 0)
            p2 = outer_param(True, k2, j, g, r, PARAM)
            d[C1X, j], d[C1Y, j], d[CL2, j], d[XX, j] = rtr_guide_angle(p1, p2, g, r,
                                                                        g[ASSEMBLY, r])
    return 0


@body
def _closeness(inner_r, rtr, rot1, det, p1, p2, ux, uy, norm2, reach, gap, size):
    """A dyad row's closeness to a dead centre, min(sin^2 tau, (pivots' distance /
    size)^2) (the numpy path's ``closeness2``), and 1 for each way the numpy path would
    refuse the row (the links do not reach, a gap, exactly singular)."""
    if inner_r:
        sin2 = det * det / norm2
    else:
        if rtr:
            dx, dy = p1[0] - p2[0], p1[1] - p2[1]
            st = (ux * dx + uy * dy) / math.sqrt(dx * dx + dy * dy)
        else:
            pt = p2 if rot1 else p1
            st = ux * pt[3] - uy * pt[2]
        sin2 = st * st
    bad = 0
    if reach >= 0.0:
        rs = reach / size
        sin2 = fmin(sin2, rs * rs) if sin2 == sin2 else sin2
        bad += 0 if rs > SINGULAR_FAIL else 1
    bad += 0 if gap <= 1e-9 * size else 1
    bad += 0 if sin2 > SINGULAR_FAIL2 else 1
    return sin2, bad


@body
def _known_acc(rot, ground, p, k, j, xx, xy, qd, cx, cy):
    """The known part of the closing point's acceleration on one side of the dyad (the
    acceleration system's right-hand side, seed 000 ch. 5-12): centripetal about a
    rotation's pivot, or the guide's motion plus Coriolis (seed 001 eq. 8)."""
    if rot:
        ww = qd * qd
        return p[4] - ww * cy, p[5] + ww * cx
    kax, kay = _acc_known(ground, k, j, xx, xy)
    f = 2.0 * k[OM, j] * qd
    return kax - f * p[3], kay + f * p[2]


@body
def _store_param(d, j, b, p, rot):
    """A side's parameter into the dyad's data (rows 10.. and 14..): P (rot), or the
    guide's u and the line's base point (trans). One call per side: a loop over a tuple
    of both, its ``rot`` known at run time, kept LLVM from vectorising RRT and the like."""
    if rot:
        d[b, j], d[b + 1, j] = p[0], p[1]
    else:
        d[b, j], d[b + 1, j], d[b + 2, j], d[b + 3, j] = p[2], p[3], p[4], p[5]


@body
def dyad_row(kind, rot1, rot2, inner_r, rtr, j, r, g, k1, k2, m1, m2, d):
    size = g[SIZE, r]
    kk = g[ASSEMBLY, r]
    # (a fused kernel's ground bits: an outer joint's known body the ground, its motion
    # the constants it is, layout.G1, G2: a prismatic one's in the fused kernels, either
    # kind's in the guide's, guide_kernels.AFTER_RTR_ON)
    ground1, ground2 = (kind & G1) != 0, (kind & G2) != 0
    p1 = ground_param(rot1, ground1, k1, j, g, r, 0)
    p2 = ground_param(rot2, ground2, k2, j, g, r, PARAM)
    reach = -1.0
    gap = -1.0
    if inner_r:
        c1, s1, c2, s2, q1, q2, reach, gap = close_revolute(kind, p1, p2, g, r, kk)
    else:
        th = (d[C1X, j], d[C1Y, j])
        if rtr:
            reach, gap = d[CL2, j], d[XX, j]
        c1, s1, c2, s2, q1, q2 = close_prismatic(kind, p1, p2, g, r, kk, th)
    o1x, o1y = _origin(rot1, p1, c1, s1, g[P_BX, r], g[P_BY, r], q1)
    o2x, o2y = _origin(rot2, p2, c2, s2, g[PARAM + P_BX, r], g[PARAM + P_BY, r], q2)
    # the closing point X: the inner joint's point (prismatic: the slider's point)
    sfirst = g[I_SFIRST, r] != 0.0
    if inner_r or sfirst:
        lx, ly = (g[Q1X, r], g[Q1Y, r]) if inner_r else (g[I_SX, r], g[I_SY, r])
        xx, xy = o1x + (c1 * lx - s1 * ly), o1y + (s1 * lx + c1 * ly)
    else:
        lx, ly = g[I_SX, r], g[I_SY, r]
        xx, xy = o2x + (c2 * lx - s2 * ly), o2y + (s2 * lx + c2 * ly)
    c1x, c1y, k1x, k1y, w1 = _column(rot1, ground1, p1, k1, j, xx, xy)
    c2x, c2y, k2x, k2y, w2 = _column(rot2, ground2, p2, k2, j, xx, xy)
    nx = ny = ux = uy = 0.0
    if inner_r:
        a11, b12, a21, b22 = c1x, c2x, c1y, c2y
        r1, r2 = k2x - k1x, k2y - k1y
    else:
        cg, sg = (c2, s2) if sfirst else (c1, s1)
        cb, sb = g[I_CB, r], g[I_SB, r]
        ux, uy = cg * cb - sg * sb, sg * cb + cg * sb
        nx, ny = -uy, ux
        om01 = 0.0 if rot1 else k1[OM, j]
        om02 = 0.0 if rot2 else k2[OM, j]
        r1 = om02 - om01
        r2 = nx * (k2x - k1x) + ny * (k2y - k1y)
        a11, b12 = w1, w2
        a21, b22 = nx * c1x + ny * c1y, nx * c2x + ny * c2y
    det = b12 * a21 - a11 * b22
    sin2, bad = _closeness(inner_r, rtr, rot1, det, p1, p2, ux, uy, g[NORM2, r], reach,
                           gap, size)
    qd1 = (b12 * r2 - r1 * b22) / det
    qd2 = (a11 * r2 - r1 * a21) / det
    # the acceleration system's right-hand side (centripetal and Coriolis terms)
    ka1x, ka1y = _known_acc(rot1, ground1, p1, k1, j, xx, xy, qd1, c1x, c1y)
    ka2x, ka2y = _known_acc(rot2, ground2, p2, k2, j, xx, xy, qd2, c2x, c2y)
    if inner_r:
        ra1, ra2 = ka2x - ka1x, ka2y - ka1y
    else:
        al01 = 0.0 if rot1 else k1[AL, j]
        al02 = 0.0 if rot2 else k2[AL, j]
        ra1 = al02 - al01
        v1x, v1y = k1x + c1x * qd1, k1y + c1y * qd1
        v2x, v2y = k2x + c2x * qd2, k2y + c2y * qd2
        sgn = 1.0 if sfirst else -1.0
        rdot = sgn * (ux * (v1x - v2x) + uy * (v1y - v2y))
        if sfirst:
            om_g = qd2 if rot2 else k2[OM, j]
        else:
            om_g = qd1 if rot1 else k1[OM, j]
        # n.(a_slider - a_guide) = 2 omega_g rdot (Coriolis, seed 001 eq. 8)
        ra2 = 2.0 * sgn * (om_g * rdot) - (nx * (ka1x - ka2x) + ny * (ka1y - ka2y))
    qdd1 = (b12 * ra2 - ra1 * b22) / det
    qdd2 = (a11 * ra2 - ra1 * a21) / det
    _body(rot1, ground1, p1, k1, j, c1, s1, g[P_BX, r], g[P_BY, r], o1x, o1y, qd1, qdd1, m1, j)
    _body(rot2, ground2, p2, k2, j, c2, s2, g[PARAM + P_BX, r], g[PARAM + P_BY, r], o2x, o2y,
          qd2, qdd2, m2, j)
    d[XX, j], d[XY, j] = xx, xy
    d[C1X, j], d[C1Y, j], d[C2X, j], d[C2Y, j], d[DET, j] = c1x, c1y, c2x, c2y, det
    d[NX, j], d[NY, j], d[CL2, j] = nx, ny, sin2
    _store_param(d, j, 10, p1, rot1)
    _store_param(d, j, 14, p2, rot2)
    bad += nonfinite((m1[AX, j], m1[AY, j], m1[AL, j], m2[AX, j], m2[AY, j], m2[AL, j], xx, xy))
    return bad


# one compiled kernel per dyad kind (layout.KINDS), motion and reactions
MOTION = {name: _motion_kernel(code, name) for name, code in KINDS.items()}


def tile_motion_for(width: int):
    """``tile_motion(kind, rot1, rot2, inner_r, nt, wgd, w, eps, wdrv, wg, wk1, wk2, wm1,
    wm2, wd)``: a tile's motion (tiles of ``width`` rows), the crank's
    (:func:`~kinetostatics.solver.fast.kernels.crank_row`, its cos and sin in ``wdrv``
    already) then the dyad's (:func:`~kinetostatics.solver.fast.kernels.dyad_row`), each
    a loop over the whole tile (a constant count: it vectorises); the count of the
    first ``nt`` rows that are not finite. (``solve_many``'s fused kernels work out the
    same two loops in tiles of ``FUSED_TILE`` rows.)"""
    @body
    def tile_motion(kind, rot1, rot2, inner_r, nt, wgd, w, eps, wdrv, wg, wk1, wk2, wm1, wm2,
                    wd):
        bad = 0
        for t in range(width):
            f = crank_row(t, t, wgd, w, eps, wdrv)
            bad += f if t < nt else 0
        for t in range(width):
            f = dyad_row(kind, rot1, rot2, inner_r, False, t, t, wg, wk1, wk2, wm1, wm2, wd)
            bad += f if t < nt else 0
        return bad
    return tile_motion


__all__ = ["MOTION", "REACTIONS", "tile_motion_for", "body_loads", "swept_loads", "crank_motion",
           "crank_reaction", "slider_motion", "slider_reaction", "point_rows", "turn_rows"]
