"""The balancing methods of seed 002 s. 3.4: where the counterweights go and how heavy
they are, for the four-bar and the slider-crank.

Mechanisms and methods
----------------------
- four-bar (crank, coupler, rocker, four revolute joints), ``full``: counterweights
  on the crank (about A) and the rocker (about D), eqs 3.38-3.41, generalised to
  centres of mass off the link lines (linearly independent vectors, below);
- slider-crank (crank, rod, piston sliding on a ground guide): ``full`` (rod about
  B and crank about A, eqs 3.42-3.45), ``partial`` (crank about A: the rotating
  masses, eqs 3.46-3.47, plus optionally a ``fraction`` of the reciprocating first
  harmonic), ``first-harmonic`` (crank about A, eq. 3.51 with its misprint
  corrected (the printed m'_e r_e = m_B l1 A1 repeats 3.46):
  m'_e r_e = (m_B + m_C A1) l1 with A1 = 1) and ``counter-rotating`` (crank about A
  for the rotating masses plus the pair of masses of eqs 3.52-3.53 on gears
  outside the scene).

The general four-bar condition (linearly independent vectors)
-------------------------------------------------------------
With R_i the rotation of body i, local vectors b1 = AB on the crank, u = BC on the
coupler, c3 = DC on the rocker, and the coupler's first moment about B written
along and across BC, m2 (G2 - B) = q_a u + q_b J u (J: a quarter turn ccw), the
loop closure R2 u = C - B = (D - A) + R3 c3 - R1 b1 turns the total first moment
(eqs 3.32-3.34) into

    S = const + R1 U1 + R3 U3,
    U1 = m1 (G1 - A) + (m2 - q_a) b1 - q_b J b1,
    U3 = m3 (G3 - D) + q_a c3 + q_b J c3.

R1 U1 and R3 U3 are linearly independent functions of the cycle, so S is constant
if and only if counterweights on the crank and on the rocker supply the first
moments -U1 (about A) and -U3 (about D). When every centre of mass lies on its
link's line (q_b = 0 and G1, G3 on AB, DC) this is the seed's static concentration
(eq. 3.38): |U1| = m_B l1 and |U3| = m_C l3, hence eq. 3.39; otherwise the result
names the general method. The same split of the rod (m2 (G2 - B) = q_a u + q_b J u,
m_C = m3 + q_a) gives the slider-crank's rotating first moment
U_rot = m1 (G1 - A) + (m2 - q_a) b1 - q_b J b1 (|U_rot| = m_B l1 of eq. 3.46 when
the cogs are on the lines) and its reciprocating mass m_C (eq. 3.42).

Assumptions: bodies are rigid; counterweights are point masses (no moment of
inertia of their own) fixed to their body; the counter-rotating pair's gears turn
at +omega and -omega of the crank about axes on the crank axis (their location
changes only the shaking moment, not the force); the shaking force and moment
are those of the inertia loads only (the exact torsor -m a_G, -I_G eps of every
body, whatever its ``mass_model``): gravity and the scene's loads are left out.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

import kinetostatics as ks
from kinetostatics.common.angles import degree_value
from kinetostatics.model.errors import AssemblyError
from kinetostatics.model.scene import Body, Scene
from kinetostatics.solver.arith import full
from kinetostatics.solver.kinematics import Kinematics

from ..common import deg360
from ..errors import BalanceError
from .counterweights import CounterRotatingPair, place
from .linkage import (
    ON_LINE,
    CounterweightSpec,
    Linkage,
    first_moment,
    joint_points,
    off_line,
    quarter_turn,
    split_along,
    vec,
)
from .shaking import motion_at

__all__ = [
    "HARMONIC_GRID",
    "four_bar_full",
    "moment_scale",
    "slider_crank_only",
    "slider_full",
    "slider_harmonic",
    "slider_line",
    "slider_masses",
    "turn_kinematics",
]

HARMONIC_GRID = 720      # uniform positions of a full turn for the Fourier coefficients


def moment_scale(sc: Scene) -> float:
    """A first-moment scale (kg m): total mass times the mechanism's size."""
    return max(sum(b.mass for b in sc.bodies.values()), 1e-300) * sc.size


