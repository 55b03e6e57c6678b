"""Mechanism scenes: the TOML input of ``scene-format.md`` section 1, checked into dataclasses.

``load_scene`` accepts a path, a string naming a ``.toml`` file, a string of TOML text
or a dict, and returns a :class:`Scene`. Every rule of the contract is checked here;
a broken rule raises :class:`~kinetostatics.model.errors.SceneError` with one line naming
the field and the fix. Unknown keys are refused with the nearest known key suggested.
"""

from __future__ import annotations

import io
import pickle
import warnings
from typing import Any

import numpy as np

from .errors import SceneError
from .examples import SCENES
from .fields import MECHANISM, read_number, section
from .scene_types import (
    GROUND,
    TRIG_ROWS,
    Body,
    Driver,
    Friction,
    Joint,
    Load,
    MassModel,
    Scene,
)
from .scene_units import to_contract_units
from .slips import emit, mechanism_slips, read_checks
from .tomlio import (
    as_float,
    as_int,
    as_list,
    as_str,
    as_vec2,
    check_keys,
    plain_vec2,
    read_source,
    suggest,
)
from .units import Units, radians, rpm_to_rad_s

MAX_COUNT = 10_000_000
TOP_KEYS = ("title", "format", "units", "gravity", "ground", "driver", "bodies", "joints", "loads",
            "near", "motion", "balancing", "design")
DRIVER_KEYS = ("body", "joint", "speed", "speed_rpm", "acceleration", "start", "stop",
               "count", "positions")
BODY_KEYS = ("name", "mass", "inertia", "cog", "points", "mass_model")
JOINT_KEYS_R = ("name", "kind", "bodies", "points", "friction")
JOINT_KEYS_T = ("name", "kind", "guide", "slider", "line_point", "line_angle", "slider_point",
                "friction")
LOAD_KEYS = ("body", "point", "force", "moment", "resist", "when")
LOAD_WHEN = ("always", "resisting")
MOTION_KEYS = ("motor", "motor_table", "flywheel", "omega0", "cycles", "target_delta")


def load_scene(source: Any) -> Scene:
    """Load and check a mechanism scene.

    Parameters
    ----------
    source : pathlib.Path, str or dict
        A path, a string naming an existing ``.toml`` file, TOML text, or a dict.

    Returns
    -------
    Scene
        The checked scene (frozen). A dict of plain data whose content was read lately
        gives the same Scene object again (:func:`snapshot`, :func:`keepable`).

    Raises
    ------
    SceneError
        One line naming the broken rule, the field and the fix.
    """
    if isinstance(source, Scene):
        return source
    key = snapshot(source) if type(source) is dict else None
    if key is None:
        return _read(source)
    scene = _READ.get(key)
    if scene is None:
        # read from the snapshot (a deep copy): the scene's raw shares nothing with the
        # caller's dict, which may change after (the cached scene must not)
        scene = _read(pickle.loads(key))
        if keepable(scene):
            if len(_READ) >= READ_KEPT:
                try:
                    _READ.pop(next(iter(_READ)), None)  # the oldest (another thread at
                except (StopIteration, RuntimeError):   # it too: one more or less)
                    pass
            _READ[key] = scene
    return scene


class _Snapshot(pickle.Pickler):
    """A pickler of plain data alone: dicts, lists, texts, numbers, numpy arrays and
    scalars (anything else is refused: its pickle may leave out what it holds)."""

    def reducer_override(self, obj):
        if type(obj) is np.ndarray or isinstance(obj, np.generic | np.dtype) or (
                getattr(obj, "__module__", None) or "").startswith("numpy"):
            return NotImplemented   # (an array's pickle names numpy's own rebuilders)
        raise TypeError(type(obj).__name__)


def snapshot(source: dict) -> bytes | None:
    """The bytes of a scene dict's content (equal bytes: equal content, every number to
    the bit and of its type), or None: it holds something other than plain data."""
    out = io.BytesIO()
    try:
        _Snapshot(out, protocol=5).dump(source)
    except Exception:
        return None
    return out.getvalue()


def keepable(scene: Scene) -> bool:
    """Whether a scene read from a dict is kept for the next read of the same content:
    one that warned nothing (a kept scene is given again without reading, so without its
    warnings) and of at most :data:`~kinetostatics.model.scene_types.TRIG_ROWS` positions
    (small: a long sweep's reading is a small part of its solve)."""
    return (not scene.warnings and scene.driver.positions.size <= TRIG_ROWS
            and all(b.mass_model is None for b in scene.bodies.values()))


