"""Labels placed clear of each other, of the links and curves, and of the arrows.

Each label is an annotation written at an offset (in points) from its anchor. It is
tried around its anchor in sixteen directions at growing distances, on the drawn
figure (pixels): the first place where its box meets no other label, no line, no
marker and no arrow wins; a label moved farther than a short step gets a thin leader
to its anchor. A label with no free place within reach is taken off the drawing and
named in a legend below the figure ("labels not placed"), never printed over another.
"""

from __future__ import annotations

import weakref
from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.layout_engine import PlaceHolderLayoutEngine
from matplotlib.legend import Legend
from matplotlib.lines import Line2D
from matplotlib.patches import FancyArrowPatch
from matplotlib.path import Path
from matplotlib.text import Annotation, Text
from matplotlib.transforms import Bbox

from ..common.angles import radian_column
from .collide import drawn_paths, extent_rows, meets
from .style import drawn_extent, figure_boxes, lay_out, text_extent

__all__ = ["UNPLACED_TITLE", "declutter", "settle", "settled_later"]

_DIRECTIONS = radian_column(np.array([45, 135, 315, 225, 90, 270, 0, 180,
                                   22.5, 67.5, 112.5, 157.5, 202.5, 247.5, 292.5, 337.5]))
_UNITS = [np.array([np.cos(ang), np.sin(ang)]) for ang in _DIRECTIONS]
_DISTANCES = (3.0, 6.0, 10.0, 15.0, 21.0, 28.0, 36.0, 46.0, 58.0, 72.0)      # points
# the 160 tries in their order of preference: distance by distance, each direction
_TRY_UNITS = np.tile(np.array(_UNITS), (len(_DISTANCES), 1))
_TRY_DISTANCES = np.repeat(np.array(_DISTANCES), len(_UNITS))
_LEADER = 12.0          # points: a label farther than this from its anchor gets a leader
_PAD = 2.0              # pixels of free room around a placed label
# a leader: matplotlib's plain annotation arrow ("simple", a head of nothing), a 0.7 pt line
_LEADER_PROPS = {"width": 0.01, "headwidth": 0.01, "headlength": 0.01, "shrink": 0.0}
_LEADERS: weakref.WeakSet[Annotation] = weakref.WeakSet()    # labels with a leader
# the labels declutter keeps per Axes, placed again by settle
_KEPT: weakref.WeakKeyDictionary[Axes, list[Text]] = weakref.WeakKeyDictionary()
# inside settled_later: how many are open (declutter then only keeps the labels)
_LATER = [0]


def _anchor(t: Annotation) -> np.ndarray | None:
    """The anchor of an annotation in pixels (data or axes-fraction anchors only)."""
    ax = t.axes
    if t.xycoords == "data":
        return ax.transData.transform(t.xy)
    if t.xycoords == "axes fraction":
        return ax.transAxes.transform(t.xy)
    return None


def _tries(anchor: np.ndarray, scale: float, w: float, h: float) -> tuple[np.ndarray,
                                                                         np.ndarray]:
    """The offsets (pixels) of all the tries of a w x h label at ``anchor`` and their
    boxes, padded by ``_PAD``, as (x0, y0, x1, y1) rows, in order of preference.

    A box's alignment follows its offset's direction (left, right or centred, bottom, top
    or centred, as :func:`_place_one` sets the label's); the arithmetic is that of a
    ``Bbox`` built at the offset and then ``padded``, in the same order (the same floats
    as when each try was built alone)."""
    off = (_TRY_DISTANCES * scale)[:, None] * _TRY_UNITS          # dist * scale * unit
    cs = off / np.hypot(off[:, 0], off[:, 1])[:, None]
    f = np.where(cs > 0.3, 0.0, np.where(cs < -0.3, 1.0, 0.5))   # alignment fractions
    x0 = anchor[0] + off[:, 0] - f[:, 0] * w
    y0 = anchor[1] + off[:, 1] - f[:, 1] * h
    return off, np.column_stack([x0 + -_PAD, y0 + -_PAD, (x0 + w) + _PAD, (y0 + h) + _PAD])


