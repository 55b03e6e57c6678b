"""The workbench's one exception family.

Every user mistake (a bad scene, a mechanism that cannot be assembled, amplitudes
no parallelogram can join) raises a subclass of :class:`WorkbenchError`, itself a
``ValueError``. The message is one line that says what is wrong, where, and how to
mend it; the command line prints it as ``error: <message>`` and exits with code 2.
"""

from __future__ import annotations


class WorkbenchError(ValueError):
    """Base of every error caused by the user's input."""


class SceneError(WorkbenchError):
    """A scene file (or dict) breaks the contract of ``scene-format.md``."""


class AssemblyError(WorkbenchError):
    """The mechanism cannot be assembled, or is exactly singular, at some position."""


class StructureError(WorkbenchError):
    """The chain is not a driver plus dyads (Assur groups of class II)."""


class SelfLockingError(AssemblyError):
    """Joint friction locks the mechanism at every position of the sweep (seed 002
    s. 2.4): no finite driving effort moves it."""


class UnitWarning(UserWarning):
    """A number that looks like a unit slip (radians for degrees, rpm for rad/s, mm for m).
    The solve goes on; the command line prints it as a ``warning:`` line."""