# Scenes read from dicts, by the dicts' snapshots (:func:`snapshot`), the last few: the
# same dict solved again (a loop over one mechanism, a benchmark) gets the same frozen
# Scene, and with it what the solver keeps per scene (kinetostatics.solver.memo): its
# structure, assemblies and compiled geometry. Measured 2026-11-29 on the four-bar at
# 2001 positions: reading the dict 56 us, its snapshot and look-up 12 us.
_READ: dict[bytes, Scene] = {}
READ_KEPT = 16


def _read(source: Any) -> Scene:
    """:func:`load_scene` of anything but a Scene: read and checked."""
    raw, quiet = read_checks(read_source(source, bundled=SCENES))
    raw, units = to_contract_units(raw)
    top = check_keys(raw, TOP_KEYS, "scene", required=("driver", "bodies", "joints"))
    title = str(top.get("title", ""))
    if "format" in top and top["format"] != 1:
        raise SceneError(f"format = {top['format']!r} is not supported; use format = 1")
    gravity = as_vec2(top["gravity"], "gravity") if "gravity" in top else (0.0, 0.0)
    ground = _ground(top.get("ground", {}))
    bodies = _bodies(top["bodies"], units)
    joints = _joints(top["joints"], bodies, ground, units)
    driver = _driver(top["driver"], bodies, joints, units)
    loads = _loads(top.get("loads", []), bodies, units)
    near = _near(top.get("near", {}), bodies, joints)
    motion = _motion(top.get("motion")) if "motion" in top else None
    balancing = top.get("balancing")
    if balancing is not None and not isinstance(balancing, dict):
        raise SceneError("[balancing] must be a table")
    scene = Scene(title=title, gravity=gravity, ground=ground, driver=driver, bodies=bodies,
                  joints=joints, loads=loads, near=near, motion=motion, balancing=balancing,
                  raw=raw, units=units)
    texts = emit(mechanism_slips(scene), quiet)
    if texts:
        object.__setattr__(scene, "warnings", texts)     # (a frozen dataclass, made here)
    return scene


def _ground(table: Any) -> dict[str, tuple[float, float]]:
    if not isinstance(table, dict):
        raise SceneError("[ground] must be a table of point = [x, y]")
    return {str(k): plain_vec2(v) or as_vec2(v, f"ground.{k}") for k, v in table.items()}


BODY = section(MECHANISM, "bodies", "[]")
FRICTION = section(MECHANISM, "joints", "[]", "friction")
JOINT = section(MECHANISM, "joints", "[]")
DRIVER = section(MECHANISM, "driver")
LOAD = section(MECHANISM, "loads", "[]")
# the known keys as sets: an item within them is read at once; else check_keys names the
# unknown key (or what is missing) with the nearest known one
_BODY_KEYS, _R_KEYS, _T_KEYS, _DRIVER_KEYS, _LOAD_KEYS = (
    frozenset(k) for k in (BODY_KEYS, JOINT_KEYS_R, JOINT_KEYS_T, DRIVER_KEYS, LOAD_KEYS))
_number = read_number        # (the declared fields' reader, in kinetostatics.model.fields)


def _pair(table: dict, key: str, where: str) -> tuple[float, float]:
    value = table[key]
    return plain_vec2(value) or as_vec2(value, f"{where}.{key}")


def _text(value: Any, where: str, key: str) -> str:
    """A non-blank text (``where.key`` named only when it is not)."""
    if type(value) is str and value.strip():
        return value
    return as_str(value, f"{where}.{key}")


def _bodies(items: Any, units: Units) -> dict[str, Body]:
    items = as_list(items, "[[bodies]]")
    if not items:
        raise SceneError("[[bodies]] is empty: a mechanism needs at least the driver body")
    bodies: dict[str, Body] = {}
    for i, item in enumerate(items):
        body = _body(item, i, bodies, units)
        bodies[body.name] = body
    return bodies


