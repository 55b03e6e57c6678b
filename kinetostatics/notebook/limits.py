"""Limits the course teaches, checked on an interactive cell's key numbers.

A :class:`Limit` names one key number of an :class:`~kinetostatics.notebook.Explorer`
and the range the course admits for it (e.g. the smallest transmission angle
``>= 40 deg``, seed 002 eq. 2.61). When a slider moves the number outside that range the
explorer marks it: in its table (a ``limit`` column), in the widget's status line and in
:attr:`Explorer.crossed <kinetostatics.notebook.Explorer.crossed>`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Limit", "transmission_angle_limit"]


@dataclass(frozen=True)
class Limit:
    """An admissible range for one key number.

    Parameters
    ----------
    key : str
        The key number's name, as the explorer's ``numbers`` function returns it.
    min, max : float or None
        The admissible range (None: no bound on that side); at least one is given.
    source : str
        Where the course sets it, shown with the mark (e.g. ``"τ_adm, eq. 2.61"``).
    """

    key: str
    min: float | None = None
    max: float | None = None
    source: str = ""

    def __post_init__(self) -> None:
        if self.min is None and self.max is None:
            raise ValueError(f"limit on {self.key!r}: give min, max or both")
        if self.min is not None and self.max is not None and not self.min < self.max:
            raise ValueError(f"limit on {self.key!r}: needs min < max, got "
                             f"{self.min} and {self.max}")

    def describe(self) -> str:
        """The admissible range as text, e.g. ``">= 40 (τ_adm, eq. 2.61)"``."""
        if self.min is not None and self.max is not None:
            text = f"{self.min:g} to {self.max:g}"
        elif self.min is not None:
            text = f">= {self.min:g}"
        else:
            text = f"<= {self.max:g}"
        return f"{text} ({self.source})" if self.source else text

    def check(self, value: object) -> str | None:
        """None when ``value`` lies in the range (or is not a number: text, None);
        otherwise the mark, e.g. ``"below 40: 34.5 (τ_adm, eq. 2.61)"``."""
        if value is None or isinstance(value, (str, bool)):
            return None
        v = float(value)  # type: ignore[arg-type]
        if not math.isfinite(v):
            return None
        where = f" ({self.source})" if self.source else ""
        if self.min is not None and v < self.min:
            return f"below {self.min:g}: {v:.4g}{where}"
        if self.max is not None and v > self.max:
            return f"above {self.max:g}: {v:.4g}{where}"
        return None


def transmission_angle_limit(key: str) -> Limit:
    """The course's limit on the smallest transmission angle, ``>= 40 deg``
    (τ_adm ≈ 40°, seed 002 eq. 2.61), on the key number ``key``."""
    return Limit(key, min=40.0, source="τ_adm = 40°, eq. 2.61")
