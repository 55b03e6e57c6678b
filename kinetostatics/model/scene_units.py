"""A mechanism scene's ``[units]``: the scene rewritten into the contract's units, once, where
it is read; and the warnings for numbers that look like unit slips.

A scene may name the units its numbers are written in (scene-format.md, opening; the
factors in :mod:`kinetostatics.model.units`). :func:`to_contract_units` returns a copy of the
raw mapping with every number in the contract's units (m, kg, N, rad/s, and degrees for
the angles a file holds) and without ``[units]``; the scene reader then checks it as any
other scene, and ``Scene.raw`` is that copy, so the modules that rebuild a scene from it
(simulation, concentration, balancing) see one system of units. A scene in the default
units is returned as it is: its numbers are never touched.

Which quantity each field is:

- length: ``ground``, body ``points`` and ``cog``, ``near``, joint ``friction.radius`` and
  ``friction.length``, a sliding driver's ``start``/``stop``/``positions``,
  ``[balancing]`` counterweight ``radius``;
- mass: body ``mass``; inertia (mass x length^2): body ``inertia``, ``[motion]`` ``flywheel``;
- angle: a rotating driver's ``start``/``stop``/``positions``, ``line_angle``, the angles
  of ``[motion]`` ``motor_table``;
- speed: a rotating driver's ``speed``, ``[motion]`` ``omega0`` and the motor's
  ``no_load_speed`` (``speed_rpm`` is rpm whatever the table says); a sliding driver's
  ``speed`` is length/s;
- force: load ``force`` and ``resist``; moment (force x length): load ``moment``, the
  motor's ``stall_moment`` and the moments of ``motor_table``;
- acceleration (length/s^2): ``gravity``, a sliding driver's ``acceleration``; a rotating
  driver's ``acceleration`` is rad/s^2 always.
"""

from __future__ import annotations

import copy
import math
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import UnitWarning
from .units import Units, angle_slip, parse_units

if TYPE_CHECKING:
    from .scene import Scene

__all__ = ["check_unit_slips", "convert_mechanism", "to_contract_units"]

_max, _min = np.maximum.reduce, np.minimum.reduce     # np.ptp's parts, without its detours

SPEED_SLIP = 1e4
"""rad/s: a faster angular speed looks like rpm typed in a rad/s field."""


