"""Static balancing of planar mechanisms (seed 002, section 3.4).

A mechanism is statically balanced when its centre of mass stays fixed over the
cycle: then the resultant of the inertia forces, F = -m a_G, is zero (the seed's
definition, s. 3.4). This module reads a mechanism scene with a ``[balancing]``
section (scene-format.md, section 2), finds the counterweights the chosen method
asks for (the scene gives each one's body, the body point it is measured from
and its radius; the method gives its mass and direction), and computes, from the
kinematics of the same scene, the shaking force and moment over the cycle before
and after.

Mechanisms and methods
----------------------
- four-bar (crank, coupler, rocker, four revolute joints), ``full``: counterweights
  on the crank (about A) and the rocker (about D), eqs 3.38-3.41, generalised to
  centres of mass off the link lines (linearly independent vectors, below);
- slider-crank (crank, rod, piston sliding on a ground guide): ``full`` (rod about
  B and crank about A, eqs 3.42-3.45), ``partial`` (crank about A: the rotating
  masses, eqs 3.46-3.47, plus optionally a ``fraction`` of the reciprocating first
  harmonic), ``first-harmonic`` (crank about A, eq. 3.51 as corrected in SPEC:
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

import copy
import dataclasses
import math
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import pandas as pd

import kinetostatics as ks
from kinetostatics.model.errors import AssemblyError
from kinetostatics.model.scene import GROUND, Body, Scene
from kinetostatics.model.tomlio import as_float, as_list, as_str, check_keys, read_source, suggest
from kinetostatics.solver.kinematics import BodyMotion, Kinematics

from .._util import deg360
from ..errors import BalanceError, BalanceWarning

__all__ = [
    "METHODS",
    "CounterRotatingPair",
    "Counterweight",
    "MechanismBalancing",
    "balanced_scene",
    "centre_of_mass",
    "h_vectors",
    "harmonic_amplitude",
    "shaking_force",
    "shaking_tables",
    "solve_mechanism_balancing",
]

METHODS = ("full", "partial", "first-harmonic", "counter-rotating")
BALANCING_KEYS = ("method", "counterweights", "fraction", "pair_radius")
COUNTERWEIGHT_KEYS = ("body", "about", "radius")
HARMONIC_GRID = 720      # uniform positions of a full turn for the Fourier coefficients
ON_LINE = 1e-9           # a cog is on its link's line within ON_LINE x the link length
CHECK = 1e-9             # a balanced quantity is zero within CHECK x its scale


def _J(v: np.ndarray) -> np.ndarray:
    """A quarter turn ccw: J (x, y) = (-y, x)."""
    return np.array([-v[1], v[0]])


# -- results -------------------------------------------------------------------------------

@dataclass(frozen=True)
class Counterweight:
    """A counterweight: a point mass fixed to a body.

    Attributes
    ----------
    body, about : str
        The body and the body's point the radius is measured from.
    radius : float
        Distance from ``about`` (m).
    mass : float
        kg.
    position : tuple of float
        Local coordinates in the body's frame (m), at ``radius`` from ``about``.
    angle : float
        Direction from ``about`` to the mass in the body's frame, deg in [0, 360).
    """

    body: str
    about: str
    radius: float
    mass: float
    position: tuple[float, float]
    angle: float

    def to_dict(self) -> dict[str, Any]:
        """``{body, about, mass, position, radius, angle}`` (the contract's keys first)."""
        return {"body": self.body, "about": self.about, "mass": float(self.mass),
                "position": [float(self.position[0]), float(self.position[1])],
                "radius": float(self.radius), "angle": float(self.angle)}


@dataclass(frozen=True)
class CounterRotatingPair:
    """The pair of eqs 3.52-3.53: two equal masses on gears outside the scene.

    At driver position theta (deg) the co-rotating mass stands at the global angle
    ``co_angle + theta`` and the counter-rotating one at ``counter_angle - theta``,
    both at ``radius`` from ``axis`` (the crank axis, by assumption).
    """

    mass: float
    radius: float
    axis: tuple[float, float]
    co_angle: float
    counter_angle: float

    def to_dict(self) -> dict[str, Any]:
        """``{mass, radius}`` of each mass of the pair, plus the axis and the angles at
        driver position 0 (deg, [0, 360))."""
        return {"mass": float(self.mass), "radius": float(self.radius),
                "axis": [float(self.axis[0]), float(self.axis[1])],
                "co_angle": float(self.co_angle), "counter_angle": float(self.counter_angle)}


@dataclass
class MechanismBalancing:
    """The result of a mechanism's static balancing (seed 002 s. 3.4).

    Attributes
    ----------
    scene : kinetostatics.Scene
        The mechanism scene (its ``[balancing]`` as read).
    kind : str
        ``"four-bar"`` or ``"slider-crank"``.
    method : str
        One of :data:`METHODS`.
    procedure : str
        How the counterweights were found (the seed's equations, or the more general
        method used where the seed's does not apply).
    counterweights : tuple of Counterweight
    pair : CounterRotatingPair or None
        ``counter-rotating`` only.
    kin : kinetostatics.Kinematics
        The motion over the scene's sweep.
    masses : dict
        The seed's concentrated masses (eq. 3.38 or 3.42; the along-line parts where
        a cog is off its line), kg.
    fraction : float or None
        ``partial``: the fraction of the reciprocating first harmonic balanced.
    A1 : float or None
        Slider-crank: the first-harmonic coefficient of the piston travel, in units
        of the crank length (1 for a centred slider-crank, eq. 3.51).
    checks : dict
        Numerical checks: the drift of the centre of mass over the sweep before and
        after (m); for a slider-crank the first harmonic of the shaking force along the
        slider's line before and after (N, FFT over a full turn).
    """

    scene: Scene
    kind: str
    method: str
    procedure: str
    counterweights: tuple[Counterweight, ...]
    pair: CounterRotatingPair | None
    kin: Kinematics
    masses: dict[str, float]
    fraction: float | None = None
    A1: float | None = None
    checks: dict[str, float] = dataclasses.field(default_factory=dict)

    @cached_property
    def before(self) -> pd.DataFrame:
        """Shaking force and moment over the sweep without counterweights
        (:func:`shaking_force`)."""
        return shaking_force(self.kin)

    @cached_property
    def after(self) -> pd.DataFrame:
        """Shaking force and moment over the sweep with the counterweights (and pair)."""
        return shaking_force(self.kin, self.counterweights, self.pair)

    @property
    def shaking_force_before(self) -> float:
        """Largest |F| over the sweep before balancing (N)."""
        return float(self.before["F"].max()) if len(self.before) else 0.0

    @property
    def shaking_force_after(self) -> float:
        """Largest |F| over the sweep after balancing (N)."""
        return float(self.after["F"].max()) if len(self.after) else 0.0

    def centre_of_mass(self, after: bool = True) -> pd.DataFrame:
        """The mechanism's centre of mass over the sweep (:func:`centre_of_mass`)."""
        return centre_of_mass(self.kin, self.counterweights if after else ())

    def h_vectors(self, after: bool = True) -> pd.DataFrame:
        """The seed's h vectors over the sweep (:func:`h_vectors`)."""
        return h_vectors(self.kin, self.counterweights if after else ())

    @property
    def centre(self) -> tuple[float, float] | None:
        """The fixed centre of mass after ``full`` balancing (its mean over the sweep,
        m); None for the other methods."""
        if self.method != "full":
            return None
        c = self.centre_of_mass(after=True)
        return float(c["x"].mean()), float(c["y"].mean())

    def to_dict(self) -> dict[str, Any]:
        """The contract's ``balancing`` result, JSON-ready, plus the project's keys."""
        out: dict[str, Any] = {
            "method": self.method,
            "mechanism": self.kind,
            "procedure": self.procedure,
            "counterweights": [c.to_dict() for c in self.counterweights],
        }
        if self.pair is not None:
            out["counter_rotating"] = self.pair.to_dict()
        out["shaking_force_before"] = self.shaking_force_before
        out["shaking_force_after"] = self.shaking_force_after
        out["shaking_moment_before"] = float(self.before["M"].abs().max()) \
            if len(self.before) else 0.0
        out["shaking_moment_after"] = float(self.after["M"].abs().max()) \
            if len(self.after) else 0.0
        centre = self.centre
        out["centre_of_mass"] = None if centre is None else [centre[0], centre[1]]
        out["concentrated_masses"] = {k: float(v) for k, v in self.masses.items()}
        if self.fraction is not None:
            out["fraction"] = float(self.fraction)
        if self.A1 is not None:
            out["A1"] = float(self.A1)
        out["checks"] = {k: float(v) for k, v in self.checks.items()}
        return out


# -- the mechanism's shape -----------------------------------------------------------------

@dataclass(frozen=True)
class _Linkage:
    """A recognised four-bar or slider-crank: body names and joint point names."""

    kind: str                       # "four-bar" | "slider-crank"
    crank: str
    link: str                       # coupler or rod
    last: str                       # rocker or piston
    A: str                          # crank's point at the ground joint
    B1: str                         # crank's point at B
    B2: str                         # link's point at B
    C2: str                         # link's point at C
    C3: str                         # last body's point at C
    D3: str | None                  # rocker's point at the ground joint
    axis: tuple[float, float]       # the crank axis (global)
    D: tuple[float, float] | None   # the rocker's pivot (global)
    line: str | None = None         # the piston's prismatic joint

    @property
    def roles(self) -> dict[str, str]:
        if self.kind == "four-bar":
            return {"crank": self.crank, "coupler": self.link, "rocker": self.last}
        return {"crank": self.crank, "rod": self.link, "piston": self.last}

    def chain(self) -> list[tuple[str, str, str | None]]:
        """The serial chain of eqs 3.33: (body, first joint point, second joint point)."""
        return [(self.crank, self.A, self.B1), (self.link, self.B2, self.C2),
                (self.last, self.C3, self.D3 if self.kind == "four-bar" else None)]


def _describe(sc: Scene) -> str:
    joints = ", ".join(f"{j.name} ({j.kind}: {'-'.join(j.bodies)})" for j in sc.joints.values())
    return f"bodies {', '.join(sc.bodies)}; joints {joints}"


def _linkage(sc: Scene) -> _Linkage:
    """Recognise a four-bar or a slider-crank driven by its crank, else BalanceError."""
    drv = sc.driver
    if drv.kind != "R":
        raise BalanceError(f"static balancing (seed 002 s. 3.4) needs a crank driver; the driver "
                           f"{drv.body!r} slides (joint {drv.joint!r} is prismatic)")
    shape = ("static balancing (seed 002 s. 3.4) covers the four-bar (crank, coupler, rocker, "
             "four revolute joints) and the slider-crank (crank, rod, piston on a ground guide); "
             f"this scene is neither: {_describe(sc)}")
    if len(sc.bodies) != 3 or len(sc.joints) != 4:
        raise BalanceError(shape)
    crank = drv.body
    dj = sc.joints[drv.joint]
    others = [j for j in sc.joints.values() if j is not dj]
    jb = [j for j in others if crank in j.bodies]
    if len(jb) != 1 or jb[0].kind != "R" or GROUND in jb[0].bodies:
        raise BalanceError(shape)
    link = jb[0].other(crank)
    last = next(b for b in sc.bodies if b not in (crank, link))
    jc = [j for j in others if set(j.bodies) == {link, last}]
    jg = [j for j in others if set(j.bodies) == {last, GROUND}]
    if len(jc) != 1 or jc[0].kind != "R" or len(jg) != 1:
        raise BalanceError(shape)
    common = dict(crank=crank, link=link, last=last, A=dj.point_on(crank),
                  B1=jb[0].point_on(crank), B2=jb[0].point_on(link), C2=jc[0].point_on(link),
                  C3=jc[0].point_on(last), axis=sc.ground[dj.point_on(GROUND)])
    g = jg[0]
    if g.kind == "R":
        return _Linkage(kind="four-bar", D3=g.point_on(last), D=sc.ground[g.point_on(GROUND)],
                        **common)
    return _Linkage(kind="slider-crank", D3=None, D=None, line=g.name, **common)


# -- the [balancing] table -----------------------------------------------------------------

@dataclass(frozen=True)
class _CwSpec:
    body: str
    about: str
    radius: float


def _read_spec(sc: Scene, table: Any) -> tuple[str, list[_CwSpec], float | None, float | None]:
    t = check_keys(table, BALANCING_KEYS, "[balancing]", required=("method", "counterweights"))
    method = as_str(t["method"], "balancing.method")
    if method not in METHODS:
        raise BalanceError(f"balancing.method {method!r} is unknown{suggest(method, METHODS)}; "
                           f"known: {', '.join(METHODS)}")
    items = as_list(t["counterweights"], "balancing.counterweights")
    specs = []
    for i, item in enumerate(items):
        w = f"balancing.counterweights[{i}]"
        c = check_keys(item, COUNTERWEIGHT_KEYS, w, required=COUNTERWEIGHT_KEYS)
        body = as_str(c["body"], f"{w}.body")
        if body not in sc.bodies:
            raise BalanceError(f"{w}.body: unknown body {body!r}{suggest(body, sc.bodies)}; "
                               f"moving bodies: {', '.join(sc.bodies)}")
        about = as_str(c["about"], f"{w}.about")
        points = sc.bodies[body].points
        if about not in points:
            raise BalanceError(f"{w}.about: body {body!r} has no point {about!r}"
                               f"{suggest(about, points)}; its points: {', '.join(points)}")
        radius = as_float(c["radius"], f"{w}.radius", positive=True)
        specs.append(_CwSpec(body, about, radius))
    fraction = pair_radius = None
    if "fraction" in t:
        if method != "partial":
            raise BalanceError(f"balancing.fraction applies to method 'partial', not {method!r}")
        fraction = as_float(t["fraction"], "balancing.fraction", nonnegative=True)
        if fraction > 1.0:
            raise BalanceError(f"balancing.fraction must lie in [0, 1] (the share of the "
                               f"reciprocating first harmonic balanced), got {fraction:g}")
    if "pair_radius" in t:
        if method != "counter-rotating":
            raise BalanceError("balancing.pair_radius applies to method 'counter-rotating', "
                               f"not {method!r}")
        pair_radius = as_float(t["pair_radius"], "balancing.pair_radius", positive=True)
    return method, specs, fraction, pair_radius


def _assign(lk: _Linkage, method: str, specs: list[_CwSpec]) -> dict[str, _CwSpec]:
    """Match the given counterweights to the roles the method needs."""
    if lk.kind == "four-bar":
        if method != "full":
            raise BalanceError(f"method {method!r} applies to a slider-crank; a four-bar is "
                               "balanced by method 'full' (eqs 3.38-3.41)")
        need = {"crank": (lk.crank, lk.A), "rocker": (lk.last, lk.D3)}
        eqs = "eqs 3.38-3.41"
    elif method == "full":
        need = {"rod": (lk.link, lk.B2), "crank": (lk.crank, lk.A)}
        eqs = "eqs 3.42-3.45"
    else:
        need = {"crank": (lk.crank, lk.A)}
        eqs = {"partial": "eqs 3.46-3.47", "first-harmonic": "eqs 3.48-3.51",
               "counter-rotating": "eqs 3.46, 3.52-3.53"}[method]
    wanted = " and ".join(f"the {r} {b!r} (about {p})" for r, (b, p) in need.items())
    by_body = {b: r for r, (b, _) in need.items()}
    out: dict[str, _CwSpec] = {}
    for i, s in enumerate(specs):
        role = by_body.get(s.body)
        if role is None:
            raise BalanceError(f"balancing.counterweights[{i}]: method {method!r} on a "
                               f"{lk.kind} puts counterweights on {wanted} ({eqs}), "
                               f"not on {s.body!r}")
        if role in out:
            raise BalanceError(f"balancing.counterweights[{i}]: a second counterweight on "
                               f"{s.body!r}; method {method!r} takes one on {wanted}")
        out[role] = s
    missing = [r for r in need if r not in out]
    if missing:
        raise BalanceError(f"balancing.counterweights: method {method!r} on a {lk.kind} needs "
                           f"counterweights on {wanted} ({eqs}); missing: "
                           + ", ".join(f"{r} {need[r][0]!r}" for r in missing))
    return out


# -- mass properties and placement -----------------------------------------------------------

def _vec(p: Iterable[float]) -> np.ndarray:
    return np.asarray(tuple(p), dtype=float)


def _moment(body: Body, ref: np.ndarray) -> np.ndarray:
    """First moment of a body's mass about a local point: m (G - ref), local (kg m)."""
    if body.mass == 0.0:
        return np.zeros(2)
    return body.mass * (_vec(body.local("cog")) - ref)


def _split(q: np.ndarray, u: np.ndarray) -> tuple[float, float]:
    """q = q_a u + q_b J u: a first moment split along and across a link u (kg)."""
    uu = float(u @ u)
    if uu == 0.0:
        raise BalanceError("a link has its two joints at the same point: zero length")
    return float(q @ u) / uu, float(q @ _J(u)) / uu


def _off_line(body: Body, ref: np.ndarray, u: np.ndarray) -> bool:
    """True when the body's cog is off the line through ``ref`` along ``u``."""
    if body.mass == 0.0 or body.cog is None:
        return False
    d = _vec(body.cog) - ref
    n = float(np.hypot(*u))
    return abs(float(d @ _J(u))) / n > ON_LINE * n


def _place(sc: Scene, spec: _CwSpec, ref: str, W: np.ndarray, scale: float) -> Counterweight:
    """The counterweight on ``spec.body`` whose first moment about the body point ``ref``
    is W (local): m (v + d) = W with v = about - ref and |d| = radius; the lightest."""
    body = sc.bodies[spec.body]
    p = _vec(body.points[spec.about])
    v = p - _vec(body.points[ref])
    r = spec.radius
    c = float(W @ W)
    if math.sqrt(c) <= 1e-14 * scale:
        return Counterweight(spec.body, spec.about, r, 0.0, (float(p[0] + r), float(p[1])), 0.0)
    a = float(v @ v) - r * r           # m^2 (|v|^2 - r^2) - 2 m W.v + |W|^2 = 0
    b = -2.0 * float(W @ v)
    if abs(a) <= 1e-12 * max(float(v @ v), r * r):
        roots = [-c / b] if b < 0.0 else []
    else:
        disc = b * b - 4.0 * a * c
        roots = [] if disc < 0.0 else [(-b - math.sqrt(disc)) / (2.0 * a),
                                      (-b + math.sqrt(disc)) / (2.0 * a)]
    roots = [m for m in roots if m > 0.0]
    if not roots:
        raise BalanceError(
            f"no counterweight on {spec.body!r} at radius {r:g} m from {spec.about!r} can give "
            f"the first moment {math.sqrt(c):.6g} kg m about {ref!r} (the circle does not meet "
            f"the needed direction): take a larger radius or measure it from {ref!r}")
    m = min(roots)
    d = W / m - v
    pos = p + d
    return Counterweight(spec.body, spec.about, r, m, (float(pos[0]), float(pos[1])),
                         deg360(math.degrees(math.atan2(d[1], d[0]))))


# -- motion helpers ---------------------------------------------------------------------------

def _kin(sol: Any) -> Kinematics:
    """A Kinematics from a Solution (``.kin``), a Kinematics or a MechanismBalancing."""
    kin = getattr(sol, "kin", sol)
    if not isinstance(kin, Kinematics):
        raise BalanceError(f"expected a kinetostatics Solution or Kinematics, not "
                           f"{type(sol).__name__}")
    return kin


def _full(x: Any, n: int) -> np.ndarray:
    return np.broadcast_to(np.asarray(x, dtype=float), (n,))


def _motion_at(bm: BodyMotion, local: Iterable[float], n: int) -> tuple[np.ndarray, ...]:
    """x, y, vx, vy, ax, ay (arrays) of a body's local point."""
    lx, ly = (float(t) for t in local)
    rx, ry = bm.rotate(lx, ly)
    x, y = bm.ox + rx, bm.oy + ry
    vx, vy = bm.vel_arm(rx, ry)
    ax, ay = bm.acc_arm(rx, ry)
    return tuple(_full(t, n) for t in (x, y, vx, vy, ax, ay))


def _masses(kin: Kinematics, counterweights: Iterable[Counterweight]):
    """(body, mass, local point, inertia) of every body cog and counterweight."""
    for name, body in kin.scene.bodies.items():
        if body.mass != 0.0 or body.inertia != 0.0:
            yield name, body.mass, body.local("cog"), body.inertia
    for cw in counterweights:
        if cw.mass != 0.0:
            yield cw.body, cw.mass, cw.position, 0.0


def _crank_axis(scene: Scene) -> tuple[float, float]:
    drv = scene.driver
    if drv.kind != "R":
        return (0.0, 0.0)
    return scene.ground[scene.joints[drv.joint].point_on(GROUND)]


def _pair_motion(kin: Kinematics, pair: CounterRotatingPair):
    """(x, y, ax, ay) arrays of the co- and counter-rotating masses."""
    n = kin.n
    crank = kin.bodies[kin.scene.driver.body]
    th = _full(crank.theta, n)
    w = _full(crank.omega, n)
    eps = _full(crank.alpha, n)
    out = []
    for sign, phase in ((1.0, pair.co_angle), (-1.0, pair.counter_angle)):
        ang = sign * th + math.radians(phase)
        c, s = np.cos(ang), np.sin(ang)
        x = pair.axis[0] + pair.radius * c
        y = pair.axis[1] + pair.radius * s
        # a = r (theta'' J e - theta'^2 e), theta' = +-omega, theta'' = +-eps
        ax = pair.radius * (-sign * eps * s - w * w * c)
        ay = pair.radius * (sign * eps * c - w * w * s)
        out.append((x, y, ax, ay))
    return out


# -- public tables ----------------------------------------------------------------------------

def shaking_force(sol: Any, counterweights: Iterable[Counterweight] = (),
                  pair: CounterRotatingPair | None = None,
                  about: tuple[float, float] | None = None) -> pd.DataFrame:
    """Shaking force and moment over the sweep: the resultant of the inertia loads.

    F = sum -m_i a_Gi over the moving bodies and the counterweights (and the pair), the
    force the mechanism's inertia puts on the frame (s. 3.4: F_i = -m a_G); M its
    moment about ``about`` (default the crank axis), with the couples -I_Gi eps_i.

    Parameters
    ----------
    sol : kinetostatics.Solution or Kinematics
        The motion over the sweep.
    counterweights : iterable of Counterweight
        Point masses fixed to bodies.
    pair : CounterRotatingPair, optional
        The masses of eqs 3.52-3.53.
    about : (x, y), optional
        Reference point of the moment (m); default the crank axis.

    Returns
    -------
    pandas.DataFrame
        ``position, Fx, Fy, F, M`` (N, N m).
    """
    kin = _kin(sol)
    n = kin.n
    x0, y0 = about if about is not None else _crank_axis(kin.scene)
    fx, fy, mz = np.zeros(n), np.zeros(n), np.zeros(n)
    for name, m, local, inertia in _masses(kin, counterweights):
        bm = kin.bodies[name]
        x, y, _, _, ax, ay = _motion_at(bm, local, n)
        gx, gy = -m * ax, -m * ay
        fx += gx
        fy += gy
        mz += (x - x0) * gy - (y - y0) * gx - inertia * _full(bm.alpha, n)
    if pair is not None and pair.mass != 0.0:
        for x, y, ax, ay in _pair_motion(kin, pair):
            gx, gy = -pair.mass * ax, -pair.mass * ay
            fx += gx
            fy += gy
            mz += (x - x0) * gy - (y - y0) * gx
    return pd.DataFrame({"position": kin.positions, "Fx": fx, "Fy": fy, "F": np.hypot(fx, fy),
                         "M": mz})


def shaking_tables(result: MechanismBalancing) -> dict[str, pd.DataFrame]:
    """``{"before": table, "after": table}``: :func:`shaking_force` without and with the
    result's counterweights (columns ``position, Fx, Fy, F, M``)."""
    return {"before": result.before, "after": result.after}


def centre_of_mass(sol: Any, counterweights: Iterable[Counterweight] = ()) -> pd.DataFrame:
    """The mechanism's centre of mass over the sweep, eq. 3.32: m r_G = sum m_i r_i.

    Parameters
    ----------
    sol : kinetostatics.Solution or Kinematics
    counterweights : iterable of Counterweight
        Added point masses (a balanced mechanism).

    Returns
    -------
    pandas.DataFrame
        ``position, x, y, vx, vy, ax, ay, mass`` (m, m/s, m/s^2, kg) of the centre of
        mass of the moving bodies and counterweights.
    """
    kin = _kin(sol)
    n = kin.n
    acc = np.zeros((6, n))
    total = 0.0
    for name, m, local, _ in _masses(kin, counterweights):
        if m == 0.0:
            continue
        acc += m * np.array(_motion_at(kin.bodies[name], local, n))
        total += m
    if total == 0.0:
        raise BalanceError("the mechanism has no mass: its centre of mass is undefined")
    x, y, vx, vy, ax, ay = acc / total
    return pd.DataFrame({"position": kin.positions, "x": x, "y": y, "vx": vx, "vy": vy,
                         "ax": ax, "ay": ay, "mass": total})


def h_vectors(sol: Any, counterweights: Iterable[Counterweight] = ()) -> pd.DataFrame:
    """The seed's h vectors over the sweep (eqs 3.33-3.37).

    Along the serial chain A-B-C(-D) of a four-bar or slider-crank (crank, coupler or
    rod, rocker or piston), body i with mass m_i (counterweights included), cog s_i and
    link l_i measured from its first joint gives

        h_i = (m_i s_i + (m_(i+1) + ... + m_n) l_i) / m          (3.36)

    and r_G = A + h_1 + ... + h_n (3.37), A the crank axis. Each h_i is fixed in its
    body: constant length, turning with it.

    Returns
    -------
    pandas.DataFrame
        ``position, body, hx, hy, h`` (m, global components), one row per body and
        position, in chain order.
    """
    kin = _kin(sol)
    sc = kin.scene
    lk = _linkage(sc)
    cws = list(counterweights)
    chain = lk.chain()
    mass, first = [], []
    for name, p, _ in chain:
        body = sc.bodies[name]
        ref = _vec(body.points[p])
        m = body.mass + sum(c.mass for c in cws if c.body == name)
        s = _moment(body, ref) + sum((c.mass * (_vec(c.position) - ref) for c in cws
                                      if c.body == name), np.zeros(2))
        mass.append(m)
        first.append(s)
    total = sum(mass)
    if total == 0.0:
        raise BalanceError("the mechanism has no mass: the h vectors are undefined")
    parts = []
    n = kin.n
    for i, (name, p, q) in enumerate(chain):
        body = sc.bodies[name]
        link = _vec(body.points[q]) - _vec(body.points[p]) if q is not None else np.zeros(2)
        h = (first[i] + sum(mass[i + 1:]) * link) / total          # local, eq. 3.36
        hx, hy = kin.bodies[name].rotate(float(h[0]), float(h[1]))
        hx, hy = _full(hx, n), _full(hy, n)
        parts.append(pd.DataFrame({"position": kin.positions, "body": name, "hx": hx, "hy": hy,
                                   "h": np.hypot(hx, hy)}))
    return pd.concat(parts, ignore_index=True)


def harmonic_amplitude(values: Any, order: int = 1) -> float:
    """Amplitude of one harmonic of a periodic signal sampled at N uniformly spaced
    positions of one full cycle (the endpoint not repeated): 2 |FFT_k| / N.

    Parameters
    ----------
    values : array_like
        The samples.
    order : int
        The harmonic k >= 1 (k < N / 2).

    Examples
    --------
    >>> t = np.linspace(0.0, 2.0 * np.pi, 360, endpoint=False)
    >>> round(harmonic_amplitude(3.0 * np.cos(t) + np.sin(2 * t), 1), 12)
    3.0
    """
    v = np.asarray(values, dtype=float)
    if not 1 <= order < v.size / 2:
        raise BalanceError(f"harmonic {order} needs more than {2 * order} samples, "
                           f"got {v.size}")
    return float(2.0 * np.abs(np.fft.rfft(v)[order]) / v.size)


# -- the methods -------------------------------------------------------------------------------

def _scale(sc: Scene) -> float:
    """A first-moment scale (kg m): total mass times the largest point distance."""
    pts = [np.hypot(*p) for b in sc.bodies.values() for p in b.points.values()]
    pts += [np.hypot(*p) for p in sc.ground.values()]
    size = max(pts, default=1.0) or 1.0
    return max(sum(b.mass for b in sc.bodies.values()), 1e-300) * size


def _pts(sc: Scene, lk: _Linkage) -> dict[str, np.ndarray]:
    b = sc.bodies
    out = {"A": _vec(b[lk.crank].points[lk.A]), "B1": _vec(b[lk.crank].points[lk.B1]),
           "B2": _vec(b[lk.link].points[lk.B2]), "C2": _vec(b[lk.link].points[lk.C2]),
           "C3": _vec(b[lk.last].points[lk.C3])}
    if lk.D3 is not None:
        out["D3"] = _vec(b[lk.last].points[lk.D3])
    return out


def _four_bar_full(sc: Scene, lk: _Linkage, roles: dict[str, _CwSpec]):
    """Counterweights on the crank (about A) and the rocker (about D): eqs 3.38-3.41,
    in vector form (linearly independent vectors)."""
    P = _pts(sc, lk)
    m1, m2, m3 = (sc.bodies[k] for k in (lk.crank, lk.link, lk.last))
    b1 = P["B1"] - P["A"]                       # AB on the crank
    u = P["C2"] - P["B2"]                       # BC on the coupler
    c3 = P["C3"] - P["D3"]                      # DC on the rocker
    qa, qb = _split(_moment(m2, P["B2"]), u)    # m2 (G2 - B) = qa u + qb J u
    U1 = _moment(m1, P["A"]) + (m2.mass - qa) * b1 - qb * _J(b1)
    U3 = _moment(m3, P["D3"]) + qa * c3 + qb * _J(c3)
    scale = _scale(sc)
    cws = (_place(sc, roles["crank"], lk.A, -U1, scale),       # me1 r1 = m_B l1 (3.39)
           _place(sc, roles["rocker"], lk.D3, -U3, scale))     # me3 r3 = m_C l3 (3.39)
    a1 = _split(_moment(m1, P["A"]), b1)[0]
    a3 = _split(_moment(m3, P["D3"]), c3)[0]
    masses = {"m_A": m1.mass - a1, "m_B": a1 + m2.mass - qa,            # eq. 3.38
              "m_C": qa + a3, "m_D": m3.mass - a3}
    off = [name for name, body, ref, v in ((lk.crank, m1, P["A"], b1), (lk.link, m2, P["B2"], u),
                                           (lk.last, m3, P["D3"], c3))
           if _off_line(body, ref, v)]
    if off:
        proc = ("linearly independent vectors: the total first moment is const + R1 U1 + R3 U3 "
                "and the counterweights cancel U1 (crank, about A) and U3 (rocker, about D); "
                f"the cog of {', '.join(off)} is off its link's line, so the static "
                "concentration of eqs 3.38-3.39 does not apply as printed")
    else:
        proc = ("eqs 3.38-3.41: masses concentrated statically in the joints, "
                "me1 r1 = m_B l1 and me3 r3 = m_C l3 (3.39)")
    return cws, proc, masses


def _slider_full(sc: Scene, lk: _Linkage, roles: dict[str, _CwSpec]):
    """Rod about B (the rod + piston cog to B, eq. 3.43) then crank about A (the whole
    cog to A, eq. 3.44): eqs 3.42-3.45."""
    P = _pts(sc, lk)
    m1, m2, m3 = (sc.bodies[k] for k in (lk.crank, lk.link, lk.last))
    b1 = P["B1"] - P["A"]
    u = P["C2"] - P["B2"]
    scale = _scale(sc)
    W2 = -(_moment(m2, P["B2"]) + m3.mass * u)              # me2 r2 = m_C l2 (3.43)
    cw2 = _place(sc, roles["rod"], lk.B2, W2, scale)
    U1 = _moment(m1, P["A"]) + (m2.mass + m3.mass + cw2.mass) * b1
    cw1 = _place(sc, roles["crank"], lk.A, -U1, scale)     # me1 r1 = (me2 + m1B + m2 + m3) l1
    masses = _slider_masses(m1, m2, m3, P)
    off = [name for name, body, ref, v in ((lk.crank, m1, P["A"], b1), (lk.link, m2, P["B2"], u))
           if _off_line(body, ref, v)]
    proc = "eqs 3.42-3.45: the rod's counterweight puts the rod + piston cog at B (3.43), " \
           "the crank's the whole cog at A (3.44)"
    if off:
        proc += (f"; the cog of {', '.join(off)} is off its link's line: the same conditions "
                 "in vector form (the counterweights are not on the links' extensions)")
    return (cw2, cw1), proc, masses


def _slider_masses(m1: Body, m2: Body, m3: Body, P: dict[str, np.ndarray]) -> dict[str, float]:
    a1 = _split(_moment(m1, P["A"]), P["B1"] - P["A"])[0]
    a2 = _split(_moment(m2, P["B2"]), P["C2"] - P["B2"])[0]
    return {"m_A": m1.mass - a1, "m_B": a1 + m2.mass - a2, "m_C": m3.mass + a2}   # eq. 3.42


def _grid(sc: Scene) -> Kinematics:
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


def _line(gk: Kinematics, lk: _Linkage) -> tuple[np.ndarray, np.ndarray]:
    """Unit direction u of the slider's line and the points C over the grid."""
    body = gk.scene.bodies[lk.link]
    x, y, *_ = _motion_at(gk.bodies[lk.link], body.points[lk.C2], gk.n)
    pts = np.column_stack([x, y])
    _, _, vt = np.linalg.svd(pts - pts.mean(axis=0), full_matrices=False)
    u = vt[0]
    if float((pts.mean(axis=0) - _vec(lk.axis)) @ u) < 0.0:   # from the crank axis outwards
        u = -u
    return u, pts


def _slider_harmonic(sc: Scene, lk: _Linkage, gk: Kinematics):
    """First harmonic of the piston travel s(theta) = (C - A).u over the crank angle:
    a_s cos theta + b_s sin theta = l1 A1 cos(theta - phi0) (eqs 3.48-3.49).

    Returns (a_s, b_s, u, centred)."""
    P = _pts(sc, lk)
    u, pts = _line(gk, lk)
    axis = _vec(lk.axis)
    l1 = float(np.hypot(*(P["B1"] - P["A"])))
    centred = abs(float((axis - pts.mean(axis=0)) @ _J(u))) <= ON_LINE * l1
    s = (pts - axis) @ u
    th = _full(gk.bodies[lk.crank].theta, gk.n)
    a_s = 2.0 * float(np.mean(s * np.cos(th)))
    b_s = 2.0 * float(np.mean(s * np.sin(th)))
    return a_s, b_s, u, centred


def _slider_crank_only(sc: Scene, lk: _Linkage, roles: dict[str, _CwSpec], method: str,
                       fraction: float | None, pair_radius: float | None, gk: Kinematics):
    """``partial`` (3.46-3.47), ``first-harmonic`` (3.51 corrected) and
    ``counter-rotating`` (3.46 with 3.52-3.53): one counterweight on the crank."""
    P = _pts(sc, lk)
    m1, m2, m3 = (sc.bodies[k] for k in (lk.crank, lk.link, lk.last))
    b1 = P["B1"] - P["A"]
    u_rod = P["C2"] - P["B2"]
    l1 = float(np.hypot(*b1))
    qa, qb = _split(_moment(m2, P["B2"]), u_rod)
    U_rot = _moment(m1, P["A"]) + (m2.mass - qa) * b1 - qb * _J(b1)    # |U_rot| = m_B l1
    m_C = m3.mass + qa                                                    # eq. 3.42
    a_s, b_s, u, centred = _slider_harmonic(sc, lk, gk)
    if centred:
        w_rec = -m_C * b1                        # m_C l1 A1 opposite B, A1 = 1 (3.51)
        A1 = 1.0
    else:                                        # offset line: A1 and its phase by FFT
        w_rec = -m_C * (a_s * u - b_s * _J(u))
        A1 = math.hypot(a_s, b_s) / l1
    scale = _scale(sc)
    f = {"partial": fraction or 0.0, "first-harmonic": 1.0, "counter-rotating": 0.0}[method]
    W1 = -U_rot + f * w_rec
    cw = _place(sc, roles["crank"], lk.A, W1, scale)
    pair = None
    notes = []
    if method == "partial":
        proc = "eqs 3.46-3.47: the crank's counterweight balances the rotating masses, " \
               "me re = m_B l1"
        if f:
            proc += (f", plus {f:g} of the piston's first harmonic: "
                     f"me re = (m_B + {f:g} m_C A1) l1")
    elif method == "first-harmonic":
        proc = ("eq. 3.51 as corrected (SPEC): m'e re = (m_B + m_C A1) l1, A1 = 1; the first "
                "harmonic along the slider's line vanishes and reappears across it")
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
            co_angle=deg360(math.degrees(th_u - phi0 + math.pi)) if amp else 0.0,
            counter_angle=deg360(math.degrees(th_u + phi0 + math.pi)) if amp else 0.0)
        proc = ("eqs 3.46 and 3.52-3.53: the crank's counterweight balances the rotating "
                "masses (me re = m_B l1); two masses me = m_C l1 A1 / (2 re) turning at "
                "+omega and -omega about the crank axis cancel the piston's first harmonic")
    if not centred:
        notes.append("the slider's line misses the crank axis (an offset slider-crank): A1 "
                     "and its phase come from the Fourier series of the piston travel")
    off = [name for name, body, ref, v in ((lk.crank, m1, P["A"], b1),
                                           (lk.link, m2, P["B2"], u_rod))
           if _off_line(body, ref, v)]
    if off:
        notes.append(f"the cog of {', '.join(off)} is off its link's line: the rotating and "
                     "reciprocating parts are split in vector form (along and across BC)")
    if notes:
        proc += "; " + "; ".join(notes)
    return (cw,), pair, proc, _slider_masses(m1, m2, m3, P), A1, u


