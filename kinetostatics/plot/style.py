"""How a picture reads: the lecture-room style of every picture (:func:`lecture_style`,
what the command line and the sheets draw with), the larger projector style (one call
away) and the check that no two labels of a figure overlap.
"""

from __future__ import annotations

import contextlib
import functools
import weakref
from collections.abc import Iterator

import matplotlib as mpl
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.backend_bases import RendererBase
from matplotlib.backends.backend_agg import FigureCanvasAgg, RendererAgg, get_hinting_flag
from matplotlib.figure import Figure
from matplotlib.font_manager import fontManager, get_font
from matplotlib.layout_engine import PlaceHolderLayoutEngine
from matplotlib.legend import Legend
from matplotlib.mathtext import MathTextParser
from matplotlib.text import Annotation, Text

__all__ = ["LECTURE", "PROJECTOR", "SMALLEST_FONT", "FigureWalk", "drawn_extent", "figure_boxes",
           "lay_out", "laid_out", "lecture_style", "measured_once", "overlapping_texts",
           "projector", "save_laid_out", "text_extent", "undrawn_ticks"]

#: The smallest font of a picture, in points at the figure's printed size.
SMALLEST_FONT = 10.0

#: The default of the command line and the sheets: 150 dpi, no label under 10 pt.
LECTURE = {
    "figure.dpi": 150, "savefig.dpi": 150, "font.size": 11, "axes.titlesize": 11,
    "axes.labelsize": 11, "xtick.labelsize": 10, "ytick.labelsize": 10,
    "legend.fontsize": 10, "legend.title_fontsize": 10, "figure.titlesize": 12,
    "lines.linewidth": 1.8,
}

PROJECTOR = {
    "figure.dpi": 150, "savefig.dpi": 150, "font.size": 13, "axes.titlesize": 14,
    "axes.labelsize": 13, "xtick.labelsize": 12, "ytick.labelsize": 12,
    "legend.fontsize": 11, "lines.linewidth": 2.2, "axes.linewidth": 1.2,
}


class projector:
    """Pictures for a projector or a board: larger fonts, thicker lines, 150 dpi.

    One call: ``plot.projector()`` switches every later figure to the style (in a
    notebook, for the rest of the session; ``.restore()`` switches back); or
    ``with plot.projector(): fig = plot.overview(sol)`` for the figures made inside
    only. Any ``rcParams`` key may be overridden, e.g. ``projector(**{"font.size": 16})``.
    """

    def __init__(self, _base: dict | None = PROJECTOR, **overrides) -> None:
        style = {**(_base or {}), **overrides}
        self._old = {k: mpl.rcParams[k] for k in style}
        mpl.rcParams.update(style)

    def restore(self) -> None:
        """Put back the settings from before the call."""
        mpl.rcParams.update(self._old)

    def __enter__(self) -> projector:
        return self

    def __exit__(self, *exc) -> None:
        self.restore()


def lecture_style(dpi: float | None = None, **overrides) -> projector:
    """The lecture-room style: 150 dpi (or ``dpi``), labels of at least 10 pt.

    What ``python -m kinetostatics`` draws with and what the sheets switch on in their
    first cell. Like :class:`projector`: one call switches every later figure (until
    ``.restore()``), or ``with plot.lecture_style(): ...`` for the figures made inside.

    Parameters
    ----------
    dpi : float, optional
        Dots per inch of the figures and of the saved files (at least 150 is
        advised for a projector); default 150.
    **overrides
        Any other ``rcParams`` key, e.g. ``**{"font.size": 12}``.

    Returns
    -------
    projector
        The switch, with ``restore()`` and the context-manager protocol.
    """
    style = dict(LECTURE)
    if dpi is not None:
        style["figure.dpi"] = style["savefig.dpi"] = float(dpi)
    return projector(**{**style, **overrides}, _base=None)


def lay_out(fig: Figure) -> RendererBase:
    """Draw the figure without rasterising it: every layout (constrained layout, text
    extents, legend places, annotation positions) is final, no pixel is painted.

    The measures and the label placer need the layout only; painting the glyphs and
    paths cost about half of each draw. Saving the figure paints it as before.

    Returns
    -------
    RendererBase
        The canvas's renderer (the one the extents are measured with).
    """
    shared_caches(fig)
    fig.draw_without_rendering()
    return fig.canvas.get_renderer()


