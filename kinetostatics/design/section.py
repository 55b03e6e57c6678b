"""The ``[design]`` section of a mechanism scene, read and checked: :func:`read_design`.

```toml
[design]
seed = 1
population = 100                 # optional, default 100
generations = 60                 # optional, default 60
objectives = ["min Me_peak", "max transmission_min"]
constraints = ["transmission_min >= 30", "full_turn"]

[design.variables]               # a number of the scene by its TOML path = [low, high]
"ground.D.0" = [0.18, 0.42]
"bodies.crank.points.B.0" = [0.06, 0.14]

[design.follow]                  # optional: a number that keeps its ratio to a variable
"bodies.crank.cog.0" = "bodies.crank.points.B.0"

[design.targets]                 # optional: target points (m) of path_error:POINT
"coupler.P" = [[0.1, 0.2], [0.15, 0.25]]
```
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from ..model.errors import WorkbenchError
from ..model.examples import SCENES
from ..model.scene import Scene, load_scene
from ..model.tomlio import check_keys, read_source
from . import paths
from .errors import DesignError
from .paths import Path
from .vocabulary import Constraint, Objective, constraints, objectives

DESIGN_KEYS = ("seed", "population", "generations", "objectives", "constraints",
               "variables", "follow", "targets")
POPULATION = 100
GENERATIONS = 60
TURN_ROWS = 361     # rows of the whole turn that full_turn checks (a partial sweep)


@dataclass
class DesignSpec:
    """A checked ``[design]`` section and the scene it varies.

    Attributes
    ----------
    raw : dict
        The scene as typed, without ``[design]`` (every design's scene is a copy with the
        variables set).
    scene : Scene
        The scene as typed, loaded: the bundled design.
    variables : list of Path
        The numbers varied, by path; ``lower``, ``upper`` their bounds (as typed).
    follow : list of (Path, int, float)
        Numbers that keep their ratio to a variable: (its path, the variable's index,
        the ratio in the scene).
    objectives, constraints : lists
        The vocabulary's :class:`~kinetostatics.design.vocabulary.Objective` and
        :class:`~kinetostatics.design.vocabulary.Constraint`.
    full_turn : bool
        The driver must turn through a whole revolution (checked on a whole turn when
        the scene's sweep is shorter).
    seed, population, generations : int
        The search's settings.
    """

    raw: dict
    scene: Scene
    variables: list[Path]
    lower: np.ndarray
    upper: np.ndarray
    follow: list[tuple[Path, int, float]]
    objectives: list[Objective]
    constraints: list[Constraint]
    full_turn: bool
    seed: int
    population: int
    generations: int

    @property
    def names(self) -> list[str]:
        return [v.name for v in self.variables]

    @property
    def bundled(self) -> np.ndarray:
        """The variables' values in the scene as typed."""
        return np.array([v.value for v in self.variables])

    def scene_dict(self, x: np.ndarray) -> dict:
        """The design ``x``'s scene (a dict of the TOML, without ``[design]``)."""
        return paths.with_values(self.raw, *self._values(x))

    def _values(self, x: np.ndarray) -> tuple[list[Path], list[float]]:
        """The paths the design ``x`` sets (variables, then followers) and their values."""
        values = [float(v) for v in x]
        chosen = list(self.variables)
        for path, i, ratio in self.follow:
            chosen.append(path)
            values.append(values[i] * ratio)
        return chosen, values

    def set_values(self, X: np.ndarray) -> np.ndarray:
        """The numbers the designs ``X`` set (one row per design; the variables, then
        the followers: each its variable's value times its ratio, as
        :meth:`scene_dict` sets it)."""
        X = np.asarray(X, dtype=float)
        cols = [X[:, i] for i in range(X.shape[1])]
        cols += [np.array([v * ratio for v in X[:, i].tolist()]) for _, i, ratio in self.follow]
        return np.stack(cols, axis=1) if cols else np.zeros((len(X), 0))

    @cached_property
    def stack_plan(self):
        """How a population is stacked without a Scene per design
        (:func:`~kinetostatics.design.stacked.plan_of`), or None."""
        from .stacked import plan_of
        if self.turn_dict(self.raw) is not None and self.turn_plan is None:
            return None
        return plan_of(self.scene, self.raw, self._values(self.bundled)[0])

    @cached_property
    def turn_plan(self):
        """The stacking plan of the designs' whole turns (``full_turn`` over a partial
        sweep), else None."""
        turn = self.turn_dict(self.raw)
        if turn is None:
            return None
        from .stacked import plan_of
        return plan_of(load_scene(turn), self.raw, self._values(self.bundled)[0])

    def design_scene(self, x: np.ndarray) -> tuple[dict, Scene]:
        """The design ``x``'s scene as a dict and as the Scene ``load_scene`` gives for
        it (:func:`~kinetostatics.design.scenes.scene_maker`)."""
        chosen, values = self._values(x)
        design = paths.with_values(self.raw, chosen, values)
        return design, self._maker(design, values)

    def __getstate__(self) -> dict:
        state = dict(self.__dict__)
        for name in ("_maker", "stack_plan", "turn_plan"):   # (made again where needed)
            state.pop(name, None)
        return state

    @cached_property
    def _maker(self):
        from .scenes import scene_maker
        return scene_maker(self.scene, self.raw, self._values(self.bundled)[0])

    def turn_dict(self, design: dict) -> dict | None:
        """For ``full_turn`` with a sweep shorter than a turn: the design's scene over a
        whole turn from its start (``TURN_ROWS`` rows, or the sweep's count if more);
        None when the sweep is a whole turn already."""
        if not self.full_turn:
            return None
        pos = self.scene.driver.positions
        if pos.size and np.ptp(pos) >= 360.0 * (1 - 1e-12):
            return None
        drv = dict(design["driver"])
        unit = design.get("units", {}).get("angle", "deg")
        turn = 360.0 if unit == "deg" else 2 * math.pi
        start = min(drv["positions"]) if "positions" in drv else drv["start"]
        count = max(TURN_ROWS, pos.size)
        for k in ("positions", "start", "stop", "count"):
            drv.pop(k, None)
        drv.update(start=start, stop=start + turn, count=count)
        return {**design, "driver": drv}


def read_design(source: Any, *, seed: int | None = None, population: int | None = None,
                generations: int | None = None) -> DesignSpec:
    """The checked ``[design]`` section of a scene (path, TOML text or dict); ``seed``,
    ``population`` and ``generations`` given here replace the section's."""
    raw = copy.deepcopy(read_source(source, bundled=SCENES))
    if "design" not in raw:
        raise DesignError("the scene has no [design] section; add one (docs/design.md): "
                          "objectives, constraints and [design.variables]")
    section = check_keys(raw.pop("design"), DESIGN_KEYS, "[design]",
                         required=("objectives", "variables"))
    scene = load_scene(copy.deepcopy(raw))
    targets = section.get("targets", {})
    if not isinstance(targets, Mapping):
        raise DesignError("[design.targets] must be a table of \"body.point\" = [[x, y], ...]")
    objs = objectives(section["objectives"], scene, targets)
    cons, full_turn = constraints(section.get("constraints", []), scene, targets)
    variables, lower, upper = _variables(raw, section["variables"])
    follow = _follow(raw, section.get("follow", {}), variables)
    spec = DesignSpec(raw, scene, variables, lower, upper, follow, objs, cons, full_turn,
                      _count(seed, section, "seed", 1, 0),
                      _count(population, section, "population", POPULATION, 4),
                      _count(generations, section, "generations", GENERATIONS, 1))
    _check_bounds(spec)
    return spec


def _count(given: int | None, section: Mapping, key: str, default: int, least: int) -> int:
    value = section.get(key, default) if given is None else given
    if isinstance(value, bool) or not isinstance(value, int) or value < least:
        where = f"[design] {key}" if given is None else f"--{key}"
        raise DesignError(f"{where} = {value!r}: give a whole number >= {least}")
    return value


def _variables(raw: dict, table: Any) -> tuple[list[Path], np.ndarray, np.ndarray]:
    if not isinstance(table, Mapping) or not table:
        raise DesignError('[design.variables]: give at least one "path" = [low, high], e.g. '
                          '"ground.D.0" = [0.18, 0.42]')
    out, lo, hi = [], [], []
    for name, bounds in table.items():
        where = f"[design.variables] {name!r}"
        path = paths.resolve(raw, name, "[design.variables]")
        ok = (isinstance(bounds, list) and len(bounds) == 2
              and all(isinstance(b, int | float) and not isinstance(b, bool) for b in bounds)
              and all(math.isfinite(b) for b in bounds))
        if not ok:
            raise DesignError(f"{where}: give the bounds as [low, high] (two numbers), got "
                              f"{bounds!r}")
        a, b = float(bounds[0]), float(bounds[1])
        if not a < b:
            raise DesignError(f"{where} = [{bounds[0]!r}, {bounds[1]!r}]: the bounds are "
                              f"{'reversed' if a > b else 'equal'}; give [low, high] with "
                              "low < high")
        steps = path.steps
        if len(steps) == 5 and steps[0] == "bodies" and steps[2] == "points" \
                and path.value != 0.0 and not (a * path.value > 0 and b * path.value > 0):
            raise DesignError(f"{where} = [{bounds[0]!r}, {bounds[1]!r}]: a length of the "
                              f"body ({path.value!r} in the scene) would reach zero or turn "
                              "negative; keep both bounds on its side of zero")
        out.append(path)
        lo.append(a)
        hi.append(b)
    return out, np.array(lo), np.array(hi)


def _follow(raw: dict, table: Any, variables: list[Path]) -> list[tuple[Path, int, float]]:
    if not isinstance(table, Mapping):
        raise DesignError('[design.follow] must be a table of "path" = "variable path"')
    names = [v.name for v in variables]
    out = []
    for name, leader in table.items():
        where = f"[design.follow] {name!r}"
        path = paths.resolve(raw, name, "[design.follow]")
        if name in names:
            raise DesignError(f"{where}: it is a variable; a number either varies or follows")
        if leader not in names:
            raise DesignError(f"{where} = {leader!r}: follow one of the variables "
                              f"({', '.join(names)})")
        i = names.index(leader)
        if variables[i].value == 0.0:
            raise DesignError(f"{where}: the variable {leader!r} is 0 in the scene; a ratio "
                              "to it is undefined")
        out.append((path, i, path.value / variables[i].value))
    return out


def _check_bounds(spec: DesignSpec) -> None:
    """Each variable at each of its bounds (the others as typed) gives a scene the loader
    accepts (a negative mass, a zero count... are refused here, naming the bound)."""
    x0 = spec.bundled
    for i, path in enumerate(spec.variables):
        for b in (spec.lower[i], spec.upper[i]):
            x = x0.copy()
            x[i] = b
            try:
                load_scene(spec.scene_dict(x))
            except WorkbenchError as exc:
                raise DesignError(f"[design.variables] {path.name!r}: the bound {b:g} is "
                                  f"outside what the scene allows: {exc}") from None
