"""A package's public names imported on first use (PEP 562): the one lazy loader of both
packages, so that ``import kinetostatics`` and ``import balance`` cost little more than
``import numpy``."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Container, Iterable


def lazy_names(package: str, names: dict[str, str], namespace: dict,
               public: Iterable[str] = (), kept: Callable[[str], bool] | None = None,
               subpackages: bool = True) -> tuple[Callable, Callable]:
    """The ``__getattr__`` and ``__dir__`` of ``package`` (its ``globals()``:
    ``namespace``).

    Parameters
    ----------
    names : dict
        Public name -> the module it comes from, relative to ``package``
        (``{"solve": "results.solving"}``).
    public : iterable of str
        The package's ``__all__`` (listed by ``dir``).
    kept : callable, optional
        Whether a name, once imported, is kept in the namespace (default: every name;
        one not kept is looked up again each time).
    subpackages : bool
        A subpackage asked for as an attribute (``kinetostatics.plot``) is imported.
    """
    public = list(public)

    def __getattr__(name: str):
        where = names.get(name)
        if where is None:
            if subpackages:
                try:
                    return importlib.import_module(f"{package}.{name}")
                except ModuleNotFoundError as exc:
                    if exc.name != f"{package}.{name}":
                        raise
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f"{package}.{where}"), name)
        if kept is None or kept(name):
            namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(public))
    return __getattr__, __dir__


def group(names: Container[str] | Iterable[str], where: str) -> dict[str, str]:
    """``{name: where}`` for every name of ``names`` (names from one module)."""
    return dict.fromkeys(names, where)


def moved_names(module: str, moved: dict[str, tuple[str, str]]) -> Callable:
    """The ``__getattr__`` of ``module`` whose names ``moved`` (old name -> (module,
    name) where it lives now) answer for one more release, with a DeprecationWarning."""

    def __getattr__(name: str):
        if name not in moved:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        import warnings

        where, new = moved[name]
        warnings.warn(f"{module}.{name} is now {where}.{new}; the old name goes in the next "
                      "release", DeprecationWarning, stacklevel=2)
        return getattr(importlib.import_module(where), new)
    return __getattr__
