"""The seed's worked examples (seed 002 s. 2.6 and s. 2.3.3) redone by hand and by the workbench.

The seed prints no numbers for them: s. 2.6 Examples 1 (four-bar, figs 2.36-2.39) and 2
(slider-crank, figs 2.40-2.43) give the method only (link lengths, F2, F3, M3 "known"),
solved graphically with force polygons, and conclude that the reactions F21 and F01 on
the crank form a couple balanced by Me = d1 F12. Section 2.3.3 (figs 2.22-2.23) gives
Me = M2 / i12 for an external and an internal pair, also without numbers. So each example
below gets a geometry and loads of our choosing, in the seed's figures' layout; the seed's
hand method (moments about C for each link of the dyad, eqs 2.77/2.83; the force polygon
of the dyad, eqs 2.76/2.82, here a 2 x 2 linear solve; the link's polygon, eqs 2.80/2.85;
the crank, eqs 2.81/2.86 and Me = d1 F12) is computed independently of the workbench
(own position analysis by circle intersection) and compared with its tables. Both are
exact arithmetic on the same model, so the tolerance is 1e-9 of the force scale.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.transmission.gears import (
    equilibrating_moment,
    gear_pair,
    gear_ratio,
    tooth_force,
)

POSITIONS = [10.0, 55.0, 100.0, 150.0, 200.0, 250.0, 310.0]


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def rot(theta, p):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([c * p[0] - s * p[1], s * p[0] + c * p[1]])


def perp(u):
    """k x u: u turned +90 deg."""
    return np.array([-u[1], u[0]])


def me_from_d1_f12(A, B, F12):
    """Me = d1 F12 (s. 2.6): the couple of F21 (at B) and F01 = -F21 (at A) on the crank is
    balanced by Me; d1 is the arm of F12 about A, the sign that of (B - A) x F12."""
    d1 = abs(cross(B - A, F12)) / np.hypot(*F12)
    return math.copysign(d1 * np.hypot(*F12), cross(B - A, F12))


# --------------------------------------------------------------------------- Example 1

L1, L2, L3, AD = 0.08, 0.26, 0.18, 0.25
E_LOCAL = (0.11, 0.05)          # where F2 acts on the coupler
K_LOCAL = (0.09, -0.02)         # where F3 acts on the rocker
F2 = np.array([120.0, -350.0])  # N
F3 = np.array([-200.0, -150.0])  # N
M3 = 18.0                       # N m on the rocker, ccw

FOUR_BAR = {
    "title": "Seed 002 s. 2.6, Example 1 (fig. 2.36): four-bar with F2, F3, M3, no inertia",
    "ground": {"A": [0.0, 0.0], "D": [AD, 0.0]},
    "driver": {"body": "crank", "joint": "A", "speed": 10.0, "positions": POSITIONS},
    "bodies": [
        {"name": "crank", "points": {"A": [0.0, 0.0], "B": [L1, 0.0]}},
        {"name": "coupler", "points": {"B": [0.0, 0.0], "C": [L2, 0.0], "E": list(E_LOCAL)}},
        {"name": "rocker", "points": {"D": [0.0, 0.0], "C": [L3, 0.0], "K": list(K_LOCAL)}},
    ],
    "joints": [
        {"name": "A", "kind": "R", "bodies": ["ground", "crank"]},
        {"name": "B", "kind": "R", "bodies": ["crank", "coupler"]},
        {"name": "C", "kind": "R", "bodies": ["coupler", "rocker"]},
        {"name": "D", "kind": "R", "bodies": ["ground", "rocker"]},
    ],
    "loads": [
        {"body": "coupler", "point": "E", "force": F2.tolist()},
        {"body": "rocker", "point": "K", "force": F3.tolist(), "moment": M3},
    ],
    "near": {"C": [0.2, 0.15]},
}


def four_bar_by_hand(phi_deg):
    """The seed's Example 1 method at one crank angle."""
    A, D = np.array([0.0, 0.0]), np.array([AD, 0.0])
    B = A + L1 * np.array([math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))])
    # position: C on the circles (B, l2) and (D, l3), left of B -> D (the hinted assembly)
    bd = D - B
    dist = np.hypot(*bd)
    x = (L2**2 - L3**2 + dist**2) / (2 * dist)
    h = math.sqrt(L2**2 - x**2)
    C = B + (x * bd + h * perp(bd)) / dist
    th2 = math.atan2(*(C - B)[::-1])
    th3 = math.atan2(*(C - D)[::-1])
    E = B + rot(th2, E_LOCAL)
    K = D + rot(th3, K_LOCAL)
    n2, n3 = (C - B) / L2, (C - D) / L3          # along BC and along DC
    t2, t3 = perp(n2), perp(n3)
    # eqs 2.77-2.78 (signed arms): link 2 about C: (B - C) x F12t + (E - C) x F2 = 0
    f12t = cross(E - C, F2) / L2 * t2            # |F12t| = F2 d2 / l2
    # link 3 about C: (D - C) x F03t + (K - C) x F3 + M3 = 0 -> F03t = (F3 d3 + M3) / l3
    # (the seed prints M2 in 2.78; it follows from 2.77 with M3 - SPEC's misprint list)
    f03t = (cross(K - C, F3) + M3) / L3 * t3
    f03t_printed = (cross(K - C, F3) + 0.0) / L3 * t3      # "M2" = 0: no moment on link 2
    # eq. 2.76, the dyad's force polygon: F12n n2 + F03n n3 = -(F12t + F2 + F3 + F03t)
    rhs = -(f12t + F2 + F3 + f03t)
    a, b = np.linalg.solve(np.column_stack([n2, n3]), rhs)
    F12 = f12t + a * n2                          # eq. 2.79
    F03 = f03t + b * n3
    F32 = -(F12 + F2)                            # eq. 2.80
    F01 = F12                                    # eq. 2.81: F01 = -F21
    return {"B": B, "C": C, "F12": F12, "F03": F03, "F32": F32, "F01": F01,
            "Me": me_from_d1_f12(A, B, F12), "F03t": f03t, "F03t_printed": f03t_printed}


