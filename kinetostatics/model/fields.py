"""Every number-bearing field of every scene kind, declared once: where it is, what
quantity it is, its bounds, its default and one line of doc.

The units stage (:func:`to_contract_units`), the scene readers' bounds and defaults, the
messages that quote a value in the user's unit and the field tables of
docs/scene-format.md all read these declarations (a test checks the docs' tables against
:func:`markdown`). A field's ``path`` walks the scene's mapping: a text is a key, ``"[]"``
each table of a list, ``"*"`` each value of a table, ``"#0"``/``"#1"`` the first or
second number of a pair. A quantity is one of :class:`~kinetostatics.model.units.Units`'
(``"length"``, ``"mass"``, ``"inertia"``, ``"moment"``...) or a role whose quantity
depends on the scene (``"position"``: an angle for a rotating driver, a length for a
sliding one); :data:`ROLES` resolves them.

The contract's units, which a scene is converted into where it is read: SI, and degrees
for the angles a file holds (scene-format.md, "Units").
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from .errors import SceneError
from .tomlio import MAX_MAGNITUDE, MIN_MAGNITUDE, as_float
from .units import Units, parse_units

__all__ = ["BALANCING", "CAM", "MECHANISM", "Field", "ROLES", "convert", "markdown",
           "read_number", "section", "to_contract_units"]

REQUIRED = "required"
"""The ``default`` of a field the scene must give."""


@dataclass(frozen=True)
class Field:
    """One number-bearing field of a scene kind.

    Attributes
    ----------
    path : tuple of str
        Where it is in the scene's mapping (see the module's text).
    quantity : str
        Its quantity (a :class:`Units` quantity or a role of :data:`ROLES`); ``""`` for a
        pure number.
    bound : str
        ``""``, ``"nonnegative"`` or ``"positive"``.
    default : str
        The default when absent, as the docs say it (``"required"`` when it must be given,
        ``""`` when absence has its own meaning).
    doc : str
        One line: what it is.
    key : str
        The last step of ``path`` (the key a reader looks up).
    kept : bool
        The value stays in the scene's unit where it is read (a balancing field section's
        masses, radii and readings: those methods are linear in them); the units stage
        leaves it as typed and a message quotes it as it is.
    least : float
        The least magnitude other than zero (``MIN_MAGNITUDE`` for a quantity divided by:
        its square would underflow); 0: none (a positive field has ``MIN_MAGNITUDE``).
    fallback : float or None
        ``default`` as a number, or None.
    """

    path: tuple[str, ...]
    quantity: str
    bound: str = ""
    default: str = ""
    doc: str = ""
    least: float = 0.0
    kept: bool = False
    key: str = field(init=False, repr=False, compare=False)
    fallback: float | None = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        # what a reader asks for each item, told once: the key, the default as a number
        # ("0" -> 0.0; None when there is none or it is not a number)
        object.__setattr__(self, "key", self.path[-1])
        try:
            object.__setattr__(self, "fallback", float(self.default))
        except ValueError:
            object.__setattr__(self, "fallback", None)

    @property
    def name(self) -> str:
        """The field as the docs and messages name it: ``bodies[].points.*``."""
        return ".".join(self.path).replace(".[]", "[]").replace(".#", "#")


def section(fields: tuple[Field, ...], *where: str) -> dict[str, Field]:
    """The fields of one table, by key: ``section(MECHANISM, "bodies", "[]")["mass"]``."""
    return {f.path[-1]: f for f in fields if f.path[:-1] == where}


_BOUND_WORDS = {"nonnegative": "must not be negative", "positive": "must be positive"}


def read_number(table: dict, fd: Field, where: str, units: Units,
                error: type[Exception] = SceneError) -> float:
    """The number of the declared field ``fd`` in ``table`` (its default when absent),
    within the field's bounds; a value out of them is quoted as typed, in the scene's unit
    ("got -350 g"). Every scene reader reads its declared numbers through this.

    Raises
    ------
    SceneError
        Not a number, not finite, out of range, or out of the field's bounds (``error``
        when told: a balancing scene's).
    """
    key = fd.key
    if key not in table:
        return fd.fallback
    value = table[key]
    t = type(value)
    if (t is float or t is int) and -MAX_MAGNITUDE <= value <= MAX_MAGNITUDE and (
            not fd.bound or (value > 0 and (fd.bound != "positive" or value >= MIN_MAGNITUDE))
            or (value == 0 and fd.bound == "nonnegative")) and (
            not fd.least or value == 0 or not -fd.least < value < fd.least):
        return float(value)     # the common case (compared before float(): a huge int)
    x = as_float(value, f"{where}.{key}", error=error)
    if fd.bound and (x < 0.0 or (x == 0.0 and fd.bound == "positive")):
        said = (f"{x:g} {units.unit(fd.quantity)}" if fd.kept
                else units.quote(x, fd.quantity, file=True)
                if fd.quantity and fd.quantity not in ROLES
                else f"{x:g} rpm" if fd.quantity == "rpm" else f"{x:g}")
        raise error(f"{where}.{key} {_BOUND_WORDS[fd.bound]}, got {said}")
    # a positive quantity is divided by: keep it from 0 (and a field with a least magnitude)
    return as_float(x, f"{where}.{key}", positive=fd.bound == "positive",
                    smallest=fd.least or None, error=error)


def F(path: str, quantity: str, bound: str = "", default: str = "", doc: str = "",
      least: float = 0.0, kept: bool = False) -> Field:
    """A :class:`Field` from a dotted path (``"bodies.[].mass"``)."""
    return Field(tuple(path.split(".")), quantity, bound, default, doc, least, kept)


def K(path: str, quantity: str, bound: str = "", default: str = "", doc: str = "") -> Field:
    """A field kept in the scene's unit (:attr:`Field.kept`)."""
    return F(path, quantity, bound, default, doc, kept=True)