def _body(item: Any, i: int, bodies: dict, units: Units) -> Body:
    """One ``[[bodies]]`` item, its numbers read through their declarations."""
    if type(item) is not dict or not item.keys() <= _BODY_KEYS or "name" not in item:
        item = check_keys(item, BODY_KEYS, f"bodies[{i}]", required=("name",))
    name = item["name"]
    if type(name) is not str or not name.strip():
        as_str(name, f"bodies[{i}].name")
    where = f"body {name!r}"
    if name == GROUND:
        raise SceneError(f"{where}: 'ground' is reserved for the fixed body; rename it")
    if name in bodies:
        raise SceneError(f"{where}: the name is used twice; body names must be unique")
    mass = _number(item, BODY["mass"], where, units)
    inertia = _number(item, BODY["inertia"], where, units)
    cog = _pair(item, "cog", where) if "cog" in item else None
    if mass > 0.0 and cog is None:
        raise SceneError(f"{where}: mass > 0 needs 'cog' (centre of mass, local coordinates)")
    pts = item.get("points", {})
    if not isinstance(pts, dict):
        raise SceneError(f"{where}.points must be a table of name = [x, y]")
    points = {}
    for pname, pval in pts.items():
        if pname == "cog":
            raise SceneError(f"{where}.points: 'cog' is reserved for the centre of mass")
        points[str(pname)] = plain_vec2(pval) or as_vec2(pval, f"{where}.points.{pname}")
    model = None
    if "mass_model" in item:
        model = _mass_model(item["mass_model"], where, points, cog, mass, units)
    return Body(name, mass, inertia, cog, points, model)


def _mass_model(table: Any, where: str, points: dict, cog: tuple | None,
                mass: float, units: Units) -> MassModel:
    w = f"{where}.mass_model"
    if not isinstance(table, dict):
        raise SceneError(f"{w} must be a table like "
                         "{ kind = \"static\", points = [\"B\", \"C\"] }")
    kind = table.get("kind")
    if kind == "static":
        check_keys(table, ("kind", "points"), w, required=("points",))
        names = as_list(table["points"], f"{w}.points")
        if len(names) != 2:
            raise SceneError(f"{w}.points must name exactly two points of the body")
    elif kind == "dynamic":
        check_keys(table, ("kind", "point"), w, required=("point",))
        names = [table["point"]]
    else:
        raise SceneError(f"{w}.kind must be \"static\" or \"dynamic\", not {kind!r}")
    for n in names:
        if not isinstance(n, str) or n not in points:
            raise SceneError(f"{w}: {n!r} is not a point of the body{suggest(str(n), points)}")
    if mass <= 0.0 or cog is None:
        raise SceneError(f"{w}: a mass model needs mass > 0 and a cog")
    g = np.array(cog)
    if kind == "static":
        b, c = np.array(points[names[0]]), np.array(points[names[1]])
        bc = float(np.hypot(*(c - b)))
        if bc == 0.0:
            raise SceneError(f"{w}: the two points coincide")
        off = abs(float((c - b)[0] * (g - b)[1] - (c - b)[1] * (g - b)[0])) / bc
        if off > 1e-9 * bc:
            raise SceneError(f"{w}: the cog is {units.quote(off, 'length', '.3g')} off the "
                             f"line through "
                             f"{names[0]} and {names[1]}; static concentration needs it "
                             "on the line")
        t = float(np.dot(g - b, c - b)) / bc**2
        if t < 0.0 or t > 1.0:
            warnings.warn(f"{w}: the points do not bracket the cog; one concentrated mass is "
                          "negative (eq. 2.11 of the course notes)", stacklevel=3)
    else:
        gb = float(np.hypot(*(np.array(points[names[0]]) - g)))
        if gb == 0.0:
            raise SceneError(f"{w}: the point {names[0]!r} is the cog; dynamic concentration "
                             "needs a point away from it (its conjugate point goes to infinity)")
    return MassModel(kind, tuple(names))


def _point_exists(body: str, point: str, bodies: dict, ground: dict, where: str) -> None:
    if not _end(body, point, bodies, ground):
        known = list(ground if body == GROUND else bodies[body].points)
        raise SceneError(f"{where}: {point!r} is not a point of {body!r}{suggest(point, known)}; "
                         f"its points: {', '.join(known) or 'none'}")


def _body_exists(name: Any, bodies: dict, where: str, key: str) -> str:
    if type(name) is not str or not name.strip():
        as_str(name, f"{where}.{key}")
    if name != GROUND and name not in bodies:
        raise SceneError(f"{where}.{key}: unknown body {name!r}"
                         f"{suggest(name, [GROUND, *bodies])}")
    return name


