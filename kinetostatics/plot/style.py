"""How a picture reads: the projector style (one call away) and the check that no two
labels of a figure overlap.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.text import Text

__all__ = ["PROJECTOR", "declutter", "overlapping_texts", "projector"]

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

    def __init__(self, **overrides) -> None:
        style = {**PROJECTOR, **overrides}
        self._old = {k: mpl.rcParams[k] for k in style}
        mpl.rcParams.update(style)

    def restore(self) -> None:
        """Put back the settings from before the call."""
        mpl.rcParams.update(self._old)

    def __enter__(self) -> projector:
        return self

    def __exit__(self, *exc) -> None:
        self.restore()


def _undrawn_ticks(fig: Figure) -> set[int]:
    """Tick labels matplotlib keeps but does not draw (ticks outside the view)."""
    out = set()
    for ax in fig.findobj(Axes):       # insets included
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            tol = 1e-9 * (hi - lo)
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                if not lo - tol <= tick.get_loc() <= hi + tol:
                    out.update((id(tick.label1), id(tick.label2)))
    return out


def _boxes(fig: Figure, renderer) -> list[tuple[Text | Legend, object]]:
    """(text, window extent) of every drawn, non-empty text of the figure; a legend
    counts as one box (its entries are laid out by matplotlib and never collide)."""
    out = []
    legends = fig.findobj(Legend)
    inside = {id(t) for lg in legends for t in lg.findobj(Text)} | _undrawn_ticks(fig)
    for lg in legends:
        if lg.get_visible():
            out.append((lg, lg.get_window_extent(renderer)))
    for t in fig.findobj(Text):
        if id(t) in inside or not t.get_visible() or not t.get_text().strip():
            continue
        if t.axes is not None and not t.axes.get_visible():
            continue
        bb = t.get_window_extent(renderer)
        if bb.width > 0 and bb.height > 0:
            out.append((t, bb))
    return out


def overlapping_texts(fig: Figure, tolerance: float = 1.0) -> list[tuple[str, str]]:
    """The pairs of labels of a figure whose boxes overlap on the drawn figure.

    Every visible text is taken (titles, axis and tick labels, annotations, legends as
    whole boxes), after ``fig.canvas.draw()`` so that the layout is final. A label cut
    by the edge of the figure is reported too, paired with ``"outside the figure"``.

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
    fig.canvas.draw()
    boxes = _boxes(fig, fig.canvas.get_renderer())
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


_DIRECTIONS = np.deg2rad(np.arange(0.0, 360.0, 30.0))
_DISTANCES = (6.0, 12.0, 20.0, 30.0, 42.0, 56.0)
_NEAR = 20.0        # points: how far a label may go to find a place off the arrows


def _arrow_paths(fig: Figure) -> list:
    """The drawn arrows of the annotations of a figure, as paths in pixels."""
    out = []
    for ax in fig.findobj(Axes):       # insets included
        for t in ax.texts:
            patch = getattr(t, "arrow_patch", None)
            if patch is not None and patch.get_visible():
                out.append(patch.get_transform().transform_path(patch.get_path()))
    return out


def declutter(ax: Axes, texts: Sequence[Text], rounds: int = 6) -> None:
    """Move annotations (offset in points from their anchor) until no two labels of the
    figure overlap, and, where the room allows, none lies on an arrow.

    Each label that collides is tried around its anchor in twelve directions at growing
    distances; the first place clear of every other label and of the arrows wins (up to
    20 points away), else the nearest place clear of the labels, else the one farthest
    from them. The figure is
    drawn between rounds so that a constrained layout settles.

    Parameters
    ----------
    ax : Axes
        The Axes of the annotations (its figure is drawn).
    texts : sequence of Text
        Annotations with ``textcoords="offset points"``, in order of importance.
    rounds : int
        How many times to draw and re-check.
    """
    fig = ax.figure
    movable = [t for t in texts if t.get_text().strip()]
    ids = {id(t) for t in movable}
    for _ in range(rounds):
        fig.canvas.draw()
        r = fig.canvas.get_renderer()
        fixed = [bb for t, bb in _boxes(fig, r) if id(t) not in ids]
        fixed += [child.get_window_extent(r) for child in ax.child_axes]    # insets
        arrows = _arrow_paths(fig)
        placed: list = []
        moved = False

        frame = ax.get_window_extent(r)

        def clash(bb, placed=placed, fixed=fixed, frame=frame):
            inside = frame.x0 <= bb.x0 and bb.x1 <= frame.x1 and frame.y0 <= bb.y0 and \
                bb.y1 <= frame.y1
            return not inside or any(bb.overlaps(o) for o in placed) or \
                any(bb.overlaps(o) for o in fixed)

        def on_arrow(bb, arrows=arrows):
            return any(p.intersects_bbox(bb, filled=False) for p in arrows)

        for t in movable:
            bb = t.get_window_extent(r).padded(1.0)
            if not clash(bb):
                placed.append(bb)
                continue
            moved = True
            best, second, far = None, None, (-1.0, None)
            for dist in _DISTANCES:
                for ang in _DIRECTIONS:
                    c, s_ = np.cos(ang), np.sin(ang)
                    t.xyann = (dist * c, dist * s_)
                    t.set_ha("left" if c > 0.3 else "right" if c < -0.3 else "center")
                    t.set_va("bottom" if s_ > 0.3 else "top" if s_ < -0.3 else "center")
                    bb = t.get_window_extent(r).padded(1.0)
                    if not clash(bb):
                        if not on_arrow(bb):
                            best = (t.xyann, t.get_ha(), t.get_va(), bb)
                            break
                        second = second or (t.xyann, t.get_ha(), t.get_va(), bb)
                    else:
                        gap = min((_gap(bb, o) for o in placed + fixed), default=np.inf)
                        if gap > far[0]:
                            far = (gap, (t.xyann, t.get_ha(), t.get_va(), bb))
                if best is not None or (second is not None and dist >= _NEAR):
                    break       # near its anchor, even on an arrow, rather than far away
            xy, ha, va, bb = best or second or far[1]
            t.xyann = xy
            t.set_ha(ha)
            t.set_va(va)
            placed.append(bb)
        if not moved:
            return


def _gap(a, b) -> float:
    """A measure of how far apart two boxes are (negative when they overlap)."""
    dx = max(b.x0 - a.x1, a.x0 - b.x1)
    dy = max(b.y0 - a.y1, a.y0 - b.y1)
    return float(max(dx, dy))
