"""Unit slips judged on the physical quantity: one pass after a scene is converted to SI.

A slip (radians typed for degrees, rpm for rad/s, grams for kilograms) gives a plausible
number in the wrong unit. Each rule here looks at the quantity in SI, in its context, so
the same quantity gets the same answer whatever unit it was typed in, and a legitimate
value is never warned (docs/scene-format.md, "Unit slips", has the table of rules with
an example of each). A rule that fires gives one :class:`Slip`: the field, the value as
typed with its unit, what it would be if it were a slip, and the rule's name, which
``[checks] quiet = ["name"]`` in the scene silences.

This module holds the shared pieces (the :class:`Slip`, the ``[checks]`` table, the
rules on angle lists and speeds) and the mechanism scene's rules (:func:`mechanism_slips`).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .errors import SceneError, UnitWarning
from .scene_types import GROUND
from .tomlio import suggest
from .units import DEG, Units, degrees, rpm_to_rad_s

if TYPE_CHECKING:
    from .scene_types import Body, Scene

__all__ = ["RULES", "Slip", "angle_list_slip", "emit", "mechanism_slips", "read_checks",
           "tip_speed_slip", "typed"]

RULES: dict[str, str] = {
    "positions": "a rotating driver's positions: radians typed for degrees (a sweep within "
                 "2 pi degrees, over 0.9 turn if read as radians, or half a turn with "
                 "fractional values) or degrees typed "
                 "under angle = \"rad\" (more than four turns)",
    "angles": "a list of angles within 2 pi degrees, spread over a degree or more, not all "
              "whole (radians typed for degrees); any angle beyond 720 deg (degrees typed "
              "under angle = \"rad\")",
    "speed": "an angular speed whose peripheral speed over the mechanism's size exceeds "
             "400 m/s (a cam's outline: 50 m/s), or omega0 above three times the motor's "
             "no-load speed (rpm typed for rad/s)",
    "gravity": "gravity's magnitude outside 1..30 m/s^2 (not zero): m/s^2 typed under "
               "length = \"mm\" or the like",
    "mass": "a body heavier than 200 000 kg/m^3 over the cube of its size, a point mass "
            "(inertia 0, one point) over the size of the links it joins and no more than 300 "
            "times the heaviest of them (kg typed under mass = \"t\", or grams typed as "
            "kilograms)",
    "lengths": "a point farther than 100 mechanism sizes from its body's joints, or a "
               "joint's pin radius or bearing length over 10 mechanism sizes (millimetres "
               "among metres)",
    "unbalance_mass": "a rotor's unbalance masses 300 times apart or more, the heavier "
                      "1 kg or more or the lighter under 1 mg (one typed in another unit)",
    "trial_mass": "a trial mass above 2 kg (or a hundredth of the rotor's mass): grams typed "
                  "as kilograms; trial masses of one section 300 times apart, the heavier "
                  "1 kg or more or the lighter under 1 mg",
    "readings": "one run's readings 300 times off the other runs' (another vibration unit)",
    "correction": "a correction more than 100 times its trial mass",
}
"""The rules' names (the keys of ``[checks] quiet``) and what each looks for."""

TIP_SPEED = 400.0
"""m/s: an angular speed that moves the mechanism's outline faster than this looks like rpm
typed for rad/s (no linkage runs near the speed of sound)."""

DENSEST = 2e5
"""kg/m^3: a body's mass over the cube of its size above this is a slip (25 x steel's
density: a compact piston of 5.5 kg over 38 mm of points, 9.9e4 kg/m^3, is a real one; a
mass in kg typed under t, or grams typed as kilograms, is 1000 x too heavy)."""

LUMPED = 0.1
"""A body whose own size (radius of gyration's diameter, points' box) is under this
fraction of the links it joins is a point mass (the course's mass concentration): its
size is theirs."""

PIN = 10.0
"""A joint's pin radius or bearing length over this many mechanism sizes is a slip."""

HEAVIER = 300.0
"""A point mass over this many times the heaviest link it joins is a slip (grams typed as
kilograms makes it 1000 times its real self)."""
"""A body whose own size (radius of gyration's diameter, points' box) is under this
fraction of the links it joins is a point mass (the course's mass concentration): its
size is theirs."""


@dataclass(frozen=True)
class Slip:
    """One suspected unit slip.

    Attributes
    ----------
    rule : str
        The rule's name (a key of :data:`RULES`, and of ``[checks] quiet``).
    field : str
        Where in the scene (``driver.speed``, ``influence[0].runs``...).
    typed : str
        The value as typed, with its unit.
    why : str
        What looks wrong, in SI.
    if_slip : str
        What the value would be if it were a slip.
    """

    rule: str
    field: str
    typed: str
    why: str
    if_slip: str

    def text(self) -> str:
        """The one-line warning."""
        return (f"{self.field} = {self.typed}: {self.why}; if a slip, {self.if_slip}. If it "
                f"is meant, write [checks] quiet = [\"{self.rule}\"] in the scene")