class _SharedMathParser(MathTextParser):
    """Matplotlib's parser of mathtext ("path" output, Agg's), with one cache for every
    figure: an Agg renderer has a parser of its own and matplotlib's cache holds 50
    results of all parsers, so each figure parsed each of its labels again (a sixth of
    a command-line picture's time, 2026-11-30). The results depend on the text, dpi,
    font, antialiasing and hinting only (the cache's key), never on the renderer."""

    _parse_cached = getattr(MathTextParser._parse_cached, "__wrapped__", None)
    if _parse_cached is not None:
        _parse_cached = functools.lru_cache(2048)(_parse_cached)


_MATH = _SharedMathParser("path")


class _Renderer(RendererAgg):
    """Agg's renderer with the mathtext parser every figure shares (its results are the
    same; parsed once per session instead of once per figure) and each font's heights
    looked up once (:func:`_font_heights`)."""

    def __init__(self, width, height, dpi) -> None:
        super().__init__(width, height, dpi)
        if _SharedMathParser._parse_cached is not None:
            self.mathtext_parser = _MATH

    def _get_font_height_metrics(self, prop):
        return _font_heights(prop.copy(), self.dpi)

    def get_text_width_height_descent(self, s, prop, ismath):
        """Agg's measure of a text; a plain text's looked up once per session
        (:func:`_plain_text_size`), mathtext and TeX as Agg measures them."""
        if ismath:
            return super().get_text_width_height_descent(s, prop, ismath)
        rc = mpl.rcParams
        fonts = tuple(fontManager._find_fonts_by_props(prop))
        return _plain_text_size(s, fonts, prop.get_size_in_points(), self.dpi,
                                rc["text.hinting"], rc["text.kerning_factor"],
                                rc["font.enable_last_resort"])


class _Canvas(FigureCanvasAgg):
    """Agg's off-screen canvas, drawing with :class:`_Renderer` (kept while the size
    and dpi stay, as Agg keeps its own)."""

    def get_renderer(self) -> RendererAgg:
        w, h = self.get_width_height(physical=True)
        key = w, h, self.figure.dpi
        if self._lastKey != key:
            self.renderer = _Renderer(w, h, self.figure.dpi)
            self._lastKey = key
        return self.renderer


def shared_caches(fig: Figure) -> None:
    """A figure on Agg's own canvas (the command line's, the notebooks' inline
    pictures, the tests') is moved to :class:`_Canvas` (same pixels, its pyplot
    manager kept)."""
    old = fig.canvas
    if type(old) is FigureCanvasAgg:
        new = _Canvas(fig)
        new.manager = old.manager
        if old.manager is not None:
            old.manager.canvas = new


@functools.lru_cache(512)
def _font_heights(prop, dpi: float) -> tuple:
    """(ascent, descent, line gap) in pixels of the font of ``prop`` at ``dpi``: what
    matplotlib's Text measures from the font's tables at every text's layout when its
    renderer has no ``_get_font_height_metrics`` (Agg's has none), looked up once (the
    font lookups were a tenth of a picture's time, 2026-11-30). The same tables, the same
    arithmetic (matplotlib 3.11's ``Text._get_layout``)."""
    font = get_font(fontManager._find_fonts_by_props(prop))
    for table_name, gap, ascent, descent in (
            ("OS/2", "sTypoLineGap", "sTypoAscender", "sTypoDescender"),
            ("hhea", "lineGap", "ascent", "descent")):
        table = font.get_sfnt_table(table_name)
        if table is None:
            continue
        units_per_em = font.get_sfnt_table("head")["unitsPerEm"]
        scale = 1 / units_per_em * prop.get_size_in_points() * dpi / 72
        return table[ascent] * scale, -table[descent] * scale, table[gap] * scale
    return None, None, None


@functools.lru_cache(4096)
def _plain_text_size(s: str, fonts: tuple, size: float, dpi: float, *_rc) -> tuple:
    """(width, height, descent) in pixels of a plain text in ``fonts`` at ``size`` points
    and ``dpi``: what Agg measures at each figure's first layout of it (each figure's
    renderer keeps its own measures: a picture's tick labels, axis labels and titles
    were measured again by every figure), measured once. The same calls as Agg's
    ``get_text_width_height_descent`` (matplotlib 3.11); ``_rc``: the settings they read
    (hinting, kerning factor, last-resort font), part of the key."""
    font = get_font(list(fonts))
    font.clear()
    font.set_size(size, dpi)
    font.set_text(s, 0.0, flags=get_hinting_flag())
    w, h = font.get_width_height()      # width and height of the unrotated string
    d = font.get_descent()
    return w / 64.0, h / 64.0, d / 64.0