MECHANISM: tuple[Field, ...] = (
    F("gravity", "acceleration", "", "[0, 0]", "gravity's acceleration, global components"),
    F("ground.*", "length", "", REQUIRED, "a fixed point, global coordinates"),
    F("near.*", "length", "", "", "an assembly hint: a point's approximate global position "
      "at the first row"),
    F("driver.speed", "drive speed", "", REQUIRED, "the driver's speed (rad/s, or m/s "
      "for a sliding driver); or speed_rpm"),
    F("driver.speed_rpm", "rpm", "", "", "a rotating driver's speed in rpm, whatever "
      "[units] says"),
    F("driver.acceleration", "drive acceleration", "", "0", "the driver's acceleration "
      "(rad/s^2 always, or length/s^2 for a sliding driver)"),
    F("driver.start", "position", "", REQUIRED, "the first position swept (an angle, or a "
      "length along a sliding driver's line)"),
    F("driver.stop", "position", "", REQUIRED, "the last position swept"),
    F("driver.positions", "position", "", "", "instead of start/stop/count: these "
      "positions, in any order"),
    F("bodies.[].mass", "mass", "nonnegative", "0", "the body's mass"),
    F("bodies.[].inertia", "inertia", "nonnegative", "0", "its moment of inertia about its "
      "centre of mass"),
    F("bodies.[].cog", "length", "", "", "its centre of mass, local coordinates (required "
      "if mass > 0)"),
    F("bodies.[].points.*", "length", "", "", "a named point, local coordinates"),
    F("joints.[].line_angle", "angle", "", "0", "a prismatic joint's line direction in its "
      "guide's frame"),
    F("joints.[].friction.mu", "", "nonnegative", REQUIRED, "the friction coefficient"),
    F("joints.[].friction.radius", "length", "nonnegative", REQUIRED, "a revolute joint's "
      "pin radius (the friction circle's is mu x radius)"),
    F("joints.[].friction.length", "length", "nonnegative", "0", "a slider's bearing "
      "length"),
    F("loads.[].force", "force", "", "", "a constant force at the load's point, global "
      "components"),
    F("loads.[].resist", "force", "nonnegative", "", "a force of this size opposite to the "
      "point's velocity"),
    F("loads.[].moment", "moment", "", "0", "a constant moment, ccw positive"),
    F("motion.flywheel", "inertia", "nonnegative", "0", "the flywheel's moment of inertia"),
    F("motion.omega0", "speed", "positive", REQUIRED, "the crank's speed at the start"),
    F("motion.motor.stall_moment", "moment", "", REQUIRED, "the motor's moment at rest"),
    F("motion.motor.no_load_speed", "speed", "positive", REQUIRED, "the motor's speed "
      "without load"),
    F("motion.target_delta", "", "positive", "", "the speed fluctuation delta the flywheel "
      "is sized for (a 'motor' only)"),
    F("motion.motor_table.[].#0", "angle", "", REQUIRED, "a motor table row's crank angle"),
    F("motion.motor_table.[].#1", "moment", "", REQUIRED, "a motor table row's moment"),
    F("balancing.counterweights.[].radius", "length", "positive", "", "a counterweight's "
      "radius"),
    F("balancing.pair_radius", "length", "positive", "", "the radius of a pair of "
      "counter-rotating masses"),
)
"""A mechanism scene's number-bearing fields (docs/scene-format.md, section 1)."""

