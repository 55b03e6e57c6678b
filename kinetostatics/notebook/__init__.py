"""Helpers for the JupyterLab sheets: :mod:`~kinetostatics.notebook.widgets` holds the
interactive cells' explorer (sliders -> picture and key numbers),
:mod:`~kinetostatics.notebook.limits` the limits the course teaches that it marks,
:mod:`~kinetostatics.notebook.tables` shows missing table cells as a dash."""

from .limits import Limit, transmission_angle_limit
from .tables import DASH, dash_missing
from .widgets import Explorer, Slider, format_number

__all__ = ["DASH", "Explorer", "Limit", "Slider", "dash_missing", "format_number",
           "transmission_angle_limit"]