def laid_out(fig: Figure) -> RendererBase:
    """:func:`lay_out`, skipped where drawing again would change nothing: the figure was
    drawn and no artist changed since (matplotlib's ``stale``), and no layout engine moves
    its Axes at each drawing (none, or frozen by ``settle``). The measures read a finished
    figure: laid out once, not once per measure (an audit measured it twice); a figure
    just settled or saved (:func:`save_laid_out`) counts as drawn."""
    engine = fig.get_layout_engine()
    frozen = engine is None or isinstance(engine, PlaceHolderLayoutEngine)
    if fig.stale or not (frozen or fig in _MEASURED):
        return lay_out(fig)
    shared_caches(fig)      # (a figure put on Agg's own canvas since: the shared measures)
    return fig.canvas.get_renderer()


# the figures being measured (:func:`measured_once`)
_MEASURED: weakref.WeakSet = weakref.WeakSet()


@contextlib.contextmanager
def measured_once(fig: Figure) -> Iterator[None]:
    """Several measures of one figure on one drawing: inside, :func:`laid_out` draws the
    figure again only where an artist changed since (``stale``), also where a layout
    engine (constrained) would move its Axes at each drawing.

    An audit of a figure the constrained layout still lays out (a sheet's picture before
    the inline backend shows it) drew it twice, for its texts and for its collisions, at
    the same places (the audits of 8 sheets' 37 pictures the same; the sheets' runs 0.2-1.7 s
    of CPU less in 7 of 8, one run each, 2026-11-30).

    Parameters
    ----------
    fig : Figure
        The figure, laid out here if it is not yet (:func:`laid_out`).
    """
    laid_out(fig)
    _MEASURED.add(fig)
    try:
        yield
    finally:
        _MEASURED.discard(fig)


def save_laid_out(fig: Figure, fname, **kwargs) -> None:
    """``fig.savefig(fname, **kwargs)``, without matplotlib's layout drawing before the
    painting one where the layout is frozen (``settle``'s placeholder engine, whose
    layout is no layout) and the figure is saved at its own dpi.

    matplotlib draws a figure with a layout engine once more before painting it, so that
    a constrained layout is final; a frozen one is final already, and the painting
    drawing places the labels, ticks and legends as that drawing did (the same PNG bytes
    for every picture of ``solve --plot`` and ``demo`` of the bundled scenes; the
    four-bar's twelve pictures saved in 2.23 s of CPU instead of 2.82 s, 2026-11-30)."""
    engine = fig.get_layout_engine()
    unframed = not (mpl.rcParams["figure.autolayout"] or
                    mpl.rcParams["figure.constrained_layout.use"])
    if not (unframed and isinstance(engine, PlaceHolderLayoutEngine) and
            kwargs.get("dpi", fig.dpi) == fig.dpi):
        fig.savefig(fname, **kwargs)
        return
    fig.set_layout_engine(None)     # (no engine: the rcParams ask for no layout)
    try:
        fig.savefig(fname, **kwargs)
    finally:
        fig.set_layout_engine(engine)
    # as saved: the drawing just made is the figure's (savefig's colours put back mark it
    # stale); a measure after the save reads it without drawing it again
    fig.stale = False


def undrawn_ticks(fig: Figure, walk: FigureWalk | None = None) -> set[int]:
    """Tick labels matplotlib keeps but does not draw (ticks outside the view); ``walk``:
    the figure's artists as :class:`FigureWalk` found them (else walked here)."""
    walk = FigureWalk(fig) if walk is None else walk
    out = set()
    for ax in walk.of_type(Axes):       # insets included
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            tol = 1e-9 * (hi - lo)
            for tick in walk.ticks(axis):
                if not lo - tol <= tick.get_loc() <= hi + tol:
                    out.update((id(tick.label1), id(tick.label2)))
    return out


