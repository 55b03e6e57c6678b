"""Kinematics of the driver and of every dyad kind, closed form, vectorised over positions.

Seed 000: the driving element (ch. 4) and the dyads RRR (ch. 5), RTR with the guide on
either link (ch. 6, 7), TRR (ch. 8), RRT (ch. 9), TRT (ch. 10), RTT (ch. 11), TTR (ch. 12).

One formulation serves every kind. A dyad body joined to a known body K by

* a revolute joint at P rotates about P: its unknown is its angle (``rot``);
* a prismatic joint keeps K's angle (plus the line angle) and translates relative to K
  along a direction u fixed in K: its unknown is the displacement s (``trans``).

The inner joint then closes the dyad: a revolute one makes the two bodies' points Q
coincide (circle-circle, circle-line or line-line intersection: the seed's indicator
k = +-1 picks one of two assemblies, eqs 6.1, 8.1 of seed 000), a prismatic one makes
the slider's angle follow the guide's and its point S stay on the guide's line. The
velocities solve the 2 x 2 linear system ``G qdot = r`` whose columns are the
velocities of the closing point per unit of each body's unknown; the accelerations
solve the same system with the centripetal and Coriolis terms on the right.

Coordinates are kept as separate x and y arrays (one element per position).
"""

from __future__ import annotations

from contextlib import nullcontext
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from ..model.errors import AssemblyError, WorkbenchError
from ..model.scene import GROUND, Scene
from . import arith as A
from .assembly import (
    SINGULAR_FAIL,
    choose_branch,
    first_row_assembly,
    fmt_positions,
    refuse_coincident_pivots,
)
from .closure import DyadSolver, Param, body_origin, dyad_param
from .driver import BodyMotion, driver_at_first_row, driver_motion, ground_motion
from .velocity_system import (
    closing_point,
    cramer2,
    dead_centre_closeness2,
    guide_body,
    guide_line,
    inner_t_tau,
    velocity_column,
    velocity_columns,
    velocity_matrix,
)

if TYPE_CHECKING:
    from .structure import Dyad, Structure

SINGULAR_WARN = 1e-3    # sin(transmission angle) below this: the row is flagged singular
# SINGULAR_FAIL (1e-12, .assembly): below it the velocity system cannot be solved: refused


@dataclass
class DyadMotion:
    """What the reactions need from a solved dyad: its parameters, the closing point X
    (the inner joint's point; for a prismatic inner joint the slider point), the
    columns c1, c2 of the velocity system at X and its determinant."""

    dyad: Dyad
    params: tuple[Param, Param]
    k: int
    xx: object
    xy: object
    _c1: tuple | None
    _c2: tuple | None
    _det: object
    n: int
    singular: np.ndarray | None = None  # |sin tau| <= 1e-3: near a dead centre
    closeness2: np.ndarray | None = None  # min(sin^2 tau, (pivot distance / size)^2)
    probe2: np.ndarray | None = None    # closeness2 as a probe measures it (screened)
    inner_local: tuple | None = None    # revolute inner joint: its local point on each body
    slider_first: bool = False          # prismatic inner joint: body 1 is the slider
    nx: object = None                   # prismatic inner joint: left normal of the line
    ny: object = None
    _tau: tuple | None = None

    # The velocity system's columns and determinant serve the solve (the reactions);
    # after it they are let go (release) and worked out again, with the same numbers,
    # when asked for (the transmission angle): at large sizes they are five arrays over
    # the rows that no table holds.
    @property
    def c1(self) -> tuple:
        if self._c1 is None:
            self._restore()
        return self._c1

    @property
    def c2(self) -> tuple:
        if self._c2 is None:
            self._restore()
        return self._c2

    @property
    def det(self):
        if self._det is None:
            self._restore()
        return self._det

    def _restore(self) -> None:
        p1, p2 = self.params
        c1, c2 = velocity_column(p1, self.xx, self.xy), velocity_column(p2, self.xx, self.xy)
        w1, w2 = (1.0 if p.kind == "rot" else 0.0 for p in self.params)
        self._det = velocity_matrix(self.nx is None, c1, c2, w1, w2, self.nx, self.ny)[1]
        self._c1, self._c2 = c1, c2

    def release(self) -> None:
        """Let go of what only the solve needs: the velocity system's columns and
        determinant (worked out again when asked for) and the outer pivots' velocity
        and acceleration (``Param.vpx`` ... ``apy``, None after)."""
        self._c1 = self._c2 = self._det = None
        for p in self.params:
            p.vpx = p.vpy = p.apx = p.apy = None

    def _compute_tau(self):
        if self._tau is None:
            n = self.n
            if self.nx is None:
                c1, c2 = self.c1, self.c2
                norm = np.hypot(*c1) * np.hypot(*c2)
                sin_t = self.det / norm
                cos_t = -(A.mul_add(c1[0], c2[0], c1[1], c2[1])) / norm
            else:
                sin_t, cos_t = inner_t_tau(self.params, self.ny, -self.nx)
            self._tau = (A.full(np.asarray(sin_t, dtype=float), n),
                         A.full(np.asarray(cos_t, dtype=float), n))
        return self._tau

    @property
    def sin_tau(self) -> np.ndarray:
        """sin of the transmission angle: |det| / (|c1| |c2|) of the velocity system."""
        return self._compute_tau()[0]

    @property
    def cos_tau(self) -> np.ndarray:
        return self._compute_tau()[1]

    @property
    def transmission_angle(self) -> np.ndarray:
        """The transmission angle min(tau, 180 - tau) in [0, 90] deg (seed 002 eqs
        2.60-2.61): tau, the angle between the force the dyad transmits and the velocity
        of the point it drives, and 180 - tau transmit alike; 0 is a dead centre."""
        s_, c_ = self._compute_tau()
        # degrees kept (5/10): the solver's one angle result in degrees, read by the
        # tables, the pictures and the summaries alike
        return np.rad2deg(np.arctan2(np.abs(s_), np.abs(c_)))