def _friction(table: Any, where: str, kind: str, units: Units) -> Friction:
    keys = ("mu", "radius") if kind == "R" else ("mu", "length")
    where = f"{where}.friction"
    t = check_keys(table, keys, where, required=keys[:2] if kind == "R" else ("mu",))
    return Friction(*(_number(t, FRICTION[k], where, units) for k in ("mu", "radius", "length")))


def _joints(items: Any, bodies: dict, ground: dict, units: Units) -> dict[str, Joint]:
    items = as_list(items, "[[joints]]")
    joints: dict[str, Joint] = {}
    for i, item in enumerate(items):
        joint = _joint(item, i, bodies, ground, joints, units)
        joints[joint.name] = joint
    if not joints:
        raise SceneError("[[joints]] is empty")
    return joints


def _joint(item: Any, i: int, bodies: dict, ground: dict, joints: dict,
           units: Units) -> Joint:
    """One ``[[joints]]`` item: a revolute or a prismatic joint between two bodies."""
    if not isinstance(item, dict):
        raise SceneError(f"joints[{i}] must be a table")
    kind = item.get("kind")
    if kind not in ("R", "T"):
        raise SceneError(f"joints[{i}].kind must be \"R\" (revolute) or \"T\" (prismatic), "
                         f"not {kind!r}")
    if not item.keys() <= (_R_KEYS if kind == "R" else _T_KEYS) or "name" not in item:
        item = check_keys(item, JOINT_KEYS_R if kind == "R" else JOINT_KEYS_T, f"joints[{i}]",
                          required=("name",))
    name = item["name"]
    if type(name) is not str or not name.strip():
        as_str(name, f"joints[{i}].name")
    if name in joints:
        raise SceneError(f"joint {name!r}: the name is used twice; joint names must be unique")
    fr = (_friction(item["friction"], f"joint {name!r}", kind, units) if "friction" in item
          else None)
    if kind == "R":
        b, pts = item.get("bodies"), item.get("points", (name, name))
        angle = 0.0
    else:
        b = (item.get("guide"), item.get("slider"))
        pts = (item.get("line_point"), item.get("slider_point"))
        # the line angle read in degrees (the contract's unit for a file's angles) and
        # held in radians: the one conversion, here
        angle = radians(_number(item, JOINT["line_angle"], f"joint {name!r}", units))
    # the ends as written, when each is a point of a body of the scene (the rule of
    # _point_exists); else _ends names what is wrong
    if not (type(b) in (list, tuple) and type(pts) in (list, tuple) and len(b) == 2
            and len(pts) == 2 and b[0] != b[1] and _end(b[0], pts[0], bodies, ground)
            and _end(b[1], pts[1], bodies, ground)):
        _ends(item, kind, name, bodies, ground)
    return Joint(name, kind, (b[0], b[1]), (pts[0], pts[1]), friction=fr, beta=angle)


def _end(body: Any, point: Any, bodies: dict, ground: dict) -> bool:
    """True when ``body`` names the ground or a body, and ``point`` one of its points (or
    a body's ``cog``)."""
    if type(body) is not str or type(point) is not str or not point.strip():
        return False
    if body == GROUND:
        return point in ground
    b = bodies.get(body)
    return b is not None and (point in b.points or point == "cog")


def _ends(item: dict, kind: str, name: str, bodies: dict, ground: dict) -> None:
    """Refuse a joint's ends that :func:`_end` does not accept, naming what is wrong."""
    where = f"joint {name!r}"
    if kind == "R":
        if "bodies" not in item:
            raise SceneError(f"{where}: missing required key 'bodies'")
        bl = as_list(item["bodies"], f"{where}.bodies")
        if len(bl) != 2:
            raise SceneError(f"{where}.bodies must name two bodies")
        b = (_body_exists(bl[0], bodies, where, "bodies"),
             _body_exists(bl[1], bodies, where, "bodies"))
        pts = as_list(item.get("points", [name, name]), f"{where}.points")
        if len(pts) != 2:
            raise SceneError(f"{where}.points must name one point on each body")
        pts = (_text(pts[0], where, "points"), _text(pts[1], where, "points"))
    else:
        for k in ("guide", "slider", "line_point", "slider_point"):
            if k not in item:
                raise SceneError(f"{where}: missing required key {k!r}")
        b = (_body_exists(item["guide"], bodies, where, "guide"),
             _body_exists(item["slider"], bodies, where, "slider"))
        pts = (_text(item["line_point"], where, "line_point"),
               _text(item["slider_point"], where, "slider_point"))
    if b[0] == b[1]:
        raise SceneError(f"{where} joins {b[0]!r} to itself; name two different bodies")
    for body, p in zip(b, pts, strict=True):
        _point_exists(body, p, bodies, ground, where)


