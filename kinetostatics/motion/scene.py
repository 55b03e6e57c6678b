"""Motion under forces of a mechanism scene: the ``[motion]`` section of the contract.

The reduction element is the driver (a crank). From the kinematics at unit driver speed
(velocity ratios) come the reduced moment of inertia I_r(phi) of every body's exact mass
and I_G plus the flywheel (eq. 2.75) with its derivative, and the reduced moment
M_r(phi) of the scene's loads and gravity (eq. 2.72; no inertia forces). The motion
obeys d(I_r omega^2 / 2)/dphi = M_motor(phi, omega) + M_r(phi) (eq. 4.9), solved by the
Dormand-Prince integrator of :mod:`kinetostatics.motion` to 1e-12 relative.

The integrator works on a fixed grid of n steps per revolution (n = 64, 128, ...,
4096, refined where needed); M_r and I_r are evaluated at all the stage angles of all
these grids in one vectorised kinematic solve and looked up afterwards, so a 30-cycle
motion costs a few kinematic solves, not one per step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import SceneError, WorkbenchError
from ..model.fields import MECHANISM, read_number, section
from ..model.memory import check_memory
from ..model.scene import Scene, load_scene
from ..model.tomlio import as_float, as_int, as_list, check_keys
from ..model.units import Units, degrees, labelled, radians
from ..solver import arith as A
from ..solver.continuity import check_distinct
from ..solver.kinematics import solve_kinematics
from ..solver.loads import applied_loads
from ..solver.structure import analyse
from .integrator import simulate
from .phases import flywheel_for_delta
from .solution import DP5_C

TWO_PI = 2.0 * math.pi
KEY = 1e9          # cache key resolution: 1e-9 rad


MOTION = section(MECHANISM, "motion")
MOTOR = section(MECHANISM, "motion", "motor")
"""The declared ``[motion]`` fields (:data:`kinetostatics.model.fields.MECHANISM`) its
numbers are read through: bounds, defaults and the units their messages quote."""


@dataclass(frozen=True)
class MotionSpec:
    """The checked ``[motion]`` section."""

    stall_moment: float | None
    no_load_speed: float | None
    table: np.ndarray | None          # (k, 2): driver angle (rad), moment (N m)
    flywheel: float
    omega0: float
    cycles: int
    target_delta: float | None


def motion_spec(scene: Scene) -> MotionSpec:
    """Check the ``[motion]`` section (scene-format.md, "Motion under forces")."""
    m = scene.motion
    if m is None:
        raise SceneError("the scene has no [motion] section (motor, flywheel, omega0, "
                         "cycles; see the bundled four_bar_motion)")
    if scene.driver.kind != "R":
        raise SceneError("[motion]: the driver must be a crank (a sliding driver is refused)")
    if ("motor" in m) == ("motor_table" in m):
        raise SceneError("[motion]: give exactly one of 'motor' or 'motor_table'")
    stall = no_load = table = None
    if "motor" in m:
        mt = check_keys(m["motor"], ("stall_moment", "no_load_speed"), "motion.motor",
                        required=("stall_moment", "no_load_speed"))
        stall, no_load = (read_number(mt, MOTOR[k], "motion.motor", scene.units)
                          for k in ("stall_moment", "no_load_speed"))
    else:
        rows = as_list(m["motor_table"], "motion.motor_table")
        if len(rows) < 2:
            raise SceneError("motion.motor_table needs at least two [angle_deg, N m] points")
        pts = []
        for i, r in enumerate(rows):
            if not isinstance(r, list | tuple) or len(r) != 2:
                raise SceneError(f"motion.motor_table[{i}] must be [angle_deg, moment]")
            pts.append((as_float(r[0], f"motion.motor_table[{i}][0]"),
                        as_float(r[1], f"motion.motor_table[{i}][1]")))
        table = np.array(pts)
        if np.any(np.diff(table[:, 0]) <= 0):
            raise SceneError("motion.motor_table: angles must be strictly increasing")
        if table[-1, 0] - table[0, 0] > 360.0:
            raise SceneError("motion.motor_table spans more than 360 deg")
        table[:, 0] = radians(table[:, 0])        # the file's degrees, once, here
    flywheel, omega0, target = (read_number(m, MOTION[k], "motion", scene.units)
                                for k in ("flywheel", "omega0", "target_delta"))
    cycles = as_int(m["cycles"], "motion.cycles", lo=1, hi=100_000)
    if target is not None:
        if table is not None:
            raise SceneError("motion.target_delta needs a speed-dependent 'motor': with a "
                             "motor_table there is no unique steady state")
    pos = scene.driver.positions
    u = scene.units         # the mechanism scene's rule, quoted as typed (deg or rad)
    check_distinct(pos, u.unit("angle"), u.file_factor("angle"))
    start = motion_start(scene)
    if np.any(pos < start - 1e-9) or np.any(pos > start + 360.0 + 1e-9):
        first = "start" if "positions" not in scene.raw.get("driver", {}) else \
            "the smallest position"
        raise SceneError(f"[motion]: the sweep's positions must lie within one turn from "
                         f"{first} ({u.quote(start, 'angle', file=True)}), "
                         f"[{u.quote(start, 'angle', file=True)}, "
                         f"{u.quote(start + 360.0, 'angle', file=True)}]")
    return MotionSpec(stall, no_load, table, flywheel, omega0, cycles, target)


def motion_start(scene: Scene) -> float:
    """Where the motion starts (deg): the driver's ``start``, or the smallest of a
    ``positions`` list (which may come in any order)."""
    pos = scene.driver.positions
    return float(pos.min()) if "positions" in scene.raw.get("driver", {}) else float(pos[0])


class ReducedMechanism:
    """I_r(phi), dI_r/dphi and M_r(phi) of a scene, exact at any driver angle (rad), with a
    cache of the values at the integrator's grids."""

    def __init__(self, scene: Scene, phi0: float):
        self.scene = scene
        self.structure = analyse(scene)
        self.phi0 = phi0
        self._cache: dict[int, tuple[float, float, float]] = {}
        self._ahead: dict[float, tuple[float, float, float]] = {}

    def evaluate(self, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(I_r, dI_r/dphi, M_r) at the driver angles ``phi`` (rad), one kinematic solve."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        drv = replace(self.scene.driver, positions=degrees(phi.ravel()), speed=1.0,
                      acceleration=0.0)
        sc = replace(self.scene, driver=drv)
        kin = solve_kinematics(sc, self.structure)
        n = kin.n
        i_r = np.zeros(n)
        di_r = np.zeros(n)
        for name, body in sc.bodies.items():
            m = kin.bodies[name]
            if body.mass > 0.0:
                rx, ry = m.rotate(*body.cog)
                vx, vy = m.vel_arm(rx, ry)
                ax, ay = m.acc_arm(rx, ry)
                i_r = i_r + body.mass * (A.mul(vx, vx) + A.mul(vy, vy))         # eq. 2.75
                di_r = di_r + 2.0 * body.mass * (A.mul(vx, ax) + A.mul(vy, ay))
            if body.inertia > 0.0:
                i_r = i_r + body.inertia * A.mul(m.omega, m.omega)
                di_r = di_r + 2.0 * body.inertia * A.mul(m.omega, m.alpha)
        loads, _ = applied_loads(sc, kin)
        m_r = np.zeros(n)
        for ld in loads:                                                      # eq. 2.72
            m_r = m_r + np.broadcast_to(ld.power(kin), (n,))
        shape = phi.shape
        return i_r.reshape(shape), di_r.reshape(shape), m_r.reshape(shape)

    def _key(self, phi: float) -> int:
        return int(round(((phi - self.phi0) % TWO_PI) * KEY))

    def keys(self, phi: np.ndarray) -> list[int]:
        """:meth:`_key` of every angle of ``phi`` (1-D) in one pass: numpy's remainder,
        product and rint are Python's %, * and round, bit for bit (half to even), so
        the keys are the same (angles not all finite: one by one, as Python refuses
        them; below 16 angles one by one too, numpy's calls costing more than the
        loop: 1 angle 3.4 us against 34, 16 about even, 32 108 against 48)."""
        if phi.size < 16 or not np.isfinite(phi).all():
            return [self._key(p) for p in phi.tolist()]
        return np.rint(np.mod(phi - self.phi0, TWO_PI) * KEY).astype(np.int64).tolist()

    def prewarm(self, levels=(64, 128, 256, 512, 1024, 2048, 4096)) -> None:
        """Evaluate at every stage angle of the grids the integrator uses."""
        c = np.array((0.0, *DP5_C))
        pts = np.concatenate([(self.phi0 + (np.arange(n)[:, None] + c) * (TWO_PI / n)).ravel()
                              for n in levels])
        i_r, di_r, m_r = self.evaluate(pts)
        for k, a, b, m in zip(self.keys(pts), i_r.tolist(), di_r.tolist(), m_r.tolist(),
                              strict=True):
            self._cache[k] = (a, b, m)

    def prefetch(self, phis: list[float]) -> None:
        """Evaluate in one kinematic solve the angles a search may ask next (a solve of
        one angle costs about as much as of thirty). They are kept by exact angle apart
        from the cache, which takes each only when it is asked, so the cache holds what it
        held without (keys of 1e-9 rad: an angle never asked must not answer for one
        asked later); each angle's numbers are those of its own solve (the solve is
        elementwise)."""
        cand = [p for p in dict.fromkeys(phis) if p not in self._ahead]
        new = [p for p, k in zip(cand, self.keys(np.array(cand, dtype=float)), strict=True)
               if k not in self._cache]
        if new:
            try:
                vals = self.evaluate(np.array(new))
            except WorkbenchError:      # an angle the search never asks may not assemble:
                return                  # the asked ones are solved, and refused, as before
            for p, a, b, m in zip(new, *(v.tolist() for v in vals), strict=True):
                self._ahead[p] = (a, b, m)

    def cached(self, phi: float) -> tuple[float, float, float] | None:
        """(I_r, dI_r/dphi, M_r) at one angle where it was evaluated before, else None."""
        return self._cache.get(self._key(phi))

    def values(self, phi: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Cached where the angle (modulo a revolution) was evaluated before."""
        if isinstance(phi, float):
            # one angle (an integrator's stage): the cached numbers as they are, without
            # the arrays (the array road cost half of a motion run)
            hit = self.cached(phi)
            if hit is not None:
                return np.float64(hit[0]), np.float64(hit[1]), np.float64(hit[2])
        elif type(phi) is np.ndarray and phi.shape == (1,):
            # one angle in an array (a search's point): the same, in arrays of one
            hit = self.cached(float(phi[0]))
            if hit is not None:
                return np.array(hit[:1]), np.array(hit[1:2]), np.array(hit[2:])
        arr = np.asarray(phi, dtype=float)
        flat = arr.ravel().tolist()
        keys = self.keys(arr.ravel())
        missing = [(p, k) for p, k in zip(flat, keys, strict=True) if k not in self._cache]
        if missing:
            known = [self._ahead.get(p) for p, _ in missing]
            todo = [p for (p, _), v in zip(missing, known, strict=True) if v is None]
            fresh = iter(zip(*(v.tolist() for v in self.evaluate(np.array(todo))),
                             strict=True) if todo else ())
            for (_, k), v in zip(missing, known, strict=True):
                self._cache[k] = v if v is not None else next(fresh)
        out = np.array([self._cache[k] for k in keys]).reshape(arr.shape + (3,))
        return out[..., 0], out[..., 1], out[..., 2]


def _motor(spec: MotionSpec):
    """M_motor(phi, omega): the linear characteristic M = Ms (1 - omega / w0), or the table
    (absolute driver angle, linear between points, periodic)."""
    if spec.table is None:
        ms, w0 = spec.stall_moment, spec.no_load_speed

        def linear(phi, w):
            if type(w) is float:        # an integrator's stage: Python's floats, not numpy's
                return ms * (1.0 - w / w0)      # (the same IEEE operations, the same bits)
            return ms * (1.0 - np.asarray(w) / w0)
        return linear
    ang, val = spec.table[:, 0], spec.table[:, 1]
    xp = np.concatenate((ang, [ang[0] + TWO_PI]))
    fp = np.concatenate((val, [val[0]]))

    def table(phi, w):
        x = np.mod(np.asarray(phi, dtype=float) - ang[0], TWO_PI) + ang[0]
        return np.interp(x, xp, fp)
    return table


MOTION_UNITS = {"omega_mean": "rad/s", "omega_max": "rad/s", "omega_min": "rad/s", "delta": "1",
                "chi": "1", "period": "s", "flywheel_for_target": "kg m^2"}
"""The unit of each number of the motion's summary."""


@dataclass
class MotionResult:
    """The ``motion`` table (cycle, position, time, omega, alpha) and the summary (SI);
    ``units`` are the scene's ``[units]``, which the JSON repeats."""

    motion: pd.DataFrame
    summary: dict
    solution: Any
    units: Units = field(default_factory=Units)
    warnings: tuple[str, ...] = ()

    def to_json(self) -> dict:
        """``{"summary": {...}, "motion": [rows]}``: the summary says its units key by key
        and carries the scene's warnings (:func:`kinetostatics.model.units.labelled`)."""
        return {"summary": labelled(self.summary, self.units, MOTION_UNITS, self.warnings),
                "motion": self.motion.to_dict(orient="records")}


# peak memory of a motion: measured with /usr/bin/time -v on four_bar_motion, 386 MB at
# 200 cycles (361 or 3601 positions alike) and 2.76 GB at 2000: the integrator keeps
# about 1.3 MB per cycle; the table a row per cycle and position
MOTION_BASE = 150e6
MOTION_CYCLE_BYTES = 1.4e6
MOTION_ROW_BYTES = 100


def check_motion_memory(cycles: int, positions: int) -> None:
    """Refuse, in one line, a motion whose estimated peak memory is over the budget
    (:func:`kinetostatics.model.memory.check_memory`)."""
    need = MOTION_BASE + cycles * (MOTION_CYCLE_BYTES + MOTION_ROW_BYTES * positions)
    check_memory(need, f"the motion over {cycles:,} cycles of {positions:,} positions",
                 "integrate fewer cycles (motion.cycles) or use fewer positions")


def simulate_motion(scene: Any, rtol: float = 1e-12) -> MotionResult:
    """Motion of a mechanism under its loads and a motor (seed 002 ch. 4).

    Parameters
    ----------
    scene : Scene, path, TOML text or dict
        A mechanism scene with a ``[motion]`` section.

    Returns
    -------
    MotionResult
        ``motion`` table (one row per cycle and sweep position) and ``summary``:
        ``omega_mean, omega_max, omega_min, delta`` (eq. 4.20), ``chi`` (eq. 4.21),
        ``period``, ``steady`` and, with ``target_delta``, ``flywheel_for_target``.

    Raises
    ------
    SceneError, MotionError
        A bad ``[motion]`` section; a stall (the cycle and driver position are named).
    """
    sc = load_scene(scene)
    spec = motion_spec(sc)
    check_motion_memory(spec.cycles, sc.driver.positions.size)
    phi0 = radians(motion_start(sc))
    red = ReducedMechanism(sc, phi0)
    red.prewarm()
    motor = _motor(spec)

    def inertia_with(j):
        def inertia(phi):
            i_r, di_r, _ = red.values(phi)
            return i_r + j, di_r
        inertia.prefetch = red.prefetch     # golden_max's searches (cycle_stats) ask ahead
        return inertia

    def moment(phi, w, t):
        if type(phi) is float:          # an integrator's stage: no arrays, no numpy scalars
            hit = red.cached(phi)
            if hit is not None:
                return motor(phi, w) + hit[2]
        return motor(phi, w) + red.values(phi)[2]

    sol = simulate(inertia_with(spec.flywheel), moment, phi0, spec.omega0, spec.cycles,
                   rtol=rtol, periodic_inertia=True)
    positions = sc.driver.positions
    summary = sol.summary(positions)
    if spec.target_delta is not None:
        # the summary's omega_mean is cycle_stats()'s (the last whole cycle's), taken as is
        summary["flywheel_for_target"] = flywheel_for_delta(
            inertia_with(0.0), moment, spec.target_delta, phi0, summary["omega_mean"], rtol=rtol,
            periodic_inertia=True)
    return MotionResult(sol.table(positions), summary, sol, sc.units, sc.warnings)