@dataclass
class Kinematics:
    """Motions of every body over the sweep, and the solved dyads."""

    scene: Scene
    structure: Structure
    positions: np.ndarray
    bodies: dict[str, BodyMotion]
    dyads: list[DyadMotion] = field(default_factory=list)
    # rows (i, j), i before j in driver position, with a dead point between them; rows
    # whose dyads cannot close somewhere between them; end rows near a dead point beyond
    between: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=int))
    unassembled: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=int))
    ends: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))

    @property
    def n(self) -> int:
        return self.positions.size

    def release(self) -> None:
        """Let go of what only the solve needs (:meth:`DyadMotion.release`, the bodies'
        arms of their points, :meth:`~kinetostatics.solver.driver.BodyMotion.arm`)."""
        for d in self.dyads:
            d.release()
        for b in self.bodies.values():
            b.forget_arms()

    @property
    def singular(self) -> np.ndarray:
        """Rows near a dead centre of some dyad (contract: |det| <= 1e-3 |c1||c2|)."""
        out = np.zeros(self.n, dtype=bool)
        for d in self.dyads:
            out |= d.singular
        if self.between.size:
            out[self.between.ravel()] = True    # a dead point between two rows
        if self.ends.size:
            out[self.ends] = True               # a dead point just beyond an end of the sweep
        return out