def four_bar_full(sc: Scene, lk: Linkage, roles: dict[str, CounterweightSpec]):
    """Counterweights on the crank (about A) and the rocker (about D): eqs 3.38-3.41,
    in vector form (linearly independent vectors)."""
    P = joint_points(sc, lk)
    m1, m2, m3 = (sc.bodies[k] for k in (lk.crank, lk.link, lk.last))
    b1 = P["B1"] - P["A"]                       # AB on the crank
    u = P["C2"] - P["B2"]                       # BC on the coupler
    c3 = P["C3"] - P["D3"]                      # DC on the rocker
    qa, qb = split_along(first_moment(m2, P["B2"]), u)    # m2 (G2 - B) = qa u + qb J u
    U1 = first_moment(m1, P["A"]) + (m2.mass - qa) * b1 - qb * quarter_turn(b1)
    U3 = first_moment(m3, P["D3"]) + qa * c3 + qb * quarter_turn(c3)
    scale = moment_scale(sc)
    cws = (place(sc, roles["crank"], lk.A, -U1, scale),       # me1 r1 = m_B l1 (3.39)
           place(sc, roles["rocker"], lk.D3, -U3, scale))     # me3 r3 = m_C l3 (3.39)
    a1 = split_along(first_moment(m1, P["A"]), b1)[0]
    a3 = split_along(first_moment(m3, P["D3"]), c3)[0]
    masses = {"m_A": m1.mass - a1, "m_B": a1 + m2.mass - qa,            # eq. 3.38
              "m_C": qa + a3, "m_D": m3.mass - a3}
    off = [name for name, body, ref, v in ((lk.crank, m1, P["A"], b1), (lk.link, m2, P["B2"], u),
                                           (lk.last, m3, P["D3"], c3))
           if off_line(body, ref, v)]
    if off:
        proc = ("linearly independent vectors: the total first moment is const + R1 U1 + R3 U3 "
                "and the counterweights cancel U1 (crank, about A) and U3 (rocker, about D); "
                f"the cog of {', '.join(off)} is off its link's line, so the static "
                "concentration of eqs 3.38-3.39 does not apply as printed")
    else:
        proc = ("eqs 3.38-3.41: masses concentrated statically in the joints, "
                "me1 r1 = m_B l1 and me3 r3 = m_C l3 (3.39)")
    return cws, proc, masses


def slider_full(sc: Scene, lk: Linkage, roles: dict[str, CounterweightSpec]):
    """Rod about B (the rod + piston cog to B, eq. 3.43) then crank about A (the whole
    cog to A, eq. 3.44): eqs 3.42-3.45."""
    P = joint_points(sc, lk)
    m1, m2, m3 = (sc.bodies[k] for k in (lk.crank, lk.link, lk.last))
    b1 = P["B1"] - P["A"]
    u = P["C2"] - P["B2"]
    scale = moment_scale(sc)
    W2 = -(first_moment(m2, P["B2"]) + m3.mass * u)              # me2 r2 = m_C l2 (3.43)
    cw2 = place(sc, roles["rod"], lk.B2, W2, scale)
    U1 = first_moment(m1, P["A"]) + (m2.mass + m3.mass + cw2.mass) * b1
    cw1 = place(sc, roles["crank"], lk.A, -U1, scale)     # me1 r1 = (me2 + m1B + m2 + m3) l1
    masses = slider_masses(m1, m2, m3, P)
    off = [name for name, body, ref, v in ((lk.crank, m1, P["A"], b1), (lk.link, m2, P["B2"], u))
           if off_line(body, ref, v)]
    proc = "eqs 3.42-3.45: the rod's counterweight puts the rod + piston cog at B (3.43), " \
           "the crank's the whole cog at A (3.44)"
    if off:
        proc += (f"; the cog of {', '.join(off)} is off its link's line: the same conditions "
                 "in vector form (the counterweights are not on the links' extensions)")
    return (cw2, cw1), proc, masses


def slider_masses(m1: Body, m2: Body, m3: Body, P: dict[str, np.ndarray]) -> dict[str, float]:
    a1 = split_along(first_moment(m1, P["A"]), P["B1"] - P["A"])[0]
    a2 = split_along(first_moment(m2, P["B2"]), P["C2"] - P["B2"])[0]
    return {"m_A": m1.mass - a1, "m_B": a1 + m2.mass - a2, "m_C": m3.mass + a2}   # eq. 3.42


def turn_kinematics(sc: Scene) -> Kinematics:
    """The kinematics over a full turn of HARMONIC_GRID uniform positions that starts at
    the sweep's first position (so that the [near] hints pick the same assembly)."""
    start = float(sc.driver.positions[0]) if sc.driver.positions.size else 0.0
    grid = start + np.arange(HARMONIC_GRID) * (360.0 / HARMONIC_GRID)
    g = dataclasses.replace(sc, driver=dataclasses.replace(sc.driver, positions=grid))
    try:
        return ks.solve_kinematics(g, ks.analyse(g))
    except AssemblyError as exc:
        raise BalanceError(f"the crank must turn fully for this method (its Fourier series "
                           f"over a turn): {exc}") from None


def slider_line(gk: Kinematics, lk: Linkage) -> tuple[np.ndarray, np.ndarray]:
    """Unit direction u of the slider's line and the points C over the grid."""
    body = gk.scene.bodies[lk.link]
    x, y, *_ = motion_at(gk.bodies[lk.link], body.points[lk.C2], gk.n)
    pts = np.column_stack([x, y])
    _, _, vt = np.linalg.svd(pts - pts.mean(axis=0), full_matrices=False)
    u = vt[0]
    if float((pts.mean(axis=0) - vec(lk.axis)) @ u) < 0.0:   # from the crank axis outwards
        u = -u
    return u, pts


