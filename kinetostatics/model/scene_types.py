"""The checked mechanism scene as data: :class:`Scene` and its parts (bodies, joints,
the driver, loads, mass models, friction), every number in the contract's units.

:func:`kinetostatics.model.scene.load_scene` reads and checks a scene into these (and
:mod:`kinetostatics.model.scene` names them too, where the rest of the workbench imports
them from).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any

import numpy as np

from .units import DEG, Units, degrees, radians

GROUND = "ground"


@dataclass(frozen=True)
class MassModel:
    """How a body's inertia loads are modelled (seed 002 s. 2.2).

    ``kind`` is ``"static"`` (two points, eqs 2.9-2.11) or ``"dynamic"`` (one given
    point and its conjugate, eqs 2.12-2.15); ``points`` names the body points.
    """

    kind: str
    points: tuple[str, ...]


@dataclass(frozen=True)
class Friction:
    """Friction in a joint (seed 002 s. 2.4): coefficient ``mu`` and pin ``radius`` (m).

    For a revolute joint the friction-circle radius is rho = radius * mu (eq. 2.62);
    for a prismatic joint ``length`` is the slider's bearing length (optional: the
    normal reaction and its couple are then carried by its two ends, eqs 2.63-2.65).
    """

    mu: float
    radius: float = 0.0
    length: float = 0.0


@dataclass(frozen=True)
class Body:
    """A rigid moving body: mass (kg), moment of inertia about its cog (kg m^2), local points."""

    name: str
    mass: float = 0.0
    inertia: float = 0.0
    cog: tuple[float, float] | None = None
    points: dict[str, tuple[float, float]] = field(default_factory=dict)
    mass_model: MassModel | None = None

    def local(self, point: str) -> tuple[float, float]:
        """Local coordinates of a named point (``"cog"`` names the centre of mass)."""
        if point == "cog":
            return self.cog if self.cog is not None else (0.0, 0.0)
        return self.points[point]


@dataclass(frozen=True, init=False)
class Joint:
    """A revolute (``R``) or prismatic (``T``) joint between two bodies.

    For ``R``: ``bodies`` and the names of the coinciding ``points`` on each.
    For ``T``: ``bodies = (guide, slider)``; the guide carries the line through
    ``line_point`` at ``beta`` (rad, guide's local frame; the file's ``line_angle`` in
    degrees, converted once where the scene is read); ``slider_point`` of the slider stays
    on it and the slider's angle is the guide's plus ``beta``.

    ``line_angle`` (deg), as the fifth argument or by name, and the attribute
    ``line_angle`` are deprecated (for one release): give and read ``beta`` (rad).
    """

    name: str
    kind: str
    bodies: tuple[str, str]
    points: tuple[str, str]
    friction: Friction | None = None
    beta: float = 0.0

    def __init__(self, name: str, kind: str, bodies: tuple[str, str],
                 points: tuple[str, str], line_angle: float | None = None,
                 friction: Friction | None = None, beta: float = 0.0) -> None:
        if line_angle is not None:
            warnings.warn("Joint(line_angle=...) in degrees is deprecated and goes in the "
                          "next release; give beta (rad)", DeprecationWarning, stacklevel=2)
            beta = radians(line_angle)
        for key, value in (("name", name), ("kind", kind), ("bodies", bodies),
                           ("points", points), ("friction", friction), ("beta", beta)):
            object.__setattr__(self, key, value)    # (frozen: set once, here)

    @property
    def line_angle(self) -> float:
        """The line angle in degrees (``beta`` written in degrees); deprecated."""
        warnings.warn("Joint.line_angle (deg) is deprecated and goes in the next release; "
                      "read Joint.beta (rad)", DeprecationWarning, stacklevel=2)
        return degrees(self.beta)

    @property
    def guide(self) -> str:
        return self.bodies[0]

    @property
    def slider(self) -> str:
        return self.bodies[1]

    def other(self, body: str) -> str:
        """The body at the other side of the joint."""
        return self.bodies[1] if self.bodies[0] == body else self.bodies[0]

    def point_on(self, body: str) -> str:
        """The name of the joint's point on ``body``."""
        return self.points[0] if self.bodies[0] == body else self.points[1]

    @property
    def on_by(self) -> tuple[str, str]:
        """(on, by) of the reactions table: the moving body for a ground joint, else the
        second body listed (the slider for a prismatic joint)."""
        a, b = self.bodies
        if a == GROUND:
            return b, a
        if b == GROUND:
            return a, b
        return b, a


