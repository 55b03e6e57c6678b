"""Field balancing: influence coefficients and trim runs
(:mod:`~balance.field.influence`, their noise and intervals in
:mod:`~balance.field.influence_stats`), the balancer's weights (splitting, combining:
:mod:`~balance.field.weights`), ISO 21940-11 tolerances (:mod:`~balance.field.iso`),
and the scene sections that drive them (:mod:`~balance.field.scene`)."""

from __future__ import annotations

from .weights import (
    Combined,
    Placement,
    Split,
    combine_weights,
    split_correction,
)

__all__ = [
    "Combined",
    "Placement",
    "Split",
    "combine_weights",
    "split_correction",
]
