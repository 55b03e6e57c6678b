"""Balancing scenes: the TOML input of ``scene-format.md`` section 2, checked into dataclasses.

:func:`load_scene` accepts a path, a string naming a ``.toml`` file, a string of TOML
text or a dict. Sections: ``[rotor]`` (with ``[[rotor.unbalance]]`` and one or two
``[[rotor.planes]]``), ``[static_test]``, ``[[resonance_test]]``; ``title`` and
``format = 1`` may stand at the top; ``[units]`` names the units of every section
(:mod:`balance.model.scene_units` rewrites the scene once, here); the field-balancing sections
``[[influence]]``, ``[iso]``, ``[[split]]`` and ``[[combine]]`` are read by
:mod:`balance.model.field_scene`. A mechanism scene's keys (section 1) are let
through unchecked (``kinetostatics`` checks them), so that its ``[balancing]``
section can be dispatched; every other unknown key is refused with the nearest
known key suggested.

Project additions to the contract (optional, absent from the contract's examples):
``dA`` in a ``[[resonance_test]]``, the uncertainty of every amplitude, which adds an
``uncertainty`` entry to that result.

In a ``[[resonance_test]]``, ``noise = {relative, absolute}`` (the 1-sigma noise of each
amplitude reading, default relative 0.01, absolute 0) and ``confidence`` (of the
estimate's intervals and consistency test, default 0.95) set the best estimate's model.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from kinetostatics.model.errors import SceneError
from kinetostatics.model.examples import BundledScenes
from kinetostatics.model.fields import BALANCING, read_number, section
from kinetostatics.model.slips import emit, read_checks
from kinetostatics.model.tomlio import (
    as_int,
    as_list,
    as_str,
    check_keys,
    read_source,
)

from ..errors import BalanceWarning
from ..rotor.design import CorrectionPlane, Unbalance
from .field_scene import FIELD_SECTIONS, FieldScene, parse_field
from .scene_units import to_contract_units
from .slips import scene_slips
from .units import Units

# the example scenes bundled with the package (balance/scenes): a bare name is one of them
SCENES = BundledScenes("balance", ("scenes",))

__all__ = [
    "BALANCE_SECTIONS",
    "BalanceScene",
    "ResonanceSpec",
    "RotorSpec",
    "StaticTestSpec",
    "load_scene",
]

MECHANISM_KEYS = ("gravity", "ground", "driver", "bodies", "joints", "loads", "near", "motion")
BALANCE_SECTIONS = ("rotor", "static_test", "resonance_test", "balancing")
TOP_KEYS = ("title", "format", *BALANCE_SECTIONS[:3], *MECHANISM_KEYS, "balancing", "units",
            *FIELD_SECTIONS)
ROTOR_KEYS = ("speed_rpm", "unbalance", "planes")
UNBALANCE_KEYS = ("mass", "radius", "angle", "z")
PLANE_KEYS = ("z", "radius")
STATIC_KEYS = ("disk_mass", "comparison_mass", "comparison_radius", "alpha",
               "correction_radius")
RESONANCE_KEYS = ("plane", "trial_mass", "trial_radius", "correction_radius", "A1", "A2", "A3",
                  "runs", "dA", "noise", "confidence")
RUN_KEYS = ("angle", "A")
NOISE_KEYS = ("relative", "absolute")


@dataclass(frozen=True)
class RotorSpec:
    """``[rotor]``: eccentric masses, one or two correction planes, optional speed (rpm)."""

    unbalances: tuple[Unbalance, ...]
    planes: tuple[CorrectionPlane, ...]
    speed_rpm: float | None = None


@dataclass(frozen=True)
class StaticTestSpec:
    """``[static_test]``: the static balancing device of fig. 3.9 (kg, m, deg)."""

    disk_mass: float
    comparison_mass: float
    comparison_radius: float
    alpha: float
    correction_radius: float


@dataclass(frozen=True)
class ResonanceSpec:
    """One ``[[resonance_test]]``: A2 and A3 (three-run method) or ``runs`` (any marks)."""

    plane: int
    trial_mass: float
    trial_radius: float
    correction_radius: float
    A1: float
    A2: float | None = None
    A3: float | None = None
    runs: tuple[tuple[float, float], ...] | None = None
    dA: float | None = None
    noise_relative: float = 0.01
    noise_absolute: float = 0.0
    confidence: float = 0.95


@dataclass(frozen=True)
class BalanceScene:
    """A checked balancing scene; ``raw`` keeps the mapping as read, rewritten into its
    solvers' units (:mod:`balance.model.scene_units`); ``units`` is the file's ``[units]``;
    ``quiet`` the slip rules its ``[checks]`` silences and ``warnings`` the suspected unit
    slips found when it was read (:mod:`balance.model.slips`); ``source`` the mapping as
    read, ``[units]`` and ``[checks]`` included (a mechanism's ``[balancing]`` is read from
    it by the mechanism's own reader, which quotes and judges it as typed)."""

    title: str = ""
    rotor: RotorSpec | None = None
    static_test: StaticTestSpec | None = None
    resonance_tests: tuple[ResonanceSpec, ...] = ()
    balancing: dict | None = None
    raw: dict = field(default_factory=dict, repr=False)
    field_scene: FieldScene = field(default_factory=FieldScene)
    units: Units = field(default_factory=Units)
    quiet: frozenset[str] = field(default=frozenset(), compare=False)
    warnings: tuple[str, ...] = field(default=(), compare=False)
    source: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def sections(self) -> tuple[str, ...]:
        """The balancing sections present, in contract order."""
        present = {"rotor": self.rotor is not None, "static_test": self.static_test is not None,
                   "resonance_test": bool(self.resonance_tests),
                   "balancing": self.balancing is not None}
        return (tuple(k for k in BALANCE_SECTIONS if present[k])
                + self.field_scene.sections)


def load_scene(source: Any) -> BalanceScene:
    """Read and check a balancing scene (scene-format.md section 2).

    Parameters
    ----------
    source : pathlib.Path, str, dict or BalanceScene
        A path, a string naming a ``.toml`` file, TOML text, or a parsed mapping.

    Returns
    -------
    BalanceScene

    Raises
    ------
    kinetostatics.model.errors.SceneError
        One line naming the broken rule, the field and the fix: an unknown key (with
        the nearest known key), a missing field, a number out of range.
    """
    if isinstance(source, BalanceScene):
        return source
    given = read_source(source, "balancing scene", bundled=SCENES)
    raw, quiet = read_checks(given)
    raw, units = to_contract_units(raw)
    top = check_keys(raw, TOP_KEYS, "scene")
    title = as_str(top["title"], "title") if "title" in top else ""
    if "format" in top:
        as_int(top["format"], "format", lo=1, hi=1)
    rotor = _rotor(top["rotor"], units) if "rotor" in top else None
    static = _static(top["static_test"], units) if "static_test" in top else None
    tests: tuple[ResonanceSpec, ...] = ()
    if "resonance_test" in top:
        items = top["resonance_test"]
        if isinstance(items, dict):
            raise SceneError("resonance_test must be an array of tables: write "
                             "[[resonance_test]], not [resonance_test]")
        items = as_list(items, "resonance_test")
        if not items:
            raise SceneError("resonance_test is empty: give at least one [[resonance_test]]")
        tests = tuple(_resonance(item, i, units) for i, item in enumerate(items))
    balancing = top.get("balancing")
    if balancing is not None and not isinstance(balancing, dict):
        raise SceneError("[balancing] must be a table")
    scene = BalanceScene(title=title, rotor=rotor, static_test=static, resonance_tests=tests,
                         balancing=balancing, raw=raw, field_scene=parse_field(top, units),
                         units=units, quiet=quiet,
                         source=given if isinstance(given, dict) else {})
    texts = emit(scene_slips(scene), quiet, BalanceWarning)
    if texts:
        object.__setattr__(scene, "warnings", texts)     # (a frozen dataclass, made here)
    return scene


ROTOR = section(BALANCING, "rotor")
UNBALANCE = section(BALANCING, "rotor", "unbalance", "[]")
PLANE = section(BALANCING, "rotor", "planes", "[]")
STATIC = section(BALANCING, "static_test")
RESONANCE = section(BALANCING, "resonance_test", "[]")
RUN = section(BALANCING, "resonance_test", "[]", "runs", "[]")
NOISE = section(BALANCING, "resonance_test", "[]", "noise")
"""The declared fields (:data:`kinetostatics.model.fields.BALANCING`) each table's
numbers are read through: their bounds, defaults and the units their messages quote."""


def _rotor(table: Any, units: Units) -> RotorSpec:
    t = check_keys(table, ROTOR_KEYS, "[rotor]", required=("unbalance", "planes"))
    speed = read_number(t, ROTOR["speed_rpm"], "rotor", units) if "speed_rpm" in t else None
    if isinstance(t["unbalance"], dict):
        raise SceneError("rotor.unbalance must be an array of tables: write "
                         "[[rotor.unbalance]], not [rotor.unbalance]")
    items = as_list(t["unbalance"], "rotor.unbalance")
    if not items:
        raise SceneError("rotor.unbalance is empty: list the eccentric masses as "
                         "[[rotor.unbalance]] tables")
    unbalances = []
    for i, item in enumerate(items):
        w = f"rotor.unbalance[{i}]"
        u = check_keys(item, UNBALANCE_KEYS, w, required=("mass", "radius", "angle"))
        unbalances.append(Unbalance(**{k: read_number(u, UNBALANCE[k], w, units)
                                       for k in UNBALANCE_KEYS}))
    if isinstance(t["planes"], dict):
        raise SceneError("rotor.planes must be an array of tables: write [[rotor.planes]], "
                         "not [rotor.planes]")
    items = as_list(t["planes"], "rotor.planes")
    if len(items) not in (1, 2):
        raise SceneError(f"rotor.planes: {len(items)} correction planes given; give one "
                         "(static balancing) or two (dynamic balancing)")
    planes = []
    for i, item in enumerate(items):
        w = f"rotor.planes[{i}]"
        p = check_keys(item, PLANE_KEYS, w, required=("radius",))
        planes.append(CorrectionPlane(z=read_number(p, PLANE["z"], w, units),
                                      radius=read_number(p, PLANE["radius"], w, units)))
    return RotorSpec(unbalances=tuple(unbalances), planes=tuple(planes), speed_rpm=speed)


def _static(table: Any, units: Units) -> StaticTestSpec:
    t = check_keys(table, STATIC_KEYS, "[static_test]", required=STATIC_KEYS)
    spec = StaticTestSpec(**{k: read_number(t, STATIC[k], "static_test", units)
                             for k in STATIC_KEYS})
    if not 0.0 < spec.alpha <= 90.0:      # in degrees here, quoted as typed
        raise SceneError(f"static_test.alpha must lie in (0, "
                         f"{units.quote(90.0, 'angle', file=True)}], got "
                         f"{units.quote(spec.alpha, 'angle', file=True)}; it is the dial angle "
                         "at which the disk settles with the comparison mass")
    return spec


def _resonance(item: Any, i: int, units: Units) -> ResonanceSpec:
    w = f"resonance_test[{i}]"
    t = check_keys(item, RESONANCE_KEYS, w,
                   required=("trial_mass", "trial_radius", "correction_radius", "A1"))
    plane = as_int(t.get("plane", 1), f"{w}.plane", lo=1, hi=2)
    common = dict(
        plane=plane,
        **{k: read_number(t, RESONANCE[k], w, units)
           for k in ("trial_mass", "trial_radius", "correction_radius", "A1")},
        dA=read_number(t, RESONANCE["dA"], w, units) if "dA" in t else None,
        **_noise(t, w, units),
    )
    has_pair = "A2" in t or "A3" in t
    if "runs" in t:
        if has_pair:
            raise SceneError(f"{w}: give either A2 and A3 (three-run method) or runs, not both")
        runs = []
        for k, run in enumerate(as_list(t["runs"], f"{w}.runs")):
            rw = f"{w}.runs[{k}]"
            r = check_keys(run, RUN_KEYS, rw, required=RUN_KEYS)
            runs.append((read_number(r, RUN["angle"], rw, units),
                         read_number(r, RUN["A"], rw, units)))
        return ResonanceSpec(runs=tuple(runs), **common)
    for key in ("A2", "A3"):
        if key not in t:
            raise SceneError(f"{w}: missing required key {key!r} (or give runs = "
                             "[{angle = .., A = ..}, ...] instead of A2 and A3)")
    return ResonanceSpec(A2=read_number(t, RESONANCE["A2"], w, units),
                         A3=read_number(t, RESONANCE["A3"], w, units), **common)


def _noise(t: dict, w: str, units: Units) -> dict[str, float]:
    """``noise = {relative, absolute}`` and ``confidence`` of a ``[[resonance_test]]``."""
    out: dict[str, float] = {}
    if "noise" in t:
        n = check_keys(t["noise"], NOISE_KEYS, f"{w}.noise")
        for key in NOISE_KEYS:
            if key in n:
                out[f"noise_{key}"] = read_number(n, NOISE[key], f"{w}.noise", units)
        if out.get("noise_relative", 0.01) == 0.0 and out.get("noise_absolute", 0.0) == 0.0:
            raise SceneError(f"{w}.noise: relative and absolute are both 0; a reading "
                             "without noise has no likelihood: give the instrument's noise")
    if "confidence" in t:
        c = read_number(t, RESONANCE["confidence"], w, units)
        if not c < 1.0:
            raise SceneError(f"{w}.confidence must lie in (0, 1), got {c:g} (e.g. 0.95)")
        out["confidence"] = c
    return out
