"""Mass concentration (seed 002 s. 2.2): n-point solver, two-point closed forms, error table.

A body of mass m, centre of mass G and moment of inertia I_G is replaced by masses m_j at
points P_j (fig. 2.5). With d_j = P_j - G:

- eq. 2.3: sum m_j = m;
- eq. 2.4: sum m_j d_j = 0 (the concentrated masses keep the centre of mass);
- eq. 2.5: sum m_j |d_j|^2 = I_G (only for *dynamic* concentration).

Static concentration keeps 2.3-2.4, dynamic all three. When the points' coordinates are
free too, the seed counts the arbitrary parameters as p_S = 3n - 3 (eq. 2.7) and
p_D = 3n - 4 (eq. 2.6). Here the points are given, so the conditions are linear in the n
masses: they leave ``free = n - rank`` of them arbitrary (``n - 3`` static, ``n - 4``
dynamic for points in general position), or none, or cannot be met at all.

The concentrated masses' inertia forces are -m_j a_Pj (eq. 2.8). A static pair in B, C
with G on BC has sum m_j |d_j|^2 = m |GB| |GC|, so it misses the couple
-(I_G - m |GB| |GC|) eps: the method's error, which :func:`concentration_error_table`
measures on a whole mechanism. The scene field ``mass_model`` (``scene-format.md``) uses
the two-point models of :func:`kinetostatics.solver.loads.concentrated_masses`.
"""

from __future__ import annotations

import copy
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from .model.errors import WorkbenchError
from .model.scene import GROUND, Body, Scene, load_scene
from .results import solve
from .solver.loads import concentrated_masses

__all__ = [
    "Concentration", "ConcentrationError", "body_concentration", "concentrate",
    "concentration_error_table", "dynamic_two_point", "seed_free_parameters",
    "static_two_point",
]

TOL = 1e-9          # relative tolerance of the rank and of the residual


class ConcentrationError(WorkbenchError):
    """A mass concentration that cannot be done as asked (no solution, or not unique)."""


@dataclass(frozen=True)
class Concentration:
    """Concentrated masses of one body: point masses at chosen points that stand for it
    (statically: eqs 2.3-2.4; dynamically: eqs 2.3-2.5).

    Attributes
    ----------
    kind : str
        ``"static"`` (eqs 2.3-2.4) or ``"dynamic"`` (eqs 2.3-2.5).
    mass, inertia : float
        The body's m (kg) and I_G (kg m^2).
    cog : (float, float)
        G, local coordinates, m.
    points : ndarray, shape (n, 2)
        The concentration points, local coordinates, m.
    masses : ndarray, shape (n,)
        The concentrated masses, kg (the least-norm solution when not unique).
    free : int
        Masses left arbitrary by the conditions with these points: n - rank.
    seed_free : int
        The seed's count of arbitrary parameters when the points are free too:
        3n - 3 (eq. 2.7) or 3n - 4 (eq. 2.6).
    """

    kind: str
    mass: float
    inertia: float
    cog: tuple[float, float]
    points: np.ndarray
    masses: np.ndarray
    free: int
    seed_free: int

    @property
    def unique(self) -> bool:
        """True when the conditions fix the masses."""
        return self.free == 0

    @property
    def negative(self) -> bool:
        """True when some concentrated mass is negative (points not bracketing G)."""
        return bool(np.any(self.masses < 0.0))

    @property
    def points_inertia(self) -> float:
        """sum m_j |P_j - G|^2, kg m^2 (equals I_G for a dynamic concentration)."""
        d = self.points - np.asarray(self.cog)
        return float(np.sum(self.masses * np.einsum("ij,ij->i", d, d)))

    @property
    def missing_inertia(self) -> float:
        """I_G - sum m_j |P_j - G|^2: the concentrated masses miss the couple
        ``-missing_inertia * eps`` (0 for dynamic concentration)."""
        return self.inertia - self.points_inertia

    def inertia_forces(self, ax: Any, ay: Any) -> tuple[np.ndarray, np.ndarray]:
        """Eq. 2.8: F_ij = -m_j a_Pj. ``ax, ay`` have shape (n, ...) (one row per point)."""
        shape = (-1,) + (1,) * (np.ndim(ax) - 1)
        m = self.masses.reshape(shape)
        return -m * np.asarray(ax, dtype=float), -m * np.asarray(ay, dtype=float)

    def table(self) -> pd.DataFrame:
        """``x, y, m`` per point (local coordinates)."""
        return pd.DataFrame({"x": self.points[:, 0], "y": self.points[:, 1], "m": self.masses})


