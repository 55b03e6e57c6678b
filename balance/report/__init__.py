"""The balancing report: the plain text the CLI prints (:mod:`~balance.report.text`) and
the HTML/PDF document for the customer file (:mod:`~balance.report.document`)."""

from __future__ import annotations

from kinetostatics.common.lazy import group, lazy_names

# (loaded on first use: the text the CLI prints needs neither matplotlib nor the document)
_DOCUMENT = ("influence_figure", "iso_figure", "report_figures", "report_scene",
             "write_report")

__all__ = list(_DOCUMENT)

__getattr__, __dir__ = lazy_names(__name__, group(_DOCUMENT, "document"), globals(), __all__)
