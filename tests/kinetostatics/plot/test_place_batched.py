"""Issue 32: the label placer tries every place of a label at once (numpy) and walks the
figure once per room; the places it picks and the boxes it keeps clear of are those of
the one-by-one search it replaced (kept here as the reference), so every picture stays
the same to the byte."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.legend import Legend
from matplotlib.path import Path
from matplotlib.text import Text
from matplotlib.transforms import Bbox

from kinetostatics import plot as kp
from kinetostatics.plot import place as P
from kinetostatics.plot.collide import meets, overlapping_rows
from kinetostatics.plot.style import FigureWalk, figure_boxes, lay_out, undrawn_ticks


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def _crowded():
    """Two Axes of lines, markers, arrows and a legend, with labels crowding one point
    each (some placed far, with leaders, some not at all)."""
    fig, (ax, bx) = plt.subplots(1, 2, layout="constrained", figsize=(6.4, 3.2))
    t = np.linspace(0, 2 * np.pi, 60)
    ax.plot(np.cos(t), np.sin(t), lw=2, label="circle")
    ax.plot(np.cos(t[::6]), 0.5 * np.sin(t[::6]), "o", ms=5, label="points")
    ax.annotate("", (0.9, 0.1), (-0.9, -0.1), arrowprops={"arrowstyle": "-|>"})
    ax.legend(loc="best")
    bx.plot([0, 1, 2], [2, 0, 1], lw=3)
    texts = {a: [a.annotate(f"label {k}", xy, xytext=(0, 0), textcoords="offset points")
                 for k, xy in enumerate([(0, 0)] * 6 + [(0.7, 0.7), (1, 0)])]
             for a in (ax, bx)}
    return fig, texts


def _tries_one_by_one(a, scale: float, w: float, h: float):
    """The 160 tries of a w x h label at ``a`` as the search before issue 32 built them,
    one at a time, in order: (distance, offset, padded box)."""
    for dist in P._DISTANCES:
        for unit in P._UNITS:
            off = dist * scale * unit
            c, s = off / np.hypot(*off)
            fx = 0.0 if c > 0.3 else 1.0 if c < -0.3 else 0.5
            fy = 0.0 if s > 0.3 else 1.0 if s < -0.3 else 0.5
            x0, y0 = a + off - np.array([fx * w, fy * h])
            yield dist, off, Bbox([[x0, y0], [x0 + w, y0 + h]]).padded(P._PAD)


def _one_by_one(t, room, renderer, scale):
    """The reference: each of the 160 places built and tested alone, in order (the
    search before issue 32)."""
    a = P._anchor(t)
    if a is None:
        return True
    bb = P.text_extent(t, renderer)
    w, h = bb.width, bb.height
    f = room.frame
    for dist, off, box in _tries_one_by_one(a, scale, w, h):
        c, s = off / np.hypot(*off)
        if not (f.x0 <= box.x0 and box.x1 <= f.x1 and f.y0 <= box.y0 and
                box.y1 <= f.y1) or overlapping_rows(room.box_rows, box).any():
            continue
        if any(meets(room.paths[k], box)
               for k in np.flatnonzero(overlapping_rows(room.path_rows, box))):
            continue
        far = dist > P._LEADER
        if far and not room.leader_clear(a, box, box):
            continue
        t.xyann = tuple(off / scale)
        t.set_ha("left" if c > 0.3 else "right" if c < -0.3 else "center")
        t.set_va("bottom" if s > 0.3 else "top" if s < -0.3 else "center")
        P._set_leader(t, far)
        tip = np.clip(a, [box.x0, box.y0], [box.x1, box.y1])
        room.take(box.padded(-P._PAD + 0.5), Path([a, tip]) if far else None)
        return True
    return False


def _placed(monkeypatch, search) -> list:
    monkeypatch.setattr(P, "_place_one", search)
    fig, texts = _crowded()
    for ax, labels in texts.items():
        kp.declutter(ax, labels)
    kp.settle(fig)
    return [(t.xyann, t.get_ha(), t.get_va(), t.arrow_patch is not None, t.get_visible())
            for labels in texts.values() for t in labels]


def test_the_batched_search_places_every_label_where_the_one_by_one_did(monkeypatch):
    batched = _placed(monkeypatch, P._place_one)
    reference = _placed(monkeypatch, _one_by_one)
    assert batched == reference
    # the drawing tests what it should: labels near, far (a leader), and not placed
    assert {far for _o, _h, _v, far, _s in reference} == {True, False}
    assert not all(shown for *_p, shown in reference)


def test_the_tries_are_the_boxes_built_one_by_one():
    """Every try's box, to the last bit, in the order of preference (labels of any size
    anywhere on a figure, at two resolutions)."""
    rng = np.random.default_rng(32)
    for anchor, (w, h), dpi in zip(rng.uniform(0, 1500, (20, 2)), rng.uniform(1, 200, (20, 2)),
                                   [150, 200] * 10, strict=True):
        scale = dpi / 72.0
        offs, rows = P._tries(anchor, scale, w, h)
        k = 0
        for _dist, off, box in _tries_one_by_one(anchor, scale, w, h):
            assert np.array_equal(offs[k], off)
            assert np.array_equal(rows[k], box.extents)
            k += 1
        assert k == len(rows) == 160


def test_one_walk_finds_what_findobj_finds():
    """The walk lists the artists of ``fig.findobj()`` in its order, each axis' ticks as
    asked of the axis, and the boxes of the figure's texts are the same."""
    fig, texts = _crowded()
    kp.declutter(next(iter(texts)), next(iter(texts.values())))
    r = lay_out(fig)
    walk = FigureWalk(fig)
    assert [id(a) for a in walk.artists] == [id(a) for a in fig.findobj()]
    assert [id(a) for a in walk.of_type(Text)] == [id(a) for a in fig.findobj(Text)]
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            assert walk.ticks(axis) == axis.get_major_ticks() + axis.get_minor_ticks()
    assert undrawn_ticks(fig, walk) == undrawn_ticks(fig)
    # the boxes as searched by findobj (before issue 32)
    legends = fig.findobj(Legend)
    inside = {id(t) for lg in legends for t in lg.findobj(Text)} | undrawn_ticks(fig)
    want = [(id(lg), lg.get_window_extent(r).extents) for lg in legends]
    want += [(id(t), P.text_extent(t, r).extents) for t in fig.findobj(Text)
             if id(t) not in inside and t.get_visible() and t.get_text().strip()
             and P.text_extent(t, r).width > 0 and P.text_extent(t, r).height > 0]
    got = [(id(t), bb.extents) for t, bb in figure_boxes(fig, r)]
    assert len(got) == len(want) > 10
    assert all(a == b and np.array_equal(u, v) for (a, u), (b, v) in zip(got, want,
                                                                          strict=True))


