"""Benchmarks: speed against error, the speed table and the table writers.

:mod:`~kinetostatics.bench.accuracy` (positions per second of the kinematics and of the
whole solve, with the error against independent closed forms),
:mod:`~kinetostatics.bench.speed` (every figure as a ratio to a hand-written baseline)
and :mod:`~kinetostatics.bench.tables` (the CSV and Parquet writers and the start-up).
``python -m kinetostatics bench`` runs them.

The names of :mod:`~kinetostatics.bench.accuracy` are importable from here too
(``from kinetostatics import bench; bench.bench_kinematics()``), loaded on first use so
that ``kinetostatics.bench.tables`` starts without pandas.
"""

from __future__ import annotations

from ..common.lazy import group, lazy_names

_ACCURACY = ("FB", "SC", "bench_against_reference", "bench_kinematics", "bench_reactions",
             "find_reference", "fourbar_closed_form", "fourbar_matrix_solution",
             "fourbar_scene", "load_reference", "run_bench", "slider_closed_form",
             "slider_crank_reference_scene", "slider_crank_scene")

__all__ = list(_ACCURACY)


__getattr__, __dir__ = lazy_names(__name__, group(_ACCURACY, "accuracy"), globals(),
                                  __all__, subpackages=False)
