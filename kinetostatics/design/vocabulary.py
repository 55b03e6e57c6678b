"""What a design can be judged by: one vocabulary for the objectives and the constraints.

Each :class:`Quantity` is one number of a solved design, in SI or degrees, computed from
its :class:`~kinetostatics.results.Solution` over every row of its sweep (a feasible
design has no row near a dead centre: none is left out):

- ``Me_peak`` (N m): max |Me| over the rows (``Fe_peak``, N, for a sliding driver);
- ``Me_rms`` (N m): the root mean square of Me along the sweep, the mean by the
  trapezoid rule over increasing driver position, as the summary's ``Me_mean``
  (``Fe_rms``, N);
- ``reaction_peak`` (N): the largest joint reaction |F| over every joint and row;
- ``transmission_min`` (deg): the smallest transmission angle min(tau, 180 - tau) over
  the dyads and the rows (seed 002 eqs 2.60-2.61), as the summary's
  ``transmission_angle_min``;
- ``frame_force_peak`` (N): the largest |F| of the force on the frame (the ``frame``
  table: the ground joints' reactions on the ground);
- ``stroke:POINT`` (m): the travel of a point along x, max - min over the rows;
  ``stroke:POINT@ANGLE`` along the direction at ANGLE deg from +x;
- ``path_error:POINT`` (m): the root mean square, over the section's target points of
  that point, of the distance from each target to the nearest row of the point's path.

POINT is ``body.point`` (a point of a body by its key, or ``body.cog``) or a revolute
joint's name.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..common.angles import radian_value
from ..model.scene import GROUND, Scene
from ..solver.continuity import sweep_order
from .errors import DesignError

UNITS = {"Me_peak": "N m", "Fe_peak": "N", "Me_rms": "N m", "Fe_rms": "N",
         "reaction_peak": "N", "transmission_min": "deg", "frame_force_peak": "N",
         "stroke": "m", "path_error": "m"}
_ROTATING = {"Me_peak", "Me_rms"}
_SLIDING = {"Fe_peak", "Fe_rms"}
_WITH_POINT = {"stroke", "path_error"}
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_CONSTRAINT = re.compile(rf"^\s*(\S+)\s*(>=|<=)\s*({_NUMBER})\s*$")
_OBJECTIVE = re.compile(r"^\s*(min|max)\s+(\S+)\s*$")


@dataclass(frozen=True)
class Quantity:
    """One number of a solved design (see the module's vocabulary).

    Attributes
    ----------
    name : str
        As written in the section (``"Me_peak"``, ``"stroke:coupler.P@90"``).
    kind : str
        The vocabulary's word (``"Me_peak"``, ``"stroke"``).
    unit : str
        Its unit (SI or deg).
    body, point : str or None
        The point of ``stroke`` and ``path_error``: its body and its key (or ``"cog"``).
    direction : float
        The direction of a stroke (rad from +x).
    targets : ndarray or None
        The target points (m) of ``path_error``, shape (k, 2).
    """

    name: str
    kind: str
    unit: str
    body: str | None = None
    point: str | None = None
    direction: float = 0.0
    targets: np.ndarray | None = field(default=None, compare=False)

    def of(self, sol) -> float:
        """The quantity of one solved design."""
        k = self.kind
        if k in ("Me_peak", "Fe_peak"):
            return float(np.max(np.abs(sol.Me)))
        if k in ("Me_rms", "Fe_rms"):
            return _rms(sol)
        if k == "reaction_peak":
            n = sol.positions.size
            return max(float(np.max(np.broadcast_to(np.hypot(*sol.reaction(j)), (n,))))
                       for j in sol.scene.joints)
        if k == "transmission_min":
            return min(float(np.min(dm.transmission_angle)) for dm in sol.kin.dyads)
        if k == "frame_force_peak":
            return float(sol.frame["F"].max())
        x, y = self.path(sol)
        if k == "stroke":
            s = x * math.cos(self.direction) + y * math.sin(self.direction)
            return float(np.max(s) - np.min(s))
        return _path_error(x, y, self.targets)

    def of_designs(self, run) -> np.ndarray:
        """The quantity of each of the ``run.m`` designs stacked one after another, each
        over ``run.n`` rows, in ``run.sol`` (the :class:`~kinetostatics.results.Solution`
        of the stacked scene): the same numbers, bit for bit, as :meth:`of` gives each
        design's own Solution (the same elementwise arrays, reduced per design along C
        rows: max, min and the row sums of the trapezoid run alike)."""
        k, sol, m, n = self.kind, run.sol, run.m, run.n
        total = m * n
        if k in ("Me_peak", "Fe_peak"):
            return np.max(np.abs(sol.Me).reshape(m, n), axis=1)
        if k in ("Me_rms", "Fe_rms"):
            return _rms_rows(np.asarray(sol.Me, dtype=float).reshape(m, n), run.positions)
        if k == "reaction_peak":
            out = np.full(m, -np.inf)
            for j in sol.scene.joints:
                h = np.broadcast_to(np.hypot(*sol.reaction(j)), (total,)).reshape(m, n)
                out = np.maximum(out, np.max(h, axis=1))
            return out
        if k == "transmission_min":
            out = np.full(m, np.inf)
            for dm in sol.kin.dyads:
                out = np.minimum(out, np.min(dm.transmission_angle.reshape(m, n), axis=1))
            return out
        if k == "frame_force_peak":
            return np.max(sol.frame["F"].to_numpy().reshape(m, n), axis=1)
        x, y = (a.reshape(m, n) for a in self.path(sol))
        if k == "stroke":
            s = x * math.cos(self.direction) + y * math.sin(self.direction)
            return np.max(s, axis=1) - np.min(s, axis=1)
        t = self.targets
        d2 = (x[:, None, :] - t[None, :, :1]) ** 2 + (y[:, None, :] - t[None, :, 1:]) ** 2
        return np.sqrt(np.mean(np.min(d2, axis=2), axis=1))

    def path(self, sol) -> tuple[np.ndarray, np.ndarray]:
        """The global x, y (m) of the quantity's point over the rows."""
        body = sol.scene.bodies[self.body]
        local = body.cog if self.point == "cog" else body.local(self.point)
        n = sol.positions.size
        x, y = sol.kin.bodies[self.body].point(local)
        return np.broadcast_to(x, (n,)), np.broadcast_to(y, (n,))


