"""The results of a kinetostatic solve and their writers.

:mod:`~kinetostatics.results.solution` (:class:`Solution`: arrays inside, tidy pandas
tables built on demand), :mod:`~kinetostatics.results.longtable` (the long tables,
chunk by chunk from the arrays), :mod:`~kinetostatics.results.csvtext` (CSV text, whole
columns at a time) and :mod:`~kinetostatics.results.output` (the CSV, Parquet and
``summary.json`` writers), :mod:`~kinetostatics.results.streamed` (``solve --out`` of a
sweep too long to hold: solved and written block by block, with
:mod:`~kinetostatics.results.sweepangles`). :func:`solve` and :func:`solve_many`
(:mod:`~kinetostatics.results.solving`) wrap the solver's arrays in Solutions.
"""

from __future__ import annotations

from .solution import Solution
from .solving import solve, solve_many, solve_outcomes

__all__ = ["Solution", "solve", "solve_many", "solve_outcomes"]
