"""The balancing report: the plain text the CLI prints (:mod:`~balance.report.text`) and
the HTML/PDF document for the customer file (:mod:`~balance.report.document`)."""

from __future__ import annotations

from .document import (
    influence_figure,
    iso_figure,
    report_figures,
    report_scene,
    write_report,
)

__all__ = [
    "influence_figure",
    "iso_figure",
    "report_figures",
    "report_scene",
    "write_report",
]
