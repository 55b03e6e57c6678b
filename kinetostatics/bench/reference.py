"""The speed baseline: closed forms of a four-bar, a slider-crank and a shaper, written by
hand.

The yardstick ``python -m kinetostatics bench`` times the solver against: what a
careful engineer writes for one mechanism, vectorised with numpy, with no structure
analysis, no checks and no tables. It shares no code with the solver; the tests compare
it with :func:`kinetostatics.solve` on the same mechanisms (``bench.accuracy``'s
``fourbar_scene`` and ``slider_crank_reference_scene``), and its Me closes the virtual
power balance.

Conventions: planar, z out of the page, counter-clockwise positive, the crank A-B turns
about A = (0, 0) at a constant speed ``w2`` (rad/s, alpha2 = 0), ``th`` its angle (rad).

* four-bar: A-B crank ``a``, B-C coupler ``b``, D-C rocker ``c``, D = (d, 0); the branch
  with C to the left of B->D (the bundled ``four_bar``'s); cogs at mid-links; a force
  ``P`` at C on the rocker.
* slider-crank: A-B crank ``r``, B-C rod ``l``, the piston's pin C on the x axis; cogs
  at mid-links and at C.
* shaper (the bundled ``shaper``, its own frame and names): crank O2-A ``r`` about
  O2 = (0, ``h2``), a block at A sliding in the slotted lever O4-E (``L``, O4 = (0, 0)),
  the link E-F ``l``, the ram's pin F on the line y = ``hr``; cogs at mid-crank, at A,
  at mid-lever, mid-link and ``c6`` ahead of F on the ram; gravity; a force ``P`` on
  the ram (at T, which moves with it) while the ram moves against it.

Forces ``F_ij`` are of body i on body j (1 the ground, 2 the crank, 3 the coupler or
rod, 4 the rocker or piston; the shaper's 3 the block, 4 the lever, 5 the link, 6 the
ram): ``FA`` = F12, ``FB`` = F23, ``FC`` = F34, ``FD`` = F14;
``Me`` the moment of the motor on the crank. Each body's equilibrium is written with its
d'Alembert inertia loads, -m a at the cog and -I alpha (seed 002 s. 2.6: the dyad's
reactions from the moment equations about its joints, solved by Cramer's rule).
"""

from __future__ import annotations

import math

import numpy as np

FB = {"a": 0.1, "b": 0.25, "c": 0.2, "d": 0.3, "m2": 1.2, "m3": 2.0, "m4": 1.5,
      "I2": 0.004, "I3": 0.012, "I4": 0.006, "P": (0.0, -500.0)}
SC = {"r": 0.15, "l": 0.35, "m2": 2.0, "m3": 3.0, "m4": 1.5,
      "I2": 2.0 * 0.15 ** 2 / 12, "I3": 3.0 * 0.35 ** 2 / 12,   # slender bars
      "w2": 1500.0 * 2.0 * math.pi / 60.0}                       # 1500 rpm
SH = {"r": 0.10, "h2": 0.30, "L": 0.60, "l": 0.30, "hr": 0.55, "c6": 0.10,
      "m2": 1.5, "m3": 0.5, "m4": 4.0, "m5": 1.0, "m6": 8.0,
      "I2": 0.003, "I3": 0.0003, "I4": 0.12, "I5": 0.008, "P": 400.0, "g": 9.81,
      "w2": 10.0}


def _cross(ax, ay, bx, by):
    """z of (a x b)."""
    return ax * by - ay * bx


def fourbar_kin(th, w2: float, p: dict = FB) -> dict:
    """Positions, velocities and accelerations of the four-bar at crank angles ``th``.

    C is where the circles about B (radius b) and D (radius c) meet; the loop
    vB + w3 k x u = w4 k x w (u = C - B, w = C - D) dotted with w and with u gives w3
    and w4, and its derivative gives alpha3 and alpha4 the same way (the determinant
    ``den`` = u x w vanishes at the dead points)."""
    a, b, c, d = p["a"], p["b"], p["c"], p["d"]
    th = np.asarray(th, dtype=float)
    bx, by = a * np.cos(th), a * np.sin(th)
    # B -> D: its length s, unit vector e; C sits x along e and h to its left
    ex, ey = d - bx, -by
    s2 = ex * ex + ey * ey
    s = np.sqrt(s2)
    ex, ey = ex / s, ey / s
    along = (b * b - c * c + s2) / (2.0 * s)
    h = np.sqrt(b * b - along * along)
    cx = bx + along * ex - h * ey
    cy = by + along * ey + h * ex
    ux, uy = cx - bx, cy - by
    wx, wy = cx - d, cy
    den = _cross(ux, uy, wx, wy)
    vbx, vby = -w2 * by, w2 * bx
    w3 = -(vbx * wx + vby * wy) / den
    w4 = -(vbx * ux + vby * uy) / den
    abx, aby = -w2 * w2 * bx, -w2 * w2 * by
    rx = w3 * w3 * ux - w4 * w4 * wx - abx
    ry = w3 * w3 * uy - w4 * w4 * wy - aby
    al3 = (rx * wx + ry * wy) / den
    al4 = (rx * ux + ry * uy) / den
    acx = -al4 * wy - w4 * w4 * wx
    acy = al4 * wx - w4 * w4 * wy
    return {"Bx": bx, "By": by, "Cx": cx, "Cy": cy, "ux": ux, "uy": uy, "wx": wx, "wy": wy,
            "den": den, "w3": w3, "w4": w4, "al3": al3, "al4": al4,
            "vBx": vbx, "vBy": vby, "vCx": -w4 * wy, "vCy": w4 * wx,
            "aBx": abx, "aBy": aby, "aCx": acx, "aCy": acy}