def _driver(table: Any, bodies: dict, joints: dict, units: Units) -> Driver:
    t = table
    if type(t) is not dict or not t.keys() <= _DRIVER_KEYS or "body" not in t or "joint" not in t:
        t = check_keys(table, DRIVER_KEYS, "[driver]", required=("body", "joint"))
    body = _body_exists(t["body"], bodies, "driver", "body")
    if body == GROUND:
        raise SceneError("driver.body cannot be the ground")
    jname = _text(t["joint"], "driver", "joint")
    if jname not in joints:
        raise SceneError(f"driver.joint: unknown joint {jname!r}{suggest(jname, joints)}")
    joint = joints[jname]
    if set(joint.bodies) != {body, GROUND}:
        raise SceneError(f"driver.joint {jname!r} must join the driver {body!r} to the ground, "
                         f"but it joins {joint.bodies[0]!r} and {joint.bodies[1]!r}")
    kind = joint.kind
    if "speed" in t and "speed_rpm" in t:
        raise SceneError("[driver]: give 'speed' or 'speed_rpm', not both")
    if "speed_rpm" in t:
        if kind != "R":
            raise SceneError("driver.speed_rpm is for a rotating driver; a sliding driver "
                             "takes 'speed' in m/s")
        speed = rpm_to_rad_s(_number(t, DRIVER["speed_rpm"], "driver", units))
    elif "speed" in t:
        speed = _number(t, DRIVER["speed"], "driver", units)
    else:
        raise SceneError("[driver]: missing required key 'speed' (rad/s or m/s) or 'speed_rpm'")
    acc = _number(t, DRIVER["acceleration"], "driver", units)
    driver = Driver(body, jname, kind, speed, acc, _positions(t, units))
    if kind == "R" and "positions" not in t and driver.positions.size <= TRIG_ROWS:
        # a linspace as read: its cos and sin shared with the same sweep's (Driver.trig)
        key = (driver.positions[0].hex(), driver.positions[-1].hex(), driver.positions.size)
        object.__setattr__(driver, "sweep", key)
    if "positions" not in t and widely_spaced(driver.positions):
        object.__setattr__(driver, "increasing", True)
    return driver


def widely_spaced(grid: np.ndarray) -> bool:
    """Whether ``grid``, known to be ``np.linspace(start, stop, count)`` (two rows or more),
    strictly increases, told from its ends and size alone: its step ``s`` (as linspace
    works it out) is more than ``4 E``, ``E = spacing(4 M)``, ``M = max(|start|, |stop|)``
    (each row ``fl(fl(i s) + start)`` is within ``E`` of ``start + i s``, and the last,
    ``stop``, within ``E`` of ``start + (count - 1) s``: each row then exceeds the one
    before by more than ``s - 2 E``). False where that is not shown (a sweep that
    decreases, or steps of a few ulps: checked row by row then, as positions typed)."""
    if grid.size < 2:
        return False
    start, stop = float(grid[0]), float(grid[-1])
    step = (stop - start) / (grid.size - 1)
    return bool(step > 4.0 * np.spacing(4.0 * max(abs(start), abs(stop))))


def _positions(t: dict, units: Units) -> np.ndarray:
    """The driver's positions: a ``positions`` list, or start/stop/count."""
    if "positions" in t:
        if "start" in t or "stop" in t or "count" in t:
            raise SceneError("[driver]: give 'positions' or start/stop/count, not both")
        pos = as_list(t["positions"], "driver.positions")
        if not pos:
            raise SceneError("driver.positions is empty; list at least one position")
        if len(pos) > MAX_COUNT:
            raise SceneError(f"driver.positions has {len(pos):_} entries; at most {MAX_COUNT:_}")
        return np.array([as_float(p, f"driver.positions[{i}]") for i, p in enumerate(pos)])
    if "start" not in t or "stop" not in t or "count" not in t:
        missing = [k for k in ("start", "stop", "count") if k not in t]
        raise SceneError(f"[driver]: missing required key {missing[0]!r} "
                         "(or give 'positions = [...]')")
    start = _number(t, DRIVER["start"], "driver", units)
    stop = _number(t, DRIVER["stop"], "driver", units)
    count = t["count"]
    if type(count) is not int or not 1 <= count <= MAX_COUNT:
        count = as_int(count, "driver.count", lo=1, hi=MAX_COUNT)
    return _sweep(start, stop, count)