def _rms(sol) -> float:
    """sqrt of the trapezoid mean of Me^2 along increasing driver position (the
    summary's mean of Me, of Me^2)."""
    order = sol.order
    me2 = np.asarray(sol.Me, dtype=float)[order] ** 2
    pos = sol.positions.astype(float)[order]
    if pos.size > 1 and pos[-1] != pos[0]:
        return math.sqrt(float(np.trapezoid(me2, pos) / (pos[-1] - pos[0])))
    return math.sqrt(float(me2.mean()))


def _rms_rows(me: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """:func:`_rms` of each row of ``me`` (designs x rows, all at ``positions``)."""
    order = sweep_order(positions)
    me2 = np.ascontiguousarray(me[:, order]) ** 2      # (C rows: each summed as alone)
    pos = positions.astype(float)[order]
    if pos.size > 1 and pos[-1] != pos[0]:
        return np.sqrt(np.trapezoid(me2, pos, axis=1) / (pos[-1] - pos[0]))
    return np.sqrt(me2.mean(axis=1))


def _path_error(x: np.ndarray, y: np.ndarray, targets: np.ndarray) -> float:
    """RMS over the targets of the distance to the nearest row of the path (x, y)."""
    d2 = (x[None, :] - targets[:, :1]) ** 2 + (y[None, :] - targets[:, 1:]) ** 2
    return math.sqrt(float(np.mean(np.min(d2, axis=1))))


@dataclass(frozen=True)
class Objective:
    """A quantity to minimise or to maximise (``sense`` +1 or -1: the value the search
    minimises is ``sense * value``)."""

    quantity: Quantity
    sense: int

    @property
    def text(self) -> str:
        return f"{'min' if self.sense > 0 else 'max'} {self.quantity.name}"


@dataclass(frozen=True)
class Constraint:
    """``quantity >= limit`` (``sign`` +1) or ``quantity <= limit`` (``sign`` -1)."""

    quantity: Quantity
    sign: int
    limit: float

    @property
    def text(self) -> str:
        return f"{self.quantity.name} {'>=' if self.sign > 0 else '<='} {self.limit:g}"

    def excess(self, value: float) -> float:
        """How far ``value`` breaks the constraint, relative to the limit (<= 0: kept)."""
        scale = abs(self.limit) if self.limit != 0.0 else 1.0
        return (self.limit - value) * self.sign / scale


def quantity(text: Any, scene: Scene, targets: Mapping[str, Any], where: str) -> Quantity:
    """The :class:`Quantity` named ``text`` for ``scene`` (checked against its driver,
    its dyads and its points)."""
    if not isinstance(text, str):
        raise DesignError(f"{where}: give a quantity's name as text, got {text!r}")
    kind, _, arg = text.partition(":")
    if kind not in UNITS:
        raise DesignError(f"{where}: unknown quantity {text!r}; the vocabulary is "
                          f"{', '.join(UNITS)} (stroke:POINT, path_error:POINT)")
    rotating = scene.driver.kind == "R"
    if kind in _ROTATING and not rotating:
        raise DesignError(f"{where}: {kind} needs a rotating driver; this scene's driver "
                          f"slides: use {kind.replace('Me', 'Fe')}")
    if kind in _SLIDING and rotating:
        raise DesignError(f"{where}: {kind} needs a sliding driver; this scene's driver "
                          f"rotates: use {kind.replace('Fe', 'Me')}")
    if kind not in _WITH_POINT:
        if arg:
            raise DesignError(f"{where}: {kind} takes no ':{arg}'")
        return Quantity(text, kind, UNITS[kind])
    if not arg:
        raise DesignError(f"{where}: {kind} names a point: {kind}:body.point")
    spot, _, angle = arg.partition("@")
    body, point = _point(spot, scene, where)
    direction = 0.0
    if angle:
        if kind != "stroke" or not re.fullmatch(_NUMBER, angle):
            raise DesignError(f"{where}: {text!r}: only a stroke takes a direction, "
                              "as stroke:POINT@ANGLE (deg)")
        direction = radian_value(float(angle))
    tg = None
    if kind == "path_error":
        tg = _targets(targets, spot, where)
    return Quantity(text, kind, UNITS[kind], body, point, direction, tg)


def _point(spot: str, scene: Scene, where: str) -> tuple[str, str]:
    """(body, point key) of ``body.point`` or of a revolute joint's name."""
    if spot in scene.joints and scene.joints[spot].kind == "R":
        j = scene.joints[spot]
        i = 0 if j.bodies[0] != GROUND else 1
        return j.bodies[i], j.points[i]
    body, dot, point = spot.partition(".")
    if not dot or body not in scene.bodies:
        raise DesignError(f"{where}: {spot!r} names no point: give body.point (bodies: "
                          f"{', '.join(scene.bodies)}) or a revolute joint's name")
    b = scene.bodies[body]
    if point == "cog":
        if b.cog is None:
            raise DesignError(f"{where}: body {body!r} has no cog")
        return body, point
    if point not in b.points:
        raise DesignError(f"{where}: body {body!r} has no point {point!r} (it has "
                          f"{', '.join(b.points)}, cog)")
    return body, point


def _targets(targets: Mapping[str, Any], spot: str, where: str) -> np.ndarray:
    if spot not in targets:
        raise DesignError(f"{where}: path_error:{spot} needs target points: "
                          f'[design.targets] "{spot}" = [[x, y], ...] (m)')
    pts = targets[spot]
    try:
        arr = np.array(pts, dtype=float)
    except (TypeError, ValueError):
        arr = np.zeros((0, 0))
    if arr.ndim != 2 or arr.shape[1] != 2 or arr.shape[0] < 1 or not np.isfinite(arr).all():
        raise DesignError(f"[design.targets] {spot!r}: give a list of [x, y] points (m), got "
                          f"{pts!r}")
    return arr


def objectives(items: Any, scene: Scene, targets: Mapping[str, Any]) -> list[Objective]:
    """The section's ``objectives``: ``"min NAME"`` or ``"max NAME"`` each."""
    if isinstance(items, str) or not isinstance(items, Sequence) or not items:
        raise DesignError('[design] objectives: give a list such as ["min Me_peak", '
                          f'"max transmission_min"], got {items!r}')
    out = []
    for i, text in enumerate(items):
        m = _OBJECTIVE.match(text) if isinstance(text, str) else None
        if m is None:
            raise DesignError(f"[design] objectives[{i}]: {text!r}: write 'min NAME' or "
                              "'max NAME'")
        q = quantity(m.group(2), scene, targets, f"[design] objectives[{i}]")
        out.append(Objective(q, 1 if m.group(1) == "min" else -1))
    names = [o.quantity.name for o in out]
    if len(set(names)) != len(names):
        raise DesignError(f"[design] objectives: {names} names a quantity twice")
    return out


def constraints(items: Any, scene: Scene, targets: Mapping[str, Any]
                ) -> tuple[list[Constraint], bool]:
    """The section's ``constraints`` (``"NAME >= number"``, ``"NAME <= number"``), and
    whether ``full_turn`` is among them."""
    if isinstance(items, str) or not isinstance(items, Sequence):
        raise DesignError('[design] constraints: give a list such as ["transmission_min >= '
                          f'40", "full_turn"], got {items!r}')
    out = []
    full_turn = False
    for i, text in enumerate(items):
        where = f"[design] constraints[{i}]"
        if text == "full_turn":
            if scene.driver.kind != "R":
                raise DesignError(f"{where}: full_turn needs a rotating driver (a crank)")
            full_turn = True
            continue
        m = _CONSTRAINT.match(text) if isinstance(text, str) else None
        if m is None:
            raise DesignError(f"{where}: unknown constraint {text!r}; write 'NAME >= number',"
                              " 'NAME <= number' (NAME from the objectives' vocabulary: "
                              f"{', '.join(UNITS)}) or 'full_turn'")
        q = quantity(m.group(1), scene, targets, where)
        out.append(Constraint(q, 1 if m.group(2) == ">=" else -1, float(m.group(3))))
    return out, full_turn