def fourbar_dyad(th, w2: float, p: dict = FB) -> dict:
    """The four-bar's joint forces and Me at crank angles ``th``.

    The coupler's moments about C give u x F23 = M3 and the rocker's about D, with
    F34 = F23 - m3 a3, give w x F23 = w x (m3 a3 - P) - M4: two lines for F23 (Cramer,
    determinant u x w). The rest follows from the forces on each body."""
    k = fourbar_kin(th, w2, p)
    m2, m3, m4, i3, i4 = p["m2"], p["m3"], p["m4"], p["I3"], p["I4"]
    px, py = p["P"]
    ux, uy, wx, wy, den = k["ux"], k["uy"], k["wx"], k["wy"], k["den"]
    a3x, a3y = 0.5 * (k["aBx"] + k["aCx"]), 0.5 * (k["aBy"] + k["aCy"])
    a4x, a4y = 0.5 * k["aCx"], 0.5 * k["aCy"]
    # inertia moments about C (coupler, cog at -u/2 from C) and D (rocker, cog at w/2)
    m3c = _cross(-0.5 * ux, -0.5 * uy, -m3 * a3x, -m3 * a3y) - i3 * k["al3"]
    m4d = _cross(0.5 * wx, 0.5 * wy, -m4 * a4x, -m4 * a4y) - i4 * k["al4"]
    rhs = _cross(wx, wy, m3 * a3x - px, m3 * a3y - py) - m4d
    f23x = (m3c * wx - ux * rhs) / den
    f23y = (m3c * wy - uy * rhs) / den
    f34x, f34y = f23x - m3 * a3x, f23y - m3 * a3y
    f14x, f14y = m4 * a4x - f34x - px, m4 * a4y - f34y - py
    f12x, f12y = f23x + m2 * 0.5 * k["aBx"], f23y + m2 * 0.5 * k["aBy"]
    me = _cross(k["Bx"], k["By"], f23x, f23y)   # the crank's cog force passes through A
    return {"FA": (f12x, f12y), "FB": (f23x, f23y), "FC": (f34x, f34y),
            "FD": (f14x, f14y), "Me": me, "kin": k}


def slider_kin(th, w2: float, p: dict = SC) -> dict:
    """The slider-crank's motion at crank angles ``th``: the rod u = C - B keeps length
    l with C on the x axis; C's velocity and acceleration have no y part, which gives
    w3 and alpha3."""
    r, rod = p["r"], p["l"]
    th = np.asarray(th, dtype=float)
    bx, by = r * np.cos(th), r * np.sin(th)
    uy = -by
    ux = np.sqrt(rod * rod - uy * uy)
    vbx, vby = -w2 * by, w2 * bx
    w3 = -vby / ux
    abx, aby = -w2 * w2 * bx, -w2 * w2 * by
    al3 = (w3 * w3 * uy - aby) / ux
    return {"Bx": bx, "By": by, "Cx": bx + ux, "ux": ux, "uy": uy, "w3": w3, "al3": al3,
            "vBx": vbx, "vBy": vby, "vCx": vbx - w3 * uy,
            "aBx": abx, "aBy": aby, "aCx": abx - al3 * uy - w3 * w3 * ux}


def slider_dyad(th, w2: float, p: dict = SC) -> dict:
    """The slider-crank's joint forces, the guide's normal force ``N`` and Me: the
    piston's x equation gives F34x, the rod's forces F23x, the rod's moments about C
    (u x F23 = M3) F23y."""
    k = slider_kin(th, w2, p)
    m2, m3, m4, i3 = p["m2"], p["m3"], p["m4"], p["I3"]
    ux, uy = k["ux"], k["uy"]
    a3x, a3y = 0.5 * (k["aBx"] + k["aCx"]), 0.5 * k["aBy"]
    m3c = _cross(-0.5 * ux, -0.5 * uy, -m3 * a3x, -m3 * a3y) - i3 * k["al3"]
    f34x = m4 * k["aCx"]
    f23x = f34x + m3 * a3x
    f23y = (m3c + uy * f23x) / ux
    f34y = f23y - m3 * a3y
    f12x, f12y = f23x + m2 * 0.5 * k["aBx"], f23y + m2 * 0.5 * k["aBy"]
    return {"FA": (f12x, f12y), "FB": (f23x, f23y), "FC": (f34x, f34y), "N": -f34y,
            "Me": _cross(k["Bx"], k["By"], f23x, f23y), "kin": k}