def seed_free_parameters(n: int, kind: str = "static") -> int:
    """The seed's number of arbitrary parameters for n points: p_S = 3n - 3 (eq. 2.7),
    p_D = 3n - 4 (eq. 2.6)."""
    _kind(kind)
    return 3 * int(n) - (3 if kind == "static" else 4)


def _kind(kind: str) -> str:
    if kind not in ("static", "dynamic"):
        raise ConcentrationError(f"kind must be \"static\" or \"dynamic\", not {kind!r}")
    return kind


def _fmt(p) -> str:
    return f"({p[0]:.6g}, {p[1]:.6g})"


def concentrate(mass: float, cog: Sequence[float], points: Any, inertia: float = 0.0,
                kind: str = "static", unique: bool = False) -> Concentration:
    """Masses at given points that keep the body's mass, cog and (dynamic) I_G.

    Solves the linear conditions 2.3-2.4 (static) or 2.3-2.5 (dynamic) for the n masses.
    When they leave some masses free, the least-norm masses (smallest sum of m_j^2) are
    returned, unless ``unique=True``.

    Parameters
    ----------
    mass : float
        m, kg (> 0).
    cog : (float, float)
        G, m (any frame; the points in the same frame).
    points : array_like, shape (n, 2)
        The concentration points, m.
    inertia : float
        I_G, kg m^2 (>= 0); used by the dynamic kind.
    kind : {"static", "dynamic"}
    unique : bool
        Refuse a request whose masses are not fixed by the conditions.

    Returns
    -------
    Concentration

    Raises
    ------
    ConcentrationError
        Bad input; a request that cannot be met (the points' affine hull misses G: all
        points on a line that misses G, or all at one point away from G; for dynamic,
        points whose masses cannot reach I_G); with ``unique=True``, an under-determined
        one (the message gives the number of free masses).

    Examples
    --------
    >>> c = concentrate(2.0, (0.1, 0.0), [(0.0, 0.0), (0.4, 0.0)])
    >>> c.masses.round(6).tolist(), c.free, c.seed_free
    ([1.5, 0.5], 0, 3)
    """
    _kind(kind)
    m = float(mass)
    ig = float(inertia)
    if not np.isfinite(m) or m <= 0.0:
        raise ConcentrationError(f"mass must be > 0 kg, not {mass}")
    if not np.isfinite(ig) or ig < 0.0:
        raise ConcentrationError(f"inertia (I_G) must be >= 0 kg m^2, not {inertia}")
    g = np.asarray(cog, dtype=float)
    if g.shape != (2,) or not np.all(np.isfinite(g)):
        raise ConcentrationError(f"cog must be a pair of finite numbers, not {cog!r}")
    pts = np.asarray(points, dtype=float)
    if pts.ndim == 1 and pts.size == 2:
        pts = pts.reshape(1, 2)
    if pts.ndim != 2 or pts.shape[1] != 2 or pts.shape[0] == 0:
        raise ConcentrationError("points must be a list of (x, y) pairs, at least one")
    if not np.all(np.isfinite(pts)):
        raise ConcentrationError("points must be finite")
    n = pts.shape[0]
    d = pts - g
    r2 = np.einsum("ij,ij->i", d, d)
    L = float(np.sqrt(r2.max())) or 1.0          # length scale: every row in kg
    rows = [np.ones(n), d[:, 0] / L, d[:, 1] / L]
    rhs = [m, 0.0, 0.0]
    if kind == "dynamic":
        rows.append(r2 / L**2)
        rhs.append(ig / L**2)
    A = np.array(rows)
    b = np.array(rhs)
    scale = float(np.abs(b).max())
    sol, _, rank, _ = np.linalg.lstsq(A, b, rcond=TOL)
    resid = float(np.abs(A @ sol - b).max())
    if resid > TOL * scale:
        raise ConcentrationError(_why_impossible(m, g, pts, ig, kind))
    free = n - int(rank)
    seed = seed_free_parameters(n, kind)
    if unique and free > 0:
        raise ConcentrationError(
            f"{kind} concentration in {n} points is under-determined: {free} of the masses "
            f"are arbitrary (the seed counts p = {seed} parameters with free points, "
            f"eq. 2.{6 if kind == 'dynamic' else 7}); give {n - free} points in general "
            "position, or ask for the least-norm masses (unique=False)")
    out = Concentration(kind=kind, mass=m, inertia=ig, cog=(float(g[0]), float(g[1])),
                        points=pts.copy(), masses=sol, free=free, seed_free=seed)
    if out.unique and out.negative:
        warnings.warn(f"{kind} concentration: a concentrated mass is negative "
                      f"({out.masses.min():.6g} kg): the points do not surround the cog "
                      "(seed 002 eq. 2.11 for two points)", stacklevel=2)
    return out