def read_checks(raw: dict, error: type[Exception] = SceneError) -> tuple[dict, frozenset[str]]:
    """The scene without its ``[checks]`` table, and the rules it silences.

    Raises
    ------
    SceneError
        ``[checks]`` not a table, a key other than ``quiet``, or a rule not in :data:`RULES`.
    """
    if not isinstance(raw, dict) or "checks" not in raw:
        return raw, frozenset()
    table = raw["checks"]
    if not isinstance(table, dict) or set(table) - {"quiet"}:
        raise error("[checks] must be a table with one key, quiet = [\"rule\", ...]")
    quiet = table.get("quiet", [])
    if not isinstance(quiet, list) or not all(isinstance(q, str) for q in quiet):
        raise error("checks.quiet must be a list of rule names, e.g. [\"trial_mass\"]")
    for q in quiet:
        if q not in RULES:
            raise error(f"checks.quiet: unknown rule {q!r}{suggest(q, RULES)}; "
                        f"known: {', '.join(RULES)}")
    return {k: v for k, v in raw.items() if k != "checks"}, frozenset(quiet)


def emit(slips: Iterable[Slip], quiet: frozenset[str], category: type[Warning] = UnitWarning,
         stacklevel: int = 3) -> tuple[str, ...]:
    """Warn once per slip not silenced; the warnings' texts, for the outputs."""
    texts = tuple(s.text() for s in slips if s.rule not in quiet)
    for t in texts:
        warnings.warn(t, category, stacklevel=stacklevel)
    return texts


def typed(values: float | Sequence[float], quantity: str, units: Units, *,
          file: bool = True) -> str:
    """Values in the contract's units (``file``: degrees for angles) or SI, written as
    typed: in the scene's unit, with its name (``"350 g"``, ``"[0, 0.5, ...] rad"``)."""
    if isinstance(values, int | float):
        return units.quote(values, quantity, file=file)
    f = units.file_factor(quantity) if file else units.factor(quantity)
    unit = units.unit(quantity)
    vals = [v / f for v in values]
    shown = ", ".join(f"{v:g}" for v in vals[:4]) + (", ..." if len(vals) > 4 else "")
    return f"[{shown}] {unit}".rstrip()


def angle_list_slip(rad: Sequence[float]) -> str | None:
    """What is wrong with a list of angles (SI, radians), or None.

    Radians typed for degrees: at least two angles, all within 2 pi degrees, spread over
    1 degree or more, not all whole degrees. Degrees typed under ``angle = "rad"``: an
    angle beyond 720 degrees. A single small angle (a 4.5 deg split) is never judged.

    >>> angle_list_slip([0.0, 1.5 * DEG, 4.4 * DEG]) is not None
    True
    >>> angle_list_slip([0.0, 4.5 * DEG]) is None, angle_list_slip([4.5 * DEG]) is None
    (False, True)
    >>> angle_list_slip([30.0, 120.0]) is not None
    True
    """
    if any(abs(a) > 4.0 * math.pi * (1.0 + 1e-9) for a in rad):
        return "beyond two turns: degrees typed under angle = \"rad\"?"
    deg = [a / DEG for a in rad]
    if len(deg) < 2 or any(abs(d) > 2.0 * math.pi * 1.01 for d in deg):
        return None
    if max(deg) - min(deg) < 1.0 or all(abs(d - round(d)) <= 1e-6 for d in deg):
        return None
    return "all within 2 pi degrees with fractional values: radians typed for degrees?"


def tip_speed_slip(omega: float, size: float) -> bool:
    """True when ``omega`` (rad/s) moves a point at ``size`` (m) faster than
    :data:`TIP_SPEED`."""
    return abs(omega) * size > TIP_SPEED


def mechanism_slips(scene: Scene) -> list[Slip]:
    """The suspected slips of a read mechanism scene (every number in the contract's
    units), rule by rule (:data:`RULES`)."""
    u = scene.units
    out = _position_slips(scene, u) + _speed_slips(scene, u) + _gravity_slips(scene, u)
    out += _mass_slips(scene, u) + _far_points(scene, u) + _line_angle_slips(scene, u)
    out += _friction_slips(scene, u)
    if scene.motion is not None:
        out += _motor_table_slips(scene.motion, u)
    return out


