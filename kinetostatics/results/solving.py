"""The public solves: :func:`solve` and :func:`solve_many` wrap the solver's arrays
(:func:`~kinetostatics.solver.pipeline.solve_arrays`,
:func:`~kinetostatics.solver.many.solve_all`) in :class:`~kinetostatics.results.Solution`
objects."""

from __future__ import annotations

import warnings
from collections.abc import Iterable
from concurrent.futures import Executor
from operator import attrgetter
from typing import Any

from ..model.errors import UnitWarning
from ..solver.many import collector_paused, solve_all, solved_outcomes
from ..solver.pipeline import solve_arrays
from .solution import Solution


def solve(scene: Any, positions: Any = None, *, allow_repeats: bool = False) -> Solution:
    """Kinematics, reactions in every joint and the equilibrating moment over the sweep.

    Parameters
    ----------
    scene : Scene, pathlib.Path, str or dict
        A loaded scene, a path to a ``.toml`` file, TOML text or a dict
        (``scene-format.md`` section 1).
    positions : array_like, optional
        Driver positions (deg or m) at which to solve the same mechanism, in any order
        (each listed once): each dyad keeps the assembly chosen at the scene's own first
        row. Default: the scene's sweep. The tables keep the given order; the summary,
        the continuity of angles and the dead points between rows follow increasing
        driver position.
    allow_repeats : bool
        Solve a sweep that lists a position more than once instead of refusing it (for
        the project's own callers, e.g. a simulation's record that passes a position
        twice, or a reference row prepended to a batch); each repeat is its own row.

    Returns
    -------
    Solution
        Arrays and lazily built tables: ``kinematics``, ``bodies``, ``reactions``,
        ``driver``, ``dyads``, ``sliders``, ``frame``, ``reduced`` and ``summary()``.

    Raises
    ------
    SceneError, StructureError, AssemblyError
        One-line messages for a bad scene (a position listed twice included), a chain
        that is not driver + dyads, a mechanism that cannot be assembled or is exactly
        singular somewhere.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> sol = ks.solve(ks.example("four_bar"))
    >>> round(float(sol.driver["Me"].abs().max()), 1) > 0
    True
    """
    return Solution.of(solve_arrays(scene, positions, allow_repeats=allow_repeats))


def solve_many(scenes: Iterable[Any], *, executor: Executor | None = None,
               batch: int | None = None) -> list[Solution]:
    """The :class:`~kinetostatics.results.Solution` of each scene, in order, with exactly
    the numbers :func:`~kinetostatics.solve` gives each alone.

    Scenes of the same structure (the same bodies, points, joints, driver, loads and
    gravity; their lengths, ground points, masses, inertias, hints and sweeps may differ)
    are solved together in one vectorised pass, stacked along the position axis; the
    others are grouped by structure.

    Parameters
    ----------
    scenes : iterable of Scene, path, TOML text or dict
        What :func:`~kinetostatics.solve` takes, one per mechanism.
    executor : concurrent.futures.Executor, optional
        Spreads the scenes over its workers in batches of ``batch`` scenes (a
        ``ProcessPoolExecutor``, or a dask.distributed ``Client.get_executor()``); it is
        not shut down. Default: all in this process (usually the fastest for a few
        thousand scenes: one process solves them stacked).
    batch : int, optional
        Scenes per task for ``executor`` (default: about 4 tasks per 100 scenes, at
        least 32 scenes a task).

    Returns
    -------
    list of Solution
        One per scene, in the order given. Each scene's suspected unit slips are warned
        (:class:`~kinetostatics.model.errors.UnitWarning`) led by its place in the list
        and its title, and kept in its ``scene.warnings``.

    Raises
    ------
    WorkbenchError
        The error :func:`~kinetostatics.solve` raises for the first scene (in order) that
        it refuses, of the same class, its message led by the scene's place in the list:
        ``scenes[417]: body 'rocker'.mass must not be negative, got -1``.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> sols = ks.solve_many([ks.example("four_bar"), ks.example("slider_crank")])
    >>> [s.scene.title for s in sols] == [ks.solve(ks.example(n)).scene.title
    ...                                   for n in ("four_bar", "slider_crank")]
    True
    """
    items = list(scenes)
    with collector_paused():       # (the Solutions made too: thousands of small objects)
        out = Solution.all_of(solve_all(items, executor, batch))
    if any(map(_SLIPS, out)):           # the unit slips, each naming its scene
        for i, r in enumerate(out):
            for text in r.scene.warnings:
                title = f" ({r.scene.title})" if r.scene.title else ""
                warnings.warn(f"scenes[{i}]{title}: {text}", UnitWarning, stacklevel=2)
    return out


_SLIPS = attrgetter("scene.warnings")       # (a Solution's scene's unit slips)


def solve_outcomes(items: list[Any], *, lean: bool = True) -> list[Solution | Exception]:
    """Per scene, its Solution or the exception :func:`solve` raises for it, as
    :func:`solve_many` solves them (``lean``: see
    :func:`~kinetostatics.solver.many.solved_outcomes`)."""
    return Solution.all_of(solved_outcomes(items, lean=lean))
