"""The picture standard, measured on a drawn figure: what :func:`audit` reports and what
the tests hold every picture of the sheets, the command line and the reports to.

- at least 150 dpi (:data:`LOWEST_DPI`) and no text under 10 pt
  (:data:`~kinetostatics.plot.style.SMALLEST_FONT`);
- no collision (:func:`~kinetostatics.plot.collisions`);
- at most one label taken off the drawing ("labels not placed", :func:`declutter`);
- every text in the notation of docs/notation.md (:func:`notation_problems`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.text import Text

from .collide import collisions
from .notation import notation_problems
from .place import UNPLACED_TITLE
from .style import SMALLEST_FONT, laid_out, measured_once, undrawn_ticks

__all__ = ["LOWEST_DPI", "PictureAudit", "audit", "figure_texts", "not_placed"]

#: The lowest resolution of a picture a student or a report reader sees.
LOWEST_DPI = 150.0


@dataclass
class PictureAudit:
    """What :func:`audit` measured on one figure."""

    dpi: float
    smallest_font: float
    collisions: list[tuple[str, str]] = field(default_factory=list)
    not_placed: list[str] = field(default_factory=list)
    notation: list[tuple[str, str]] = field(default_factory=list)

    @property
    def problems(self) -> list[str]:
        """One line per breach of the standard (empty: the figure meets it)."""
        out = []
        if self.dpi < LOWEST_DPI:
            out.append(f"{self.dpi:g} dpi (at least {LOWEST_DPI:g})")
        if self.smallest_font < SMALLEST_FONT:
            out.append(f"text of {self.smallest_font:g} pt (at least {SMALLEST_FONT:g})")
        out += [f"collision: {a!r} on {b!r}" for a, b in self.collisions]
        if len(self.not_placed) > 1:
            out.append(f"{len(self.not_placed)} labels not placed: {self.not_placed}")
        out += [f"notation: {t!r}: {why}" for t, why in self.notation]
        return out


def figure_texts(fig: Figure) -> list[str]:
    """Every text a reader sees on the figure: titles, axis and tick labels, labels,
    legend entries and titles (hidden, empty and undrawn tick labels left out), on the
    figure as laid out last (:func:`~kinetostatics.plot.style.laid_out`: a finished
    figure measured before is not drawn again)."""
    laid_out(fig)
    undrawn = undrawn_ticks(fig)
    out = []
    for t in fig.findobj(Text):
        if id(t) in undrawn or not t.get_visible() or not t.get_text().strip():
            continue
        if t.axes is not None and not t.axes.get_visible():
            continue
        out.append(t.get_text())
    return out


def not_placed(fig: Figure) -> list[str]:
    """The labels :func:`~kinetostatics.plot.declutter` took off the drawing."""
    return [t.get_text() for lg in fig.findobj(Legend)
            if lg.get_title().get_text() == UNPLACED_TITLE for t in lg.get_texts()]


def audit(fig: Figure, dpi: float | None = None) -> PictureAudit:
    """Measure one figure against the picture standard.

    Parameters
    ----------
    fig : Figure
        A finished figure (after :func:`~kinetostatics.plot.settle` where it has one).
    dpi : float, optional
        The resolution it is written at (default: the figure's own).

    Returns
    -------
    PictureAudit
        The measures; ``.problems`` lists the breaches.
    """
    if not hasattr(fig.canvas, "get_renderer"):     # a bare Figure(): an off-screen canvas
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        FigureCanvasAgg(fig)
    with measured_once(fig):            # (the texts and the collisions: one drawing)
        texts = figure_texts(fig)
        hits = collisions(fig)
    sizes = [t.get_fontsize() for t in fig.findobj(Text)
             if t.get_visible() and t.get_text().strip() and t.get_text() in texts]
    return PictureAudit(dpi=float(dpi if dpi is not None else fig.dpi),
                        smallest_font=min(sizes, default=SMALLEST_FONT),
                        collisions=hits, not_placed=not_placed(fig),
                        notation=notation_problems(texts))
