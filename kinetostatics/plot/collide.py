"""Collisions on a drawn figure: a label over another label, over a link or curve, over
an arrow, or a legend over the data. Measured on the rendered figure (window extents of
the texts against each other and against the drawn paths, all in pixels).
"""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.legend import Legend
from matplotlib.patches import Arc, FancyArrowPatch
from matplotlib.path import Path
from matplotlib.text import Annotation, Text

from .style import drawn_extent, overlapping_texts

__all__ = ["GUIDE", "collisions", "drawn_paths", "extent_rows", "label_boxes", "meets",
           "overlapping_rows"]

#: The gid of a faint guide line (as a grid line: labels and legends may cross it).
GUIDE = "guide"


def _shrunk(bb, tol: float):
    return bb.padded(-tol)


def drawn_paths(ax: Axes, skip=()) -> list[tuple[str, Path, int]]:
    """(name, path in pixels, id of the artist) of every drawn line, marker set and
    arrow of an Axes (the artists whose ids are in ``skip`` left out).

    Lines are taken with their markers (a marker-only line counts by its points); the
    arrows of annotations and free arrow patches by their drawn outline. Grid lines,
    spines and tick marks are not data and are left out, and so are faint guide lines
    drawn like a grid line (``gid="guide"``: the axes through the origin of a vector
    diagram).
    """
    out: list[tuple[str, Path, int]] = []
    for ln in ax.get_lines():
        if not ln.get_visible() or len(ln.get_xdata()) == 0 or id(ln) in skip or \
                ln.get_gid() == GUIDE:
            continue
        name = ln.get_label() if not ln.get_label().startswith("_") else "a line"
        xy = ln.get_transform().transform(np.column_stack(
            [np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)]))
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        if len(xy) == 0:
            continue
        if ln.get_linestyle() not in ("None", "none", "", " ") and len(xy) > 1:
            out.append((name, Path(xy), id(ln)))
        if ln.get_marker() not in (None, "None", "none", "", " "):
            for p in xy:            # a marker: a small square around its point
                r = 0.5 * ln.get_markersize() * ax.figure.dpi / 72.0
                out.append((name, Path.unit_rectangle().transformed(
                    _box_transform(p, r)), id(ln)))
    for t in ax.texts:
        patch = getattr(t, "arrow_patch", None)
        if isinstance(t, Annotation) and patch is not None and patch.get_visible() and \
                t.get_visible() and id(patch) not in skip:
            out.append((f"arrow of '{t.get_text()}'" if t.get_text().strip() else "an arrow",
                        patch.get_transform().transform_path(patch.get_path()), id(patch)))
    for p in ax.patches:
        if isinstance(p, FancyArrowPatch | Arc) and p.get_visible() and id(p) not in skip:
            name = "an arc" if isinstance(p, Arc) else "an arrow"
            out.append((name, p.get_transform().transform_path(p.get_path()), id(p)))
    return out


def _box_transform(p, r):
    from matplotlib.transforms import Affine2D
    return Affine2D().scale(2 * r).translate(p[0] - r, p[1] - r)


def label_boxes(ax: Axes, renderer) -> list[tuple[Text, object]]:
    """(text, extent in pixels) of the drawn, non-empty texts inside an Axes' data area
    (annotations and ``ax.text`` labels; titles and tick labels are outside the data)."""
    out = []
    for t in ax.texts:
        bb = drawn_extent(t, renderer)
        if bb is not None:
            out.append((t, bb))
    return out


def collisions(fig: Figure, tolerance: float = 1.0) -> list[tuple[str, str]]:
    """Every collision on a drawn figure.

    - two labels overlap, or a label is cut by the figure's edge
      (:func:`~kinetostatics.plot.overlapping_texts`);
    - a label in the data area lies on a line (a link, a curve, a guide), a marker or an
      arrow other than its own (its box, shrunk by ``tolerance`` pixels, meets the path);
    - a legend inside an Axes covers a curve, a marker or an arrow of that Axes.

    Parameters
    ----------
    fig : Figure
        The figure, laid out and drawn here if it is not yet.
    tolerance : float
        Pixels by which a box may touch a path before it counts.

    Returns
    -------
    list of (str, str)
        The two names of each collision; empty when the figure is clear.
    """
    hits = list(overlapping_texts(fig, tolerance))
    r = fig.canvas.get_renderer()
    for ax in fig.findobj(Axes):
        if not ax.get_visible():
            continue
        paths = drawn_paths(ax)
        # each path's extent once (not once per label: a fifth of the measure's time)
        rows = extent_rows([p.get_extents() for _n, p, _s in paths])
        for t, bb in label_boxes(ax, r):
            own = id(getattr(t, "arrow_patch", None))
            box = _shrunk(bb, tolerance)
            for k in np.flatnonzero(overlapping_rows(rows, box)):
                name, path, src = paths[k]
                if src != own and meets(path, box):
                    hits.append((t.get_text(), name))
        lg = ax.get_legend()
        if lg is not None and lg.get_visible() and _inside(lg, ax, r):
            box = _shrunk(lg.get_window_extent(r), tolerance)
            for k in np.flatnonzero(overlapping_rows(rows, box)):
                if meets(paths[k][1], box):
                    hits.append(("legend", paths[k][0]))
    return hits


def _inside(lg: Legend, ax: Axes, r) -> bool:
    """A legend whose box lies (partly) over the data area of its Axes."""
    return lg.get_window_extent(r).overlaps(ax.get_window_extent(r))


def extent_rows(boxes) -> np.ndarray:
    """The (x0, y0, x1, y1) rows of boxes, each ordered low to high (as
    :meth:`Bbox.overlaps` orders them)."""
    e = np.array([b.extents for b in boxes], dtype=float).reshape(-1, 4)
    return np.column_stack([np.minimum(e[:, 0], e[:, 2]), np.minimum(e[:, 1], e[:, 3]),
                            np.maximum(e[:, 0], e[:, 2]), np.maximum(e[:, 1], e[:, 3])])


def overlapping_rows(rows: np.ndarray, box) -> np.ndarray:
    """Which rows of :func:`extent_rows` overlap ``box``: :meth:`Bbox.overlaps` for all
    at once (a NaN overlaps nothing)."""
    (x0, y0, x1, y1), = extent_rows([box])
    return (rows[:, 0] <= x1) & (x0 <= rows[:, 2]) & (rows[:, 1] <= y1) & (y0 <= rows[:, 3])


def meets(path: Path, box) -> bool:
    """A path whose extent overlaps the box (:func:`overlapping_rows`) crosses the box
    or lies (partly) inside it (``intersects_bbox`` alone is not reliable on closed
    arrow paths)."""
    if path.intersects_bbox(box, filled=False):
        return True
    v = path.vertices
    return bool(np.any((v[:, 0] > box.x0) & (v[:, 0] < box.x1) &
                       (v[:, 1] > box.y0) & (v[:, 1] < box.y1)))
