"""Issue 22: the command line's pictures for the lecture room. On every picture type
(overview, Me, polar diagrams, mechanism with loads, velocity and acceleration plans,
instantaneous centres, free-body diagrams with their force polygons) of every bundled
scene of the demo, each at one position (another place of the cycle per scene): no label
over another label, a link, a curve, a marker or an arrow, no legend over data (measured
on the drawn figure); 150 dpi and no font under 10 pt.

The figures are drawn once per session (``lecture_figures`` in conftest.py) and shared
with the other picture tests, and measured once (``audited``: the collisions, the sizes
and the notation of each figure in one measure).

Before the work of issue 22 the same measure found 1730 collisions in 132 of the 150
figures (docs/pictures-collisions.md).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest

from kinetostatics import plot as kp
from kinetostatics.plot import cli as plot_cli
from kinetostatics.plot.cli import write_pictures
from kinetostatics.plot.style import SMALLEST_FONT, lay_out

from .conftest import PICTURE_SCENES


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


@pytest.mark.parametrize("name", PICTURE_SCENES)
def test_no_collisions_on_any_cli_picture(name, audited):
    bad = {stem: a.collisions for stem, a in audited(name).items() if a.collisions}
    assert not bad, bad


def test_collisions_sees_a_label_on_a_link_and_a_legend_on_a_curve():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], label="link")
    ax.annotate("on the link", (0.5, 0.5), xytext=(0, 0), textcoords="offset points",
                ha="center", va="center")
    ax.annotate("", (0.9, 0.5), (0.1, 0.5), arrowprops={"arrowstyle": "-|>"})
    ax.legend(loc="center")
    hits = kp.collisions(fig)
    assert ("on the link", "link") in hits
    assert ("legend", "link") in hits and ("on the link", "an arrow") in hits


def test_declutter_and_settle_clear_a_crowded_drawing():
    fig, ax = plt.subplots(layout="constrained")
    ax.plot([0, 1], [0, 1], lw=3)
    texts = [ax.annotate(f"label {k}", (0.5, 0.5), xytext=(0, 0),
                         textcoords="offset points") for k in range(4)]
    assert kp.collisions(fig)
    kp.declutter(ax, texts)
    kp.settle(fig)
    assert not kp.collisions(fig)


def test_a_figure_changed_after_its_measure_is_drawn_again():
    """The measures draw a finished figure (no layout engine moving it) only when
    something changed since its last drawing: a new tick format is drawn and measured."""
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    assert kp.collisions(fig) == []
    ax.xaxis.set_major_formatter(lambda x, pos: f"a long tick label {x:g}")
    assert any("a long tick label" in a for a, _b in kp.collisions(fig))


def test_a_finished_figure_is_drawn_once_for_all_its_measures(monkeypatch):
    """The measures read a settled figure as settle left it (its labels placed on its
    last drawing, its layout frozen): none draws it again, the collisions and an audit
    after them (as the picture tests run them) read that drawing; a change draws it
    once (measured: an audit of the four-bar's twelve pictures 1.29 s of CPU drawing each
    again, 0.58 s without)."""
    from matplotlib.figure import Figure

    from kinetostatics.plot.audit import audit
    drawn = []
    real = Figure.draw_without_rendering
    with kp.lecture_style():
        fig, ax = plt.subplots(layout="constrained")
        ax.plot([0, 1], [0, 1], lw=3)
        texts = [ax.annotate(f"label {k}", (0.5, 0.5), xytext=(0, 0),
                             textcoords="offset points") for k in range(3)]
        kp.declutter(ax, texts)
        kp.settle(fig)
        monkeypatch.setattr(Figure, "draw_without_rendering",
                            lambda self: drawn.append(self) or real(self))
        assert kp.collisions(fig) == [] and audit(fig).problems == []
        assert kp.collisions(fig) == [] and len(drawn) == 0
        ax.lines[0].set_linewidth(2.0)      # stale: drawn again, once, for its measures
        assert kp.collisions(fig) == [] and audit(fig).problems == []
        assert len(drawn) == 1


def test_an_audit_draws_a_figure_under_constrained_layout_once(monkeypatch):
    """An audit of a figure the constrained layout still lays out (a sheet's picture
    before the inline backend shows it) reads its texts and collisions on one drawing,
    with what two drawings measured (measured: the audit hook's drawings a fifth of its
    time in a sheet's run, 2026-11-30)."""
    from matplotlib.figure import Figure

    from kinetostatics.plot.audit import audit
    with kp.lecture_style():
        fig, ax = plt.subplots(layout="constrained")
        ax.plot([0, 1], [0, 1], lw=3, label="a line")
        ax.set(title="a title", xlabel="x [m]")
        ax.legend(loc="best")
        twice = audit(fig)
        drawn = []
        real = Figure.draw_without_rendering
        monkeypatch.setattr(Figure, "draw_without_rendering",
                            lambda self: drawn.append(self) or real(self))
        assert audit(fig) == twice and len(drawn) == 1
        assert audit(fig) == twice and len(drawn) == 2      # (a layout engine: drawn again)


def test_a_settled_figure_is_saved_with_one_drawing(monkeypatch, tmp_path):
    """A settled figure (its layout frozen) is saved by the command line with the painting
    drawing only, pixel for pixel what savefig writes after its own layout drawing
    (measured: the four-bar's twelve pictures saved in 2.23 s of CPU, 2.82 s by savefig)."""
    from matplotlib.figure import Figure

    from kinetostatics.plot.style import save_laid_out
    with kp.lecture_style():
        fig, ax = plt.subplots(layout="constrained")
        ax.plot([0, 1], [0, 1], lw=3)
        ax.legend(["a line"], loc="best")
        texts = [ax.annotate(f"label {k}", (0.5, 0.5), xytext=(0, 0),
                             textcoords="offset points") for k in range(3)]
        kp.declutter(ax, texts)
        kp.settle(fig)
        drawn = []
        real = Figure.draw
        monkeypatch.setattr(Figure, "draw", lambda self, r: drawn.append(r) or real(self, r))
        save_laid_out(fig, tmp_path / "one.png", dpi=150)
        assert len(drawn) == 1
        fig.savefig(tmp_path / "two.png", dpi=150)
        assert len(drawn) == 3
        save_laid_out(fig, tmp_path / "three.png", dpi=150)
        # the figure as saved is the one measured: an audit after the save draws nothing
        assert kp.collisions(fig) == [] and len(drawn) == 4
    png = [(tmp_path / f"{n}.png").read_bytes() for n in ("one", "two", "three")]
    assert png[0] == png[1] == png[2]


# one scene: the size rule is the style's, the same for every scene
@pytest.mark.parametrize("name", ["scotch_yoke"])
def test_cli_pictures_lecture_size(name, lecture_figures, audited, tmp_path, monkeypatch):
    """Every figure of ``solve --plot`` is drawn at 150 dpi and no text of it is under
    10 pt (the smallest of the texts a reader sees, on the drawn figure: ``audited``);
    ``--dpi`` writes more (every file of ``solve --plot`` at 150 dpi: test_cli.py's
    test_solve_plot_writes_the_pictures reads them)."""
    sol, pos, figs = lecture_figures(name)
    measured = audited(name)
    assert set(measured) == set(figs)
    for stem, fig in figs.items():
        assert fig.dpi == measured[stem].dpi == 150, stem
        assert measured[stem].smallest_font >= SMALLEST_FONT, stem
    # --dpi: one figure is enough (each file costs a full drawing); write_pictures saves
    # the figures it is given (the same drawing as above)
    monkeypatch.setattr(plot_cli, "cli_figures", lambda s, p=None: {"driver": figs["driver"]})
    paths = write_pictures(sol, tmp_path / "big", [pos], dpi=220)
    from PIL import Image
    with Image.open(paths[0]) as im:
        assert round(im.info["dpi"][0]) == 220


def test_lecture_style_is_a_switch():
    base = plt.rcParams["figure.dpi"]
    with kp.lecture_style():
        fig = plt.figure()
        assert fig.dpi == 150 and plt.rcParams["legend.fontsize"] >= SMALLEST_FONT
    assert plt.rcParams["figure.dpi"] == base
    style = kp.lecture_style(dpi=200)
    assert plt.figure().dpi == 200
    style.restore()
    assert plt.rcParams["figure.dpi"] == base


def test_figures_share_one_mathtext_parser():
    """Every laid-out figure's renderer parses mathtext with one shared parser (its
    labels parsed once per session, not once per figure) and looks each font's heights
    up once, measuring as matplotlib's own renderer does (a mathtext label and a plain
    two-line one, whose height is the font's)."""
    from matplotlib.mathtext import MathTextParser

    from kinetostatics.plot.style import text_extent

    def extents(fig, ax, r):
        return np.array([text_extent(t, r).extents for t in ax.texts])

    def labelled():
        fig, ax = plt.subplots()
        ax.text(0.2, 0.5, r"$F^{i}_{\mathrm{coupler}}$ 12.5 N")
        ax.text(0.2, 0.2, "reaction\nA on B", fontsize=10)
        return fig, ax
    drawn = []
    for _ in range(2):
        fig, ax = labelled()
        r = lay_out(fig)
        drawn.append((r.mathtext_parser, extents(fig, ax, r)))
    assert drawn[0][0] is drawn[1][0] and type(drawn[0][0]) is not MathTextParser
    fig, ax = labelled()
    fig.draw_without_rendering()            # matplotlib's own parser and font lookups
    r = fig.canvas.get_renderer()
    assert type(r.mathtext_parser) is MathTextParser
    assert (extents(fig, ax, r) == drawn[0][1]).all()


def test_labels_kept_for_settle_are_placed_by_it():
    """Inside ``settled_later`` declutter only keeps the labels (no drawing): settle
    places them on the final layout."""
    from kinetostatics.plot.place import settled_later
    fig, ax = plt.subplots(layout="constrained")
    ax.plot([0, 1], [0, 1], lw=3)
    texts = [ax.annotate(f"label {k}", (0.5, 0.5), xytext=(0, 0),
                         textcoords="offset points") for k in range(4)]
    with settled_later():
        assert kp.declutter(ax, texts) == []
    assert all(t.xyann == (0, 0) for t in texts)        # kept, not placed
    kp.settle(fig)
    assert not kp.collisions(fig)
