"""The search: pymoo's NSGA-II over the section's variables, a whole population judged
by one stacked solve per generation (:func:`search`); a plain random search of the same
number of evaluations to compare with (:func:`random_search`); the hypervolume.

pymoo is imported here only (the ``[design]`` extra): without it, one line says what to
install.
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable
from concurrent.futures import Executor
from dataclasses import dataclass, field

import numpy as np

from .errors import DesignError, MissingExtra
from .judging import Evaluation, evaluate, excess, minimised
from .section import DesignSpec

REFERENCE = 1.1     # the hypervolume's reference point, in normalised objectives


def _pymoo():
    try:
        import pymoo  # noqa: F401
    except ImportError:
        raise MissingExtra("design needs pymoo, its optimiser: pip install -e '.[design]'"
                           ) from None


@dataclass
class Archive:
    """Every feasible non-dominated design met so far (variables ``X``, objective values
    ``values``), and the count of every evaluation and of why designs were infeasible."""

    spec: DesignSpec
    X: np.ndarray = field(init=False)
    values: np.ndarray = field(init=False)
    evaluations: int = 0
    infeasible: int = 0
    reasons: Counter = field(default_factory=Counter)

    def __post_init__(self):
        self.X = np.zeros((0, len(self.spec.variables)))
        self.values = np.zeros((0, len(self.spec.objectives)))

    def add(self, X: np.ndarray, ev: Evaluation) -> None:
        """Count a judged population and keep its feasible designs that no other
        feasible design dominates."""
        self.evaluations += len(X)
        self.infeasible += int((~ev.feasible).sum())
        self.reasons.update(r for r in ev.reasons if r is not None)
        X = np.concatenate([self.X, X[ev.feasible]])
        values = np.concatenate([self.values, ev.values[ev.feasible]])
        keep = non_dominated(minimised(self.spec, values))
        _, first = np.unique(X[keep], axis=0, return_index=True)    # (a design once)
        keep = keep[np.sort(first)]
        self.X, self.values = X[keep], values[keep]

    def front(self) -> tuple[np.ndarray, np.ndarray]:
        """The front's variables and values, ordered by the objectives in turn (the
        first objective as minimised first)."""
        f = minimised(self.spec, self.values)
        order = np.lexsort(f.T[::-1]) if len(f) else np.zeros(0, dtype=int)
        return self.X[order], self.values[order]


def non_dominated(F: np.ndarray) -> np.ndarray:
    """Indices of the rows of ``F`` (minimised) that no other row dominates."""
    if len(F) == 0:
        return np.zeros(0, dtype=int)
    from pymoo.util.nds.non_dominated_sorting import NonDominatedSorting
    return np.sort(np.asarray(NonDominatedSorting().do(F, only_non_dominated_front=True)))


def search(spec: DesignSpec, *, executor: Executor | None = None, parts: int = 1,
           progress: Callable[[int, int, int], None] | None = None) -> Archive:
    """NSGA-II (pymoo) over ``spec``: ``spec.population`` designs for ``spec.generations``
    generations from ``spec.seed``; every generation judged by :func:`evaluate` (one
    stacked solve, or ``parts`` through ``executor``). ``progress(generation,
    evaluations, front size)`` after each generation."""
    _pymoo()
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem

    archive = Archive(spec)

    class _Designs(Problem):
        def __init__(self):
            super().__init__(n_var=len(spec.variables), n_obj=len(spec.objectives),
                             n_ieq_constr=1 + len(spec.constraints), xl=spec.lower,
                             xu=spec.upper)

        def _evaluate(self, X, out, *args, **kwargs):
            ev = evaluate(spec, X, executor, parts)
            archive.add(X, ev)
            out["F"] = minimised(spec, ev.values, ev.feasible)
            out["G"] = excess(spec, ev)

    algorithm = NSGA2(pop_size=spec.population)
    algorithm.setup(_Designs(), termination=("n_gen", spec.generations), seed=spec.seed,
                    verbose=False)
    generation = 0
    while algorithm.has_next():
        algorithm.next()
        generation += 1
        if progress is not None:
            progress(generation, archive.evaluations, len(archive.X))
    return archive


def random_search(spec: DesignSpec, evaluations: int, seed: int, *,
                  executor: Executor | None = None, parts: int = 1) -> Archive:
    """A plain random search: ``evaluations`` designs drawn uniformly within the bounds
    (numpy's generator from ``seed``), judged as the search judges them, in batches of
    the population's size."""
    _pymoo()
    rng = np.random.default_rng(seed)
    archive = Archive(spec)
    left = evaluations
    while left > 0:
        n = min(left, spec.population)
        X = spec.lower + rng.random((n, len(spec.variables))) * (spec.upper - spec.lower)
        archive.add(X, evaluate(spec, X, executor, parts))
        left -= n
    return archive


def normalisation(spec: DesignSpec, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The ideal and nadir points of a front, as minimised (a maximised objective
    negated): each objective's best and worst over the front."""
    f = minimised(spec, values)
    return f.min(axis=0), f.max(axis=0)


def hypervolume(spec: DesignSpec, values: np.ndarray, ideal: np.ndarray, nadir: np.ndarray
                ) -> float:
    """The hypervolume of the designs' objective ``values``, as minimised and normalised
    (f - ideal) / (nadir - ideal) (a span of 0 taken as 1), against the reference point
    ``REFERENCE`` in every objective (pymoo's HV)."""
    _pymoo()
    from pymoo.indicators.hv import HV
    if len(values) == 0:
        return 0.0
    span = np.where(nadir > ideal, nadir - ideal, 1.0)
    f = (minimised(spec, values) - ideal) / span
    return float(HV(ref_point=np.full(f.shape[1], REFERENCE))(f))


def no_feasible(archive: Archive) -> DesignError:
    """The error of a search that met no feasible design."""
    common = archive.reasons.most_common(1)
    why = f"the commonest reason: {common[0][0]} ({common[0][1]} designs)" if common else ""
    return DesignError(f"no feasible design among the {archive.evaluations} tried; {why}; "
                       "widen the bounds or relax the constraints")


def timed(fn: Callable, *args, **kwargs):
    """``fn(*args, **kwargs)`` and its wall time (s)."""
    t = time.perf_counter()
    out = fn(*args, **kwargs)
    return out, time.perf_counter() - t