# -- the entry point ----------------------------------------------------------------------------

def solve_mechanism_balancing(scene: Any, *, method: str | None = None,
                              counterweights: list[Mapping[str, Any]] | None = None,
                              fraction: float | None = None,
                              pair_radius: float | None = None) -> MechanismBalancing:
    """Static balancing of a four-bar or slider-crank scene (seed 002 s. 3.4).

    Parameters
    ----------
    scene : pathlib.Path, str, dict or kinetostatics.Scene
        A mechanism scene (scene-format.md section 1) with a ``[balancing]`` table:
        ``method`` (``full``, ``partial``, ``first-harmonic``, ``counter-rotating``),
        ``counterweights`` (a list of ``{body, about, radius}``) and, as project
        additions, ``fraction`` (``partial``: the share in [0, 1] of the piston's first
        harmonic balanced besides the rotating masses, default 0 as in eq. 3.46) and
        ``pair_radius`` (``counter-rotating``: the radius of the pair's masses, m,
        default the crank counterweight's radius).
    method, counterweights, fraction, pair_radius : optional
        Replace the corresponding entries of the scene's ``[balancing]``.

    Returns
    -------
    MechanismBalancing
        ``.to_dict()`` gives the contract's keys: ``counterweights`` (``{body, about,
        mass, position}``), ``counter_rotating`` (``{mass, radius}``) and
        ``shaking_force_before``, ``shaking_force_after`` (N).

    Raises
    ------
    BalanceError, SceneError
        One line: no ``[balancing]``, an unknown method, body or point, a radius <= 0,
        a method that does not apply to the mechanism, a mechanism that is neither a
        four-bar nor a slider-crank.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> raw = ks.load_scene(ks.example("four_bar")).raw
    >>> raw["balancing"] = {"method": "full", "counterweights": [
    ...     {"body": "crank", "about": "A", "radius": 0.06},
    ...     {"body": "rocker", "about": "D", "radius": 0.08}]}
    >>> res = solve_mechanism_balancing(raw)
    >>> res.shaking_force_after < 1e-9 * res.shaking_force_before
    True
    """
    raw = scene.raw if isinstance(scene, Scene) else read_source(scene, "mechanism scene")
    raw = dict(raw)
    table = dict(raw.get("balancing") or {})
    for key, value in (("method", method), ("counterweights", counterweights),
                       ("fraction", fraction), ("pair_radius", pair_radius)):
        if value is not None:
            table[key] = value
    if not table:
        raise BalanceError("the scene has no [balancing] table: give method and "
                           "counterweights (scene-format.md section 2)")
    raw["balancing"] = table
    sc = ks.load_scene(raw)
    lk = _linkage(sc)
    method_, specs, fraction_, pair_radius_ = _read_spec(sc, table)
    roles = _assign(lk, method_, specs)
    kin = ks.solve_kinematics(sc, ks.analyse(sc))
    pair = None
    A1 = None
    u = None
    gk = None
    if lk.kind == "four-bar":
        cws, proc, masses = _four_bar_full(sc, lk, roles)
    else:
        gk = _grid(sc)
        if method_ == "full":
            cws, proc, masses = _slider_full(sc, lk, roles)
            u = _line(gk, lk)[0]
        else:
            cws, pair, proc, masses, A1, u = _slider_crank_only(
                sc, lk, roles, method_, fraction_, pair_radius_, gk)
    res = MechanismBalancing(scene=sc, kind=lk.kind, method=method_, procedure=proc,
                             counterweights=tuple(cws), pair=pair, kin=kin, masses=masses,
                             fraction=(fraction_ or 0.0) if method_ == "partial" else None,
                             A1=A1)
    res.checks = _checks(res, gk, u)
    return res


