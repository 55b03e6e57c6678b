"""Mechanism scenes: the TOML input of ``scene-format.md`` section 1, checked into dataclasses.

``load_scene`` accepts a path, a string naming a ``.toml`` file, a string of TOML text
or a dict, and returns a :class:`Scene`. Every rule of the contract is checked here;
a broken rule raises :class:`~kinetostatics.model.errors.SceneError` with one line naming
the field and the fix. Unknown keys are refused with the nearest known key suggested.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .errors import SceneError
from .examples import SCENES
from .scene_types import GROUND, Body, Driver, Friction, Joint, Load, MassModel, Scene
from .scene_units import to_contract_units
from .slips import emit, mechanism_slips, read_checks, typed
from .tomlio import (
    MAX_MAGNITUDE,
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
from .units import Units, rpm_to_rad_s

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
        The checked scene.

    Raises
    ------
    SceneError
        One line naming the broken rule, the field and the fix.
    """
    if isinstance(source, Scene):
        return source
    raw, quiet = read_checks(read_source(source, bundled=SCENES))
    raw, units = to_contract_units(raw)
    top = check_keys(raw, TOP_KEYS, "scene", required=("driver", "bodies", "joints"))
    title = str(top.get("title", ""))
    if "format" in top and top["format"] != 1:
        raise SceneError(f"format = {top['format']!r} is not supported; use format = 1")
    gravity = as_vec2(top.get("gravity", [0.0, 0.0]), "gravity")
    ground = _ground(top.get("ground", {}))
    bodies = _bodies(top["bodies"], units)
    joints = _joints(top["joints"], bodies, ground)
    driver = _driver(top["driver"], bodies, joints)
    loads = _loads(top.get("loads", []), bodies)
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


_BODY_PLAIN = frozenset(BODY_KEYS) - {"mass_model"}


def _plain_nonnegative(value: Any) -> float | None:
    """``as_float(value, ..., nonnegative=True)`` of a Python float or int that passes,
    else None (the long way then names what is wrong)."""
    if type(value) in (float, int) and 0.0 <= value <= MAX_MAGNITUDE:
        return float(value)         # (compared before float(): a huge int never raises here)
    return None


def _plain_body(item: Any, bodies: dict) -> Body | None:
    """The :class:`Body` of a body written the usual way (a text name, numbers, pairs of
    floats, no mass model), every rule of :func:`_bodies` met, told without building a
    message; else None, and :func:`_bodies` checks the item the long way and names what
    is wrong. It accepts only what the long way accepts, and gives the same Body."""
    if type(item) is not dict or not item.keys() <= _BODY_PLAIN:
        return None
    name = item.get("name")
    if type(name) is not str or not name.strip() or name == GROUND or name in bodies:
        return None
    mass = _plain_nonnegative(item.get("mass", 0.0))
    if mass is None:
        return None
    inertia = _plain_nonnegative(item.get("inertia", 0.0))
    if inertia is None:
        return None
    cog = None
    if "cog" in item:
        cog = plain_vec2(item["cog"])
        if cog is None:
            return None
    if mass > 0.0 and cog is None:
        return None
    pts = item.get("points", {})
    if type(pts) is not dict:
        return None
    points = {}
    for pname, pval in pts.items():
        if type(pname) is not str or pname == "cog":
            return None
        xy = plain_vec2(pval)
        if xy is None:
            return None
        points[pname] = xy
    return Body(name, mass, inertia, cog, points, None)


def _bodies(items: Any, units: Units) -> dict[str, Body]:
    items = as_list(items, "[[bodies]]")
    if not items:
        raise SceneError("[[bodies]] is empty: a mechanism needs at least the driver body")
    bodies: dict[str, Body] = {}
    for i, item in enumerate(items):
        plain = _plain_body(item, bodies)
        if plain is not None:
            bodies[plain.name] = plain
            continue
        where = f"bodies[{i}]"
        item = check_keys(item, BODY_KEYS, where, required=("name",))
        name = as_str(item["name"], f"{where}.name")
        where = f"body {name!r}"
        if name == GROUND:
            raise SceneError(f"{where}: 'ground' is reserved for the fixed body; rename it")
        if name in bodies:
            raise SceneError(f"{where}: the name is used twice; body names must be unique")
        mass = as_float(item.get("mass", 0.0), f"{where}.mass")
        inertia = as_float(item.get("inertia", 0.0), f"{where}.inertia")
        for key, value, quantity in (("mass", mass, "mass"), ("inertia", inertia, "inertia")):
            if value < 0.0:         # the value quoted as typed, in the scene's unit
                raise SceneError(f"{where}.{key} must not be negative, got "
                                 f"{typed(value, quantity, units)}")
        cog = (plain_vec2(item["cog"]) or as_vec2(item["cog"], f"{where}.cog")
               if "cog" in item else None)
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
        bodies[name] = Body(name, mass, inertia, cog, points, model)
    return bodies


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
    names = ground if body == GROUND else bodies[body].points
    if point not in names and not (point == "cog" and body != GROUND):
        known = list(names)
        raise SceneError(f"{where}: {point!r} is not a point of {body!r}{suggest(point, known)}; "
                         f"its points: {', '.join(known) or 'none'}")


