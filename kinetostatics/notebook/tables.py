"""Tables as the sheets show them: a not-applicable cell shows a dash, never ``NaN``."""

from __future__ import annotations

import pandas as pd
from pandas.io.formats.style import Styler

__all__ = ["DASH", "dash_missing"]

DASH = "–"


def dash_missing(table: pd.DataFrame, precision: int = 4) -> Styler:
    """``table`` styled for display: numbers with ``precision`` decimals, every missing
    (NaN or None) cell shown as a dash. Only for showing; compute with the table."""
    return table.style.format(precision=precision, na_rep=DASH)