def solve_dyad(scene: Scene, dyad: Dyad, motions: dict[str, BodyMotion],
               k: int | None = None, strict: bool = True, screened: bool = False) -> DyadMotion:
    """Positions, velocities and accelerations of a dyad's two bodies over the sweep.

    Adds both bodies' :class:`BodyMotion` to ``motions`` and returns the dyad data the
    reactions need. ``k`` is the dyad's assembly (seed 000 eqs 6.1, 8.1); ``None`` chooses
    it from the ``[near]`` hints at the first row of ``scene``. ``strict = False`` (used
    to probe between rows) returns whatever the closed form gives where the dyad cannot
    close or is singular, instead of refusing; ``screened`` with it: ``closeness2`` and
    ``singular`` as a strict solve measures them, ``probe2`` as a probe does (one pass
    gives a screen's numbers and, on the rows that close, a strict solve's).

    Raises
    ------
    AssemblyError
        Where the dyad cannot close (which positions and by how much), where two
        assemblies exist and no ``[near]`` hint settles them, or at an exactly singular
        position.
    """
    n = scene.driver.positions.size
    solver = DyadSolver(scene, dyad)
    pr = (dyad_param(scene, dyad, 0, motions), dyad_param(scene, dyad, 1, motions))
    k = 1 if solver.branches == 1 else k
    # (an assembly to choose: picked inside the closure where it can, from the sweep's
    # own first row; else closed twice at that row, choose_branch)
    closed = _close(scene, dyad, solver, pr, None, strict, lambda two: first_row_assembly(
        scene, dyad, solver, pr, two)) if k is None and solver.picks else None
    if closed is None:
        k = choose_branch(scene, dyad, solver, pr) if k is None else k
        closed = _close(scene, dyad, solver, pr, k, strict)
    cs, ss, reach = closed
    k = solver.k if k is None else k
    org = [body_origin(pr[i], cs[i], ss[i]) for i in range(2)]
    vs = _VelocitySystem(dyad, solver, pr, cs, org)
    sin2 = dead_centre_closeness2(vs, pr, reach, n, solver if strict or screened else None)
    probe2 = dead_centre_closeness2(vs, pr, reach, n) if screened else None
    sing = ~(sin2 > SINGULAR_WARN**2)
    exact = np.flatnonzero(~(sin2 > SINGULAR_FAIL**2)) if sing.any() else ()
    if strict and len(exact):
        raise AssemblyError(
            f"dyad {dyad.label} is exactly singular (dead centre: transmission angle 0) at "
            f"driver position(s) {fmt_positions(scene, exact)}; its velocities are undefined "
            "there: leave those positions out of the sweep")
    qd = vs.solve(vs.r1, vs.r2)
    # a turning body's omega^2 (qd qd), for the acceleration system and again for the
    # accelerations of its points (kept by its motion: BodyMotion.omega2)
    w2 = [qd[i] * qd[i] if p.kind == "rot" else None for i, p in enumerate(pr)]
    qdd = vs.solve(*_acceleration_rhs(vs, pr, qd, w2))
    for i, p in enumerate(pr):
        motions[dyad.bodies[i]] = _body_motion(p, cs[i], org[i], qd[i], qdd[i], w2[i])
    ib, loc, arm = vs.arm           # (its cos and sin are the body's: kept for the reactions)
    motions[dyad.bodies[ib]].keep_arm(loc, arm)
    inner = dyad.inner
    return DyadMotion(dyad, pr, k, vs.xx, vs.xy, vs.c1, vs.c2, vs.det, n,
                      singular=sing, closeness2=sin2, probe2=probe2,
                      inner_local=tuple(solver.q) if inner.kind == "R" else None,
                      slider_first=inner.kind == "T" and solver.slider_first,
                      nx=vs.nx, ny=vs.ny)


def _close(scene: Scene, dyad: Dyad, solver: DyadSolver, pr, k, strict: bool, first=None):
    """Step 1, positions: each body's (cos, sin) and displacement for assembly k (or the
    one ``first`` picks, :meth:`DyadSolver.positions`: None if it does not), and the
    outer pivots' distance over the mechanism's size (or None); refuses (``strict``)
    rows where the links do not reach or the pivots coincide."""
    n = scene.driver.positions.size
    closed = solver.positions(pr, k, first)
    if closed is None:
        return None
    cs, ss, gap = closed
    reach = solver.reach            # the pivots' distance (or None)
    if reach is not None:
        reach = A.full(reach / scene.size, n)
        if strict:
            refuse_coincident_pivots(scene, dyad, reach)
    if gap is not None and strict:
        gap = A.full(gap, n)
        bad = np.flatnonzero(~(gap <= 1e-9 * scene.size))
        if bad.size:
            raise AssemblyError(
                f"dyad {dyad.label} cannot be assembled at driver position(s) "
                f"{fmt_positions(scene, bad, gap[bad])}: the links do not reach; shorten "
                "the sweep or change the lengths")
    return cs, ss, reach