def _body_exists(name: Any, bodies: dict, where: str) -> str:
    name = as_str(name, where)
    if name != GROUND and name not in bodies:
        raise SceneError(f"{where}: unknown body {name!r}"
                         f"{suggest(name, [GROUND, *bodies])}")
    return name


def _friction(table: Any, where: str, kind: str) -> Friction:
    keys = ("mu", "radius") if kind == "R" else ("mu", "length")
    t = check_keys(table, keys, f"{where}.friction", required=keys[:2] if kind == "R"
                   else ("mu",))
    return Friction(as_float(t["mu"], f"{where}.friction.mu", nonnegative=True),
                    as_float(t.get("radius", 0.0), f"{where}.friction.radius", nonnegative=True),
                    as_float(t.get("length", 0.0), f"{where}.friction.length", nonnegative=True))


_R_PLAIN = frozenset(JOINT_KEYS_R) - {"friction"}
_T_PLAIN = frozenset(JOINT_KEYS_T) - {"friction"}


def _plain_joint(item: Any, bodies: dict, ground: dict, joints: dict) -> Joint | None:
    """The :class:`Joint` of a joint written the usual way (texts for its name, bodies
    and points, a float ``line_angle``, known keys, no friction), every rule of
    :func:`_joints` met, told without building a message; else None, and
    :func:`_joints` checks the item the long way and names what is wrong. It accepts
    only what the long way accepts, and gives the same Joint."""
    if type(item) is not dict:
        return None
    kind, name = item.get("kind"), item.get("name")
    if (type(kind) is not str or type(name) is not str or not name.strip()
            or name in joints):
        return None
    angle = 0.0
    if kind == "R":
        pair = item.get("bodies")
        if not item.keys() <= _R_PLAIN or type(pair) is not list or len(pair) != 2:
            return None
        pts = item.get("points", [name, name])
        if type(pts) is not list or len(pts) != 2:
            return None
        b0, b1 = pair
        p0, p1 = pts
    elif kind == "T":
        if not item.keys() <= _T_PLAIN:
            return None
        b0, b1 = item.get("guide"), item.get("slider")
        p0, p1 = item.get("line_point"), item.get("slider_point")
        if "line_angle" in item:
            angle = item["line_angle"]
            if type(angle) not in (float, int) or not -MAX_MAGNITUDE <= angle <= MAX_MAGNITUDE:
                return None         # (compared before float(): a huge int never raises here)
            angle = float(angle)
    else:
        return None
    if (type(b0) is not str or type(b1) is not str or type(p0) is not str
            or type(p1) is not str or b0 == b1
            or not (b0.strip() and b1.strip() and p0.strip() and p1.strip())):
        return None
    for b, p in ((b0, p0), (b1, p1)):
        if b == GROUND:
            if p not in ground:
                return None
        elif b not in bodies or (p not in bodies[b].points and p != "cog"):
            return None
    return Joint(name, kind, (b0, b1), (p0, p1), angle, None)