def shaper_kin(th, w2: float, p: dict = SH) -> dict:
    """The shaper's motion at crank angles ``th`` (constant ``w2``).

    A = O2 + r (cos th, sin th) lies on the lever's line through O4: the lever's angle
    is A's polar angle, A = s e (e the lever's unit vector, n = k x e); vA = s' e +
    s w4 n and aA = (s'' - s w4^2) e + (s al4 + 2 s' w4) n give w4, s', al4 (the
    Coriolis term 2 s' w4). F sits on y = hr at l from E, ahead of it; F's velocity and
    acceleration have no y part, which gives w5 and al5."""
    r, h2, big, rod, hr = p["r"], p["h2"], p["L"], p["l"], p["hr"]
    th = np.asarray(th, dtype=float)
    c, s_ = np.cos(th), np.sin(th)
    ax, ay = r * c, h2 + r * s_
    s = np.sqrt(ax * ax + ay * ay)
    ex, ey = ax / s, ay / s
    vax, vay = -w2 * r * s_, w2 * r * c
    ds = vax * ex + vay * ey
    w4 = (vay * ex - vax * ey) / s
    aax, aay = -w2 * w2 * r * c, -w2 * w2 * r * s_
    al4 = ((aay * ex - aax * ey) - 2.0 * ds * w4) / s
    bx, by = big * ex, big * ey                     # E
    vex, vey = -w4 * by, w4 * bx
    aex = -al4 * by - w4 * w4 * bx
    aey = al4 * bx - w4 * w4 * by
    uy = hr - by
    ux = np.sqrt(rod * rod - uy * uy)               # F - E
    w5 = -vey / ux
    al5 = (w5 * w5 * uy - aey) / ux
    return {"Ax": ax, "Ay": ay, "s": s, "ex": ex, "ey": ey, "ds": ds, "w4": w4,
            "al4": al4, "vAx": vax, "vAy": vay, "aAx": aax, "aAy": aay,
            "Ex": bx, "Ey": by, "vEx": vex, "vEy": vey, "aEx": aex, "aEy": aey,
            "ux": ux, "uy": uy, "w5": w5, "al5": al5, "Fx": bx + ux,
            "vFx": vex - w5 * uy, "aFx": aex - al5 * uy - w5 * w5 * ux}


def shaper_dyad(th, w2: float, p: dict = SH) -> dict:
    """The shaper's joint forces and Me at crank angles ``th``, each body's equilibrium
    with its d'Alembert loads and its weight: the ram's x equation gives F56x, the
    link's moments about E F56y, its forces F45; the block (every force through A) takes
    from the lever a normal force Q n and the couple I3 al4; the lever's moments about
    O4 give Q; the block's forces F23, and the crank's moments about O2 Me. P acts on
    the ram while vF . P < 0."""
    k = shaper_kin(th, w2, p)
    g = -p["g"]
    m2, m3, m4, m5, m6 = p["m2"], p["m3"], p["m4"], p["m5"], p["m6"]
    ux, uy, ex, ey, s = k["ux"], k["uy"], k["ex"], k["ey"], k["s"]
    load = np.where(k["vFx"] * p["P"] < 0.0, p["P"], 0.0)
    f56x = m6 * k["aFx"] - load
    # the link: d'Alembert force at its middle, moments about E
    g5x, g5y = -m5 * 0.5 * (k["aEx"] + k["aFx"]), m5 * (g - 0.5 * k["aEy"])
    m5e = _cross(0.5 * ux, 0.5 * uy, g5x, g5y) - p["I5"] * k["al5"]
    f56y = (uy * f56x + m5e) / ux
    f45x, f45y = f56x - g5x, f56y - g5y
    # the lever: cog at L/2 on e, moments about O4 (block's Q n at A = s e, couple -C)
    cx, cy = 0.5 * p["L"] * ex, 0.5 * p["L"] * ey
    a4x = -k["al4"] * cy - k["w4"] ** 2 * cx
    a4y = k["al4"] * cx - k["w4"] ** 2 * cy
    couple = p["I3"] * k["al4"]
    m4o = (_cross(cx, cy, -m4 * a4x, m4 * (g - a4y)) - p["I4"] * k["al4"]
           - _cross(k["Ex"], k["Ey"], f45x, f45y))
    q = (m4o - couple) / s
    # the block: F23 + Q n + m3 (g - aA) = 0
    f23x = -q * -ey - m3 * -k["aAx"]
    f23y = -q * ex - m3 * (g - k["aAy"])
    rx, ry = k["Ax"], k["Ay"] - p["h2"]
    me = _cross(rx, ry, f23x, f23y) - _cross(0.5 * rx, 0.5 * ry, m2 * 0.5 * w2 * w2 * rx,
                                              m2 * (g + 0.5 * w2 * w2 * ry))
    return {"FA": (f23x, f23y), "FE": (f45x, f45y), "FF": (f56x, f56y), "Q": q, "Me": me,
            "kin": k}