CAM: tuple[Field, ...] = (
    F("cam.speed", "speed", "positive", REQUIRED, "the cam's speed (or speed_rpm)"),
    F("cam.speed_rpm", "rpm", "positive", "", "the cam's speed in rpm, whatever [units] "
      "says"),
    F("cam.base_radius", "length", "positive", "", "the base circle's radius (or "
      "transmission_angle)"),
    F("cam.transmission_angle", "angle", "positive", "", "the admissible transmission "
      "angle, from which the base radius follows"),
    F("cam.roller_radius", "length", "nonnegative", "0", "the roller's radius"),
    F("cam.follower.stroke", "length", "positive", REQUIRED, "a translating follower's "
      "stroke"),
    F("cam.follower.offset", "length", "", "0", "its offset (or \"optimal\", with "
      "transmission_angle)"),
    F("cam.follower.stroke_angle", "angle", "positive", REQUIRED, "an oscillating "
      "follower's swing"),
    F("cam.follower.arm", "length", "positive", REQUIRED, "its arm"),
    F("cam.follower.pivot_distance", "length", "positive", REQUIRED, "its pivot's distance "
      "from the cam's centre"),
    F("cam.segments.[].angle", "angle", "positive", REQUIRED, "a segment's cam angle"),
    F("cam.loads.force", "force", "", "0", "a translating follower's constant force"),
    F("cam.loads.moment", "moment", "", "0", "an oscillating follower's constant moment"),
    F("cam.loads.mass", "mass", "nonnegative", "0", "a translating follower's mass"),
    F("cam.loads.inertia", "inertia", "nonnegative", "0", "an oscillating follower's "
      "moment of inertia about its pivot"),
    F("cam.loads.gravity", "acceleration", "", "0", "gravity along the follower's axis"),
    F("cam.loads.spring_rate", "spring rate", "nonnegative", "0", "the return spring's "
      "rate (per length, or per rad)"),
    F("cam.loads.spring_preload", "follower load", "", "0", "the spring's load at the "
      "lowest position"),
    F("cam.loads.friction", "", "nonnegative", "0", "the guide's (translating) or the "
      "pin's (oscillating) friction coefficient"),
    F("cam.loads.guide_length", "length", "nonnegative", "0", "the guide's length b"),
    F("cam.loads.guide_gap", "length", "nonnegative", "0", "the guide's gap a at the lowest "
      "position (needed with guide friction)"),
    F("cam.loads.pin_radius", "length", "nonnegative", "0", "the pivot pin's radius"),
)
"""A cam scene's number-bearing fields (docs/cam-scenes.md)."""

