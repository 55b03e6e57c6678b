"""The compiled closures of a dyad's inner joint, row by row (numba): the numpy path's
``DyadSolver._inner_r`` and ``_inner_t`` (:mod:`kinetostatics.solver.closure`) and the RTR
guide's angle, each with its seed equation. Inlined into the dyads' kernels
(:mod:`~kinetostatics.solver.fast.kernels`) by LLVM.
"""

from __future__ import annotations

import math

from .jitbase import body, fmax, fmin
from .layout import (
    I_CB,
    I_LX,
    I_LY,
    I_RTR,
    I_SB,
    I_SFIRST,
    I_SX,
    I_SY,
    P_BX,
    P_BY,
    PARAM,
    Q1X,
    Q1Y,
    Q2X,
    Q2Y,
    ROT1,
    ROT2,
    W1X,
    W1Y,
    W2X,
    W2Y,
)


@body
def rot_angle(dx, dy, wx, wy):
    """cos, sin of the angle that turns the local vector l onto (dx, dy) (|d| = |l|),
    given (wx, wy) = l / |l|^2."""
    return dx * wx + dy * wy, dy * wx - dx * wy


@body
def close_revolute(kind, p1, p2, g, r, k):
    """A revolute inner joint closed (the numpy path's ``DyadSolver._inner_r``): each
    body's (cos, sin), the displacements, the reach and the gap (> 0: cannot close)."""
    rot1, rot2 = (kind & ROT1) != 0, (kind & ROT2) != 0
    q1x, q1y, q2x, q2y = g[Q1X, r], g[Q1Y, r], g[Q2X, r], g[Q2Y, r]
    a1x = q1x - g[P_BX, r] if rot1 else q1x
    a1y = q1y - g[P_BY, r] if rot1 else q1y
    a2x = q2x - g[PARAM + P_BX, r] if rot2 else q2x
    a2y = q2y - g[PARAM + P_BY, r] if rot2 else q2y
    if rot1 and rot2:
        # circle-circle (RRR, seed 000 eq. 5.1): Q = P1 + x e + k h J e
        r1s, r2s = a1x * a1x + a1y * a1y, a2x * a2x + a2y * a2y
        ex, ey = p2[0] - p1[0], p2[1] - p1[1]
        d2 = ex * ex + ey * ey
        reach = math.sqrt(d2)
        inv = 1.0 / reach
        x = (d2 + (r1s - r2s)) * (0.5 * inv)
        h2 = r1s - x * x
        gap = -1.0
        if not h2 >= 0.0:
            r1, r2 = math.sqrt(r1s), math.sqrt(r2s)
            gap = fmax(reach - (r1 + r2), abs(r1 - r2) - reach)
        kh = (k * inv) * math.sqrt(fmax(h2, 0.0))
        xi = x * inv
        tx, ty = xi * ex - kh * ey, xi * ey + kh * ex
        c1, s1 = rot_angle(tx, ty, g[W1X, r], g[W1Y, r])
        c2, s2 = rot_angle((p1[0] + tx) - p2[0], (p1[1] + ty) - p2[1], g[W2X, r], g[W2Y, r])
        return c1, s1, c2, s2, 0.0, 0.0, reach, gap
    if not rot1 and not rot2:
        # line-line (TRT, seed 000 ch. 10): Q01 + s1 u1 = Q02 + s2 u2
        q01x = p1[4] + (p1[0] * q1x - p1[1] * q1y)
        q01y = p1[5] + (p1[1] * q1x + p1[0] * q1y)
        q02x = p2[4] + (p2[0] * q2x - p2[1] * q2y)
        q02y = p2[5] + (p2[1] * q2x + p2[0] * q2y)
        rx, ry = q02x - q01x, q02y - q01y
        det = p1[3] * p2[2] - p1[2] * p2[3]
        s1 = (ry * p2[2] - rx * p2[3]) / det
        s2 = (p1[2] * ry - p1[3] * rx) / det
        return p1[0], p1[1], p2[0], p2[1], s1, s2, -1.0, -1.0
    # circle-line (RRT / TRR, seed 000 ch. 9 and 8)
    pr, pt = (p1, p2) if rot1 else (p2, p1)
    arx, ary = (a1x, a1y) if rot1 else (a2x, a2y)
    qx, qy = (q2x, q2y) if rot1 else (q1x, q1y)
    rs = arx * arx + ary * ary
    q0x = pt[4] + (pt[0] * qx - pt[1] * qy)
    q0y = pt[5] + (pt[1] * qx + pt[0] * qy)
    wx, wy = q0x - pr[0], q0y - pr[1]
    ux, uy = pt[2], pt[3]
    b = ux * wx + uy * wy
    disc = b * b - (wx * wx + wy * wy) + rs
    gap = -1.0
    if not disc >= 0.0:
        gap = abs(ux * wy - uy * wx) - math.sqrt(rs)
    s = k * math.sqrt(fmax(disc, 0.0)) - b
    cr, sr = rot_angle(wx + s * ux, wy + s * uy, g[W1X, r] if rot1 else g[W2X, r],
                        g[W1Y, r] if rot1 else g[W2Y, r])
    if rot1:
        return cr, sr, pt[0], pt[1], 0.0, s, -1.0, gap
    return pt[0], pt[1], cr, sr, s, 0.0, -1.0, gap


