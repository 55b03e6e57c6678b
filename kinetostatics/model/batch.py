"""Many scene dicts of one form read at once: :func:`load_scenes`.

Variants of one mechanism (an exercise's, a design study's) are dicts of one form: the
same keys in the same order, the same texts and whole numbers, lists of the same
lengths; only their decimal numbers differ. The first of them is read by
:func:`~kinetostatics.model.scene.load_scene`, which checks every rule of the contract.
For the others, what the rules check on the form (names, references, kinds, keys) holds
as it held for the first, so only their numbers are checked: every decimal number of
all of them at once (finite, at most 1e12 in magnitude), then, per scene, the few rules
that depend on a value (a mass, an inertia, a friction or a ``resist`` force not
negative; a mass > 0 needs a cog; a "resisting" force has no moment). The scene is then
built from the numbers as :func:`load_scene` builds it, and its unit slips are checked
as :func:`load_scene` checks them.

A dict of another form, one whose numbers break a rule, or a family that this reader
does not build (``[units]``, a mass model) is read by :func:`load_scene` itself: its
scene, or its error, is exactly that one's.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .errors import SceneError
from .scene import MAX_COUNT, Body, Driver, Friction, Joint, Load, Scene, _sweep, load_scene
from .scene_units import check_unit_slips
from .tomlio import MAX_MAGNITUDE, as_int
from .units import Units

__all__ = ["load_scenes"]


def load_scenes(sources: list[Any]) -> list[Scene | Exception]:
    """Each source's :class:`~kinetostatics.model.scene.Scene`, or the exception
    :func:`~kinetostatics.model.scene.load_scene` raises for it, in order.

    Parameters
    ----------
    sources : list
        What :func:`load_scene` takes; dicts of one form are read together.

    Returns
    -------
    list
        Per source, its Scene (equal to ``load_scene(source)``, field by field) or the
        exception ``load_scene(source)`` raises.
    """
    out: list[Any] = [None] * len(sources)
    families: list[_Family] = []
    pending: list[tuple[int, _Family, list]] = []
    for i, src in enumerate(sources):
        if type(src) is dict:
            for fam in families:
                numbers = fam.numbers(src)
                if numbers is not None:
                    pending.append((i, fam, numbers))
                    break
            else:
                out[i] = _load(src)
                if isinstance(out[i], Scene) and _buildable(src):
                    families.append(_Family(src, out[i]))
        else:
            out[i] = _load(src)
    if pending:
        counts = [len(p[2]) for p in pending]
        flat = np.array([x for p in pending for x in p[2]], dtype=float)
        bad = ~(np.abs(flat) <= MAX_MAGNITUDE)          # NaN, infinite or too large
        ends = np.cumsum(counts)
        sick = np.zeros(len(pending), dtype=bool)
        if bad.any():
            sick[np.searchsorted(ends, np.flatnonzero(bad), side="right")] = True
        for (i, fam, _), ill in zip(pending, sick, strict=True):
            src = sources[i]
            sc = None if ill else fam.build(src)
            out[i] = sc if sc is not None else _load(src)     # load_scene's own error
    return out


def _load(src: Any) -> Scene | Exception:
    try:
        return load_scene(src)
    except Exception as exc:        # the caller raises it where load_scene would
        return exc


def _buildable(raw: dict) -> bool:
    """A family this reader builds: no ``[units]`` (numbers as written) and no mass model."""
    if "units" in raw:
        return False
    bodies = raw.get("bodies")
    return all(isinstance(b, dict) and "mass_model" not in b for b in bodies)


_PLAIN = (str, int, bool, type(None))


def _numbers(d: Any, t: Any, out: list) -> bool:
    """Whether ``d`` has the form of ``t`` (keys in order, texts, whole numbers, booleans,
    list lengths); its decimal numbers appended to ``out``. (A value that is the very
    object of ``t`` is of its form: ``t`` was read without error.)"""
    if type(d) is dict:
        if type(t) is not dict or len(d) != len(t) or list(d) != list(t):
            return False
        pairs = zip(d.values(), t.values(), strict=True)
    elif type(d) is list:
        if type(t) is not list or len(d) != len(t):
            return False
        pairs = zip(d, t, strict=True)
    else:
        return False
    for v, v2 in pairs:
        tv = type(v)
        if tv is float:
            if type(v2) is not float:
                return False
            out.append(v)
        elif tv is list and len(v) == 2 and type(v[0]) is float and type(v[1]) is float:
            if type(v2) is not list or len(v2) != 2 or type(v2[0]) is not float \
                    or type(v2[1]) is not float:        # a point [x, y], told at once
                return False
            out += v
        elif tv is dict or tv is list:
            if not _numbers(v, v2, out):
                return False
        elif v is not v2 and not (tv in _PLAIN and type(v2) is tv and v == v2):
            return False
    return True


class _Family:
    """Dicts of the form of one that :func:`load_scene` read without error."""

    def __init__(self, raw: dict, scene: Scene):
        self.raw = raw
        self.scene = scene

    def numbers(self, d: dict) -> list | None:
        """The decimal numbers of ``d`` if it has the family's form, else None."""
        out: list = []
        return out if _numbers(d, self.raw, out) else None

    def build(self, d: dict) -> Scene | None:
        """The scene of ``d`` (its numbers finite and in range) as :func:`load_scene`
        builds it; None where a rule on a value may refuse it (read by load_scene)."""
        base = self.scene
        if "format" in d and d["format"] != 1:      # (a decimal 1.0 may differ)
            return None
        g = d.get("gravity")
        gravity = (float(g[0]), float(g[1])) if g is not None else (0.0, 0.0)
        ground = {str(k): (float(v[0]), float(v[1])) for k, v in d.get("ground", {}).items()}
        bodies = {}
        for item, b0 in zip(d["bodies"], base.bodies.values(), strict=True):
            mass = float(item.get("mass", 0.0))
            inertia = float(item.get("inertia", 0.0))
            if mass < 0.0 or inertia < 0.0:
                return None
            c = item.get("cog")
            cog = (float(c[0]), float(c[1])) if c is not None else None
            if mass > 0.0 and cog is None:
                return None
            points = {str(p): (float(v[0]), float(v[1]))
                      for p, v in item.get("points", {}).items()}
            bodies[b0.name] = Body(b0.name, mass, inertia, cog, points, None)
        joints = {}
        for item, j0 in zip(d["joints"], base.joints.values(), strict=True):
            fr = item.get("friction")
            angle = float(item.get("line_angle", 0.0)) if j0.kind == "T" else 0.0
            if fr is None and angle == j0.line_angle and \
                    math.copysign(1.0, angle) == math.copysign(1.0, j0.line_angle):
                joints[j0.name] = j0            # nothing of its own: the first's
                continue
            friction = None
            if fr is not None:
                friction = Friction(float(fr["mu"]), float(fr.get("radius", 0.0)),
                                    float(fr.get("length", 0.0)))
                if min(friction.mu, friction.radius, friction.length) < 0.0:
                    return None
            joints[j0.name] = Joint(j0.name, j0.kind, j0.bodies, j0.points, angle, friction)
        driver = self._driver(d["driver"])
        if driver is None:
            return None
        loads = []
        for item, l0 in zip(d.get("loads", []), base.loads, strict=True):
            f = item.get("force")
            force = (float(f[0]), float(f[1])) if f is not None else None
            resist = float(item["resist"]) if "resist" in item else None
            if resist is not None and resist < 0.0:
                return None
            moment = float(item.get("moment", 0.0))
            if l0.when == "resisting" and moment:
                return None
            loads.append(Load(l0.body, l0.point, force, moment, resist, l0.when))
        near = {str(k): (float(v[0]), float(v[1])) for k, v in d.get("near", {}).items()}
        motion = dict(d["motion"]) if "motion" in d else None
        scene = Scene(title=str(d.get("title", "")), gravity=gravity, ground=ground, driver=driver,
                      bodies=bodies, joints=joints, loads=tuple(loads), near=near,
                      motion=motion, balancing=d.get("balancing"), raw=dict(d),
                      units=Units())
        check_unit_slips(scene, scene.units)
        return scene

    def _driver(self, t: dict) -> Driver | None:
        d0 = self.scene.driver
        if "speed_rpm" in t:
            speed = float(t["speed_rpm"]) * math.pi / 30.0
        else:
            speed = float(t["speed"])
        acc = float(t.get("acceleration", 0.0))
        if "positions" in t:
            positions = np.array([float(p) for p in t["positions"]])
        else:
            try:        # a whole number written as a decimal one is checked again
                count = as_int(t["count"], "driver.count", lo=1, hi=MAX_COUNT)
            except SceneError:
                return None
            positions = _sweep(float(t["start"]), float(t["stop"]), count)
        return Driver(d0.body, d0.joint, d0.kind, speed, acc, positions)
