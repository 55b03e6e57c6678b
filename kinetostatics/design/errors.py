"""The error of a bad ``[design]`` section."""

from __future__ import annotations

from ..model.errors import SceneError


class DesignError(SceneError):
    """A ``[design]`` section breaks its rules (docs/design.md): a variable that names
    nothing, reversed bounds, an unknown objective, no feasible design in the bounds.
    One line; the command line prints it as ``error: ...`` and exits with code 2."""


class MissingExtra(DesignError):
    """pymoo, the optimiser of ``design``, is not installed."""