def _drift(c: pd.DataFrame) -> float:
    if not len(c):
        return 0.0
    return float(np.hypot(c["x"] - c["x"].mean(), c["y"] - c["y"].mean()).max())


def _checks(res: MechanismBalancing, gk: Kinematics | None, u: np.ndarray | None
            ) -> dict[str, float]:
    """Numerical checks of the closed forms (the balancing is verified, not assumed)."""
    if sum(b.mass for b in res.scene.bodies.values()) == 0.0:
        raise BalanceError("the mechanism has no mass (every body's mass is 0): there is "
                           "nothing to balance")
    out = {"centre_of_mass_drift_before": _drift(res.centre_of_mass(after=False)),
           "centre_of_mass_drift_after": _drift(res.centre_of_mass(after=True))}
    size = _scale(res.scene) / max(sum(b.mass for b in res.scene.bodies.values()), 1e-300)
    if res.method == "full" and out["centre_of_mass_drift_after"] > CHECK * size:
        warnings.warn(f"after full balancing the centre of mass still moves by "
                      f"{out['centre_of_mass_drift_after']:.3g} m", BalanceWarning,
                      stacklevel=3)
    if gk is not None and u is not None:
        before = shaking_force(gk)
        after = shaking_force(gk, res.counterweights, res.pair)
        fb = before["Fx"].to_numpy() * u[0] + before["Fy"].to_numpy() * u[1]
        fa = after["Fx"].to_numpy() * u[0] + after["Fy"].to_numpy() * u[1]
        out["first_harmonic_before"] = harmonic_amplitude(fb, 1)
        out["first_harmonic_after"] = harmonic_amplitude(fa, 1)
        out["line_angle"] = deg360(math.degrees(math.atan2(u[1], u[0])))
        if res.method in ("first-harmonic", "counter-rotating", "full") and \
                out["first_harmonic_after"] > CHECK * max(out["first_harmonic_before"], 1e-300):
            warnings.warn(f"after {res.method} balancing the first harmonic along the line is "
                          f"still {out['first_harmonic_after']:.3g} N", BalanceWarning,
                          stacklevel=3)
    return out