@body
def close_prismatic(kind, p1, p2, g, r, k, th):
    """A prismatic inner joint closed (``DyadSolver._inner_t``): RTR from the angle
    ``th`` of the guide (worked out in a pass before, with its cos and sin), RTT and TTR
    from the other body's angle."""
    rot1, rot2 = (kind & ROT1) != 0, (kind & ROT2) != 0
    sfirst = g[I_SFIRST, r] != 0.0
    ps, pg = (p1, p2) if sfirst else (p2, p1)
    rots = rot1 if sfirst else rot2
    cb, sb = g[I_CB, r], g[I_SB, r]
    slx, sly = g[I_SX, r], g[I_SY, r]
    llx, lly = g[I_LX, r], g[I_LY, r]
    bs = 0 if sfirst else PARAM             # the slider's parameter rows
    bg = PARAM - bs
    if rot1 and rot2:
        cg, sg = th[0], th[1]
        cs_, ss_ = cg * cb - sg * sb, sg * cb + cg * sb
        s = 0.0
    elif rots:
        # RTT: the slider's angle is the guide's + beta; its point stays on the line
        cs_, ss_ = pg[0] * cb - pg[1] * sb, pg[1] * cb + pg[0] * sb
        ax_, ay_ = slx - g[bs + P_BX, r], sly - g[bs + P_BY, r]
        sx = ps[0] + (cs_ * ax_ - ss_ * ay_)
        sy = ps[1] + (ss_ * ax_ + cs_ * ay_)
        l0x = pg[4] + (pg[0] * llx - pg[1] * lly)
        l0y = pg[5] + (pg[1] * llx + pg[0] * lly)
        den = cs_ * pg[3] - ss_ * pg[2]
        s = (cs_ * (sy - l0y) - ss_ * (sx - l0x)) / den
        cg, sg = pg[0], pg[1]
    else:
        # TTR: the guide's angle is the slider's - beta
        cg, sg = ps[0] * cb + ps[1] * sb, ps[1] * cb - ps[0] * sb
        ax_, ay_ = llx - g[bg + P_BX, r], lly - g[bg + P_BY, r]
        lx = pg[0] + (cg * ax_ - sg * ay_)
        ly = pg[1] + (sg * ax_ + cg * ay_)
        ux, uy = ps[0], ps[1]
        s0x = ps[4] + (ps[0] * slx - ps[1] * sly)
        s0y = ps[5] + (ps[1] * slx + ps[0] * sly)
        den = ux * ps[3] - uy * ps[2]
        s = -(ux * (s0y - ly) - uy * (s0x - lx)) / den
        cs_, ss_ = ps[0], ps[1]
    if sfirst:
        return cs_, ss_, cg, sg, s if not rots else 0.0, s if rots else 0.0
    return cg, sg, cs_, ss_, s if rots else 0.0, s if not rots else 0.0


@body
def rtr_guide_angle(p1, p2, g, r, k):
    """RTR (seed 000 ch. 6-7): the guide's angle theta_g = delta - beta + side, with
    delta the direction of D (the guide's pivot to the slider's) and sin(side) = -+c/|D|,
    as its cos and sin (no angle worked out: delta's cos and sin are D / |D|, each turn
    a rotation), the pivots' distance |D| and the gap."""
    sfirst = g[I_SFIRST, r] != 0.0
    ps, pg = (p1, p2) if sfirst else (p2, p1)
    c = g[I_RTR, r]
    dx, dy = ps[0] - pg[0], ps[1] - pg[1]
    dn = math.sqrt(dx * dx + dy * dy)
    y = -c / dn
    gap = -1.0
    if not abs(y) <= 1.0:
        gap = abs(c) - dn if y == y else math.inf
    # x = asin(y) as its cos and sin (x in [-pi/2, pi/2]: cos x >= 0); a slot through the
    # guide's pivot (c = 0, the shaper's and the slotted lever's): y = +-0, cos x = 1
    sx = fmin(fmax(y, -1.0), 1.0)
    cx = math.sqrt((1.0 - sx) * (1.0 + sx))
    # delta - beta: D / |D| turned by -beta. (Measured 2026-11-30, the shaper's solve on
    # the compiled path, processor time, best of 7 at a load of 7: 171 -> 134 ns a row at
    # 2e5 rows, 150 -> 119 at 1e6, against atan2 and libm's cos and sin of the angle)
    ux, uy = dx / dn, dy / dn
    cb, sb = g[I_CB, r], g[I_SB, r]
    ca, sa = ux * cb + uy * sb, uy * cb - ux * sb
    if k > 0:           # side = -x
        return ca * cx + sa * sx, sa * cx - ca * sx, dn, gap
    # side = x - pi
    return -(ca * cx - sa * sx), -(sa * cx + ca * sx), dn, gap