@pytest.fixture(scope="module")
def four_bar():
    return ks.solve(FOUR_BAR), [four_bar_by_hand(p) for p in POSITIONS]


def test_example_1_positions(four_bar):
    sol, hand = four_bar
    k = sol.kinematics
    c = k[(k.body == "coupler") & (k.point == "C")]
    assert np.allclose(c[["x", "y"]].to_numpy(), [h["C"] for h in hand], atol=1e-12)


def test_example_1_reactions_and_me(four_bar):
    sol, hand = four_bar
    scale = max(np.hypot(*h["F12"]) for h in hand)
    for joint, key, sign in (("B", "F12", 1.0), ("D", "F03", 1.0), ("C", "F32", -1.0),
                             ("A", "F01", 1.0)):
        fx, fy = sol.reaction(joint)       # B: on coupler by crank; C: on rocker by coupler
        want = np.array([sign * h[key] for h in hand])
        assert np.allclose(fx, want[:, 0], atol=1e-9 * scale), joint
        assert np.allclose(fy, want[:, 1], atol=1e-9 * scale), joint
    # Me = d1 F12, with the sense of the couple
    me = np.array([h["Me"] for h in hand])
    assert np.allclose(sol.Me, me, atol=1e-9 * scale * L1)
    assert (np.sign(sol.Me) == np.sign(me)).all()


def test_example_1_printed_2_78_misprint(four_bar):
    """F03t with M3 (from 2.77) agrees with the workbench; the printed M2 (= 0 here) does not."""
    sol, hand = four_bar
    fx, fy = sol.reaction("D")
    for i, h in enumerate(hand):
        n3 = (h["C"] - np.array([AD, 0.0])) / L3
        t3 = perp(n3)
        ft = fx[i] * t3[0] + fy[i] * t3[1]       # the workbench's F03 across DC
        assert ft == pytest.approx(h["F03t"] @ t3, abs=1e-9 * abs(ft) + 1e-9)
        assert abs(ft - h["F03t_printed"] @ t3) == pytest.approx(abs(M3) / L3, rel=1e-9)


# --------------------------------------------------------------------------- Example 2

R, L = 0.10, 0.32
E2_LOCAL = (0.12, 0.02)          # where F2 acts on the rod
F2_SC = np.array([60.0, -250.0])  # N on the rod
F3_SC = np.array([-900.0, 0.0])   # N on the piston at C, along x-x

SLIDER_CRANK = {
    "title": "Seed 002 s. 2.6, Example 2 (fig. 2.40): slider-crank with F2, F3, no inertia",
    "ground": {"A": [0.0, 0.0], "O": [0.0, 0.0]},
    "driver": {"body": "crank", "joint": "A", "speed": 10.0, "positions": POSITIONS},
    "bodies": [
        {"name": "crank", "points": {"A": [0.0, 0.0], "B": [R, 0.0]}},
        {"name": "rod", "points": {"B": [0.0, 0.0], "C": [L, 0.0], "E": list(E2_LOCAL)}},
        {"name": "piston", "points": {"C": [0.0, 0.0]}},
    ],
    "joints": [
        {"name": "A", "kind": "R", "bodies": ["ground", "crank"]},
        {"name": "B", "kind": "R", "bodies": ["crank", "rod"]},
        {"name": "C", "kind": "R", "bodies": ["rod", "piston"]},
        {"name": "C-slide", "kind": "T", "guide": "ground", "slider": "piston",
         "line_point": "O", "line_angle": 0.0, "slider_point": "C"},
    ],
    "loads": [
        {"body": "rod", "point": "E", "force": F2_SC.tolist()},
        {"body": "piston", "point": "C", "force": F3_SC.tolist()},
    ],
    "near": {"C": [0.4, 0.0]},
}