def _why_impossible(m: float, g: np.ndarray, pts: np.ndarray, ig: float, kind: str) -> str:
    """One line saying why conditions 2.3-2.5 have no solution."""
    c = pts.mean(axis=0)
    spread = pts - c
    sv = np.linalg.svd(spread, compute_uv=False) if len(pts) > 1 else np.zeros(1)
    size = float(np.abs(pts - g).max()) or 1.0
    affine = int(np.sum(sv > TOL * size))
    if affine == 0 and float(np.hypot(*(c - g))) > TOL * size:
        return (f"{kind} concentration impossible: all the points are at {_fmt(c)}, "
                f"not at the cog {_fmt(g)} (one point must be the cog, eq. 2.4)")
    if affine == 1:
        _, _, vt = np.linalg.svd(spread)
        t = vt[0]
        off = abs(float(t[0] * (g[1] - c[1]) - t[1] * (g[0] - c[0])))
        if off > TOL * size:
            return (f"{kind} concentration impossible: the points lie on one line that misses "
                    f"the cog {_fmt(g)} by {off:.6g} m (eq. 2.4 needs the cog on it)")
    # static conditions solvable: the points' inertia about G is fixed, and not I_G
    st = concentrate(m, g, pts, kind="static")
    return (f"dynamic concentration impossible with these points: every set of masses that "
            f"keeps m and the cog gives sum m_j |GP_j|^2 = {st.points_inertia:.6g} kg m^2, not "
            f"I_G = {ig:.6g} kg m^2 (eq. 2.5); move a point or add one off their "
            "line/circle")


# --------------------------------------------------------------------------- closed forms

def static_two_point(mass: Any, a: Any, b: Any) -> tuple[np.ndarray, np.ndarray]:
    """Static concentration in two points A, B on a line through G (eqs 2.9-2.11).

    With G at the origin, A at x1 = a and B at x2 = -b (fig. 2.6):
    ``m1 = m b / (a + b)``, ``m2 = m a / (a + b)``.

    Parameters
    ----------
    mass : float or array_like
        m, kg.
    a, b : float or array_like
        Distances of A and B from G (on opposite sides when both > 0), m.

    Returns
    -------
    (m1, m2) : floats or ndarrays, kg
        A negative one (with a warning) when the points do not bracket G (a < 0 or b < 0).

    Examples
    --------
    >>> [round(v, 9) for v in static_two_point(2.0, 0.1, 0.3)]
    [1.5, 0.5]
    """
    m, aa, bb = (np.asarray(v, dtype=float) for v in (mass, a, b))
    if np.any(aa + bb == 0.0):
        raise ConcentrationError("static two-point concentration needs two distinct points "
                                 "(a + b = 0 puts them together)")
    if np.any(aa < 0.0) or np.any(bb < 0.0):
        warnings.warn("static concentration: the points do not bracket the cog; a "
                      "concentrated mass is negative (seed 002 eq. 2.11)", stacklevel=2)
    m1 = m * bb / (aa + bb)
    m2 = m * aa / (aa + bb)
    if m1.ndim == 0:
        return float(m1), float(m2)
    return m1, m2


