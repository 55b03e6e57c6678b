"""A design's Scene without reading its whole dict again: :func:`scene_maker`.

``load_scene`` reads and checks every number of a scene (about 65 us a four-bar, a
tenth of a generation's time at 1000 designs). A design changes a few numbers of the
scene as typed; where each is a number ``load_scene`` copies as it is into the Scene (a
ground point's or a body point's coordinate, a centre of mass, a mass, an inertia, in a
scene without ``[units]``: no conversion), the design's Scene is the bundled Scene with
those numbers replaced: the same Scene ``load_scene`` gives for the design's dict (a
test compares them field by field), built for a few dataclass copies. Any other path,
a ``[units]`` table or a mass model: ``load_scene`` itself.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

from ..model.scene import Scene, load_scene
from .paths import Path


def scene_maker(scene: Scene, raw: dict, paths: Sequence[Path]
                ) -> Callable[[dict, Sequence[float]], Scene]:
    """A function (design's dict, the values of ``paths``) -> the design's Scene."""
    where = direct_places(scene, raw, paths)
    if where is None:
        return lambda design, values: load_scene(design)

    def make(design: dict, values: Sequence[float]) -> Scene:
        ground = dict(scene.ground)
        bodies: dict = {}
        for (kind, name, key, i), v in zip(where, values, strict=True):
            if kind == "ground":
                ground[name] = _set(ground[name], i, v)
                continue
            b = bodies.get(name) or {"points": dict(scene.bodies[name].points)}
            bodies[name] = b
            if kind == "points":
                b["points"][key] = _set(b["points"][key], i, v)
            elif kind == "cog":
                b["cog"] = _set(b.get("cog", scene.bodies[name].cog), i, v)
            else:
                b[kind] = float(v)
        return replace(scene, ground=ground, raw=design,
                       bodies={**scene.bodies, **{n: replace(scene.bodies[n], **b)
                                                  for n, b in bodies.items()}})
    return make


def direct_places(scene: Scene, raw: dict, paths: Sequence[Path]) -> list | None:
    """Where each of ``paths`` sits in the Scene, (kind, ground point or body name, point
    key, coordinate), when every one is a number ``load_scene`` copies as it is (and the
    scene has no ``[units]``); else None."""
    if "units" in raw or not all(_direct(scene, raw, p) for p in paths):
        return None
    return [_place(raw, p) for p in paths]


def _set(pair: tuple[float, float], i: int, v: float) -> tuple[float, float]:
    return (float(v), pair[1]) if i == 0 else (pair[0], float(v))


def _place(raw: dict, path: Path) -> tuple[str, str, str | None, int | None]:
    """(kind, ground point or body name, point key, coordinate) of a direct path."""
    s = path.steps
    if s[0] == "ground":
        return "ground", s[1], None, s[2]
    name = raw["bodies"][s[1]]["name"]
    if s[2] == "points":
        return "points", name, s[3], s[4]
    if s[2] == "cog":
        return "cog", name, None, s[3]
    return s[2], name, None, None


def _direct(scene: Scene, raw: dict, path: Path) -> bool:
    """Whether ``load_scene`` copies the number at ``path`` into the Scene as it is."""
    s = path.steps
    if s[0] == "ground":
        return len(s) == 3 and s[2] in (0, 1)
    if s[0] != "bodies" or len(s) < 3 or not isinstance(s[1], int):
        return False
    body = scene.bodies.get(raw["bodies"][s[1]].get("name"))
    if body is None or body.mass_model is not None:
        return False
    if s[2] == "points":
        return len(s) == 5 and s[4] in (0, 1)
    if s[2] == "cog":
        return len(s) == 4 and s[3] in (0, 1) and body.cog is not None
    return len(s) == 3 and s[2] in ("mass", "inertia")