def slider_crank_by_hand(phi_deg):
    """The seed's Example 2 method at one crank angle."""
    A = np.array([0.0, 0.0])
    B = R * np.array([math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg))])
    C = np.array([B[0] + math.sqrt(L**2 - B[1] ** 2), 0.0])
    th2 = math.atan2(*(C - B)[::-1])
    E = B + rot(th2, E2_LOCAL)
    n2 = (C - B) / L
    t2 = perp(n2)
    f12t = cross(E - C, F2_SC) / L * t2          # eqs 2.83-2.84: F12t = F2 d2 / l2
    normal = np.array([0.0, 1.0])                # F03 perpendicular to x-x
    a, f03 = np.linalg.solve(np.column_stack([n2, normal]), -(f12t + F2_SC + F3_SC))  # 2.82
    F12 = f12t + a * n2
    F03 = f03 * normal
    F32 = -(F12 + F2_SC)                         # eq. 2.85
    return {"C": C, "F12": F12, "F03": F03, "F32": F32, "F01": F12,      # eq. 2.86
            "Me": me_from_d1_f12(A, B, F12)}


def test_example_2_reactions_and_me():
    sol = ks.solve(SLIDER_CRANK)
    hand = [slider_crank_by_hand(p) for p in POSITIONS]
    scale = max(np.hypot(*h["F12"]) for h in hand)
    for joint, key, sign in (("B", "F12", 1.0), ("C-slide", "F03", 1.0), ("C", "F32", -1.0),
                             ("A", "F01", 1.0)):
        fx, fy = sol.reaction(joint)
        want = np.array([sign * h[key] for h in hand])
        assert np.allclose(fx, want[:, 0], atol=1e-9 * scale), joint
        assert np.allclose(fy, want[:, 1], atol=1e-9 * scale), joint
    me = np.array([h["Me"] for h in hand])
    assert np.allclose(sol.Me, me, atol=1e-9 * scale * R)
    # "F03 d3 = 0": the guide's reaction passes through the centre of joint C
    r = sol.reactions[sol.reactions.joint == "C-slide"]
    assert np.allclose(r["M"], 0.0, atol=1e-9 * scale * L)
    assert np.allclose(r["offset"].dropna(), 0.0, atol=1e-9)
    assert np.allclose(r["N"], [h["F03"][1] for h in hand], atol=1e-9 * scale)


# --------------------------------------------------------------------------- s. 2.3.3

# Our numbers (the seed has none): M2 = 120 N m on gear 2, r_w1 = 40 mm, r_w2 = 120 mm,
# alpha = 20 deg. By hand: i12 = 120/40 = 3 (the seed's magnitude), F12 = 120 /
# (0.120 cos 20 deg) = 1064.2 N, Me = 120 / 3 = 40.0 N m (eqs 2.53, 2.55, 2.57, 2.59).
@pytest.mark.parametrize("internal,fig", [(False, "2.22"), (True, "2.23")])
def test_gears_me_is_m2_over_i12(internal, fig):
    g = gear_pair(120.0, 0.040, 0.120, alpha_deg=20.0, internal=internal)
    assert abs(g.i12) == pytest.approx(3.0, rel=1e-12), fig
    assert float(g.F) == pytest.approx(1064.2, abs=0.05)                  # eq. 2.53 / 2.57
    assert tooth_force(120.0, 0.120, 20.0) == pytest.approx(float(g.F), rel=1e-14)
    assert abs(float(g.Me)) == pytest.approx(40.0, rel=1e-12)            # eq. 2.55 / 2.59
    assert float(g.Me) == pytest.approx(120.0 / gear_ratio(0.040, 0.120, internal), rel=1e-12)
    assert float(g.Me) == pytest.approx(equilibrating_moment(120.0, 0.040, 0.120, internal))
    # external: gear 1 turns against gear 2, so Me has the opposite sign of M2; internal: same
    assert np.sign(float(g.Me)) == (1.0 if internal else -1.0)
    # F02 = -F12 and F01 = -F21 (the text after eqs 2.53 and 2.57)
    assert (float(g.F02x), float(g.F02y)) == pytest.approx((-float(g.F12x), -float(g.F12y)))
    assert (float(g.F01x), float(g.F01y)) == pytest.approx((-float(g.F21x), -float(g.F21y)))
