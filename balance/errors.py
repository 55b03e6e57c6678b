"""Errors and warnings of the balancing package.

Every mistake in the input raises :class:`BalanceError` (a
:class:`~kinetostatics.model.errors.WorkbenchError`, hence a ``ValueError``) with one line
saying what is wrong, where, and how to mend it; scene-format mistakes raise
:class:`~kinetostatics.model.errors.SceneError` from the shared TOML helpers. Results that
are computed but deserve caution (a clipped arccos argument, a trial mass much
smaller than the unbalance) emit a :class:`BalanceWarning`.
"""

from __future__ import annotations

from kinetostatics.model.errors import SceneError, WorkbenchError

__all__ = ["BalanceError", "BalanceWarning", "SceneError", "WorkbenchError"]


class BalanceError(WorkbenchError):
    """Balancing data that no method can turn into a correction (coincident planes,
    amplitudes no parallelogram can join, too few trial runs, ...)."""


class BalanceWarning(UserWarning):
    """A result that was computed but should be read with care."""
