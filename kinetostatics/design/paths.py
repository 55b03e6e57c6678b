"""Numbers of a scene named by their path in the TOML: ``"ground.D.0"``,
``"bodies.crank.points.B.0"``, ``"bodies.rocker.mass"``, ``"loads.0.force.1"``.

A path is resolved once, against the scene as typed, into a :class:`Path` (the keys and
list indices that reach the number); setting a design's numbers then copies only the
tables and lists along the paths (the scene as typed is never changed), so that a
population of scenes costs a few small copies each.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from .errors import DesignError

_INDEX = re.compile(r"\d+")


@dataclass(frozen=True)
class Path:
    """A number of the scene: its dotted ``name`` as typed, the ``steps`` (dict keys and
    list indices) that reach it and its ``value`` in the scene as typed."""

    name: str
    steps: tuple[str | int, ...]
    value: float


def resolve(raw: Mapping[str, Any], name: str, where: str) -> Path:
    """The :class:`Path` of ``name`` in the scene ``raw`` (as typed): a table's key, a
    list's index, or the ``name`` of an item of a list of tables (a body by its name, a
    joint by its name); a point by its key. ``where`` leads the message of a path that
    names nothing or names something that is not a number."""
    if not isinstance(name, str) or not name:
        raise DesignError(f"{where}: a variable is a dotted path into the scene, got {name!r}")
    node: Any = raw
    steps: list[str | int] = []
    for part in name.split("."):
        at = ".".join(name.split(".")[:len(steps)]) or "the scene"
        if isinstance(node, Mapping):
            if part not in node:
                known = ", ".join(map(str, node)) or "nothing"
                raise DesignError(f"{where}: {name!r} names nothing: {at} has no {part!r} "
                                  f"(it holds {known})")
            steps.append(part)
            node = node[part]
        elif isinstance(node, Sequence) and not isinstance(node, str):
            idx = _item(node, part)
            if idx is None:
                names = [it.get("name") for it in node if isinstance(it, Mapping)]
                hint = (f"names {', '.join(map(str, names))}" if any(names)
                        else f"items 0 to {len(node) - 1}")
                raise DesignError(f"{where}: {name!r} names nothing: {at} has no item "
                                  f"{part!r} ({hint})")
            steps.append(idx)
            node = node[idx]
        else:
            raise DesignError(f"{where}: {name!r} names nothing: {at} is a number")
    if isinstance(node, bool) or not isinstance(node, int | float):
        raise DesignError(f"{where}: {name!r} is not a number in the scene (it is "
                          f"{_kind(node)}); a variable names one number, e.g. "
                          f"{name}.0 for a point's x")
    return Path(name, tuple(steps), float(node))


def _item(items: Sequence, part: str) -> int | None:
    """The index of a list's item named ``part`` (its ``name``), or ``part`` as an
    index."""
    for i, it in enumerate(items):
        if isinstance(it, Mapping) and it.get("name") == part:
            return i
    if _INDEX.fullmatch(part) and int(part) < len(items):
        return int(part)
    return None


def _kind(value: Any) -> str:
    if isinstance(value, Mapping):
        return "a table"
    if isinstance(value, list):
        return "a list"
    return f"{type(value).__name__} {value!r}"


def with_values(raw: dict, paths: Sequence[Path], values: Sequence[float]) -> dict:
    """A copy of the scene ``raw`` with the number of each path set to its value: the
    tables and lists along the paths are copied, everything else is shared with ``raw``
    (which is left as it was)."""
    out = dict(raw)
    copied: set[tuple] = {()}
    for path, value in zip(paths, values, strict=True):
        node: Any = out
        for k, step in enumerate(path.steps[:-1]):
            key = path.steps[:k + 1]
            child = node[step]
            if key not in copied:
                child = dict(child) if isinstance(child, Mapping) else list(child)
                node[step] = child
                copied.add(key)
            node = child
        node[path.steps[-1]] = value
    return out


def get(raw: Mapping[str, Any], path: Path) -> Any:
    """The value at ``path`` in ``raw``."""
    node: Any = raw
    for step in path.steps:
        node = node[step]
    return node