_FIELD_RUNS = {"runs": "run", "trim": "trim run"}
BALANCING: tuple[Field, ...] = (
    F("rotor.speed_rpm", "rpm", "positive", "", "the rotor's speed in rpm, whatever [units] "
      "says"),
    F("rotor.unbalance.[].mass", "mass", "nonnegative", REQUIRED, "an unbalance's mass"),
    F("rotor.unbalance.[].radius", "length", "nonnegative", REQUIRED, "its radius"),
    F("rotor.unbalance.[].angle", "angle", "", REQUIRED, "its angle"),
    F("rotor.unbalance.[].z", "length", "", "0", "its place along the axis"),
    F("rotor.planes.[].z", "length", "", "0", "a correction plane's place"),
    F("rotor.planes.[].radius", "length", "positive", REQUIRED, "its correction radius"),
    F("static_test.disk_mass", "mass", "positive", REQUIRED, "the disk's mass"),
    F("static_test.comparison_mass", "mass", "positive", REQUIRED, "the comparison mass"),
    F("static_test.comparison_radius", "length", "positive", REQUIRED, "its radius"),
    F("static_test.correction_radius", "length", "positive", REQUIRED, "the correction's "
      "radius"),
    F("static_test.alpha", "angle", "", REQUIRED, "the device's angle", MIN_MAGNITUDE),
    F("resonance_test.[].trial_mass", "mass", "positive", REQUIRED, "the trial mass"),
    F("resonance_test.[].trial_radius", "length", "positive", REQUIRED, "its radius"),
    F("resonance_test.[].correction_radius", "length", "positive", REQUIRED, "the "
      "correction's radius"),
    F("resonance_test.[].A1", "", "nonnegative", REQUIRED, "the amplitude without trial "
      "mass (the readings' own unit)", MIN_MAGNITUDE),
    *(F(f"resonance_test.[].{a}", "", "positive", "", f"the amplitude with the trial mass "
        f"at {at} (instead of runs)") for a, at in (("A2", "0 deg"), ("A3", "180 deg"))),
    F("resonance_test.[].dA", "", "nonnegative", "", "the uncertainty of every amplitude"),
    F("resonance_test.[].noise.relative", "", "nonnegative", "0.01", "1-sigma noise of a "
      "reading, relative"),
    F("resonance_test.[].noise.absolute", "", "nonnegative", "0", "1-sigma noise of a "
      "reading, in the readings' unit"),
    F("resonance_test.[].confidence", "", "positive", "0.95", "the estimate's confidence, "
      "below 1"),
    F("resonance_test.[].runs.[].angle", "angle", "", REQUIRED, "a run's trial mass angle"),
    F("resonance_test.[].runs.[].A", "", "positive", REQUIRED, "the run's amplitude"),
    F("influence.[].initial.[].#1", "angle", "", REQUIRED, "a reading's phase without "
      "trial mass"),
    F("influence.[].coefficients.[].[].#1", "angle", "", "", "a stored coefficient's "
      "phase"),
    *(f for key, one in _FIELD_RUNS.items() for f in (
        F(f"influence.[].{key}.[].angle", "angle", "", "", f"a {one} mass's angle"),
        F(f"influence.[].{key}.[].readings.[].#1", "angle", "", REQUIRED,
          f"a {one} reading's phase"),
        F(f"influence.[].{key}.[].masses.[].#1", "angle", "", "", f"a {one}'s mass "
          "angle, per plane"))),
    F("influence.[].phase_noise", "angle", "nonnegative", "1 deg", "1-sigma of each phase"),
    F("influence.[].split.first", "angle", "", "0", "the first position's angle"),
    *(K(f"influence.[].{key}.[].mass", "mass", "positive", "", f"a {one}'s mass (or masses)")
      for key, one in _FIELD_RUNS.items()),
    K("influence.[].trial_radius", "length", "positive", "", "the trial masses' radius"),
    K("influence.[].correction_radius", "length", "positive", "", "the corrections' radius"),
    F("influence.[].dA", "", "nonnegative", "", "the uncertainty of every reading"),
    F("split.[].angle", "angle", "", REQUIRED, "the mass's angle"),
    F("split.[].first", "angle", "", "0", "the first position's angle"),
    K("split.[].mass", "mass", "nonnegative", REQUIRED, "the mass to split"),
    K("split.[].radius", "length", "positive", "", "its radius (with correction_radius)"),
    K("split.[].correction_radius", "length", "positive", "", "the positions' radius"),
    F("combine.[].weights.[].angle", "angle", "", REQUIRED, "a weight's angle"),
    K("combine.[].weights.[].mass", "mass", "nonnegative", REQUIRED, "a weight's mass"),
    K("combine.[].weights.[].radius", "length", "positive", "", "its radius"),
    K("combine.[].radius", "length", "positive", "", "the radius the sum is given at"),
    F("iso.grade", "", "positive", REQUIRED, "the balance quality grade G (mm/s)"),
    K("iso.rotor_mass", "mass", "positive", REQUIRED, "the rotor's mass"),
    F("iso.speed_rpm", "rpm", "positive", REQUIRED, "its service speed in rpm"),
    F("iso.static_share", "", "positive", "0.5", "a narrow rotor's static share of U_per"),
    K("iso.cog", "length", "", "", "the z of the centre of mass (with bearings)"),
    F("iso.residual.[].#1", "angle", "", "", "a residual's phase"),
)
"""A balancing scene's number-bearing fields converted where it is read (docs/balancing.md,
"Units"): the seed's methods' masses, lengths and angles; the field sections' angles
only (their masses, radii and readings stay in the scene's units, and so do their
results: the methods are linear in them)."""

ROLES: dict[str, Callable[[dict], str | None]] = {
    # a quantity by the scene's context; None: the field keeps its value
    "position": lambda raw: "length" if _driver_kind(raw) == "T" else "angle",
    "drive speed": lambda raw: "velocity" if _driver_kind(raw) == "T" else "speed",
    "drive acceleration": lambda raw: "acceleration" if _driver_kind(raw) == "T" else None,
    "rpm": lambda raw: None,
    "follower load": lambda raw: "moment" if _follower_kind(raw) == "oscillating" else "force",
    "spring rate": lambda raw: ("moment" if _follower_kind(raw) == "oscillating"
                                else "stiffness"),
}
"""The quantity of a role in a scene: a driver's position is an angle or a length, a
follower's load a moment or a force; ``speed_rpm`` is rpm whatever ``[units]`` says."""