class _VelocitySystem:
    """Step 2, the dyad's velocity system ``G qdot = r`` at its closing point X (the
    inner joint's point; for a prismatic inner joint the slider point): a revolute inner
    joint makes both bodies' points at X move alike, ``c1 qd1 - c2 qd2 = k2 - k1``; a
    prismatic one keeps the slider's angle on the guide's, ``w1 qd1 - w2 qd2 = omega0_2 -
    omega0_1``, and its point on the line, ``n.(c1 qd1 - c2 qd2) = n.(k2 - k1)``."""

    def __init__(self, dyad: Dyad, solver: DyadSolver, pr, cs, org):
        inner = dyad.inner
        self.revolute = inner.kind == "R"
        self.slider_first = solver.slider_first
        self.guide = guide_body(solver)
        self.arm: list = []         # (the closing point's body, local point and arm)
        xx, xy = closing_point(dyad, solver, cs, org, self.arm)
        (c1, k1, w1), (c2, k2, w2) = (velocity_columns(pr[0], xx, xy),
                                      velocity_columns(pr[1], xx, xy))
        if inner.kind == "R":
            r1, r2 = A.sub(k2[0], k1[0]), A.sub(k2[1], k1[1])
            nx = ny = None
            ux = uy = None
        else:
            ux, uy = guide_line(solver, cs)
            nx, ny = -uy, ux
            om0 = [0.0 if p.kind == "rot" else p.known.omega for p in pr]
            r1 = A.sub(om0[1], om0[0])
            r2 = A.mul_add(nx, A.sub(k2[0], k1[0]), ny, A.sub(k2[1], k1[1]))
        self.a, self.det = velocity_matrix(inner.kind == "R", c1, c2, w1, w2, nx, ny)
        self.xx, self.xy = xx, xy
        self.c1, self.c2, self.k1, self.k2 = c1, c2, k1, k2
        self.r1, self.r2 = r1, r2
        self.ux, self.uy, self.nx, self.ny = ux, uy, nx, ny

    def solve(self, r1, r2):
        """qdot (or qddot) for the right-hand side (r1, r2), Cramer's rule."""
        return cramer2(*self.a, r1, r2, self.det)


def _acceleration_rhs(vs: _VelocitySystem, pr, qd, w2):
    """Step 4, the right-hand side of the acceleration system (the same matrix): the
    centripetal and Coriolis terms (``w2``: each turning body's qd qd)."""
    xx, xy = vs.xx, vs.xy
    ka = []
    for i, p in enumerate(pr):
        if p.kind == "rot":
            # a_P - omega^2 (X - P), with X - P = (c_y, -c_x) from the column c = J (X - P)
            # (the same differences, computed once)
            cx, cy = vs.c1 if i == 0 else vs.c2
            w2_ = w2[i]
            # (A.sub and A.add of the product, written into the product's own array,
            # A.into: the same values, two fresh arrays fewer a turning body)
            t, u = w2_ * cy, w2_ * cx
            ka.append((A.into(np.subtract, A.sub, p.apx, t, False, A.fresh(t, w2_, cy)),
                       A.into(np.add, A.add, p.apy, u, False, A.fresh(u, w2_, cx))))
        else:
            kax, kay = p.known.acc_at(xx, xy)
            f = A.mul(2.0 * p.known.omega, qd[i])          # Coriolis 2 omega_K x v_rel
            ka.append((A.sub_mul(kax, f, p.uy), A.add_mul(kay, f, p.ux)))
    if vs.revolute:
        return A.sub(ka[1][0], ka[0][0]), A.sub(ka[1][1], ka[0][1])
    c1, c2, k1, k2 = vs.c1, vs.c2, vs.k1, vs.k2
    ux, uy, nx, ny = vs.ux, vs.uy, vs.nx, vs.ny
    al0 = [0.0 if p.kind == "rot" else p.known.alpha for p in pr]
    r1 = A.sub(al0[1], al0[0])
    v1 = (A.add_mul(k1[0], c1[0], qd[0]), A.add_mul(k1[1], c1[1], qd[0]))
    v2 = (A.add_mul(k2[0], c2[0], qd[1]), A.add_mul(k2[1], c2[1], qd[1]))
    sgn = 1.0 if vs.slider_first else -1.0
    rdot = A.mul(sgn, A.mul_add(ux, A.sub(v1[0], v2[0]), uy, A.sub(v1[1], v2[1])))
    ig = vs.guide
    om_g = qd[ig] if pr[ig].kind == "rot" else pr[ig].known.omega
    # n.(a_slider - a_guide) = 2 omega_g rdot (Coriolis, seed 001 eq. 8)
    r2 = A.sub(A.mul(2.0 * sgn, A.mul(om_g, rdot)),
               A.mul_add(nx, A.sub(ka[0][0], ka[1][0]), ny, A.sub(ka[0][1], ka[1][1])))
    return r1, r2