def _joints(items: Any, bodies: dict, ground: dict) -> dict[str, Joint]:
    items = as_list(items, "[[joints]]")
    joints: dict[str, Joint] = {}
    for i, item in enumerate(items):
        plain = _plain_joint(item, bodies, ground, joints)
        if plain is not None:
            joints[plain.name] = plain
            continue
        where = f"joints[{i}]"
        if not isinstance(item, dict):
            raise SceneError(f"{where} must be a table")
        kind = item.get("kind")
        if kind not in ("R", "T"):
            raise SceneError(f"{where}.kind must be \"R\" (revolute) or \"T\" (prismatic), "
                             f"not {kind!r}")
        item = check_keys(item, JOINT_KEYS_R if kind == "R" else JOINT_KEYS_T, where,
                          required=("name",))
        name = as_str(item["name"], f"{where}.name")
        where = f"joint {name!r}"
        if name in joints:
            raise SceneError(f"{where}: the name is used twice; joint names must be unique")
        fr = _friction(item["friction"], where, kind) if "friction" in item else None
        if kind == "R":
            if "bodies" not in item:
                raise SceneError(f"{where}: missing required key 'bodies'")
            bl = as_list(item["bodies"], f"{where}.bodies")
            if len(bl) != 2:
                raise SceneError(f"{where}.bodies must name two bodies")
            b = tuple(_body_exists(x, bodies, f"{where}.bodies") for x in bl)
            pts = item.get("points", [name, name])
            pts = as_list(pts, f"{where}.points")
            if len(pts) != 2:
                raise SceneError(f"{where}.points must name one point on each body")
            pts = tuple(as_str(p, f"{where}.points") for p in pts)
            angle = 0.0
        else:
            for k in ("guide", "slider", "line_point", "slider_point"):
                if k not in item:
                    raise SceneError(f"{where}: missing required key {k!r}")
            b = (_body_exists(item["guide"], bodies, f"{where}.guide"),
                 _body_exists(item["slider"], bodies, f"{where}.slider"))
            pts = (as_str(item["line_point"], f"{where}.line_point"),
                   as_str(item["slider_point"], f"{where}.slider_point"))
            angle = as_float(item.get("line_angle", 0.0), f"{where}.line_angle")
        if b[0] == b[1]:
            raise SceneError(f"{where} joins {b[0]!r} to itself; name two different bodies")
        for body, p in zip(b, pts, strict=True):
            _point_exists(body, p, bodies, ground, where)
        joints[name] = Joint(name, kind, b, pts, angle, fr)
    if not joints:
        raise SceneError("[[joints]] is empty")
    return joints


_DRIVER_PLAIN = frozenset(("body", "joint", "speed", "acceleration", "start", "stop", "count"))


def _plain_float(value: Any) -> float | None:
    """``as_float(value, ...)`` of a Python float or int that passes, else None (the
    long way then names what is wrong)."""
    if type(value) in (float, int) and -MAX_MAGNITUDE <= value <= MAX_MAGNITUDE:
        return float(value)         # (compared before float(): a huge int never raises here)
    return None


def _plain_driver(table: Any, bodies: dict, joints: dict) -> Driver | None:
    """The :class:`Driver` of a sweep written the usual way (texts for the body and the
    joint, numbers for speed, acceleration, start and stop, a whole count), every rule
    of :func:`_driver` met, told without building a message; else None, and
    :func:`_driver` checks the table the long way and names what is wrong. It accepts
    only what the long way accepts, and gives the same Driver."""
    if type(table) is not dict or not table.keys() <= _DRIVER_PLAIN:
        return None
    body, jname, count = table.get("body"), table.get("joint"), table.get("count")
    # a name among the bodies (joints) is a checked one: a non-blank text, not "ground"
    if (type(body) is not str or type(jname) is not str or body not in bodies
            or jname not in joints or set(joints[jname].bodies) != {body, GROUND}
            or type(count) is not int or not 1 <= count <= MAX_COUNT):
        return None
    speed = _plain_float(table.get("speed"))
    acc = _plain_float(table.get("acceleration", 0.0))
    start = _plain_float(table.get("start"))
    stop = _plain_float(table.get("stop"))
    if speed is None or acc is None or start is None or stop is None:
        return None
    return Driver(body, jname, joints[jname].kind, speed, acc, _sweep(start, stop, count))