def balanced_scene(result: MechanismBalancing) -> dict[str, Any]:
    """The scene as a dict with each counterweight added to its body's mass, cog and
    moment of inertia (point masses), ready for ``kinetostatics.solve``.

    The ``[balancing]`` table is dropped, and so is the ``mass_model`` of a body that
    takes a counterweight (the new cog need not lie on its two points). The pair of a
    ``counter-rotating`` result is outside the scene and is not added.
    """
    raw = copy.deepcopy(result.scene.raw)
    raw.pop("balancing", None)
    for entry in raw.get("bodies", []):
        name = entry.get("name")
        cws = [c for c in result.counterweights if c.body == name and c.mass != 0.0]
        if not cws:
            continue
        body = result.scene.bodies[name]
        g0 = _vec(body.local("cog"))
        m = body.mass + sum(c.mass for c in cws)
        g = (body.mass * g0 + sum((c.mass * _vec(c.position) for c in cws), np.zeros(2))) / m
        inertia = body.inertia + body.mass * float((g0 - g) @ (g0 - g)) + sum(
            c.mass * float((_vec(c.position) - g) @ (_vec(c.position) - g)) for c in cws)
        entry["mass"] = float(m)
        entry["cog"] = [float(g[0]), float(g[1])]
        entry["inertia"] = float(inertia)
        entry.pop("mass_model", None)
    return raw