def _body_motion(p: Param, cs, org, qd, qdd, w2) -> BodyMotion:
    """Step 5, a dyad body's motion from its unknown's rate and acceleration (``w2``: a
    turning body's qd qd, kept by its motion, :meth:`BodyMotion.omega2`)."""
    c, sn = cs
    ox, oy = org
    kb = p.known
    if p.kind == "rot" and p.local == (0.0, 0.0):
        # the body's origin is its pivot P: it moves as P
        om, al = qd, qdd
        vx, vy, ax_, ay_ = p.vpx, p.vpy, p.apx, p.apy
    elif p.kind == "rot":
        om, al = qd, qdd
        rax, ray = A.rotate(c, sn, -p.local[0], -p.local[1])   # o - P = -R a
        w2_ = w2            # (om * om)
        vx = A.sub_mul(p.vpx, om, ray)
        vy = A.add_mul(p.vpy, om, rax)
        ax_ = A.sub_mul(A.sub_mul(p.apx, al, ray), w2_, rax)
        ay_ = A.sub_mul(A.add_mul(p.apy, al, rax), w2_, ray)
    else:
        om, al = kb.omega, kb.alpha
        vkx, vky = kb.vel_at(ox, oy)
        akx, aky = kb.acc_at(ox, oy)
        f = A.mul(2.0 * kb.omega, qd)
        vx, vy = A.add_mul(vkx, qd, p.ux), A.add_mul(vky, qd, p.uy)
        ax_ = A.sub_mul(A.add_mul(akx, qdd, p.ux), f, p.uy)
        ay_ = A.add_mul(A.add_mul(aky, qdd, p.uy), f, p.ux)
    motion = BodyMotion(None, c, sn, om, al, ox, oy, vx, vy, ax_, ay_)
    if w2 is not None:
        motion.keep_omega2(w2)
    return motion


def with_positions(scene: Scene, positions) -> Scene:
    """The same scene with the driver at other positions (deg for a crank, m for a slider)."""
    pos = np.atleast_1d(np.asarray(positions, dtype=float))
    return replace(scene, driver=replace(scene.driver, positions=pos))


def choose_assembly(scene: Scene, structure: Structure) -> tuple[int, ...]:
    """Each dyad's assembly k = +-1, chosen once at the scene's first row.

    The ``[near]`` hints describe the scene's first row (scene-format section 1): there
    each dyad takes the assembly whose hinted points lie closest; a dyad with one
    assembly (or none to choose) gets k = 1.

    Raises
    ------
    AssemblyError
        A dyad that cannot close at the first row (by how much), or two assemblies that no
        hint settles (with the hint to add).
    """
    if len(structure.assembly) == len(structure.dyads):
        return structure.assembly
    plain = _plain_first_row(scene, structure)
    if plain is not None:
        return plain
    first = with_positions(scene, scene.driver.positions[:1])
    motions: dict[str, BodyMotion] = {GROUND: ground_motion(),
                                      scene.driver.body: driver_motion(first)}
    return tuple(solve_dyad(first, dyad, motions).k for dyad in structure.dyads)


PLAIN = 1e-6    # a first row this far from every refusal is decided in numbers


def _plain_first_row(scene: Scene, structure: Structure) -> tuple[int, ...] | None:
    """:func:`choose_assembly` by the short road: each dyad's assembly from the first
    row's positions alone, in Python numbers (the same operations as a one-row solve, on
    the same doubles), with no velocities, accelerations or arrays; None where that row
    is not plain, PLAIN away from every refusal: a dyad that does not close there,
    pivots that nearly coincide (pivot distance over the mechanism's size), a
    transmission angle near a dead centre (sin^2 tau), assemblies no hint tells apart
    by PLAIN of the size squared, or any refusal. The full road then decides alike or
    refuses with its message. (Measured 2026-11-29, four-bar: 200 us by the one-row
    solve, N us here.)"""
    drv = scene.driver
    if not drv.positions.size or "segments" in scene.__dict__:
        return None
    first = driver_at_first_row(scene)
    motions: dict[str, BodyMotion] = {GROUND: ground_motion(), drv.body: first}
    ks = []
    try:
        for dyad in structure.dyads:
            k = _plain_dyad(scene, dyad, motions)
            if k is None:
                return None
            ks.append(k)
    except (WorkbenchError, ArithmeticError, ValueError):
        return None
    return tuple(ks)


