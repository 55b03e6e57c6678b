"""The sheets' interactive cells: sliders that change a scene and redraw a picture and
its key numbers.

An :class:`Explorer` ties together a few :class:`Slider` s (a length, a speed, a mass,
...), a ``compute`` function (slider values -> a result, e.g. a solved scene), a ``draw``
function (result -> a picture in the explorer's own figure) and a ``numbers`` function
(result -> the key numbers, shown as a table). It works without a browser:
``explorer.set(speed=60.0)`` recomputes, redraws and returns the new numbers, so a test
can set a value and check that the picture and the numbers change.
:meth:`Explorer.widget` wraps the same object in ipywidgets sliders for JupyterLab.

A value for which the scene cannot be solved (a link too short to close the loop, ...)
is not an exception in the sheet: the explorer keeps the message of the
:class:`~kinetostatics.model.errors.WorkbenchError` (any ``ValueError``), writes it in
the picture and shows no numbers, until a value that can be solved is set.
"""

from __future__ import annotations

import io
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import pandas as pd
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["Explorer", "Slider", "format_number"]


@dataclass(frozen=True)
class Slider:
    """One slider of an explorer.

    Parameters
    ----------
    name : str
        Keyword under which the value reaches ``compute`` (a Python identifier).
    label : str
        What the slider changes, with its unit (e.g. ``"crank AB [m]"``).
    min, max, step : float
        Range and step of the slider.
    value : float
        Starting value, within ``[min, max]``.
    """

    name: str
    label: str
    min: float
    max: float
    step: float
    value: float

    def __post_init__(self) -> None:
        if not self.name.isidentifier():
            raise ValueError(f"slider name {self.name!r} is not a Python identifier")
        if not (self.min < self.max and self.step > 0):
            raise ValueError(f"slider {self.name!r}: needs min < max and step > 0, got "
                             f"min={self.min}, max={self.max}, step={self.step}")
        self.check(self.value)

    def check(self, value: float) -> float:
        """``value`` as a float, or a ``ValueError`` naming the slider when it is out of
        the slider's range or not finite."""
        v = float(value)
        tol = 1e-9 * (self.max - self.min)
        if not math.isfinite(v) or v < self.min - tol or v > self.max + tol:
            raise ValueError(f"slider {self.name!r}: {value!r} is outside "
                             f"[{self.min:g}, {self.max:g}]")
        return v


def format_number(x: Any, digits: int = 4) -> str:
    """A number as text with ``digits`` significant digits (``-`` for None); text stays
    text. Used for the explorer's table, so that no ``nan`` ever reaches a sheet: a NaN
    or infinite number raises, because a key number must be a value."""
    if x is None:
        return "-"
    if isinstance(x, str):
        return x
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(f"a key number is {v}: compute it where it is defined, or "
                         "report None")
    if v == int(v) and abs(v) < 1e6:
        return str(int(v))
    return f"{v:.{digits}g}"