def _position_slips(scene: Scene, u: Units) -> list[Slip]:
    drv = scene.driver
    if drv.kind != "R":
        return []
    pos = drv.positions
    listed = "positions" in scene.raw.get("driver", {})
    if listed:
        lo, hi = float(pos.min()), float(pos.max())
    else:                       # a linear sweep: its ends are its extremes
        lo, hi = sorted((float(pos[0]), float(pos[-1])))
    ends = [lo, hi] if hi > lo else [lo]
    field = "driver.positions" if listed else "driver.start..stop"
    if hi - lo > 4.0 * 360.0:
        return [Slip("positions", field, typed(ends, "angle", u),
                     f"the sweep spans {(hi - lo) / 360:.3g} turns",
                     f"it is [{lo:g}, {hi:g}] deg: write angle = \"deg\" in [units]")]
    # within one turn of degrees, and most of a turn as radians (or half a turn with
    # fractional values): a 5 deg sweep in whole degrees is a real one
    if max(abs(lo), abs(hi)) <= 2.0 * math.pi * 1.01 and (
            hi - lo >= 0.9 * 2.0 * math.pi or (hi - lo >= math.pi and not all(
                abs(v - round(v)) <= 1e-9 for v in (pos if listed else ends)))):
        return [Slip("positions", field, typed(ends, "angle", u),
                     f"a sweep of {hi - lo:.4g} deg, all within 2 pi degrees",
                     f"radians typed for degrees: [{degrees(lo):.4g}, "
                     f"{degrees(hi):.4g}] deg")]
    return []


def _speed_slips(scene: Scene, u: Units) -> list[Slip]:
    out = []
    size = scene.size
    drv = scene.driver
    if drv.kind == "R" and tip_speed_slip(drv.speed, size):
        out.append(_rpm_slip("driver.speed", drv.speed, size, u))
    mo = scene.motion
    if mo is None:
        return out
    omega0 = mo.get("omega0")
    motor = mo.get("motor") if isinstance(mo.get("motor"), dict) else {}
    w0 = motor.get("no_load_speed")
    if _num(omega0) and tip_speed_slip(omega0, size):
        out.append(_rpm_slip("motion.omega0", omega0, size, u))
    elif _num(omega0) and _num(w0) and w0 > 0 and abs(omega0) > 3.0 * w0:
        out.append(Slip("speed", "motion.omega0", typed(omega0, "speed", u),
                        f"{abs(omega0) / w0:.3g} times the motor's no-load speed "
                        f"{typed(w0, 'speed', u)}",
                        f"{rpm_to_rad_s(omega0):.4g} rad/s (rpm typed for rad/s)"))
    if _num(w0) and tip_speed_slip(w0, size):
        out.append(_rpm_slip("motion.motor.no_load_speed", w0, size, u))
    return out


def _rpm_slip(field: str, omega: float, size: float, u: Units) -> Slip:
    return Slip("speed", field, typed(omega, "speed", u),
                f"moves the mechanism's outline ({size:.3g} m) at {abs(omega) * size:.3g} m/s",
                f"{rpm_to_rad_s(omega):.4g} rad/s (rpm typed for rad/s)")


def _gravity_slips(scene: Scene, u: Units) -> list[Slip]:
    g = math.hypot(*scene.gravity)
    if g == 0.0 or 1.0 <= g <= 30.0:
        return []
    return [Slip("gravity", "gravity", typed(list(scene.gravity), "acceleration", u),
                 f"|g| = {g:.4g} m/s^2", f"9.81 m/s^2 is "
                 f"{typed(9.81, 'acceleration', u)} (acceleration is length/s^2)")]


def _mass_slips(scene: Scene, u: Units) -> list[Slip]:
    out = []
    for name, b in scene.bodies.items():
        if b.mass <= 0.0:
            continue
        # the body's size: twice its radius of gyration (zero for a point mass), or its
        # points' box's diagonal
        extent = 2.0 * math.sqrt(b.inertia / b.mass)
        if b.mass <= DENSEST * extent**3:
            continue                        # light enough for its radius of gyration
        extent = max(_box(b), extent)
        reach, heaviest = _joined(scene, name)
        why = None
        if extent < LUMPED * reach:
            # a point mass (the course's mass concentration, a piston as one point): it
            # has no size of its own, so it is judged against the links it joins
            extent = reach
            if heaviest > 0.0 and b.mass > HEAVIER * heaviest:
                why = (f"a point mass {b.mass / heaviest:.3g} times the heaviest link it "
                       f"joins ({heaviest:.4g} kg)")
        density = b.mass / extent**3
        if density > DENSEST:
            why = f"{density:.3g} kg/m^3 over the cube of its size ({extent:.3g} m)"
        if why is not None:
            out.append(Slip("mass", f"body {name!r}.mass", typed(b.mass, "mass", u), why,
                            f"{b.mass / 1000:g} kg (kilograms typed under mass = \"t\", or "
                            "grams as kilograms)"))
    return out