def _plain_dyad(scene: Scene, dyad: Dyad, motions: dict[str, BodyMotion]) -> int | None:
    """One dyad of :func:`_plain_first_row`: its assembly, its bodies' positions added to
    ``motions`` (no speeds: none is read), or None."""
    solver = DyadSolver(scene, dyad)
    pr = (dyad_param(scene, dyad, 0, motions), dyad_param(scene, dyad, 1, motions))
    size = scene.size
    if solver.branches == 1:
        k = 1
    elif solver.picks:
        k = None
    else:
        k = choose_branch(scene, dyad, solver, pr, margin=PLAIN)
    closed = solver.positions(pr, k, None if k is not None else lambda two: (
        first_row_assembly(scene, dyad, solver, pr, two, margin=PLAIN)))
    if closed is None or closed[2] is not None:
        return None
    cs, ss, _ = closed
    reach = solver.reach
    if reach is not None and not float(reach) > PLAIN * size:
        return None
    org = [body_origin(pr[i], cs[i], ss[i]) for i in range(2)]
    if not _plain_sin2(dyad, solver, pr, cs, org) > PLAIN:
        return None
    for i, name in enumerate(dyad.bodies):
        motions[name] = BodyMotion(None, float(cs[i][0]), float(cs[i][1]), 0.0, 0.0,
                                   float(org[i][0]), float(org[i][1]), 0.0, 0.0, 0.0, 0.0)
    return solver.k if k is None else k


def _plain_sin2(dyad: Dyad, solver: DyadSolver, pr, cs, org) -> float:
    """sin^2 of a dyad's transmission angle at the first row
    (:func:`~kinetostatics.solver.velocity_system.dead_centre_closeness2`, numbers): for a
    revolute inner joint at X, det(c1, c2)^2 / (|c1|^2 |c2|^2) of the velocity columns
    (c = J (X - P) of a turning body, u of a translating one) worked out here."""
    if dyad.inner.kind != "R":
        return float(dead_centre_closeness2(_VelocitySystem(dyad, solver, pr, cs, org), pr, None, 1,
                                 solver)[0])
    rx, ry = A.rotate(cs[0][0], cs[0][1], *solver.q[0])
    xx, xy = org[0][0] + rx, org[0][1] + ry
    (ax, ay), (bx, by) = (velocity_column(p, xx, xy) for p in pr)
    det = ax * by - ay * bx
    return float(det * det / ((ax * ax + ay * ay) * (bx * bx + by * by)))


def solve_kinematics(scene: Scene, structure: Structure, positions=None,
                     strict: bool = True, screened: bool = False) -> Kinematics:
    """Motions of every body over the driver's sweep (vectorised, closed form).

    Parameters
    ----------
    scene : Scene
        The mechanism.
    structure : Structure
        Its driver and dyads (:func:`~kinetostatics.analyse`); each dyad keeps the assembly
        the structure carries (chosen at the scene's first row when it carries none).
    positions : array_like, optional
        Driver positions (deg or m) at which to evaluate the same mechanism, in any order;
        default the scene's sweep.
    strict : bool
        Refuse positions where a dyad cannot close or is exactly singular (the default);
        ``False`` probes such positions (between rows) without refusing.
    screened : bool
        With ``strict = False``: both closeness measures (:func:`solve_dyad`).
    """
    if len(structure.assembly) == len(structure.dyads):
        assembly: tuple = structure.assembly
    elif positions is None and strict:
        # the sweep's own first row is the scene's: each dyad chooses its assembly there
        # inside the one solve (solve_dyad with k = None), as choose_assembly would
        assembly = (None,) * len(structure.dyads)
    else:
        assembly = choose_assembly(scene, structure)
    if positions is not None:
        scene = with_positions(scene, positions)
    motions: dict[str, BodyMotion] = {GROUND: ground_motion(),
                                      scene.driver.body: driver_motion(scene)}
    kin = Kinematics(scene, structure, scene.driver.positions, motions)
    with np.errstate(all="ignore") if not strict else nullcontext():
        for dyad, k in zip(structure.dyads, assembly, strict=True):
            kin.dyads.append(solve_dyad(scene, dyad, motions, k, strict, screened))
    kin.structure = replace(structure, assembly=tuple(d.k for d in kin.dyads))
    return kin
