"""Helpers for the JupyterLab sheets: :mod:`~kinetostatics.notebook.widgets` holds the
interactive cells' explorer (sliders -> picture and key numbers),
:mod:`~kinetostatics.notebook.tables` shows missing table cells as a dash."""

from .tables import DASH, dash_missing
from .widgets import Explorer, Slider, format_number

__all__ = ["DASH", "Explorer", "Slider", "dash_missing", "format_number"]