def dynamic_two_point(mass: Any, inertia: Any, a: Any) -> tuple[Any, Any, Any]:
    """Dynamic concentration in two points (eqs 2.12-2.14).

    With G at the origin and the given point A at x1 = a (fig. 2.7), the second point is
    at ``x2 = -I_G / (m a)`` and ``m1 = m I_G / (m a^2 + I_G)``,
    ``m2 = m^2 a^2 / (m a^2 + I_G)``. The forces are -m1 a_A and -m2 a_C (eq. 2.15).

    Parameters
    ----------
    mass, inertia : float or array_like
        m (kg, > 0) and I_G (kg m^2, >= 0).
    a : float or array_like
        Abscissa of A from G on the line through G, m; nonzero.

    Returns
    -------
    (m1, m2, x2) : floats or ndarrays

    Raises
    ------
    ConcentrationError
        a = 0 (the second point goes to infinity), m <= 0 or I_G < 0.

    Examples
    --------
    >>> [round(v, 9) for v in dynamic_two_point(2.0, 0.02, 0.1)]
    [1.0, 1.0, -0.1]
    """
    m, ig, aa = (np.asarray(v, dtype=float) for v in (mass, inertia, a))
    if np.any(m <= 0.0) or np.any(ig < 0.0):
        raise ConcentrationError("dynamic concentration needs m > 0 and I_G >= 0")
    if np.any(aa == 0.0):
        raise ConcentrationError("dynamic concentration at the cog itself (a = 0): the second "
                                 "point x2 = -I_G / (m a) goes to infinity; choose a point "
                                 "away from the cog")
    den = m * aa**2 + ig
    m1 = m * ig / den
    m2 = m**2 * aa**2 / den
    x2 = -ig / (m * aa)
    if m1.ndim == 0:
        return float(m1), float(m2), float(x2)
    return m1, m2, x2


def body_concentration(body: Body) -> Concentration:
    """The concentration of a scene body's ``mass_model`` (from
    :func:`kinetostatics.solver.loads.concentrated_masses`, the model the solver uses); a body
    without one is a single mass at its cog (static, n = 1)."""
    if body.mass <= 0.0:
        raise ConcentrationError(f"body {body.name!r} has no mass to concentrate")
    pairs = concentrated_masses(body)
    kind = "static" if body.mass_model is None else body.mass_model.kind
    pts = np.array([p for p, _ in pairs], dtype=float)
    ms = np.array([mk for _, mk in pairs], dtype=float)
    n = len(pairs)
    cog = body.cog or (0.0, 0.0)
    return Concentration(kind=kind, mass=body.mass, inertia=body.inertia,
                         cog=(float(cog[0]), float(cog[1])), points=pts, masses=ms,
                         free=0, seed_free=seed_free_parameters(n, kind))


# --------------------------------------------------------------------------- error table

def _joint_points(sc: Scene) -> dict[str, list[str]]:
    """Per moving body, the names of its revolute joint points, in joint order."""
    out: dict[str, list[str]] = {name: [] for name in sc.bodies}
    for j in sc.joints.values():
        if j.kind != "R":
            continue
        for body, point in zip(j.bodies, j.points, strict=True):
            if body != GROUND and point not in out[body]:
                out[body].append(point)
    return out


