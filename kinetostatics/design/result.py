"""What a design search gives: :class:`DesignResult` (the front, the designs' scenes,
the summary), and :func:`design`, the search from a scene with a ``[design]`` section."""

from __future__ import annotations

import time
from collections.abc import Callable
from concurrent.futures import Executor
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from .judging import Evaluation, evaluate, minimised
from .optimiser import Archive, hypervolume, no_feasible, normalisation, search
from .section import DesignSpec, read_design


@dataclass
class DesignResult:
    """The non-dominated feasible designs of a search, and how it went.

    Attributes
    ----------
    spec : DesignSpec
        The checked section and its scene.
    X, values : ndarray
        The front's variables (as typed in the scene) and objective values (SI, deg; a
        maximised objective as its value), one row per design, ordered by the first
        objective as minimised.
    bundled : Evaluation
        The scene's own design, judged as the others.
    summary : dict
        What ``summary.json`` holds (evaluations, infeasible count, generations, seed,
        time, hypervolume with its normalisation and reference point, ...).
    """

    spec: DesignSpec
    X: np.ndarray
    values: np.ndarray
    bundled: Evaluation
    summary: dict

    @cached_property
    def front(self) -> pd.DataFrame:
        """One row per design: the variables by path, the objectives by name, and
        ``scene``, its scene's file relative to the output folder (``designs/007.toml``)."""
        cols: dict[str, Any] = {n: self.X[:, i] for i, n in enumerate(self.spec.names)}
        for k, o in enumerate(self.spec.objectives):
            cols[o.quantity.name] = self.values[:, k]
        cols["scene"] = [self.scene_file(i) for i in range(len(self.X))]
        return pd.DataFrame(cols)

    def scene_file(self, i: int) -> str:
        """Design ``i``'s scene file, relative to the output folder."""
        width = max(3, len(str(len(self.X) - 1)))
        return f"designs/{i:0{width}d}.toml"

    @property
    def scenes(self) -> list[dict]:
        """Each design's full scene (a dict of its TOML, without ``[design]``), in the
        order of :attr:`front`: what :func:`kinetostatics.solve` takes."""
        return [self.spec.scene_dict(x) for x in self.X]

    @cached_property
    def compromise(self) -> int:
        """The front's design nearest the ideal point, the objectives normalised by the
        front's ideal and nadir (each in [0, 1]): a balanced choice to draw."""
        ideal, nadir = normalisation(self.spec, self.values)
        span = np.where(nadir > ideal, nadir - ideal, 1.0)
        f = (minimised(self.spec, self.values) - ideal) / span
        return int(np.argmin(np.hypot.reduce(f, axis=1) if f.shape[1] > 1 else f[:, 0]))

    def solve(self, i: int):
        """The :func:`kinetostatics.solve` of design ``i`` of the front."""
        from ..solver.pipeline import solve
        return solve(self.spec.scene_dict(self.X[i]))

    def write(self, out: str | Path, *, dpi: float = 150) -> list[Path]:
        """front.csv, designs/*.toml, summary.json, front.png and compromise.png in
        ``out``; the paths written."""
        from .output import write_result
        return write_result(self, Path(out), dpi=dpi)


def design(scene: Any, *, population: int | None = None, generations: int | None = None,
           seed: int | None = None, executor: Executor | None = None, parts: int = 1,
           progress: Callable[[int, int, int], None] | None = None) -> DesignResult:
    """A multi-objective search over a scene's dimensions (its ``[design]`` section,
    docs/design.md): pymoo's NSGA-II, each generation one stacked solve.

    Parameters
    ----------
    scene : path, TOML text or dict
        A mechanism scene with a ``[design]`` section.
    population, generations, seed : int, optional
        Replace the section's.
    executor : concurrent.futures.Executor, optional
        Spreads each generation over its workers in ``parts`` parts (a
        ``ProcessPoolExecutor``, a dask ``Client.get_executor()``); the numbers are the
        same.
    parts : int
        Parts per generation for ``executor``.
    progress : callable, optional
        ``progress(generation, evaluations, front size)`` after each generation.

    Returns
    -------
    DesignResult
        ``.front`` (DataFrame), ``.scenes``, ``.summary``.

    Raises
    ------
    DesignError
        One line: a bad section, or no feasible design in the bounds (how many were
        tried, the commonest reason).
    """
    t0 = time.perf_counter()
    spec = read_design(scene, seed=seed, population=population, generations=generations)
    archive = search(spec, executor=executor, parts=parts, progress=progress)
    if len(archive.X) == 0:
        raise no_feasible(archive)
    X, values = archive.front()
    bundled = evaluate(spec, spec.bundled[None, :])
    summary = _summary(spec, archive, values, bundled, time.perf_counter() - t0)
    return DesignResult(spec, X, values, bundled, summary)


def _summary(spec: DesignSpec, archive: Archive, values: np.ndarray, bundled: Evaluation,
             seconds: float) -> dict:
    ideal, nadir = normalisation(spec, values)
    objectives = [{"name": o.quantity.name, "sense": "min" if o.sense > 0 else "max",
                   "unit": o.quantity.unit} for o in spec.objectives]
    own = {"feasible": bool(bundled.feasible[0]), "reason": bundled.reasons[0]}
    if bundled.feasible[0]:
        own["objectives"] = dict(zip([o["name"] for o in objectives],
                                     map(float, bundled.values[0]), strict=True))
    return {
        "title": spec.scene.title,
        "objectives": objectives,
        "constraints": [c.text for c in spec.constraints] + (["full_turn"] if spec.full_turn
                                                             else []),
        "variables": {v.name: [float(a), float(b)] for v, a, b in
                      zip(spec.variables, spec.lower, spec.upper, strict=True)},
        "follow": {p.name: spec.variables[i].name for p, i, _ in spec.follow},
        "optimiser": "NSGA-II (pymoo)",
        "seed": spec.seed, "population": spec.population, "generations": spec.generations,
        "evaluations": archive.evaluations, "infeasible": archive.infeasible,
        "infeasible_reasons": dict(archive.reasons.most_common()),
        "front_size": int(len(values)),
        "time_s": seconds,
        "hypervolume": {
            "value": hypervolume(spec, values, ideal, nadir),
            "objectives": "as minimised (a maximised objective negated), each normalised "
                          "(f - ideal) / (nadir - ideal)",
            "ideal": ideal.tolist(), "nadir": nadir.tolist(),
            "reference_point": [1.1] * len(ideal)},
        "bundled_design": own,
        "units": {o["name"]: o["unit"] for o in objectives},
    }