def _number(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def _scale(table: Any, key: str, f: float) -> None:
    """table[key] times f, where it is a number or a list of numbers (nested lists too);
    anything else is left for the reader to refuse with its own message."""
    if isinstance(table, dict) and key in table:
        table[key] = _scaled(table[key], f)


def _scaled(value: Any, f: float) -> Any:
    if _number(value):
        return value * f
    if isinstance(value, list):
        return [_scaled(v, f) for v in value]
    return value


def _each(items: Any) -> list:
    return [x for x in items if isinstance(x, dict)] if isinstance(items, list) else []


def _points(table: Any, f: float) -> None:
    if isinstance(table, dict):
        for key in table:
            _scale(table, key, f)


def _driver_kind(raw: dict) -> str | None:
    drv = raw.get("driver")
    name = drv.get("joint") if isinstance(drv, dict) else None
    for j in _each(raw.get("joints")):
        if j.get("name") == name:
            return j.get("kind")
    return None


def to_contract_units(raw: dict) -> tuple[dict, Units]:
    """The raw scene with its numbers in the contract's units, and the scene's units.

    Parameters
    ----------
    raw : dict
        The mapping as read (it is not changed).

    Returns
    -------
    (dict, Units)
        Without ``[units]``, every number in m, kg, N, N m, kg m^2, rad/s, m/s^2 and degrees.

    Raises
    ------
    SceneError
        ``[units]`` that is not a table, or names an unknown quantity or unit.
    """
    if "units" not in raw:
        return raw, Units()
    units = parse_units(raw["units"])
    return convert_mechanism({k: v for k, v in raw.items() if k != "units"}, units), units


def convert_mechanism(raw: dict, units: Units) -> dict:
    """A copy of a mechanism scene's mapping (without ``[units]``) with the numbers written in
    ``units`` rewritten in the contract's units; keys it does not know are left as they are
    (a balancing scene's sections: :mod:`balance.model.scene_units` converts those). In the
    default units, ``raw`` itself is returned."""
    if units.is_default:
        return raw
    out = _copy(raw)
    f = units.file_factor
    L, M, I, A, W, F, T = (f("length"), f("mass"), f("inertia"), f("angle"), f("speed"),
                           f("force"), f("moment"))
    _scale(out, "gravity", f("acceleration"))
    _points(out.get("ground"), L)
    _points(out.get("near"), L)
    for b in _each(out.get("bodies")):
        _scale(b, "mass", M)
        _scale(b, "inertia", I)
        _scale(b, "cog", L)
        _points(b.get("points"), L)
    for j in _each(out.get("joints")):
        _scale(j, "line_angle", A)
        fr = j.get("friction")
        _scale(fr, "radius", L)
        _scale(fr, "length", L)
    for ld in _each(out.get("loads")):
        _scale(ld, "force", F)
        _scale(ld, "resist", F)
        _scale(ld, "moment", T)
    drv = out.get("driver")
    if isinstance(drv, dict):
        rotating = _driver_kind(out) != "T"
        for key in ("start", "stop", "positions"):
            _scale(drv, key, A if rotating else L)
        _scale(drv, "speed", W if rotating else f("velocity"))
        if not rotating:
            _scale(drv, "acceleration", f("acceleration"))
    mo = out.get("motion")
    if isinstance(mo, dict):
        _scale(mo, "flywheel", I)
        _scale(mo, "omega0", W)
        motor = mo.get("motor")
        _scale(motor, "stall_moment", T)
        _scale(motor, "no_load_speed", W)
        table = mo.get("motor_table")
        if isinstance(table, list):
            mo["motor_table"] = [[_scaled(r[0], A), _scaled(r[1], T)]
                                 if isinstance(r, list) and len(r) == 2 else r for r in table]
    bal = out.get("balancing")
    if isinstance(bal, dict):
        for cw in _each(bal.get("counterweights")):
            _scale(cw, "radius", L)
        _scale(bal, "pair_radius", L)
    return out


_PLAIN = (str, int, float, bool, type(None))


def _copy(value: Any) -> Any:
    """``copy.deepcopy`` of a scene's mapping, quicker on what TOML gives (tables, lists,
    texts, numbers: each plain value is immutable and kept as it is)."""
    t = type(value)
    if t is dict:
        return {k: _copy(v) for k, v in value.items()}
    if t is list:
        return [_copy(v) for v in value]
    if t in _PLAIN:
        return value
    return copy.deepcopy(value)


def _warn(text: str) -> None:
    warnings.warn(text, UnitWarning, stacklevel=4)


def check_unit_slips(scene: Scene, units: Units) -> None:
    """Warn (:class:`UnitWarning`) where a number looks like a unit slip (scene-format.md,
    opening): a rotating driver's positions that all lie within [-2 pi, 2 pi] with fractional
    values, or that span about 2 pi, under ``angle = "deg"`` (radians typed for degrees); a
    speed above 1e4 rad/s (rpm typed for rad/s: the driver's, ``[motion]`` ``omega0`` and
    ``no_load_speed``); the angles of ``motor_table`` likewise, and the prismatic joints'
    ``line_angle`` values; a point or cog farther from
    its body's joints than 100 times the mechanism's size (a length typed in mm among
    metres). A warning never stops the solve."""
    drv = scene.driver
    pos = drv.positions
    if drv.kind == "R" and units.angle == "deg":
        typed = _typed_positions(scene)
        if angle_slip(typed, "deg") or (pos.size > 1 and _spans_a_turn(pos)):
            shown = ", ".join(f"{v:g}" for v in typed[:4]) + (", ..." if len(typed) > 4 else "")
            _warn(f"driver positions [{shown}] look like radians (all within 2 pi, with "
                  "fractional values) but angles are in degrees (a full turn is 360); write "
                  "them in degrees, or angle = \"rad\" in [units]")
    if drv.kind == "R" and abs(drv.speed) > SPEED_SLIP:
        _warn(f"driver.speed = {drv.speed:.6g} rad/s ({abs(drv.speed) * 30 / math.pi:.4g} "
              "rpm) looks like rpm in a rad/s field; give speed_rpm, or speed = \"rpm\" in "
              "[units]")
    lines = {n: j.line_angle for n, j in scene.joints.items() if j.kind == "T"}
    if lines and angle_slip(list(lines.values()), units.angle):
        shown = ", ".join(f"{n} = {a:g}" for n, a in lines.items())
        _warn(f"line_angle ({shown}) looks like radians (within 2 pi, with fractional "
              "values) but angles are in degrees; write it in degrees, or angle = \"rad\" "
              "in [units]")
    if scene.motion is not None:
        _motion_slips(scene.motion, units)
    _far_points(scene, units)


def _spans_a_turn(pos: np.ndarray) -> bool:
    """True when the positions span 2 pi within 1 % (max - min: radians typed in a
    degree field).

    The span is at least the distance between the first and the last position (the
    largest is not below either, the smallest not above), and rounding keeps that order;
    so a sweep whose ends lie farther apart than 2 pi by more than 1 % (every sweep in
    degrees over more than about 6.35 deg, a full turn's 360 among them) is told by its
    two ends, without the two passes over the array."""
    turn = 2.0 * math.pi
    if abs(float(pos[-1]) - float(pos[0])) - turn > 0.01 * turn:
        return False
    return abs(float(_max(pos) - _min(pos)) - turn) <= 0.01 * turn


def _typed_positions(scene: Scene) -> list[float]:
    """The driver's positions as the file gives them (start and stop, or the list)."""
    drv = scene.raw.get("driver", {})
    if "positions" in drv:
        return [float(x) for x in drv["positions"]]
    return [float(drv["start"]), float(drv["stop"])]


def _motion_slips(motion: dict, units: Units) -> None:
    speeds = [("motion.omega0", motion.get("omega0"))]
    motor = motion.get("motor")
    if isinstance(motor, dict):
        speeds.append(("motion.motor.no_load_speed", motor.get("no_load_speed")))
    for where, w in speeds:
        if _number(w) and abs(w) > SPEED_SLIP:
            _warn(f"{where} = {w:.6g} rad/s ({abs(w) * 30 / math.pi:.4g} rpm) looks like rpm "
                  "in a rad/s field; write speed = \"rpm\" in [units]")
    table = motion.get("motor_table")
    if isinstance(table, list) and len(table) > 1:
        angles = [r[0] for r in table if isinstance(r, list) and r and _number(r[0])]
        if len(angles) > 1 and angle_slip(angles, units.angle):
            _warn(f"motion.motor_table: the angles {angles[:4]} look like radians (all within "
                  "2 pi, with fractional values) but angles are in degrees; write them in "
                  "degrees, or angle = \"rad\" in [units]")


def _far_points(scene: Scene, units: Units) -> None:
    joint_pts: dict[str, list[tuple[float, float]]] = {b: [] for b in scene.bodies}
    for j in scene.joints.values():
        if j.kind != "R":
            continue
        for b, p in zip(j.bodies, j.points, strict=True):
            if b in joint_pts:
                joint_pts[b].append(scene.bodies[b].points[p])
    pts = [p for b in joint_pts.values() for p in b] + list(scene.ground.values())
    if len(pts) < 2 or _all_near(scene, joint_pts, pts):
        return
    arr = np.asarray(pts, dtype=float)
    size = float(np.max(np.hypot(*(arr - arr.mean(axis=0)).T)))
    if size <= 0.0:
        return          # every joint at one point (a lone crank): no size to compare with
    unit = units.length
    f = units.factor("length")
    for name, body in scene.bodies.items():
        ref = joint_pts[name]
        if not ref:
            continue
        named = dict(body.points)
        if body.cog is not None:
            named["cog"] = body.cog
        for pname, p in named.items():
            far = min(math.hypot(p[0] - q[0], p[1] - q[1]) for q in ref)
            if far > 100.0 * size:
                _warn(f"body {name!r}: point {pname} = [{p[0] / f:g}, {p[1] / f:g}] {unit} is "
                      f"{far / f:.3g} {unit} from the body's joints, over 100 times the "
                      f"mechanism's size ({size / f:.3g} {unit}): millimetres among metres (a "
                      f"length typed in another unit)? Every length is in {unit}")


def _all_near(scene: Scene, joint_pts: dict, pts: list) -> bool:
    """True when every point and cog clearly lies within 100 sizes of its body's joints
    (the usual scene, told in plain Python without numpy's cost per call); a scene near
    that line, or with a point beyond it, is left to the exact test (False)."""
    n = len(pts)
    mx = my = 0.0
    for x, y in pts:
        mx += x
        my += y
    mx, my = mx / n, my / n
    hypot = math.hypot
    # the largest distance from the mean and the largest coordinate (finite numbers:
    # the same maxima, taken at once)
    size = max([hypot(x - mx, y - my) for x, y in pts])
    scale = max([abs(c) for xy in pts for c in xy])
    if not size > 1e-6 * scale:     # rounding could weigh here: the exact test decides
        return False
    limit = 100.0 * size * (1.0 - 1e-6)     # a margin for the rounding of mean and size
    for name, body in scene.bodies.items():
        ref = joint_pts[name]
        if not ref:
            continue
        named = list(body.points.values())
        if body.cog is not None:
            named.append(body.cog)
        for p in named:
            if p in ref:            # a joint's own point: at distance 0 (limit > 0)
                continue
            x, y = p
            for q in ref:
                if hypot(x - q[0], y - q[1]) <= limit:
                    break
            else:
                return False
    return True