def _box(b: Body) -> float:
    """The diagonal of the box of a body's points and centre of mass (m)."""
    pts = list(b.points.values()) + ([b.cog] if b.cog is not None else [])
    xs, ys = [p[0] for p in pts] or [0.0], [p[1] for p in pts] or [0.0]
    return math.hypot(max(xs) - min(xs), max(ys) - min(ys))


def _joined(scene: Scene, name: str) -> tuple[float, float]:
    """The size (m) and the heaviest mass (kg) of the moving links a body shares a joint
    with; the size is the largest own size (radius of gyration's diameter or points' box)
    of them, or the mechanism's size when the body joins only the ground or point masses."""
    sizes, masses = [0.0], [0.0]
    for j in scene.joints.values():
        if name in j.bodies:
            other = j.other(name)
            if other != GROUND and other != name:
                o = scene.bodies[other]
                gyration = 2.0 * math.sqrt(o.inertia / o.mass) if o.mass > 0.0 else 0.0
                sizes.append(max(gyration, _box(o)))
                masses.append(o.mass)
    reach = max(sizes)
    return (reach if reach > 0.0 else scene.size), max(masses)


def _line_angle_slips(scene: Scene, u: Units) -> list[Slip]:
    lines = {n: j.beta for n, j in scene.joints.items() if j.kind == "T"}
    why = angle_list_slip(list(lines.values()))
    if why is None:
        return []
    field = "line_angle of " + ", ".join(f"joint {n!r}" for n in lines)
    return [Slip("angles", field, typed(list(lines.values()), "angle", u, file=False), why,
                 "write them in the unit [units] names for angles")]


def _motor_table_slips(motion: dict, u: Units) -> list[Slip]:
    table = motion.get("motor_table")
    if not isinstance(table, list):
        return []
    angles = [r[0] for r in table if isinstance(r, list) and r and _num(r[0])]
    why = angle_list_slip([a * DEG for a in angles])
    if why is None:
        return []
    return [Slip("angles", "motion.motor_table", typed(angles, "angle", u), why,
                 "write them in degrees, or angle = \"rad\" in [units]")]


def _friction_slips(scene: Scene, u: Units) -> list[Slip]:
    """A pin radius or a bearing length over ``PIN`` mechanism sizes: no pin (an eccentric
    sheave's included) is larger than the mechanism it joins."""
    out = []
    for name, j in scene.joints.items():
        fr = j.friction
        for key, value in (("radius", fr.radius), ("length", fr.length)) if fr else ():
            if value is not None and value > PIN * scene.size:
                out.append(Slip("lengths", f"joint {name!r}.friction.{key}",
                                typed(value, "length", u, file=False),
                                f"{value / scene.size:.3g} times the mechanism's size "
                                f"({scene.size:.3g} m)",
                                f"{typed(value / 1000, 'length', u, file=False)} "
                                "(millimetres among metres)"))
    return out


def _num(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def _far_points(scene: Scene, u: Units) -> list[Slip]:
    joint_pts: dict[str, list[tuple[float, float]]] = {b: [] for b in scene.bodies}
    for j in scene.joints.values():
        if j.kind != "R":
            continue
        for b, p in zip(j.bodies, j.points, strict=True):
            if b in joint_pts:
                joint_pts[b].append(scene.bodies[b].local(p))     # "cog" too
    pts = [p for b in joint_pts.values() for p in b] + list(scene.ground.values())
    if len(pts) < 2:
        return []
    mx = sum([p[0] for p in pts]) / len(pts)
    my = sum([p[1] for p in pts]) / len(pts)
    size = max([math.hypot(x - mx, y - my) for x, y in pts])
    if size <= 0.0:
        return []       # every joint at one point (a lone crank): no size to compare with
    # a point within 99 sizes of the joints' centre lies within 100 of each of its
    # body's joints (each joint is within one size of the centre): one pass tells most
    hypot = math.hypot
    if max([hypot(x - mx, y - my) for b in scene.bodies.values() for x, y in b.points.values()]
           + [hypot(b.cog[0] - mx, b.cog[1] - my) for b in scene.bodies.values()
              if b.cog is not None]) <= 99.0 * size:
        return []
    limit = (100.0 * size) ** 2
    out = []
    for name, body in scene.bodies.items():
        ref = joint_pts[name]
        if not ref:
            continue
        named = list(body.points.items()) + ([("cog", body.cog)] if body.cog else [])
        for pname, (x, y) in named:
            if all((x - a) ** 2 + (y - b) ** 2 > limit for a, b in ref):
                far = min([math.hypot(x - a, y - b) for a, b in ref])
                out.append(Slip("lengths", f"body {name!r}.points.{pname}",
                                typed([x, y], "length", u),
                                f"{far:.3g} m from the body's joints, over 100 times the "
                                f"mechanism's size ({size:.3g} m)",
                                f"{typed([x / 1000, y / 1000], 'length', u)} (millimetres "
                                "among metres)"))
    return out
