"""Linkage detection for static balancing (seed 002 s. 3.4): which body is the crank,
the coupler or rod, the rocker or piston; the ``[balancing]`` table read against it;
first moments of the bodies about their joint points.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from kinetostatics.model.scene import GROUND, Body, Scene
from kinetostatics.model.tomlio import as_float, as_list, as_str, check_keys, suggest

from ..errors import BalanceError

__all__ = [
    "BALANCING_KEYS",
    "COUNTERWEIGHT_KEYS",
    "METHODS",
    "ON_LINE",
    "CounterweightSpec",
    "Linkage",
    "assign_roles",
    "first_moment",
    "joint_points",
    "off_line",
    "quarter_turn",
    "read_spec",
    "recognise",
    "split_along",
    "vec",
]

METHODS = ("full", "partial", "first-harmonic", "counter-rotating")
BALANCING_KEYS = ("method", "counterweights", "fraction", "pair_radius")
COUNTERWEIGHT_KEYS = ("body", "about", "radius")
ON_LINE = 1e-9           # a cog is on its link's line within ON_LINE x the link length


def quarter_turn(v: np.ndarray) -> np.ndarray:
    """A quarter turn ccw: J (x, y) = (-y, x)."""
    return np.array([-v[1], v[0]])



# -- the mechanism's shape -----------------------------------------------------------------

@dataclass(frozen=True)
class Linkage:
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


def recognise(sc: Scene) -> Linkage:
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
        return Linkage(kind="four-bar", D3=g.point_on(last), D=sc.ground[g.point_on(GROUND)],
                        **common)
    return Linkage(kind="slider-crank", D3=None, D=None, line=g.name, **common)


# -- the [balancing] table -----------------------------------------------------------------

@dataclass(frozen=True)
class CounterweightSpec:
    body: str
    about: str
    radius: float


def read_spec(sc: Scene, table: Any
              ) -> tuple[str, list[CounterweightSpec], float | None, float | None]:
    """The ``[balancing]`` table checked against the scene: (method, counterweight specs,
    fraction, pair radius)."""
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
        specs.append(CounterweightSpec(body, about, radius))
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


def assign_roles(lk: Linkage, method: str, specs: list[CounterweightSpec]
                 ) -> dict[str, CounterweightSpec]:
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
    out: dict[str, CounterweightSpec] = {}
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

def vec(p: Iterable[float]) -> np.ndarray:
    return np.asarray(tuple(p), dtype=float)


def first_moment(body: Body, ref: np.ndarray) -> np.ndarray:
    """First moment of a body's mass about a local point: m (G - ref), local (kg m)."""
    if body.mass == 0.0:
        return np.zeros(2)
    return body.mass * (vec(body.local("cog")) - ref)


def split_along(q: np.ndarray, u: np.ndarray) -> tuple[float, float]:
    """q = q_a u + q_b J u: a first moment split along and across a link u (kg)."""
    uu = float(u @ u)
    if uu == 0.0:
        raise BalanceError("a link has its two joints at the same point: zero length")
    return float(q @ u) / uu, float(q @ quarter_turn(u)) / uu


def off_line(body: Body, ref: np.ndarray, u: np.ndarray) -> bool:
    """True when the body's cog is off the line through ``ref`` along ``u``."""
    if body.mass == 0.0 or body.cog is None:
        return False
    d = vec(body.cog) - ref
    n = float(np.hypot(*u))
    return abs(float(d @ quarter_turn(u))) / n > ON_LINE * n


def joint_points(sc: Scene, lk: Linkage) -> dict[str, np.ndarray]:
    b = sc.bodies
    out = {"A": vec(b[lk.crank].points[lk.A]), "B1": vec(b[lk.crank].points[lk.B1]),
           "B2": vec(b[lk.link].points[lk.B2]), "C2": vec(b[lk.link].points[lk.C2]),
           "C3": vec(b[lk.last].points[lk.C3])}
    if lk.D3 is not None:
        out["D3"] = vec(b[lk.last].points[lk.D3])
    return out


