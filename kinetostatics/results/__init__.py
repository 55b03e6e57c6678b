"""The results of a kinetostatic solve and their writers.

:mod:`~kinetostatics.results.solution` (:class:`Solution`: arrays inside, tidy pandas
tables built on demand), :mod:`~kinetostatics.results.longtable` (the long tables,
chunk by chunk from the arrays), :mod:`~kinetostatics.results.csvtext` (CSV text, whole
columns at a time) and :mod:`~kinetostatics.results.output` (the CSV, Parquet and
``summary.json`` writers).
"""

from __future__ import annotations

from .solution import Solution

__all__ = ["Solution"]
