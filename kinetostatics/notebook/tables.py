"""Tables as the sheets show them: a not-applicable cell shows a dash, never ``NaN``."""

from __future__ import annotations

import pandas as pd

__all__ = ["DASH", "dash_missing"]

DASH = "–"


def dash_missing(table: pd.DataFrame) -> pd.DataFrame:
    """A copy of ``table`` for display, with every missing (NaN or None) cell shown as a
    dash. The numbers keep their type where they are present; use it only for showing,
    never for computing."""
    out = table.astype(object)
    return out.where(table.notna(), DASH)
