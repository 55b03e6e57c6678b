"""Kinetostatics of planar mechanisms: a driver plus dyads, over the whole cycle.

The public API::

    import kinetostatics as ks
    scene = ks.load_scene("four_bar.toml")     # or TOML text, or a dict
    sol = ks.solve(scene)                      # kinematics, reactions, Me
    sol.driver, sol.reactions, sol.kinematics, sol.bodies, sol.summary()

Bundled examples: ``ks.example("four_bar")`` (also ``slider_crank``, ``slotted_lever``,
``scotch_yoke``, ``sliding_driver``, ``shaper``).

More of the course, one module per topic: :mod:`~kinetostatics.concentration` (mass
concentration, s. 2.2), :mod:`~kinetostatics.gears` (s. 2.3.3),
:mod:`~kinetostatics.friction` (s. 2.4), :mod:`~kinetostatics.reduction` (s. 2.5),
:mod:`~kinetostatics.motion` and :func:`simulate_motion` (motion under forces, ch. 4),
:mod:`~kinetostatics.efficiency` (s. 4.3), :mod:`~kinetostatics.cams` (ch. 1),
:mod:`~kinetostatics.exercises` (exercise variants and grading),
:mod:`~kinetostatics.plot` (pictures). The pymunk cross-check is
:mod:`kinetostatics.crosscheck` (``crosscheck``, ``study``; it imports pymunk, so
``import kinetostatics`` does not load it).
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from .errors import AssemblyError, SceneError, StructureError, WorkbenchError
from .kinematics import Kinematics, solve_kinematics
from .motion_scene import simulate_motion
from .results import Solution
from .scene import Scene, load_scene
from .solver import solve
from .structure import Dyad, Structure, analyse

__all__ = [
    "AssemblyError", "Dyad", "Kinematics", "Scene", "SceneError", "Solution", "Structure",
    "StructureError", "WorkbenchError", "analyse", "cam_examples", "example", "examples",
    "load_scene", "scene_path",
    "simulate_motion", "solve", "solve_kinematics",
]


def examples() -> list[str]:
    """Names of the bundled mechanism scenes (``four_bar``, ``four_bar_motion``, ...)."""
    return sorted(p.name[:-5] for p in resources.files(__package__).joinpath("scenes").iterdir()
                  if p.name.endswith(".toml"))


def cam_examples() -> list[str]:
    """Names of the bundled ``[cam]`` scenes (docs/cam-scenes.md)."""
    folder = resources.files(__package__).joinpath("scenes", "cams")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def example(name: str) -> Path:
    """Path of a bundled scene, e.g. ``example("four_bar")`` or ``example("translating_roller")``
    (a cam scene)."""
    root = resources.files(__package__).joinpath("scenes")
    for folder in (root, root.joinpath("cams")):
        path = Path(str(folder.joinpath(f"{name}.toml")))
        if path.is_file():
            return path
    raise SceneError(f"no bundled example {name!r}; known: "
                     f"{', '.join(examples() + cam_examples())}")


def scene_path(name: str | Path) -> Path:
    """A scene file's path: ``name`` itself when it exists or looks like a file, else the
    bundled example of that name (so the CLI takes ``four_bar`` as well as a path)."""
    path = Path(name)
    if path.exists() or path.suffix == ".toml" or path.parent != Path("."):
        return path
    try:
        return example(str(name))
    except SceneError:
        raise SceneError(f"{name}: no such scene file, and not a bundled example "
                         f"({', '.join(examples() + cam_examples())})") from None