def _driver(table: Any, bodies: dict, joints: dict) -> Driver:
    plain = _plain_driver(table, bodies, joints)
    if plain is not None:
        return plain
    t = check_keys(table, DRIVER_KEYS, "[driver]", required=("body", "joint"))
    body = _body_exists(t["body"], bodies, "driver.body")
    if body == GROUND:
        raise SceneError("driver.body cannot be the ground")
    jname = as_str(t["joint"], "driver.joint")
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
        speed = rpm_to_rad_s(as_float(t["speed_rpm"], "driver.speed_rpm"))
    elif "speed" in t:
        speed = as_float(t["speed"], "driver.speed")
    else:
        raise SceneError("[driver]: missing required key 'speed' (rad/s or m/s) or 'speed_rpm'")
    acc = as_float(t.get("acceleration", 0.0), "driver.acceleration")
    has_range = [k for k in ("start", "stop", "count") if k in t]
    if "positions" in t:
        if has_range:
            raise SceneError("[driver]: give 'positions' or start/stop/count, not both")
        pos = as_list(t["positions"], "driver.positions")
        if not pos:
            raise SceneError("driver.positions is empty; list at least one position")
        if len(pos) > MAX_COUNT:
            raise SceneError(f"driver.positions has {len(pos):_} entries; at most {MAX_COUNT:_}")
        positions = np.array([as_float(p, f"driver.positions[{i}]") for i, p in enumerate(pos)])
    else:
        missing = [k for k in ("start", "stop", "count") if k not in t]
        if missing:
            raise SceneError(f"[driver]: missing required key {missing[0]!r} "
                             "(or give 'positions = [...]')")
        start = as_float(t["start"], "driver.start")
        stop = as_float(t["stop"], "driver.stop")
        count = as_int(t["count"], "driver.count", lo=1, hi=MAX_COUNT)
        positions = _sweep(start, stop, count)
    return Driver(body, jname, kind, speed, acc, positions)


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


_FORCE_PLAIN = frozenset(("body", "point", "force"))


def _plain_force(item: Any, bodies: dict) -> Load | None:
    """The :class:`Load` of a force written the usual way (``body``, ``point`` and a pair
    of floats ``force``, nothing else), every rule of :func:`_loads` met, told without
    building a message; else None, and :func:`_loads` checks the item the long way and
    names what is wrong. It accepts only what the long way accepts, and gives the same
    Load."""
    if type(item) is not dict or item.keys() != _FORCE_PLAIN:
        return None
    body, point = item["body"], item["point"]
    if (type(body) is not str or type(point) is not str or body not in bodies
            or not body.strip() or not point.strip()):
        return None
    force = plain_vec2(item["force"])
    if force is None:
        return None
    b = bodies[body]
    if point not in b.points and (point != "cog" or b.cog is None):
        return None
    return Load(body, point, force, 0.0, None, "always")


def _loads(items: Any, bodies: dict) -> tuple[Load, ...]:
    items = as_list(items, "[[loads]]")
    loads = []
    for i, item in enumerate(items):
        plain = _plain_force(item, bodies)
        if plain is not None:
            loads.append(plain)
            continue
        where = f"loads[{i}]"
        item = check_keys(item, LOAD_KEYS, where, required=("body",))
        body = _body_exists(item["body"], bodies, f"{where}.body")
        if body == GROUND:
            raise SceneError(f"{where}.body: a load on the ground does nothing; "
                             "put it on a moving body")
        if "force" in item and "resist" in item:
            raise SceneError(f"{where}: give 'force' or 'resist', not both")
        force = as_vec2(item["force"], f"{where}.force") if "force" in item else None
        resist = (as_float(item["resist"], f"{where}.resist", nonnegative=True)
                  if "resist" in item else None)
        moment = as_float(item.get("moment", 0.0), f"{where}.moment")
        point = None
        if force is not None or resist is not None:
            if "point" not in item:
                raise SceneError(f"{where}: a force needs 'point' (a point of {body!r} or \"cog\")")
        if "point" in item:
            point = as_str(item["point"], f"{where}.point")
            b = bodies[body]
            if point != "cog" and point not in b.points:
                raise SceneError(f"{where}.point: {point!r} is not a point of {body!r}"
                                 f"{suggest(point, [*b.points, 'cog'])}")
            if point == "cog" and b.cog is None:
                raise SceneError(f"{where}.point: body {body!r} has no 'cog'")
        if force is None and resist is None and "moment" not in item:
            raise SceneError(f"{where}: give a 'force', a 'resist' force or a 'moment'")
        when = as_str(item.get("when", "always"), f"{where}.when")
        if when not in LOAD_WHEN:
            raise SceneError(f"{where}.when: {when!r} is not one of {', '.join(LOAD_WHEN)}"
                             f"{suggest(when, LOAD_WHEN)}")
        if when == "resisting" and (force is None or moment):
            raise SceneError(f"{where}.when = \"resisting\" applies to a constant 'force' "
                             "alone (a 'resist' force always resists; give no 'moment')")
        loads.append(Load(body, point, force, moment, resist, when))
    return tuple(loads)


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
