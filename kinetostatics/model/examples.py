"""The bundled example scenes, and the one place where a scene name becomes a path.

Both command lines (``python -m kinetostatics ...``, ``python -m balance ...``) and the
Python API (``ks.solve("four_bar")``, ``balance.solve("rotor_two_plane")``) resolve a
scene the same way, through a :class:`BundledScenes` of their package: a path that exists
is that file; otherwise a bare name is the bundled example of that name; anything else is
"no such file".
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from .errors import SceneError


class BundledScenes:
    """The example scenes a package ships in its data folders.

    Parameters
    ----------
    package : str
        The package that holds them, e.g. ``"kinetostatics"``.
    folders : tuple of str
        Data folders of the package, searched in order (``"scenes"``, ``"scenes/cams"``).
    """

    def __init__(self, package: str, folders: tuple[str, ...]):
        self.package, self.folders = package, folders

    def _folder(self, folder: str):
        return resources.files(self.package).joinpath(*folder.split("/"))

    def names(self, folder: str | None = None) -> list[str]:
        """Names of the bundled scenes (of one folder, or of all)."""
        out = []
        for f in ([folder] if folder else self.folders):
            out += sorted(p.name[:-5] for p in self._folder(f).iterdir()
                          if p.name.endswith(".toml"))
        return out

    def find(self, name: str) -> Path | None:
        """Path of the bundled scene ``name`` (with or without ``.toml``), or None."""
        stem = name[:-5] if name.endswith(".toml") else name
        if not stem or "/" in stem or "\\" in stem:
            return None
        for f in self.folders:
            path = Path(str(self._folder(f).joinpath(f"{stem}.toml")))
            if path.is_file():
                return path
        return None

    def path(self, name: str) -> Path:
        """Path of a bundled scene; :class:`SceneError` naming the known ones if none."""
        found = self.find(str(name))
        if found is None:
            raise SceneError(f"no bundled example {name!r}; known: {', '.join(self.names())}")
        return found

    def resolve(self, name: str | Path) -> Path:
        """A scene's path: ``name`` itself when it exists, else the bundled example of that
        name; :class:`SceneError` ("no such file") when it is neither."""
        path = Path(name)
        if path.exists():
            return path
        found = self.find(str(name))
        if found is not None:
            return found
        raise SceneError(f"{name}: no such scene file, and not a bundled example "
                         f"({', '.join(self.names())})")


SCENES = BundledScenes("kinetostatics", ("scenes", "scenes/cams"))


def examples() -> list[str]:
    """Names of the bundled mechanism scenes (``four_bar``, ``four_bar_motion``, ...)."""
    return SCENES.names("scenes")


def cam_examples() -> list[str]:
    """Names of the bundled ``[cam]`` scenes (docs/cam-scenes.md)."""
    return SCENES.names("scenes/cams")


def example(name: str) -> Path:
    """Path of a bundled scene, e.g. ``example("four_bar")`` or
    ``example("translating_roller")`` (a cam scene)."""
    return SCENES.path(name)


def scene_path(name: str | Path) -> Path:
    """A scene file's path: ``name`` itself when it exists, else the bundled example of
    that name (so the CLI takes ``four_bar`` as well as a path)."""
    return SCENES.resolve(name)