_SWEEPS: dict[tuple[str, str, int], np.ndarray] = {}


def _sweep(start: float, stop: float, count: int) -> np.ndarray:
    """``np.linspace(start, stop, count)``, a copy of its own; the last few sweeps are
    remembered (variants of one mechanism share theirs, and a copy costs less)."""
    key = (start.hex(), stop.hex(), count)       # the bits: -0.0 is not 0.0
    done = _SWEEPS.get(key)
    if done is None:
        done = np.linspace(start, stop, count)
        if count > 100_000:
            return done
        if len(_SWEEPS) >= 16:
            _SWEEPS.clear()
        _SWEEPS[key] = done
    return done.copy()


def _loads(items: Any, bodies: dict, units: Units) -> tuple[Load, ...]:
    items = as_list(items, "[[loads]]")
    return tuple(_load(item, i, bodies, units) for i, item in enumerate(items))


def _load(item: Any, i: int, bodies: dict, units: Units) -> Load:
    """One ``[[loads]]`` item: a force, a ``resist`` force and/or a moment on a body."""
    where = f"loads[{i}]"
    if type(item) is not dict or not item.keys() <= _LOAD_KEYS or "body" not in item:
        item = check_keys(item, LOAD_KEYS, where, required=("body",))
    body = _body_exists(item["body"], bodies, where, "body")
    if body == GROUND:
        raise SceneError(f"{where}.body: a load on the ground does nothing; "
                         "put it on a moving body")
    if "force" in item and "resist" in item:
        raise SceneError(f"{where}: give 'force' or 'resist', not both")
    force = _pair(item, "force", where) if "force" in item else None
    resist = _number(item, LOAD["resist"], where, units) if "resist" in item else None
    moment = _number(item, LOAD["moment"], where, units)
    point = None
    if (force is not None or resist is not None) and "point" not in item:
        raise SceneError(f"{where}: a force needs 'point' (a point of {body!r} or \"cog\")")
    if "point" in item:
        point = _text(item["point"], where, "point")
        b = bodies[body]
        if point != "cog" and point not in b.points:
            raise SceneError(f"{where}.point: {point!r} is not a point of {body!r}"
                             f"{suggest(point, [*b.points, 'cog'])}")
        if point == "cog" and b.cog is None:
            raise SceneError(f"{where}.point: body {body!r} has no 'cog'")
    if force is None and resist is None and "moment" not in item:
        raise SceneError(f"{where}: give a 'force', a 'resist' force or a 'moment'")
    when = _text(item.get("when", "always"), where, "when")
    if when not in LOAD_WHEN:
        raise SceneError(f"{where}.when: {when!r} is not one of {', '.join(LOAD_WHEN)}"
                         f"{suggest(when, LOAD_WHEN)}")
    if when == "resisting" and (force is None or moment):
        raise SceneError(f"{where}.when = \"resisting\" applies to a constant 'force' "
                         "alone (a 'resist' force always resists; give no 'moment')")
    return Load(body, point, force, moment, resist, when)


def _near(table: Any, bodies: dict, joints: dict) -> dict[str, tuple[float, float]]:
    if not isinstance(table, dict):
        raise SceneError("[near] must be a table of hint = [x, y]")
    near = {}
    for key, val in table.items():
        key = str(key)
        if "." in key:
            b, p = key.split(".", 1)
            if b not in bodies:
                raise SceneError(f"near.{key}: unknown body {b!r}{suggest(b, bodies)}")
            if p != "cog" and p not in bodies[b].points:
                raise SceneError(f"near.{key}: {p!r} is not a point of {b!r}"
                                 f"{suggest(p, bodies[b].points)}")
        else:
            rev = [j for j, jt in joints.items() if jt.kind == "R"]
            if key not in rev:
                raise SceneError(f"near.{key}: not a revolute joint{suggest(key, rev)}; "
                                 "hint keys are revolute joint names or \"body.point\"")
        near[key] = as_vec2(val, f"near.{key}")
    return near


def _motion(table: Any) -> dict[str, Any]:
    t = check_keys(table, MOTION_KEYS, "[motion]", required=("omega0", "cycles"))
    return dict(t)