def _overlaps(rows: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(boxes x rows) which rows of :func:`extent_rows` overlap which boxes:
    :func:`overlapping_rows` for many boxes at once."""
    return ((rows[:, 0] <= boxes[:, 2:3]) & (boxes[:, 0:1] <= rows[:, 2]) &
            (rows[:, 1] <= boxes[:, 3:4]) & (boxes[:, 1:2] <= rows[:, 3]))


class _Shown:
    """The boxes of a figure's texts on one drawing (:func:`figure_boxes`), shared by the
    rooms of its Axes: measured once per drawing, and again only for the labels an Axes
    placed (measuring every text of the figure for each Axes was a third of the
    placing's time, 2026-11-30)."""

    def __init__(self, fig, renderer) -> None:
        self.pairs = figure_boxes(fig, renderer)

    def others(self, ids: set[int]) -> list:
        """The boxes of the texts whose ids are not in ``ids``."""
        return [bb for t, bb in self.pairs if id(t) not in ids]

    def moved(self, texts: list[Annotation], renderer) -> None:
        """Measure ``texts`` again (placed since: the boxes the next Axes keeps clear of),
        and every legend at "best" (matplotlib places it clear of the texts as they are
        now)."""
        ids = {id(t) for t in texts}
        pairs = [(t, t.get_window_extent(renderer) if _at_best(t) else
                  drawn_extent(t, renderer) if id(t) in ids else bb) for t, bb in self.pairs]
        self.pairs = [(t, bb) for t, bb in pairs if bb is not None]


class _Room:
    """What a label must keep clear of on one Axes: boxes and drawn paths (pixels), with
    their extents as arrays (a label tries up to 160 places against every one)."""

    def __init__(self, ax: Axes, movable: list[Annotation], renderer, shown: _Shown) -> None:
        ids = {id(t) for t in movable}
        self.frame = ax.get_window_extent(renderer).padded(-_PAD)
        self.boxes = shown.others(ids)
        self.boxes += [child.get_window_extent(renderer) for child in ax.child_axes]
        own = {id(t.arrow_patch) for t in movable if t.arrow_patch is not None}
        self.paths = [p for _name, p, _src in drawn_paths(ax, skip=own)]
        self.box_rows = extent_rows(self.boxes)
        self.path_rows = extent_rows([p.get_extents() for p in self.paths])

    def open_rows(self, boxes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Of candidate boxes (rows x0, y0, x1, y1, low to high): which lie inside the
        frame and meet no box, and for each which paths' extents they overlap (the paths
        to test exactly, :meth:`clear_of_paths`); all candidates at once."""
        f = self.frame
        inside = ((f.x0 <= boxes[:, 0]) & (boxes[:, 2] <= f.x1) &
                  (f.y0 <= boxes[:, 1]) & (boxes[:, 3] <= f.y1))
        return (inside & ~_overlaps(self.box_rows, boxes).any(axis=1),
                _overlaps(self.path_rows, boxes))

    def clear_of_paths(self, box: Bbox, near: np.ndarray) -> bool:
        """The box meets none of the paths ``near`` (a mask of :attr:`paths`)."""
        return not any(meets(self.paths[k], box) for k in np.flatnonzero(near))

    def leader_clear(self, a: np.ndarray, box: Bbox, skip: Bbox) -> bool:
        """A leader from the anchor to the box's nearest point crosses no other label."""
        seg = Path([a, np.clip(a, [box.x0, box.y0], [box.x1, box.y1])])
        return not any(seg.intersects_bbox(b, filled=False) for b in self.boxes
                       if b is not skip)

    def take(self, box: Bbox, leader: Path | None) -> None:
        self.boxes.append(box)
        self.box_rows = np.vstack([self.box_rows, extent_rows([box])])
        if leader is not None:
            self.paths.append(leader)
            self.path_rows = np.vstack([self.path_rows, extent_rows([leader.get_extents()])])


def _set_leader(t: Annotation, on: bool) -> None:
    """A thin grey leader from the label to its anchor (or none). The leader is the
    annotation's own arrow without an arrow style: matplotlib then starts it at the corner
    or side middle of the label nearest the anchor (the point the placing kept clear)."""
    if on:
        t.arrowprops = dict(_LEADER_PROPS)
        t.arrow_patch = FancyArrowPatch((0, 0), (1, 1), color="0.45", lw=0.7)
        t.arrow_patch.set_figure(t.get_figure())
        _LEADERS.add(t)
    elif t in _LEADERS:
        t.arrowprops = None
        t.arrow_patch = None
        _LEADERS.discard(t)


def _place_one(t: Annotation, room: _Room, renderer, scale: float) -> bool:
    a = _anchor(t)
    if a is None:
        return True
    bb = text_extent(t, renderer)
    w, h = bb.width, bb.height
    # every try screened at once against the frame, the boxes and the paths' extents;
    # the open ones tested exactly in order of preference (the first free one wins)
    offs, rows = _tries(a, scale, w, h)
    open_, near = room.open_rows(rows)
    for k in np.flatnonzero(open_):
        off = offs[k]
        box = Bbox(rows[k].reshape(2, 2))
        if not room.clear_of_paths(box, near[k]):
            continue
        far = bool(_TRY_DISTANCES[k] > _LEADER)
        if far and not room.leader_clear(a, box, box):
            continue
        c, s = off / np.hypot(*off)
        t.xyann = tuple(off / scale)
        t.set_ha("left" if c > 0.3 else "right" if c < -0.3 else "center")
        t.set_va("bottom" if s > 0.3 else "top" if s < -0.3 else "center")
        _set_leader(t, far)
        tip = np.clip(a, [box.x0, box.y0], [box.x1, box.y1])
        room.take(box.padded(-_PAD + 0.5), Path([a, tip]) if far else None)
        return True
    return False


UNPLACED_TITLE = "labels not placed (no free room at their point)"


def _not_placed(fig, texts: list[Text]) -> None:
    """Take the labels off the drawing and name them in a legend below the figure (one
    legend per figure: a later call adds to it)."""
    old = next((lg for lg in fig.legends if lg.get_title().get_text() == UNPLACED_TITLE),
               None)
    handles = [] if old is None else list(old.legend_handles)
    labels = [] if old is None else [t.get_text() for t in old.get_texts()]
    for t in texts:
        t.set_visible(False)
        handles.append(Line2D([], [], ls="none", marker="o", ms=4, color=t.get_color()))
        labels.append(" ".join(t.get_text().split()))
    if old is not None:
        old.remove()
    others = [lg for lg in fig.legends if lg is not old]
    fig.legend(handles, labels, loc="outside upper center" if others else "outside lower right",
               fontsize=10,
               title=UNPLACED_TITLE, title_fontsize=10, ncol=min(3, len(handles)))


def _legend_off_data(ax: Axes, renderer) -> bool:
    """An Axes legend over a line, a marker or an arrow goes outside, to the right (True
    if it went)."""
    lg = ax.get_legend()
    if lg is None or not lg.get_visible():
        return False
    box = lg.get_window_extent(renderer)
    if not box.overlaps(ax.get_window_extent(renderer)):
        return False
    if any(meets(p, box) for _n, p, _s in drawn_paths(ax) if p.get_extents().overlaps(box)):
        lg.set_bbox_to_anchor((1.02, 1.0), transform=ax.transAxes)
        lg.set_loc("upper left")
        lg.borderaxespad = 0.0
        return True
    return False


def _at_best(artist) -> bool:
    """A legend that matplotlib places at its "best" place (clear of the data and the
    texts as they are at each drawing or measure)."""
    return isinstance(artist, Legend) and artist._loc in (0, "best")


def _fix_best(ax: Axes, renderer) -> None:
    """A legend at loc="best" stays where it was drawn (its place no longer moves with
    the labels placed after it)."""
    lg = ax.get_legend()
    if lg is not None and _at_best(lg):
        x0, y0 = ax.transAxes.inverted().transform(lg.get_window_extent(renderer).p0)
        lg.set_loc((float(x0), float(y0)))
        lg.borderaxespad = 0.0


def _thin_ticks(ax: Axes, renderer) -> bool:
    """Fewer ticks on an axis whose tick labels touch each other; True if changed."""
    from matplotlib.ticker import MaxNLocator
    changed = False
    for axis in (ax.xaxis, ax.yaxis):
        labels = [t for t in axis.get_ticklabels() if t.get_visible() and t.get_text()]
        boxes = [t.get_window_extent(renderer).padded(2.0) for t in labels]
        if any(a.overlaps(b) for a, b in zip(boxes[:-1], boxes[1:], strict=True)):
            n = max(2, len(labels) - 2)
            loc = axis.get_major_locator()
            if isinstance(loc, MaxNLocator):
                loc.set_params(nbins=n)
            else:
                axis.set_major_locator(MaxNLocator(nbins=n, steps=[1, 2, 2.5, 5, 10]))
            changed = True
    return changed


def settle(fig) -> None:
    """The last step of a picture: legends off the data, the layout made final, every
    label registered by :func:`declutter` placed again on the final layout.

    Steps: a legend inside an Axes that covers data goes outside to the right; labels
    are placed (those with no free room named in the figure's legend of labels not
    placed); the constrained layout is then frozen and the labels placed once more, so
    that the saved figure is the one measured.
    """
    axes = [ax for ax in fig.axes if ax in _KEPT]
    r = lay_out(fig)
    moved = any([_legend_off_data(ax, r) for ax in fig.axes])
    if moved or not _frozen(fig):
        # (every Axes' labels on this drawing: a label's box and a "best" legend's place
        # are measured afresh from it, and the labels are out of the layout; drawn again
        # only when a legend of labels not placed came, which changes the layout. A
        # drawing per Axes moved the Axes by a thousandth of a pixel and cost a fifth of
        # the overview's time, 2026-11-29)
        shown = _Shown(fig, r)
        for ax in axes:
            if _place_again(ax, r, shown):
                r = lay_out(fig)
                shown = _Shown(fig, r)
    else:
        _place_kept(fig, axes, r)
    before = _corners(fig)
    lay_out(fig)
    # drawn once more where the layout had not settled (an Axes moved by more than half
    # a pixel: its tick labels changed with its size, and an axis label came out of the
    # figure, the four-bar sheet's Explorer at crank 0.13 m, speed 45 rad/s after one
    # drawing of a new picture; 2026-11-30)
    if before.shape != _corners(fig).shape or \
            np.abs(before - _corners(fig)).max(initial=0.0) > 0.5:
        lay_out(fig)
    for _ in range(3):
        if not any([_thin_ticks(ax, r) for ax in fig.axes]):
            break
        lay_out(fig)
    for ax in fig.axes:
        _fix_best(ax, r)
    # the final layout (the drawing just made: _fix_best pins each legend where it was
    # drawn, so drawing again moved nothing but by a thousandth of a pixel, a drawing a
    # figure), frozen: the labels of every Axes are placed on it until a legend of labels
    # not placed comes (a drawing per Axes cost a seventh of a picture's time)
    if fig.get_layout_engine() is not None:
        fig.set_layout_engine("none")
    _place_kept(fig, axes, r)
    # the figure as its measures read it (not stale): its layout frozen, its labels placed
    # on its last drawing and positioned again by each measure. An audit drew every
    # picture once more before it measured it (a drawing a picture); its measures the same
    # without (the audits of all 112 command-line pictures of the 9 bundled scenes; the
    # boxes and paths within 0.016 px of the drawn figure's, which an equal-aspect Axes'
    # next drawing nudges, 2026-11-30).
    # A change after settle makes the figure stale: measured on a new drawing.
    fig.stale = False


def _corners(fig) -> np.ndarray:
    """The corners (pixels) of the figure's Axes as the last drawing placed them."""
    return np.array([ax.get_position().extents for ax in fig.axes],
                    dtype=float).reshape(-1, 4) * np.tile(fig.bbox.size, 2)


def _place_again(ax: Axes, renderer, shown: _Shown) -> bool:
    """Place the labels :func:`declutter` kept on ``ax`` on the figure as drawn last
    (``renderer``, its texts' boxes ``shown``), those with no free place named in the
    legend of labels not placed (True: the legend came, the layout changed)."""
    missing = _place(ax, _movable(_KEPT[ax]), renderer, hide=False, shown=shown)
    if missing:
        _not_placed(ax.figure, missing)
    return bool(missing)


def _frozen(fig) -> bool:
    """No layout engine moves the figure's Axes when it is drawn (none, or frozen by
    :func:`settle`)."""
    engine = fig.get_layout_engine()
    return engine is None or isinstance(engine, PlaceHolderLayoutEngine)


def _place_kept(fig, axes: list[Axes], r):
    """Place the labels :func:`declutter` kept on each of ``axes`` on the figure as drawn
    last, drawn again after each Axes with labels not placed (the legend of them changes
    the layout)."""
    shown = _Shown(fig, r)
    for ax in axes:
        if _place(ax, _movable(_KEPT[ax]), r, shown=shown):
            r = lay_out(fig)
            shown = _Shown(fig, r)
    return r


class settled_later:
    """``with settled_later(): ...``: the figures made inside are finished by
    :func:`settle`, so :func:`declutter` there only keeps its labels for it (settle places
    every kept label again on the final layout: placing them first on a layout that is
    not yet final cost a drawing of the figure and was undone)."""

    def __enter__(self) -> settled_later:
        _LATER[0] += 1
        return self

    def __exit__(self, *exc) -> None:
        _LATER[0] -= 1


def declutter(ax: Axes, texts: Sequence[Text], rounds: int = 1,
              remember: bool = True) -> list[Text]:
    """Place annotations (offset in points from their anchor) clear of every other
    label, line, marker and arrow of the figure.

    Parameters
    ----------
    ax : Axes
        The Axes of the annotations (its figure is drawn).
    texts : sequence of Text
        Annotations with ``textcoords="offset points"``, in order of importance (the
        first ones get the places nearest their anchors).
    rounds : int
        How many times to draw and place (a constrained layout settles in between).
    remember : bool
        Keep the labels on the Axes for :func:`settle`, which places them again once
        the figure is complete.

    Returns
    -------
    list of Text
        The labels that found no free place (hidden and named in a legend); none inside
        :class:`settled_later` (the labels are kept, placed by :func:`settle`).
    """
    movable = _movable(texts)
    if remember:
        old = _KEPT.get(ax, [])
        _KEPT[ax] = old + [t for t in movable if all(t is not o for o in old)]
        if _LATER[0]:
            return []
    missing: list[Text] = []
    for _ in range(rounds):
        missing = _place(ax, movable, lay_out(ax.figure), hide=False)
    if missing:
        _not_placed(ax.figure, missing)
    return missing


def _movable(texts: Sequence[Text]) -> list[Annotation]:
    """The visible annotations with letters, written at an offset in points (left out of
    the layout: they are placed on it)."""
    movable = [t for t in texts if isinstance(t, Annotation) and t.get_visible() and
               t.get_text().strip() and t.anncoords == "offset points"]
    for t in movable:
        t.set_in_layout(False)
    return movable


def _place(ax: Axes, movable: list[Annotation], renderer, hide: bool = True,
           shown: _Shown | None = None) -> list[Text]:
    """Place the labels on the figure as drawn last (``renderer``; ``shown``: the boxes
    of its texts on that drawing, measured here if not given, brought up to date for the
    labels placed); those with no free place are returned, and with ``hide`` taken off
    the drawing (:func:`_not_placed`)."""
    shown = _Shown(ax.figure, renderer) if shown is None else shown
    room = _Room(ax, movable, renderer, shown)
    scale = ax.figure.dpi / 72.0
    missing = [t for t in movable if not _place_one(t, room, renderer, scale)]
    shown.moved(movable, renderer)
    if missing and hide:
        _not_placed(ax.figure, missing)
    return missing
