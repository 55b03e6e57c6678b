"""The result of a kinetostatic solve: arrays inside, tidy pandas tables built on demand.

Tables of the contract (``scene-format.md``, "Results"): ``reactions``, ``driver``,
``kinematics``, ``bodies``; and the project's own: ``dyads`` (transmission angle per
dyad, eq. 2.60-2.61), ``sliders`` (relative motion in every prismatic joint),
``frame`` (the force and moment the mechanism transmits to its frame), ``reduced``
(reduced moment and moment of inertia, eqs 2.72-2.75). The solver works on arrays;
at 1e6 positions the kinematics table alone has about 1e7 rows, so every table is
built only when asked for and then kept.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from ..model.errors import WorkbenchError
from ..model.scene import GROUND, Scene
from ..solver import arith as A
from ..solver.continuity import sweep_order
from ..solver.cut import CutSolved
from ..solver.kinematics import Kinematics
from ..solver.loads import PointLoad
from ..solver.reactions import DriverReaction, JointReaction
from ..solver.solved import DEFERRED, Deferred, Solved, drive_values
from ..solver.structure import Structure
from . import longtable as tables
from .longtable import LongTable, TiledPositions, offsets, shared
from .sweepangles import degree_angles

if TYPE_CHECKING:
    import pandas as pd

@dataclass
class Solution:
    """Kinematics, loads, reactions and the driver's equilibrating moment over a sweep.

    Attributes
    ----------
    scene, structure, kin
        The checked scene, its structure (driver + dyads) and the motion arrays.
    loads : list of PointLoad
        Applied loads, gravity and inertia loads (with joint friction, the friction loads
        too). Without friction the solve lets them go (:meth:`release_loads`: no table
        of the contract needs them) and they are computed again, with the same numbers,
        when first asked for.
    joint_reactions : dict
        Per joint, the reaction arrays (:class:`~kinetostatics.solver.reactions.JointReaction`).
    drive : DriverReaction
        ``Me`` (N m) on a crank or ``Fe`` (N) on a sliding driver.
    undefined_load : ndarray of bool
        Rows where a ``resist`` point stands still.
    self_locking : ndarray of bool or None
        With joint friction: rows where no finite driving effort moves the mechanism
        (friction locks it; Me/Fe and the reactions are NaN there and stay out of the
        summary); None without friction.
    path : str
        Which solve path made the arrays: ``"numpy"`` (the reference) or ``"fast"``
        (the compiled kernels, :mod:`kinetostatics.solver.fast`).
    """

    scene: Scene
    structure: Structure
    kin: Kinematics
    loads: list[PointLoad]
    joint_reactions: dict[str, JointReaction]
    drive: DriverReaction
    undefined_load: np.ndarray
    self_locking: np.ndarray | None = None
    path: ClassVar[str] = "numpy"       # (set on the instance by the compiled path)

    # -- arrays -----------------------------------------------------------------
    def release_loads(self) -> None:
        """Let the loads go (about 120 MB at 1e6 positions, in no contract table), to be
        computed again as the solve computes them when next asked for; with joint
        friction they are kept (the friction loads come from the friction solve)."""
        from ..solver.friction import has_friction
        if not has_friction(self.scene):
            self.__dict__["_loads"] = None

    def _get_loads(self) -> list[PointLoad]:
        loads = self.__dict__.get("_loads")
        if loads is None:
            from ..solver.loads import applied_loads, inertia_loads
            inertia = inertia_loads(self.scene, self.kin)
            applied, _ = applied_loads(self.scene, self.kin)
            loads = self.__dict__["_loads"] = applied + inertia   # the order of the solve
        return loads

    def _set_loads(self, value: list[PointLoad] | None) -> None:
        self.__dict__["_loads"] = value
    # -- made from the solver's arrays ----------------------------------------------
    @classmethod
    def of(cls, solved: Solved | Deferred) -> Solution:
        """The Solution of a :class:`Solved` (every array) or of a
        :class:`~kinetostatics.solver.solved.Deferred` (a lean long sweep, one scene of a
        stack: the other arrays come when first read), without the dataclass'
        constructor (:func:`dataclasses.replace` and a copy use it, solving then)."""
        new = object.__new__(cls)
        if type(solved) is Solved:
            new.__dict__.update(scene=solved.scene, structure=solved.structure,
                                kin=solved.kin, _loads=solved.loads,
                                joint_reactions=solved.joint_reactions, drive=solved.drive,
                                undefined_load=solved.undefined_load,
                                self_locking=solved.self_locking)
        else:
            new.__dict__.update(solved.known, _deferred=solved)
        path = getattr(solved, "path", None)    # (set by the compiled path)
        if path is not None:
            new.__dict__["path"] = path
        return new

    @classmethod
    def all_of(cls, outcomes: list) -> list:
        """:meth:`of` of each outcome (an exception as it is), a stacked scene's (a CutSolved)
        given its dict at once (1000 four-bars: 0.38 ms, 0.44 with ``s.path``; 2026-11-30)."""
        make, of, out = object.__new__, cls.of, []
        for s in outcomes:
            if type(s) is CutSolved:
                out.append(new := make(cls))
                new.__dict__ = d = {"scene": s[0], "structure": s[1], "self_locking": None,
                                    "_deferred": s}
                if s[5] is not None:    # (its path; None: the numpy path's, the class's)
                    d["path"] = s[5]
            else:
                out.append(s if isinstance(s, Exception) else of(s))
        return out

    @classmethod
    def block_of(cls, solved: Solved, angles: dict[str, np.ndarray],
                 largest_n: dict[int, float]) -> Solution:
        """A block of rows of a long sweep, its tables those rows of the sweep's, given
        the sweep's ``angles`` there and max |N| per prismatic joint (a streamed write)."""
        new = cls.of(solved)
        new.__dict__.update(angles=angles, _largest_n=largest_n)
        return new

    def __getattr__(self, name: str):
        d = self.__dict__
        source = d.get("_deferred")
        if source is None or name not in DEFERRED:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        d.update(source.give(name, d))
        d.pop("_onepass", None)     # (what a one-pass table kept: the arrays are whole now)
        if all(f in d for f in DEFERRED):
            d.pop("_deferred", None)    # (another thread may have done it too: the same)
        return d[name]

    def __getstate__(self) -> dict:
        for name in DEFERRED:           # the state holds arrays, not the solver's closure
            getattr(self, name)
        return {k: v for k, v in self.__dict__.items() if k != "_deferred"}

    @property
    def positions(self) -> np.ndarray:
        d = self.__dict__
        if "kin" in d:
            return d["kin"].positions
        source = d.get("_deferred")
        return self.kin.positions if source is None else source.positions

    @property
    def driver_quantity(self) -> str:
        return "Me" if self.drive.kind == "R" else "Fe"

    @property
    def Me(self) -> np.ndarray:
        """Equilibrating moment (crank) or force (sliding driver) over the sweep (a
        read-only view of the solver's array)."""
        return drive_values(self.drive, self.positions.shape)

    @property
    def singular(self) -> np.ndarray:
        """Rows where the mechanism is singular (:attr:`Kinematics.singular
        <kinetostatics.solver.kinematics.Kinematics.singular>`; of a deferred solve,
        from the flags it kept, without solving again)."""
        d = self.__dict__
        source = d.get("_deferred")
        if "kin" in d or source is None:
            return self.kin.singular
        return source.singular()

    def reaction(self, joint: str) -> tuple[np.ndarray, np.ndarray]:
        """(Fx, Fy) of a joint's reaction on its ``on`` body, arrays over positions."""
        return self.joint_reactions[joint].force(self.positions.size)

    # -- contract tables --------------------------------------------------------
    @cached_property
    def driver(self) -> pd.DataFrame:
        """``position, Me`` (or ``Fe``), ``singular``, ``undefined_load`` (and, with joint
        friction, ``self_locking``)."""
        n = self.positions.size
        if n < tables.SHARE_ROWS:
            # a short sweep: columns of its own (copies cost less than the shared Series
            # pandas needs to know a column is shared, and nothing can see a write to them)
            return tables.own_frame(self._driver_columns(), n)
        cols, value, keep = self._driver_columns(True), self.drive.value, self.__dict__.setdefault
        whole, own = tables.whole_column, tables.own_column  # (undefined_load too: 1 MB at 1e6)
        # the solver's own arrays, held once (pandas copies a column before a write), its
        # positions too (the long tables' column filled for it: 2.9 ms at 1e6 rows, 2026-11-30)
        cols["position"] = keep("_position_column", shared(self.positions)) \
            if self.positions.dtype == np.float64 else self._tiled.column(1)
        cols[self.driver_quantity] = keep("_drive_column", shared(value)) \
            if whole(value, n) else tables.table_column(self.Me, n)
        cols["undefined_load"] = keep("_undefined_column", shared(self.undefined_load)) \
            if whole(self.undefined_load, n, np.bool_) else own(self.undefined_load, n, np.bool_)
        return tables.columns_frame({c: cols[c] for c in self.driver_names()}, copy=False)

    def columns(self, table: str) -> dict:
        """The columns of a short table (``driver``, ``dyads``, ``sliders``, ``frame``) as
        arrays by name, without pandas (the CSV writer takes them as they are)."""
        return getattr(self, f"_{table}_columns")()

    def driver_names(self) -> list[str]:
        """The ``driver`` table's columns, in order."""
        names = ["position", self.driver_quantity, "singular", "undefined_load"]
        return names if self.self_locking is None else [*names, "self_locking"]

    def _driver_columns(self, shared_columns: bool = False) -> dict:
        """The ``driver`` table's columns, each an array of its own (a copy, or made for
        it). ``shared_columns``: without ``position``, the driving effort and
        ``undefined_load``, which the caller takes shared (no copy made only to be replaced)."""
        n, own = self.positions.size, tables.own_column
        cols = {} if shared_columns else {"position": own(self.positions, n),
                                          self.driver_quantity: own(self.drive.value, n)}
        fresh = "kin" not in self.__dict__ and self.__dict__.get("_deferred") is not None
        cols["singular"] = (tables.made_column if fresh else own)(self.singular, n, np.bool_)
        if not shared_columns:
            cols["undefined_load"] = own(self.undefined_load, n, np.bool_)
        if self.self_locking is not None:
            cols["self_locking"] = own(self.self_locking, n, np.bool_)
        return cols

    @cached_property
    def reactions(self) -> pd.DataFrame:
        """``position, joint, on, by, Fx, Fy, F, N, M, offset``; on revolute rows N and M
        are 0 (a pin carries no couple) and offset is empty. ``joint``, ``on`` and ``by``
        are categorical; one block of rows per joint."""
        return self._long_frame("reactions")

    def _points(self):
        for name, body in self.scene.bodies.items():
            names = list(body.points) + (["cog"] if body.cog is not None else [])
            for p in names:
                yield name, p, body.local(p)

    @cached_property
    def kinematics(self) -> pd.DataFrame:
        """``position, body, point, x, y, vx, vy, ax, ay`` for every named point and cog
        (``body`` and ``point`` categorical), one block of rows per point."""
        return self._long_frame("kinematics")

    def _long_frame(self, name: str) -> pd.DataFrame:
        """A long table as a DataFrame: of a lean long sweep, built while it is solved
        again block by block (:mod:`kinetostatics.results.onepass`), else from the
        solver's arrays (:meth:`LongTable.frame`)."""
        from .onepass import lean_frame
        frame = lean_frame(self, name)
        return self.long_table(name).frame() if frame is None else frame

    @cached_property
    def bodies(self) -> pd.DataFrame:
        """``position, body, angle`` (deg, continuous), ``omega, alpha`` (rad/s, rad/s^2);
        ``body`` categorical, one block of rows per body."""
        return self.long_table("bodies").frame()

    LONG_TABLES = ("reactions", "kinematics", "bodies")

    @cached_property
    def _tiled(self) -> TiledPositions:
        """The ``position`` column of the long tables, held once for all of them."""
        points = sum(1 for _ in self._points())
        return TiledPositions(self.positions,
                              max(len(self.scene.joints), points, len(self.scene.bodies)))

    def long_table(self, name: str) -> LongTable:
        """The definition of a long table (``reactions``, ``kinematics``, ``bodies``):
        block names and how to compute any chunk of positions from the solver's arrays
        (:mod:`kinetostatics.results.longtable`)."""
        return {"reactions": self._reactions_long, "kinematics": self._kinematics_long,
                "bodies": self._bodies_long}[name]()

    def _reactions_long(self) -> LongTable:
        n = self.positions.size
        joints = list(self.scene.joints)
        largest = dict(self.__dict__.get("_largest_n", {}))   # per prismatic joint: max |N|

        def chunk(i: int, part: slice) -> dict:
            r = self.joint_reactions[joints[i]]
            # r.force(n), one chunk at a time (the same numbers: negation is exact)
            fx = np.broadcast_to(r.fx, (n,))[part]
            fy = np.broadcast_to(r.fy, (n,))[part]
            if r.sign <= 0:
                fx, fy = -fx, -fy
            out = {"Fx": fx, "Fy": fy, "F": np.hypot(fx, fy)}
            if r.N is None:
                return {**out, "N": 0.0, "M": 0.0, "offset": np.nan}
            nn = np.broadcast_to(np.asarray(r.N, dtype=float), (n,))
            if i not in largest:
                largest[i] = np.abs(nn).max() if n else 0.0
            nn = nn[part]
            mm = np.broadcast_to(np.asarray(r.M, dtype=float), (n,))[part]
            return {**out, "N": nn, "M": mm, "offset": offsets(nn, mm, largest[i])}

        return LongTable(self.positions, tables.reaction_labels(joints, self.joint_reactions),
                         tables.REACTIONS_FLOATS, chunk, self._tiled,
                         {"Fx": lambda: self._force_columns()[0],
                          "Fy": lambda: self._force_columns()[1]})

    def _force_columns(self) -> tuple[pd.Series, pd.Series]:
        """The ``reactions`` table's ``Fx`` and ``Fy`` columns, held once with the joint
        reactions: each joint's force on its ``on`` body (``JointReaction.force``) is
        laid into its block of the column, and the joint's ``fx, fy`` become views of
        that block, its ``sign`` folded in (``sign = 1``: the same numbers, negation
        being exact)."""
        hit = self.__dict__.get("_forces_shared")
        if hit is None:
            n = self.positions.size
            reactions = [self.joint_reactions[j] for j in self.scene.joints]
            fx_all, fy_all = np.empty(n * len(reactions)), np.empty(n * len(reactions))
            for i, r in enumerate(reactions):
                block = slice(i * n, (i + 1) * n)
                for value, out in ((r.fx, fx_all[block]), (r.fy, fy_all[block])):
                    if r.sign > 0:
                        out[:] = np.broadcast_to(value, (n,))
                    else:
                        np.negative(np.broadcast_to(value, (n,)), out=out)
                r.fx, r.fy, r.sign = fx_all[block], fy_all[block], 1.0
            hit = self.__dict__["_forces_shared"] = (shared(fx_all), shared(fy_all))
        return hit

    def _kinematics_long(self, bodies: dict | None = None) -> LongTable:
        """The ``kinematics`` table from the bodies' motion (``bodies``: each body's
        :class:`~kinetostatics.solver.driver.BodyMotion` over the sweep; default the
        solution's own)."""
        points = list(self._points())
        motions = self.kin.bodies if bodies is None else bodies

        def chunk(i: int, part: slice) -> dict:
            b, _, loc = points[i]
            m = motions[b].take(part)
            # the arm itself, not (origin + arm) - origin: no rounding, whether the origin
            rx, ry = m.rotate(*loc)     # is a number or an array (a stack's rows)
            x, y = A.add(m.ox, rx), A.add(m.oy, ry)
            vx, vy = m.vel_arm(rx, ry)
            ax, ay = m.acc_arm(rx, ry)
            return {"x": x, "y": y, "vx": vx, "vy": vy, "ax": ax, "ay": ay}

        return LongTable(self.positions, tables.point_labels(points),
                         tables.KINEMATICS_FLOATS, chunk, self._tiled)

    def _bodies_long(self) -> LongTable:
        n = self.positions.size
        names = list(self.scene.bodies)

        def chunk(i: int, part: slice) -> dict:
            m = self.kin.bodies[names[i]]
            return {"angle": self.angles[names[i]][part],
                    "omega": np.broadcast_to(m.omega, (n,))[part],
                    "alpha": np.broadcast_to(m.alpha, (n,))[part]}

        def angle() -> pd.Series:
            self.angles                     # noqa: B018 (the angles, laid out block by block)
            if "_angle_column" not in self.__dict__:
                self.__dict__["_angle_column"] = shared(self.__dict__["_angle_whole"])
            return self.__dict__["_angle_column"]

        return LongTable(self.positions, {"body": names}, ("angle", "omega", "alpha"), chunk,
                         self._tiled, {"angle": angle})

    @cached_property
    def angles(self) -> dict[str, np.ndarray]:
        """Every body's angle (deg) per row: continuous along increasing driver position
        and following the true motion between rows, however far apart
        (:func:`kinetostatics.solver.continuity.body_angles`, in degrees:
        :func:`kinetostatics.results.sweepangles.degree_angles`).

        The arrays are views of one array laid out as the ``bodies`` table's ``angle``
        column (body after body, in the scene's order), which that table shares."""
        found = degree_angles(self.kin)
        n = self.positions.size
        whole = np.empty(n * len(self.scene.bodies))
        out = {}
        for i, b in enumerate(self.scene.bodies):
            whole[i * n:(i + 1) * n] = found.pop(b)
            out[b] = whole[i * n:(i + 1) * n]
        self.__dict__["_angle_whole"] = whole
        return out

    @cached_property
    def order(self) -> np.ndarray:
        """The rows in increasing driver position: the order of the motion, along which
        the summary's means, extremes and intervals are taken."""
        return sweep_order(self.positions)

    # -- project tables ---------------------------------------------------------
    @cached_property
    def dyads(self) -> pd.DataFrame:
        """``position, dyad, kind, bodies, transmission_angle, tau, sin_tau, singular`` per
        dyad.

        ``transmission_angle`` is the workbench's one definition, in [0, 90] deg:
        min(tau, 180 - tau), where tau in [0, 180] is the angle between the force a dyad's
        link transmits and the velocity of the point it drives (seed 002 eqs 2.60-2.61);
        tau and 180 - tau transmit alike, 90 deg is best, 0 is a dead centre. The summary's
        ``transmission_angle_min``, the pictures and the exercises use it. ``tau`` keeps the
        oriented angle; ``singular`` is the dyad's own flag (|sin tau| or its pivot
        distance over the mechanism's size at most 1e-3)."""
        return tables.columns_frame(self._dyads_columns())

    def _dyads_columns(self) -> dict:
        parts = []
        n = self.positions.size
        for dm in self.kin.dyads:
            tau = np.rad2deg(np.arctan2(np.abs(dm.sin_tau), dm.cos_tau))
            parts.append({
                "position": self.positions, "dyad": np.full(n, dm.dyad.index + 1),
                "kind": tables.text_column(dm.dyad.kind, n),
                "bodies": tables.text_column(f"{dm.dyad.bodies[0]}-{dm.dyad.bodies[1]}", n),
                "transmission_angle": dm.transmission_angle, "tau": tau,
                "sin_tau": np.abs(dm.sin_tau),
                "singular": np.broadcast_to(dm.singular, self.positions.shape)})
        return tables.concat_blocks(parts, ["position", "dyad", "kind", "bodies",
                                            "transmission_angle", "tau", "sin_tau", "singular"])

    @cached_property
    def sliders(self) -> pd.DataFrame:
        """Relative motion in every prismatic joint: ``s`` (m, slider point from the line
        point along the line), ``ds`` (m/s) and ``dds`` (m/s^2) seen from the guide (the
        relative acceleration, without the Coriolis term 2 omega x v_rel)."""
        return tables.columns_frame(self._sliders_columns())

    def _sliders_columns(self) -> dict:
        n = self.positions.size
        parts = []
        for name, j in self.scene.joints.items():
            if j.kind != "T":
                continue
            g, s = self.kin.bodies[j.guide], self.kin.bodies[j.slider]
            gl = self.scene.ground[j.points[0]] if j.guide == GROUND else \
                self.scene.bodies[j.guide].local(j.points[0])
            sl = self.scene.ground[j.points[1]] if j.slider == GROUND else \
                self.scene.bodies[j.slider].local(j.points[1])
            lx, ly = g.point(gl) if j.guide != GROUND else gl
            sx, sy = s.point(sl) if j.slider != GROUND else sl
            beta = j.beta
            ux, uy = g.rotate(np.cos(beta), np.sin(beta))
            vsx, vsy = s.vel_at(sx, sy)
            vgx, vgy = g.vel_at(sx, sy)
            asx, asy = s.acc_at(sx, sy)
            agx, agy = g.acc_at(sx, sy)
            rel = (ux * (sx - lx) + uy * (sy - ly))
            ds = ux * (vsx - vgx) + uy * (vsy - vgy)
            dds = ux * (asx - agx) + uy * (asy - agy)
            parts.append({"position": self.positions, "joint": tables.text_column(name, n),
                          "s": np.broadcast_to(rel, (n,)), "ds": np.broadcast_to(ds, (n,)),
                          "dds": np.broadcast_to(dds, (n,))})
        return tables.concat_blocks(parts, ["position", "joint", "s", "ds", "dds"])

    @cached_property
    def frame(self) -> pd.DataFrame:
        """Force and moment the mechanism transmits to its frame (shaking force and
        moment): the ground joints' reactions on the ground, the driver's reaction
        (-Me on the frame) included; moment about the global origin."""
        return tables.columns_frame(self._frame_columns())

    def _frame_columns(self) -> dict:
        n = self.positions.size
        fx = np.zeros(n)
        fy = np.zeros(n)
        mz = np.zeros(n)
        for name, j in self.scene.joints.items():
            if GROUND not in j.bodies:
                continue
            r = self.joint_reactions[name]
            gx, gy = (-f for f in r.force(n))
            fx += gx
            fy += gy
            mz += np.broadcast_to(r.x * gy - r.y * gx, (n,))
            if r.M is not None:
                sign = -1.0 if j.slider != GROUND else 1.0
                mz += sign * np.broadcast_to(r.M, (n,))
        if self.drive.kind == "R":
            mz -= self.Me
        else:
            j = self.scene.joints[self.scene.driver.joint]
            beta = j.beta if j.guide == GROUND else 0.0
            ux, uy = np.cos(beta), np.sin(beta)
            r = self.joint_reactions[j.name]
            fx -= self.Me * ux
            fy -= self.Me * uy
            mz -= np.broadcast_to(r.x * (self.Me * uy) - r.y * (self.Me * ux), (n,))
        return {"position": self.positions, "Fx": fx, "Fy": fy, "F": np.hypot(fx, fy),
                "M": mz}

    def low_transmission(self, admissible: float = 40.0) -> pd.DataFrame:
        """Rows of the ``dyads`` table where the transmission angle leaves the admissible
        band: ``transmission_angle`` = min(tau, 180 - tau) < ``admissible`` (deg; seed 002
        s. 2.3.4)."""
        t = self.dyads
        return t[t.transmission_angle < admissible].reset_index(drop=True)

    @cached_property
    def reaction_split(self) -> pd.DataFrame:
        """The seed's split of each dyad's outer revolute reactions (eqs 2.17-2.18, 2.22,
        2.26): ``Fn`` along the link from the outer joint to the inner joint, ``Ft``
        perpendicular to it (the link direction turned +90 deg), on the dyad body."""
        from .split import reaction_split_table
        return reaction_split_table(self)

    @cached_property
    def powers(self) -> pd.DataFrame:
        """The power balance per position: ``P_driver, P_applied, P_gravity, P_inertia,
        P_friction`` (W), adding up to zero (see
        :func:`kinetostatics.solver.reduction.power_table`)."""
        from ..solver.reduction import power_table
        return power_table(self)

    @cached_property
    def reduced(self) -> pd.DataFrame:
        """Reduced moment (force) of the loads and reduced moment of inertia (mass) to the
        driver (seed 002 eqs 2.72, 2.75), for the scene as given (any speed and
        acceleration, zero included): the velocity ratios come from the same mechanism at
        unit driver speed. ``M_red`` = the virtual power of the applied loads and gravity
        per unit driver speed, ``M_red_friction`` the same for friction, ``M_red_inertia``
        = -(I_red eps + 1/2 dI_red/dphi omega^2) (eq. 2.73; the three add up to -Me),
        ``I_red`` = sum (m v_G^2 + I_G omega^2) at unit driver speed."""
        from ..solver.reduction import reduced_table
        return reduced_table(self)

    # -- summary and files ------------------------------------------------------
    def summary(self) -> dict:
        """The contract's ``summary.json`` content. Everything that depends on the order
        of the motion (the mean by the trapezoid rule, the position of an extreme when
        several rows tie, the intervals between rows) is taken along increasing driver
        position, so that the same set of positions gives the same summary in any order."""
        from .summary import solution_summary
        return solution_summary(self)

    FILES = ("reactions", "driver", "kinematics", "bodies", "dyads", "sliders", "frame")
    # a solution's files in a folder (kinetostatics.model.outputs)
    OUTPUT_KIND = (*(f"{n}.{x}" for n in FILES for x in ("csv", "parquet")), "summary.json")

    def to_csv(self, directory: str | Path) -> list[Path]:
        """Write every table as CSV (17 significant digits) and ``summary.json``."""
        return self.write(directory, "csv")

    def write(self, directory: str | Path, fmt: str = "csv", announce=None,
              summary: dict | None = None) -> list[Path]:
        """Write every table (``fmt``: ``"csv"``, 17 significant digits, or
        ``"parquet"``) and ``summary.json``, whole or not at all (an earlier run's files
        untouched on failure: :mod:`kinetostatics.model.outputs`). A table built only for
        writing is dropped once written, and a long table not built yet is written as CSV
        straight from the solver's arrays, never held whole. ``announce`` (a callable
        taking one line) hears of every CSV table over 1e6 rows, with its size and time
        estimate (:func:`kinetostatics.results.output.write_csv`). ``summary``: the content of
        ``summary.json`` when it is not :meth:`summary` (the command line's)."""
        from ..model.outputs import staged_folder
        if fmt not in ("csv", "parquet"):
            raise WorkbenchError(f"format {fmt!r}: use csv or parquet")
        text = json.dumps(self.summary() if summary is None else summary, indent=2) + "\n"
        with staged_folder(directory, self.OUTPUT_KIND) as stage:
            self._write_tables(stage.path, fmt, announce)
            stage.file("summary.json").write_text(text)
        return [Path(directory) / f for f in (*(f"{n}.{fmt}" for n in self.FILES), "summary.json")]

    def _write_tables(self, d: Path, fmt: str, announce) -> None:
        """Every table into the folder ``d`` (the staging folder of :meth:`write`)."""
        from .output import Repeats, write_csv, write_long_csv, write_parquet
        positions = Repeats()     # the position column, formatted once for every table
        for name in self.FILES:
            kept = name in self.__dict__
            if fmt == "csv" and name in self.LONG_TABLES and not kept:
                # straight from the solver's arrays, chunk by chunk: never held whole
                write_long_csv(self.long_table(name), d / f"{name}.csv", announce, positions)
                continue
            if fmt == "csv" and not kept:
                # the short tables' columns, written without building a DataFrame
                write_csv(self.columns(name), d / f"{name}.csv", self.positions.size,
                          announce, positions)
                continue
            table = getattr(self, name)
            if fmt == "csv":
                write_csv(table, d / f"{name}.csv", self.positions.size, announce, positions)
            else:
                write_parquet(table, d / f"{name}.parquet")
            del table
            if not kept:
                del self.__dict__[name]


# ``Solution.loads`` is a dataclass field whose value may be let go and computed again
# (see Solution.release_loads): the field's attribute is a property over ``_loads``.
Solution.loads = property(Solution._get_loads, Solution._set_loads,
                          doc="Applied, gravity and inertia loads (and friction loads).")
