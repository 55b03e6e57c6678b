"""The bundled example scenes, and the one place where a scene name becomes a path
(both command lines and the Python API use :func:`scene_path`)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from .errors import SceneError

_PACKAGE = "kinetostatics"


def examples() -> list[str]:
    """Names of the bundled mechanism scenes (``four_bar``, ``four_bar_motion``, ...)."""
    return sorted(p.name[:-5] for p in resources.files(_PACKAGE).joinpath("scenes").iterdir()
                  if p.name.endswith(".toml"))


def cam_examples() -> list[str]:
    """Names of the bundled ``[cam]`` scenes (docs/cam-scenes.md)."""
    folder = resources.files(_PACKAGE).joinpath("scenes", "cams")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def example(name: str) -> Path:
    """Path of a bundled scene, e.g. ``example("four_bar")`` or ``example("translating_roller")``
    (a cam scene)."""
    root = resources.files(_PACKAGE).joinpath("scenes")
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