class Explorer:
    """Sliders -> ``compute`` -> picture and key numbers, testable without a browser.

    Parameters
    ----------
    sliders : sequence of Slider
        The values a student changes.
    compute : callable
        ``compute(**values) -> result`` with one keyword per slider.
    draw : callable
        ``draw(result, fig, **values)``: draws the result into the (cleared) figure.
    numbers : callable
        ``numbers(result, **values) -> dict`` of the key numbers (float, str or None).
    figsize : (float, float)
        Size of the explorer's figure in inches.

    Attributes
    ----------
    values : dict
        The current slider values.
    result : object or None
        The last result of ``compute`` (None when it raised).
    numbers : dict
        The last key numbers (empty when ``compute`` raised).
    error : str or None
        The message of the last ``ValueError`` raised by ``compute`` or ``draw``.
    figure : matplotlib.figure.Figure
        The picture (one figure, redrawn in place).
    """

    def __init__(self, sliders: Sequence[Slider], compute: Callable[..., Any],
                 draw: Callable[..., None], numbers: Callable[..., Mapping[str, Any]], *,
                 figsize: tuple[float, float] = (10.0, 4.0)) -> None:
        names = [s.name for s in sliders]
        if not names or len(set(names)) != len(names):
            raise ValueError(f"an explorer needs sliders with distinct names, got {names}")
        self.sliders = tuple(sliders)
        self._compute, self._draw, self._numbers = compute, draw, numbers
        self.figure = Figure(figsize=figsize, layout="constrained")
        FigureCanvasAgg(self.figure)     # a canvas that renders (no pyplot, no window)
        self.values = {s.name: s.value for s in self.sliders}
        self.result: Any = None
        self.numbers: dict[str, Any] = {}
        self.error: str | None = None
        self._listeners: list[Callable[[], None]] = []
        self._widgets: list[Any] = []
        self._update()

    def slider(self, name: str) -> Slider:
        """The slider called ``name``."""
        for s in self.sliders:
            if s.name == name:
                return s
        raise ValueError(f"no slider {name!r}; the sliders are "
                         f"{', '.join(s.name for s in self.sliders)}")

    def set(self, **values: float) -> dict[str, Any]:
        """Set slider values (by name), recompute and redraw; returns the key numbers."""
        new = dict(self.values)
        for name, v in values.items():
            new[name] = self.slider(name).check(v)
        self.values = new
        self._update()
        for f in self._listeners:
            f()
        return dict(self.numbers)

    def _update(self) -> None:
        self.figure.clear()
        try:
            self.result = self._compute(**self.values)
            self._draw(self.result, self.figure, **self.values)
            self.numbers = dict(self._numbers(self.result, **self.values))
            self.error = None
        except ValueError as exc:      # WorkbenchError and BalanceError are ValueErrors
            self.result, self.numbers, self.error = None, {}, str(exc)
            self.figure.clear()
            ax = self.figure.add_subplot()
            ax.set_axis_off()
            ax.text(0.5, 0.5, "cannot be solved with these values:\n" + self.error,
                    ha="center", va="center", wrap=True, transform=ax.transAxes,
                    color="tab:red")

    def table(self) -> pd.DataFrame:
        """The key numbers as a one-column table (text, 4 significant digits), or the
        error message."""
        if self.error is not None:
            return pd.DataFrame({"value": [self.error]}, index=["cannot be solved"])
        return pd.DataFrame({"value": [format_number(v) for v in self.numbers.values()]},
                            index=list(self.numbers))

    def png(self, dpi: int = 60) -> bytes:
        """The current picture as PNG bytes (to compare two states in a test)."""
        buf = io.BytesIO()
        self.figure.savefig(buf, format="png", dpi=dpi)
        return buf.getvalue()

    def widget(self):
        """The sliders, the picture and the table as one ipywidgets box for JupyterLab.

        Moving a slider calls :meth:`set` (on release) and redraws the output below the
        sliders. Without a browser (a headless run) the box shows the starting state.
        """
        import ipywidgets as w
        from IPython.display import display

        out = w.Output()

        def show() -> None:
            out.clear_output(wait=True)
            with out:
                display(self.figure)
                display(self.table())

        controls = []
        for s in self.sliders:
            c = w.FloatSlider(value=self.values[s.name], min=s.min, max=s.max, step=s.step,
                              description=s.label, continuous_update=False,
                              style={"description_width": "initial"},
                              layout=w.Layout(width="460px"))
            def follow(change, name=s.name) -> None:
                self.set(**{name: change["new"]})

            c.observe(follow, names="value")
            self._widgets.append((c, follow))
            controls.append(c)
        self._listeners.append(show)
        show()
        box = w.VBox([*controls, out])
        self._widgets += [(out, None), (box, None)]
        return box

    def close(self) -> None:
        """Close the widgets made by :meth:`widget` (they stop following :meth:`set`);
        the explorer itself keeps working through its Python API."""
        for widget, follow in self._widgets:
            if follow is not None:
                widget.unobserve(follow, names="value")
            widget.close()
        self._widgets.clear()
        self._listeners.clear()
