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

Updates are serialised: one update computes at a time, and a value set while one is
computing (a slider moved again, by a student faster than the scene solves) replaces the
value waiting, so the explorer computes the first and the newest value, never a stack of
stale ones; the picture is cleared and drawn once per update, after ``compute`` returns,
so it never holds two updates' axes. The limits the course teaches (a
:class:`~kinetostatics.notebook.limits.Limit` on a key number, e.g. the transmission
angle >= 40 deg) are marked when a value crosses them.
"""

from __future__ import annotations

import asyncio
import html
import io
import math
import threading
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import pandas as pd
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..plot.place import settle, settled_later
from ..plot.style import save_laid_out
from .limits import Limit

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

    @property
    def readout_format(self) -> str:
        """The slider's readout with as many decimals as its step and its ends need
        (0.125 shown as 0.125, never rounded to 0.13)."""
        digits = 0
        for v in (self.step, self.min, self.max, self.value):
            text = f"{v:.10g}"
            if "e" not in text and "." in text:
                digits = max(digits, len(text.split(".")[1]))
        return f".{min(digits, 6)}f"

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
    limits : sequence of Limit
        Admissible ranges of key numbers (by name); a number outside its range is marked.

    Attributes
    ----------
    values : dict
        The slider values of the last update.
    result : object or None
        The last result of ``compute`` (None when it raised).
    numbers : dict
        The last key numbers (empty when ``compute`` raised).
    error : str or None
        The message of the last ``ValueError`` raised by ``compute`` or ``draw``.
    crossed : dict
        Key number -> mark, for every limit the last update crossed.
    updates : int
        How many updates were computed (a value replaced while waiting is not).
    figure : matplotlib.figure.Figure
        The picture (one figure, redrawn in place).
    """

    def __init__(self, sliders: Sequence[Slider], compute: Callable[..., Any],
                 draw: Callable[..., None], numbers: Callable[..., Mapping[str, Any]], *,
                 figsize: tuple[float, float] = (10.0, 4.0),
                 limits: Sequence[Limit] = ()) -> None:
        names = [s.name for s in sliders]
        if not names or len(set(names)) != len(names):
            raise ValueError(f"an explorer needs sliders with distinct names, got {names}")
        self.sliders = tuple(sliders)
        self.limits = tuple(limits)
        self._compute, self._draw, self._numbers = compute, draw, numbers
        self.figure = Figure(figsize=figsize, layout="constrained")
        FigureCanvasAgg(self.figure)     # a canvas that renders (no pyplot, no window)
        self.values = {s.name: s.value for s in self.sliders}
        self.result: Any = None
        self.numbers: dict[str, Any] = {}
        self.error: str | None = None
        self.crossed: dict[str, str] = {}
        self.updates = 0
        self._lock = threading.Lock()     # guards _pending, _busy, _scheduled
        self._pending: dict[str, float] | None = None
        self._busy = self._scheduled = False
        self._listeners: list[Callable[[bool], None]] = []
        self._widgets: list[Any] = []
        self._update()
        missing = [lim.key for lim in self.limits if lim.key not in self.numbers]
        if self.error is None and missing:
            raise ValueError(f"limits on {missing}: no such key number; the key numbers "
                             f"are {list(self.numbers)}")

    def slider(self, name: str) -> Slider:
        """The slider called ``name``."""
        for s in self.sliders:
            if s.name == name:
                return s
        raise ValueError(f"no slider {name!r}; the sliders are "
                         f"{', '.join(s.name for s in self.sliders)}")

    def _queue(self, values: Mapping[str, float]) -> bool:
        """Check ``values`` and merge them into the waiting values (replacing any value
        waiting for the same slider); True when no update is running or scheduled."""
        with self._lock:
            new = dict(self._pending if self._pending is not None else self.values)
            for name, v in values.items():
                new[name] = self.slider(name).check(v)
            self._pending = new
            idle = not (self._busy or self._scheduled)
            return idle

    def set(self, **values: float) -> dict[str, Any]:
        """Set slider values (by name), recompute and redraw; returns the key numbers.

        Called while an update is computing (from ``compute`` itself, or from another
        thread), the values wait, replacing any values waiting before them, and the
        running update computes them next; the call returns at once with the key numbers
        of the update that is running."""
        if self._queue(values):
            with self._lock:
                self._busy = True
            self._run_pending()
        return dict(self.numbers)

    def request(self, **values: float) -> None:
        """Like :meth:`set`, but without blocking the caller when an event loop runs
        (the kernel's, when a widget moves): the update runs when the loop is free next,
        with the newest values requested by then. Without a running loop: :meth:`set`."""
        if not self._queue(values):
            return                      # the running or scheduled update takes them
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            loop = None
        if loop is None:
            with self._lock:
                self._busy = True
            self._run_pending()
            return
        with self._lock:
            self._scheduled = True
        for f in self._listeners:
            f(True)                     # shows "computing"
        loop.call_soon(self._scheduled_run)

    def _scheduled_run(self) -> None:
        with self._lock:
            self._scheduled, self._busy = False, True
        try:
            self._run_pending()
        except Exception as exc:        # noqa: BLE001 (an event loop callback: show it)
            self.error = f"{type(exc).__name__}: {exc}"
            for f in self._listeners:
                f(False)

    def _run_pending(self) -> None:
        """Compute the waiting values until none wait (the caller set ``_busy``)."""
        try:
            while True:
                with self._lock:
                    if self._pending is None:
                        self._busy = False
                        break
                    self.values, self._pending = self._pending, None
                self._update()
        except BaseException:
            with self._lock:
                self._busy, self._pending = False, None
            raise
        for f in self._listeners:
            f(False)

    def _update(self) -> None:
        self.updates += 1
        try:
            result = self._compute(**self.values)
            self.figure.clear()         # after compute: the picture holds one update
            self.figure.set_layout_engine("constrained")
            # the labels placed once, by settle, on the final layout (as the command
            # line does): placed first by each declutter of the picture, they cost a
            # drawing of the figure more per update, undone by settle (the shaper
            # sheet's update 3 -> 2 drawings; the four-bar sheet's 0.49 -> 0.34 s of
            # CPU, best of 8, its 3 drawings kept: its legend goes out and settle draws
            # it again until its layout stands; 2026-11-30)
            with settled_later():
                self._draw(result, self.figure, **self.values)
            settle(self.figure)         # labels and legends clear of the drawing
            self.numbers = dict(self._numbers(result, **self.values))
            self.result, self.error = result, None
        except ValueError as exc:      # WorkbenchError and BalanceError are ValueErrors
            self.result, self.numbers, self.error = None, {}, str(exc)
            self.figure.clear()
            ax = self.figure.add_subplot()
            ax.set_axis_off()
            ax.text(0.5, 0.5, "cannot be solved with these values:\n" + self.error,
                    ha="center", va="center", wrap=True, transform=ax.transAxes,
                    color="tab:red")
        self.crossed = {}
        for lim in self.limits:
            mark = lim.check(self.numbers.get(lim.key))
            if mark is not None:
                self.crossed[lim.key] = mark

    def table(self) -> pd.DataFrame:
        """The key numbers as a table (text, 4 significant digits; with a ``limit``
        column when the explorer has limits: the admissible range, or the mark when the
        number crosses it), or the error message."""
        if self.error is not None:
            return pd.DataFrame({"value": [self.error]}, index=["cannot be solved"])
        table = pd.DataFrame({"value": [format_number(v) for v in self.numbers.values()]},
                             index=list(self.numbers))
        if self.limits:
            ranges = {lim.key: "ok: " + lim.describe() for lim in self.limits}
            table["limit"] = [("CROSSED, " + self.crossed[k]) if k in self.crossed
                              else ranges.get(k, "") for k in table.index]
        return table

    def png(self, dpi: float | None = 60) -> bytes:
        """The current picture as PNG bytes (to compare two states in a test; ``dpi``
        None: the figure's own)."""
        # (at the figure's own dpi, the frozen layout saved without matplotlib's layout
        # drawing before the painting one: the same bytes, a drawing less per update)
        buf = io.BytesIO()
        save_laid_out(self.figure, buf, format="png",
                      dpi=dpi if dpi is not None else self.figure.dpi)
        return buf.getvalue()

    def status(self, computing: bool = False) -> str:
        """The widget's status line as HTML: computing, the error or the crossed limits,
        then the slider values of the picture shown (``values: crank = 0.1, ...``)."""
        shown = "values: " + ", ".join(f"{k} = {format_number(v)}"
                                       for k, v in self.values.items())
        if computing:
            return f"<span>computing… (picture: {html.escape(shown)})</span>"
        if self.error is not None:
            return (f"<b style='color:#c00'>{html.escape(self.error)}</b> "
                    f"<span>({html.escape(shown)})</span>")
        if self.crossed:
            marks = "; ".join(f"{k}: {m}" for k, m in self.crossed.items())
            return (f"<b style='color:#c00'>limit crossed: {html.escape(marks)}</b> "
                    f"<span>({html.escape(shown)})</span>")
        return f"<span>{html.escape(shown)}</span>"

    def widget(self, dpi: float | None = None):
        """The sliders, the picture and the table as one ipywidgets box for JupyterLab.

        Moving a slider (on release) calls :meth:`request`: the kernel stays free to
        take the next move, and the update computes the newest value. The picture is a
        PNG image widget whose value is replaced by each update (never a stack of
        outputs), under it a status line (computing, an error, a limit crossed) and the
        table of key numbers. ``dpi`` None: the figure's own.
        """
        import ipywidgets as w

        image = w.Image(value=self.png(dpi), format="png",
                        layout=w.Layout(max_width="100%", height="auto"))
        status = w.HTML(self.status())
        table = w.HTML(self.table().to_html())

        def show(computing: bool) -> None:
            status.value = self.status(computing)
            if not computing:
                image.value = self.png(dpi)
                table.value = self.table().to_html()

        controls = []
        for s in self.sliders:
            c = w.FloatSlider(value=self.values[s.name], min=s.min, max=s.max, step=s.step,
                              description=s.label, continuous_update=False,
                              readout_format=s.readout_format,
                              style={"description_width": "initial"},
                              layout=w.Layout(width="460px"))

            def follow(change, name=s.name) -> None:
                self.request(**{name: change["new"]})

            c.observe(follow, names="value")
            self._widgets.append((c, follow))
            controls.append(c)
        self._listeners.append(show)
        box = w.VBox([*controls, image, status, table])
        self._widgets += [(image, None), (status, None), (table, None), (box, None)]
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