def test_a_plain_text_is_measured_as_agg_measures_it():
    """The measure every figure shares (measured once per session) is Agg's own, to the
    last bit: plain texts of several faces, sizes and resolutions, hinting switched; the
    second figure's measure of a text is looked up, not measured."""
    import matplotlib as mpl
    from matplotlib.backends.backend_agg import RendererAgg
    from matplotlib.font_manager import FontProperties

    from kinetostatics.plot import style
    texts = ["0", "crank angle φ [deg]", "arrows: 0.05 m ≙ 200 N", "F12 = 3.2e+04 N", "lp"]
    props = [FontProperties(size=s, weight=w, style=f) for s, w, f in
             [(10, "normal", "normal"), (11, "bold", "normal"), (13, "normal", "italic")]]
    for hinting in ("force_autohint", "no_hinting"):
        with mpl.rc_context({"text.hinting": hinting}):
            for dpi in (72, 150, 200):
                shared, agg = style._Renderer(10, 10, dpi), RendererAgg(10, 10, dpi)
                for s in texts:
                    for p in props:
                        want = agg.get_text_width_height_descent(s, p, False)
                        assert shared.get_text_width_height_descent(s, p, False) == want
                        hits = style._plain_text_size.cache_info().hits
                        again = style._Renderer(20, 20, dpi)
                        assert again.get_text_width_height_descent(s, p, False) == want
                        assert style._plain_text_size.cache_info().hits == hits + 1
    # mathtext is measured by Agg's parser (shared otherwise)
    r = style._Renderer(10, 10, 150)
    p = props[0]
    assert r.get_text_width_height_descent(r"$F_{\mathrm{B}}$", p, True) == \
        RendererAgg(10, 10, 150).get_text_width_height_descent(r"$F_{\mathrm{B}}$", p, True)