def slider_harmonic(sc: Scene, lk: Linkage, gk: Kinematics):
    """First harmonic of the piston travel s(theta) = (C - A).u over the crank angle:
    a_s cos theta + b_s sin theta = l1 A1 cos(theta - phi0) (eqs 3.48-3.49).

    Returns (a_s, b_s, u, centred)."""
    P = joint_points(sc, lk)
    u, pts = slider_line(gk, lk)
    axis = vec(lk.axis)
    l1 = float(np.hypot(*(P["B1"] - P["A"])))
    centred = abs(float((axis - pts.mean(axis=0)) @ quarter_turn(u))) <= ON_LINE * l1
    s = (pts - axis) @ u
    th = full(gk.bodies[lk.crank].theta, gk.n)
    a_s = 2.0 * float(np.mean(s * np.cos(th)))
    b_s = 2.0 * float(np.mean(s * np.sin(th)))
    return a_s, b_s, u, centred


def slider_crank_only(sc: Scene, lk: Linkage, roles: dict[str, CounterweightSpec], method: str,
                       fraction: float | None, pair_radius: float | None, gk: Kinematics):
    """``partial`` (3.46-3.47), ``first-harmonic`` (3.51 corrected) and
    ``counter-rotating`` (3.46 with 3.52-3.53): one counterweight on the crank."""
    P = joint_points(sc, lk)
    m1, m2, m3 = (sc.bodies[k] for k in (lk.crank, lk.link, lk.last))
    b1 = P["B1"] - P["A"]
    u_rod = P["C2"] - P["B2"]
    l1 = float(np.hypot(*b1))
    qa, qb = split_along(first_moment(m2, P["B2"]), u_rod)
    # |U_rot| = m_B l1
    U_rot = first_moment(m1, P["A"]) + (m2.mass - qa) * b1 - qb * quarter_turn(b1)
    m_C = m3.mass + qa                                                    # eq. 3.42
    a_s, b_s, u, centred = slider_harmonic(sc, lk, gk)
    if centred:
        w_rec = -m_C * b1                        # m_C l1 A1 opposite B, A1 = 1 (3.51)
        A1 = 1.0
    else:                                        # offset line: A1 and its phase by FFT
        w_rec = -m_C * (a_s * u - b_s * quarter_turn(u))
        A1 = math.hypot(a_s, b_s) / l1
    scale = moment_scale(sc)
    f = {"partial": fraction or 0.0, "first-harmonic": 1.0, "counter-rotating": 0.0}[method]
    W1 = -U_rot + f * w_rec
    cw = place(sc, roles["crank"], lk.A, W1, scale)
    pair = None
    notes = []
    if method == "partial":
        proc = "eqs 3.46-3.47: the crank's counterweight balances the rotating masses, " \
               "me re = m_B l1"
        if f:
            proc += (f", plus {f:g} of the piston's first harmonic: "
                     f"me re = (m_B + {f:g} m_C A1) l1")
    elif method == "first-harmonic":
        proc = ("eq. 3.51 corrected (the printed one repeats eq. 3.46): m'e re = "
                "(m_B + m_C A1) l1, A1 = 1; the first harmonic along the slider's line "
                "vanishes and reappears across it")
    else:
        r_pair = pair_radius if pair_radius is not None else roles["crank"].radius
        amp = m_C * A1 * l1                                    # m_C l1 A1 (3.52)
        th_u = math.atan2(u[1], u[0])
        if centred:          # a_s cos + b_s sin = l1 cos(theta - phi0), phi0 = theta_u - beta1
            phi0 = th_u - math.atan2(b1[1], b1[0])
        else:
            phi0 = math.atan2(b_s, a_s)
        pair = CounterRotatingPair(
            mass=amp / (2.0 * r_pair), radius=r_pair, axis=(float(lk.axis[0]),
                                                            float(lk.axis[1])),
            co_angle=deg360(degree_value(th_u - phi0 + math.pi)) if amp else 0.0,
            counter_angle=deg360(degree_value(th_u + phi0 + math.pi)) if amp else 0.0)
        proc = ("eqs 3.46 and 3.52-3.53: the crank's counterweight balances the rotating "
                "masses (me re = m_B l1); two masses me = m_C l1 A1 / (2 re) turning at "
                "+omega and -omega about the crank axis cancel the piston's first harmonic")
    if not centred:
        notes.append("the slider's line misses the crank axis (an offset slider-crank): A1 "
                     "and its phase come from the Fourier series of the piston travel")
    off = [name for name, body, ref, v in ((lk.crank, m1, P["A"], b1),
                                           (lk.link, m2, P["B2"], u_rod))
           if off_line(body, ref, v)]
    if off:
        notes.append(f"the cog of {', '.join(off)} is off its link's line: the rotating and "
                     "reciprocating parts are split in vector form (along and across BC)")
    if notes:
        proc += "; " + "; ".join(notes)
    return (cw,), pair, proc, slider_masses(m1, m2, m3, P), A1, u