def _models(sc: Scene) -> tuple[dict[str, dict], dict[str, dict]]:
    """The ``mass_model`` entries of the static and the dynamic variant."""
    static: dict[str, dict] = {}
    dynamic: dict[str, dict] = {}
    for name, pts in _joint_points(sc).items():
        body = sc.bodies[name]
        if body.mass <= 0.0 or body.cog is None:
            continue
        g = np.asarray(body.cog, dtype=float)
        if len(pts) == 2:
            b, c = (np.asarray(body.points[p], dtype=float) for p in pts)
            bc = float(np.hypot(*(c - b)))
            off = (c[0] - b[0]) * (g[1] - b[1]) - (c[1] - b[1]) * (g[0] - b[0])
            if bc > 0.0 and abs(float(off)) <= TOL * bc:
                static[name] = {"kind": "static", "points": list(pts)}
        for p in pts:
            if float(np.hypot(*(np.asarray(body.points[p]) - g))) > 0.0:
                dynamic[name] = {"kind": "dynamic", "point": p}
                break
    return static, dynamic


def _variant(raw: dict, models: dict[str, dict]) -> dict:
    out = copy.deepcopy(raw)
    for item in out.get("bodies", []):
        item.pop("mass_model", None)
        if item.get("name") in models:
            item["mass_model"] = dict(models[item["name"]])
    return out


def concentration_error_table(scene: Any) -> pd.DataFrame:
    """How much Me and the joint reactions change when the inertia torsor is replaced by
    concentrated masses: "the error a student makes by dropping the inertia moment".

    The scene is solved three times (``mass_model`` set on each body of a deep copy of
    ``scene.raw``):

    - ``exact``: no ``mass_model`` anywhere (torsor F = -m a_G, M = -I_G eps, eq. 2.1);
    - ``static``: static concentration (eqs 2.9-2.11) in the two revolute joint points of
      every body that has exactly two, with its cog on their line (others stay exact);
    - ``dynamic``: dynamic concentration (eqs 2.12-2.15) at the first revolute joint point
      of every body that is not its cog (others stay exact).

    Parameters
    ----------
    scene : Scene, path, TOML text or dict
        A mechanism scene (``scene-format.md`` section 1).

    Returns
    -------
    pandas.DataFrame
        One row per model (``static``, ``dynamic``) and quantity (``Me`` or ``Fe``, then
        ``F[joint]`` = |F| of each joint): ``model, quantity, exact_max`` (max |exact|
        over the sweep), ``max_abs`` (max |model - exact|), ``position`` (where it
        occurs), ``max_rel`` (``max_abs / exact_max``, 0 when exact_max is 0). The
        concentrated bodies are in ``table.attrs["static"]`` and ``["dynamic"]``
        (body -> mass_model). The dynamic rows vanish to rounding; the static Me
        differs by the power of the missing couples, sum -(I_G - m |GB||GC|) eps omega,
        divided by the driver's speed.
    """
    sc = load_scene(scene)
    if not sc.raw:
        raise ConcentrationError("the scene has no raw table to build the variants from; "
                                 "load it with load_scene(path | text | dict)")
    static, dynamic = _models(sc)
    exact = solve(_variant(sc.raw, {}))
    variants = {"static": (static, solve(_variant(sc.raw, static))),
                "dynamic": (dynamic, solve(_variant(sc.raw, dynamic)))}
    pos = exact.positions
    ref = {exact.driver_quantity: np.asarray(exact.Me, dtype=float)}
    for j in sc.joints:
        ref[f"F[{j}]"] = np.hypot(*exact.reaction(j))
    rows = []
    for model, (_, sol) in variants.items():
        got = {sol.driver_quantity: np.asarray(sol.Me, dtype=float)}
        for j in sc.joints:
            got[f"F[{j}]"] = np.hypot(*sol.reaction(j))
        for q, r in ref.items():
            diff = np.abs(np.broadcast_to(got[q], pos.shape) - np.broadcast_to(r, pos.shape))
            k = int(np.argmax(diff)) if diff.size else 0
            top = float(np.abs(r).max()) if np.size(r) else 0.0
            mx = float(diff[k]) if diff.size else 0.0
            rows.append({"model": model, "quantity": q, "exact_max": top, "max_abs": mx,
                         "position": float(pos[k]) if pos.size else float("nan"),
                         "max_rel": mx / top if top > 0.0 else 0.0})
    table = pd.DataFrame(rows)
    table.attrs["static"] = static
    table.attrs["dynamic"] = dynamic
    return table
