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
from matplotlib.lines import Line2D
from matplotlib.patches import FancyArrowPatch
from matplotlib.path import Path
from matplotlib.text import Annotation, Text
from matplotlib.transforms import Bbox

from ..common.angles import radian_column
from .collide import drawn_paths, extent_rows, meets, overlapping_rows
from .style import figure_boxes, lay_out, text_extent

__all__ = ["UNPLACED_TITLE", "declutter", "settle", "settled_later"]

_DIRECTIONS = radian_column(np.array([45, 135, 315, 225, 90, 270, 0, 180,
                                   22.5, 67.5, 112.5, 157.5, 202.5, 247.5, 292.5, 337.5]))
_UNITS = [np.array([np.cos(ang), np.sin(ang)]) for ang in _DIRECTIONS]
_DISTANCES = (3.0, 6.0, 10.0, 15.0, 21.0, 28.0, 36.0, 46.0, 58.0, 72.0)      # points
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


def _box(anchor, off, w: float, h: float) -> Bbox:
    """The box of a w x h label whose alignment follows the direction of ``off``."""
    c, s = off / (np.hypot(*off) or 1.0)
    fx = 0.0 if c > 0.3 else 1.0 if c < -0.3 else 0.5
    fy = 0.0 if s > 0.3 else 1.0 if s < -0.3 else 0.5
    x0, y0 = anchor + off - np.array([fx * w, fy * h])
    return Bbox([[x0, y0], [x0 + w, y0 + h]])


class _Room:
    """What a label must keep clear of on one Axes: boxes and drawn paths (pixels), with
    their extents as arrays (a label tries up to 160 places against every one)."""

    def __init__(self, ax: Axes, movable: list[Annotation], renderer) -> None:
        ids = {id(t) for t in movable}
        self.frame = ax.get_window_extent(renderer).padded(-_PAD)
        self.boxes = [bb for t, bb in figure_boxes(ax.figure, renderer) if id(t) not in ids]
        self.boxes += [child.get_window_extent(renderer) for child in ax.child_axes]
        own = {id(t.arrow_patch) for t in movable if t.arrow_patch is not None}
        self.paths = [p for _name, p, _src in drawn_paths(ax, skip=own)]
        self.box_rows = extent_rows(self.boxes)
        self.path_rows = extent_rows([p.get_extents() for p in self.paths])

    def clear(self, box: Bbox) -> bool:
        f = self.frame
        if not (f.x0 <= box.x0 and box.x1 <= f.x1 and f.y0 <= box.y0 and box.y1 <= f.y1):
            return False
        if overlapping_rows(self.box_rows, box).any():
            return False
        return not any(meets(self.paths[k], box)
                       for k in np.flatnonzero(overlapping_rows(self.path_rows, box)))

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
    for dist in _DISTANCES:
        for unit in _UNITS:
            off = dist * scale * unit
            box = _box(a, off, w, h).padded(_PAD)
            if not room.clear(box):
                continue
            far = dist > _LEADER
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


def _fix_best(ax: Axes, renderer) -> None:
    """A legend at loc="best" stays where it was drawn (its place no longer moves with
    the labels placed after it)."""
    lg = ax.get_legend()
    if lg is not None and lg._loc in (0, "best"):
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
        for ax in axes:
            if _place_again(ax, r):
                r = lay_out(fig)
    else:
        _place_kept(fig, axes, r)
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


def _place_again(ax: Axes, renderer) -> bool:
    """Place the labels :func:`declutter` kept on ``ax`` on the figure as drawn last
    (``renderer``), those with no free place named in the legend of labels not placed
    (True: the legend came, the layout changed)."""
    missing = _place(ax, _movable(_KEPT[ax]), renderer, hide=False)
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
    last, drawn again after each Axes whose labels moved."""
    for ax in axes:
        if _place(ax, _movable(_KEPT[ax]), r):
            r = lay_out(fig)
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


def _place(ax: Axes, movable: list[Annotation], renderer, hide: bool = True) -> list[Text]:
    """Place the labels on the figure as drawn last (``renderer``); those with no free
    place are returned, and with ``hide`` taken off the drawing (:func:`_not_placed`)."""
    room = _Room(ax, movable, renderer)
    scale = ax.figure.dpi / 72.0
    missing = [t for t in movable if not _place_one(t, room, renderer, scale)]
    if missing and hide:
        _not_placed(ax.figure, missing)
    return missing