def _driver_kind(raw: dict) -> str | None:
    drv = raw.get("driver")
    name = drv.get("joint") if isinstance(drv, dict) else None
    joints = raw.get("joints")
    for j in joints if isinstance(joints, list) else ():
        if isinstance(j, dict) and j.get("name") == name:
            return j.get("kind")
    return None


def _follower_kind(raw: dict) -> str | None:
    cam = raw.get("cam")
    fol = cam.get("follower") if isinstance(cam, dict) else None
    return fol.get("kind") if isinstance(fol, dict) else None


def _number(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def _scaled(value: Any, f: float) -> Any:
    """A number or a (nested) list of numbers times f; anything else as it is, for the
    reader to refuse with its own message."""
    if _number(value):
        return value * f
    if isinstance(value, list):
        return [_scaled(v, f) for v in value]
    return value


def _scale_at(node: Any, path: tuple[str, ...], f: float) -> None:
    """Scale, in place, what ``path`` names under ``node``."""
    step, rest = path[0], path[1:]
    if step == "[]":
        items = [x for x in node if isinstance(x, dict | list)] if isinstance(node, list) else []
        for x in items:     # a pair or a row under "#i" or "[]", a table under a key
            if rest and (rest[0][0] == "#" or rest[0] == "[]") == isinstance(x, list):
                _scale_at(x, rest, f)
        return
    if step[0] == "#":
        if isinstance(node, list) and len(node) == 2:
            i = int(step[1:])
            node[i] = _scaled(node[i], f)
        return
    if step == "*":
        if isinstance(node, dict):
            for key in node:
                node[key] = _scaled(node[key], f)
        return
    if not isinstance(node, dict) or step not in node:
        return
    if rest:
        _scale_at(node[step], rest, f)
    else:
        node[step] = _scaled(node[step], f)


def convert(raw: dict, units: Units, fields: tuple[Field, ...]) -> dict:
    """A copy of a scene's mapping (without ``[units]``) with each of ``fields`` written in
    ``units`` rewritten in the contract's units; keys not declared are left as they are.
    In the default units ``raw`` itself is returned (its numbers never touched)."""
    if units.is_default:
        return raw
    out = _copy(raw)
    for fd in fields:
        quantity = ROLES[fd.quantity](out) if fd.quantity in ROLES else fd.quantity
        if quantity and not fd.kept:
            f = units.file_factor(quantity)
            if f != 1.0:
                _scale_at(out, fd.path, f)
    return out


def to_contract_units(raw: Any, *fields: tuple[Field, ...],
                      parse: Callable[..., Units] = parse_units) -> tuple[Any, Units]:
    """The raw scene with its declared fields in the contract's units, without
    ``[units]``, and the scene's :class:`Units`: the one units stage of every scene kind.

    Parameters
    ----------
    raw : dict
        The mapping as read (it is not changed).
    *fields : tuple of Field
        The scene kind's declarations (a balancing scene gives the mechanism's too).
    parse : callable
        Reads the ``[units]`` table (balancing's knows its own quantities and error).

    Raises
    ------
    SceneError
        ``[units]`` that is not a table, or names an unknown quantity or unit.
    """
    if not isinstance(raw, dict) or "units" not in raw:
        return raw, Units()
    units = parse(raw["units"])
    rest = {k: v for k, v in raw.items() if k != "units"}
    return convert(rest, units, tuple(f for group in fields for f in group)), units


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


_QUANTITY_WORDS = {
    "position": "angle (length if sliding)", "drive speed": "speed (velocity if sliding)",
    "drive acceleration": "rad/s^2 (acceleration if sliding)", "rpm": "rpm",
    "follower load": "force (moment if oscillating)",
    "spring rate": "force/length (moment per rad if oscillating)", "": "number",
}


def markdown(fields: tuple[Field, ...]) -> str:
    """The declarations as the docs' table: field, quantity, bounds, default, doc."""
    rows = ["| field | quantity | bounds | default | meaning |", "|---|---|---|---|---|"]
    for fd in fields:
        kept = " (kept as typed)" if fd.kept else ""
        rows.append(f"| `{fd.name}` | {_QUANTITY_WORDS.get(fd.quantity, fd.quantity)}{kept} | "
                    f"{fd.bound or ''} | {fd.default} | {fd.doc} |")
    return "\n".join(rows)