@dataclass(frozen=True)
class Driver:
    """The driving element: a crank (``kind = "R"``) or a slider on a guide (``"T"``).

    ``angles``: a crank's positions in radians, what the model computes with (converted
    once, when first read; read-only); :attr:`coordinates` the SI positions of
    either kind (rad or m). ``positions``: the same positions as the file typed them, deg
    (R) or m (T): the tables' row labels (the contract's tables repeat them bit for bit,
    which their radians written back in degrees would not) and the values the messages
    quote; never computed with in degrees. ``speed`` in rad/s or m/s; ``acceleration`` in
    rad/s^2 or m/s^2. Each row is a snapshot at the same speed and acceleration.
    """

    body: str
    joint: str
    kind: str
    speed: float
    acceleration: float
    positions: np.ndarray

    # the sweep's start, stop and count (their bits) when ``positions`` is that linspace
    # as read (set by the reader; None for positions given otherwise or replaced)
    sweep: tuple | None = field(init=False, default=None, repr=False, compare=False)
    # True when ``positions`` strictly increase, known from how the reader made them (a
    # linspace whose step is wide enough, :func:`~kinetostatics.model.scene.widely_spaced`:
    # no pass over them); False when not known (positions given otherwise or replaced)
    increasing: bool = field(init=False, default=False, repr=False, compare=False)

    @cached_property
    def angles(self) -> np.ndarray:
        """A crank's positions in radians, ``radians(positions)``, converted once when
        first read (the file and the tables give degrees, ``positions``); read-only: every
        user shares it. Not made by a long sweep the compiled path solves lean (its kernel
        takes each tile's radians, the same doubles, :meth:`angles_into`; measured
        2026-11-30, the slider-crank at 1e6 rows: 2.7 ms of a 55 ms solve spared)."""
        pos = self.positions
        angles = radians(pos if type(pos) is np.ndarray else np.asarray(pos, dtype=float))
        angles.flags.writeable = False
        return angles

    def angles_into(self, at: slice, out: np.ndarray) -> np.ndarray:
        """``angles[at]``, read-only as :attr:`angles`: a view of them once made, else the
        same doubles worked out into ``out`` (``radians(positions[at])``, in its first
        values) and a read-only view of those returned, :attr:`angles` left unmade."""
        pos = self.positions
        if "angles" in self.__dict__ or type(pos) is not np.ndarray \
                or pos.dtype != np.float64:
            return self.angles[at]
        part = pos[at]
        if out.size < part.size:
            return self.angles[at]
        done = np.multiply(part, DEG, out=out[:part.size]).view()
        done.flags.writeable = False
        return done

    @property
    def coordinates(self) -> np.ndarray:
        """The driver's positions in SI: a crank's ``angles`` (rad), a slider's
        ``positions`` (m)."""
        return self.angles if self.kind == "R" else self.positions

    def at(self, coordinates: np.ndarray) -> Driver:
        """The same driver at other positions given in SI (rad or m): its
        :attr:`coordinates` are ``coordinates`` to the bit. For positions never shown (the
        probes between rows): a crank's ``positions`` are their degrees, not typed ones."""
        x = np.asarray(coordinates, dtype=float)
        if self.kind != "R":
            return replace(self, positions=x)
        out = replace(self, positions=degrees(x))
        x = x.copy()
        x.flags.writeable = False
        object.__setattr__(out, "angles", x)        # (frozen: made here, set once)
        return out

    def trig(self) -> tuple[np.ndarray, np.ndarray]:
        """``np.cos(angles)`` and ``np.sin(angles)``, read-only. A sweep read from start,
        stop and count shares them with every scene of the same sweep (the last few sweeps
        are remembered: variants of one mechanism solved one after another, where cos and
        sin of 2001 angles cost 110 us, more than half the hand-written four-bar's time;
        measured 2026-11-29). The same doubles: the same ufuncs on the same angles."""
        key = self.sweep
        done = _TRIG.get(key) if key is not None else None
        if done is None:
            c, s = np.cos(self.angles), np.sin(self.angles)
            c.flags.writeable = s.flags.writeable = False
            done = (c, s)
            if key is not None:
                if len(_TRIG) >= 16:
                    _TRIG.clear()
                _TRIG[key] = done
        return done


_TRIG: dict[tuple, tuple[np.ndarray, np.ndarray]] = {}
TRIG_ROWS = 100_000     # sweeps of at most this many rows share their cos and sin


@dataclass(frozen=True)
class Load:
    """A constant external load on a body: a force at a point and/or a moment.

    ``resist`` (N) is a force of that magnitude opposite to the point's velocity.
    ``when = "resisting"`` (an extension, docs/scene-extensions.md) applies the constant
    ``force`` only at positions where it opposes the point's motion (its power is
    negative): a technological resistance that acts on the working stroke only, such as
    a shaper's cutting force.
    """

    body: str
    point: str | None
    force: tuple[float, float] | None = None
    moment: float = 0.0
    resist: float | None = None
    when: str = "always"


@dataclass(frozen=True)
class Scene:
    """A checked mechanism scene (``scene-format.md`` section 1).

    Every number is SI and every angle radians (``Joint.beta``, ``Driver.angles``:
    converted once, where the scene is read or, the driver's angles, first read),
    whatever units the file named; a crank's positions as typed (deg,
    ``Driver.positions``) stay beside their radians as the tables' row labels alone.
    ``raw`` is the mapping as read, rewritten into the contract's units (a file's:
    degrees for its angles;
    :mod:`kinetostatics.model.scene_units`), and ``units`` the file's ``[units]`` (for
    the output, which repeats them); ``warnings`` the suspected unit slips found when it
    was read (:mod:`kinetostatics.model.slips`), which every output repeats.
    """

    title: str
    gravity: tuple[float, float]
    ground: dict[str, tuple[float, float]]
    driver: Driver
    bodies: dict[str, Body]
    joints: dict[str, Joint]
    loads: tuple[Load, ...]
    near: dict[str, tuple[float, float]]
    motion: dict[str, Any] | None = None
    balancing: dict[str, Any] | None = None
    raw: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)
    units: Units = field(default_factory=Units, compare=False)
    warnings: tuple[str, ...] = field(default=(), compare=False)

    @cached_property
    def size(self) -> float:
        """The mechanism's size (m): the largest distance of a named point (ground points and
        every body's local points) from its frame's origin, at least 1e-3 m.

        Every length tolerance of the solver, the simulation and the balancing is measured
        against it, so a scene scaled by any factor is judged alike.
        """
        return max([1e-3] + [math.hypot(*p) for p in self.ground.values()]
                   + [math.hypot(*p) for b in self.bodies.values() for p in b.points.values()])

    def point_names(self, body: str) -> list[str]:
        """Named points of a body (ground: the ``[ground]`` table)."""
        if body == GROUND:
            return list(self.ground)
        return list(self.bodies[body].points)