class FigureWalk:
    """Every artist of a figure in ``fig.findobj()``'s order, found in one walk, with each
    axis' ticks as the walk met them (what ``get_major_ticks() + get_minor_ticks()``
    give: an axis' children; each call asks the tick locators again, and three searches
    of the figure and the ticks' own asked them four times per axis, two fifths of a
    label placing's time, 2026-11-30)."""

    def __init__(self, fig: Figure) -> None:
        self.artists: list = []
        self._ticks: dict[int, list] = {}
        self._visit(fig)

    def _visit(self, artist) -> None:
        children = artist.get_children()
        if isinstance(artist, Axis):            # [label, offsetText, *major, *minor]
            self._ticks[id(artist)] = children[2:]
        for child in children:
            self._visit(child)
        self.artists.append(artist)             # (after its children, as findobj)

    def of_type(self, kind: type) -> list:
        """The artists of a type, as ``fig.findobj(kind)`` lists them."""
        return [a for a in self.artists if isinstance(a, kind)]

    def ticks(self, axis: Axis) -> list:
        """The major and minor ticks of an axis (asked afresh if the walk did not meet
        it)."""
        found = self._ticks.get(id(axis))
        return found if found is not None else axis.get_major_ticks() + axis.get_minor_ticks()


def text_extent(t: Text, renderer):
    """The window extent of a text's letters (an annotation's arrow or leader left
    out).

    An annotation's positions are worked out again on the renderer (what drawing it
    does): on a figure drawn and unchanged since, the same positions, so the figure
    stays as drawn (not ``stale``: a measure after another, :func:`laid_out`, does not
    draw it again)."""
    if isinstance(t, Annotation):
        fig = t.get_figure(root=True)
        drawn = fig is not None and not fig.stale
        t.update_positions(renderer)
        if drawn:
            fig.stale = False
    return Text.get_window_extent(t, renderer)


def drawn_extent(t: Text, renderer):
    """The extent of a visible text with letters in it (:func:`text_extent`), or None for
    a hidden, blank or empty one."""
    if not t.get_visible() or not t.get_text().strip():
        return None
    bb = text_extent(t, renderer)
    return bb if bb.width > 0 and bb.height > 0 else None


def figure_boxes(fig: Figure, renderer) -> list[tuple[Text | Legend, object]]:
    """(text, window extent) of every drawn, non-empty text of the figure; a legend
    counts as one box (its entries are laid out by matplotlib and never collide)."""
    out = []
    walk = FigureWalk(fig)
    legends = walk.of_type(Legend)
    inside = {id(t) for lg in legends for t in lg.findobj(Text)} | undrawn_ticks(fig, walk)
    for lg in legends:
        if lg.get_visible():
            out.append((lg, lg.get_window_extent(renderer)))
    for t in walk.of_type(Text):
        if id(t) in inside or (t.axes is not None and not t.axes.get_visible()):
            continue
        bb = drawn_extent(t, renderer)
        if bb is not None:
            out.append((t, bb))
    return out


def overlapping_texts(fig: Figure, tolerance: float = 1.0) -> list[tuple[str, str]]:
    """The pairs of labels of a figure whose boxes overlap on the drawn figure.

    Every visible text is taken (titles, axis and tick labels, annotations, legends as
    whole boxes), after the figure is laid out (:func:`lay_out`) so that the layout is
    final. A label cut by the edge of the figure is reported too, paired with
    ``"outside the figure"``.

    Parameters
    ----------
    fig : Figure
    tolerance : float
        Pixels by which two boxes may touch before they count as overlapping.

    Returns
    -------
    list of (str, str)
        The texts of each overlapping pair (or a text and ``"outside the figure"``);
        empty when every label stands clear.
    """
    boxes = figure_boxes(fig, laid_out(fig))
    hits = []
    page = fig.bbox.padded(tolerance)
    for t, bb in boxes:
        if not (page.x0 <= bb.x0 and bb.x1 <= page.x1 and page.y0 <= bb.y0 and
                bb.y1 <= page.y1):
            hits.append((t.get_text() if isinstance(t, Text) else "legend",
                         "outside the figure"))
    name = {Legend: lambda a: "legend"}
    for k, (ta, a) in enumerate(boxes):
        a = a.padded(-tolerance)
        for tb, b in boxes[k + 1:]:
            if a.overlaps(b.padded(-tolerance)):
                hits.append(tuple(name.get(type(t), Text.get_text)(t) for t in (ta, tb)))
    return hits
