"""The design pictures meet the picture standard (kinetostatics.plot.audit)."""

from __future__ import annotations

import tomllib

import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import kinetostatics as ks
from kinetostatics.design import draw_design, plot_front
from kinetostatics.plot.audit import audit
from kinetostatics.plot.style import lecture_style


@pytest.fixture(scope="module")
def res():
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    raw["design"]["constraints"] = ["transmission_min >= 45", "full_turn"]
    return ks.design(raw, population=16, generations=3, seed=2)


def test_front_picture(res):
    with lecture_style():
        fig = Figure(figsize=(7.2, 5.0), layout="constrained")
        FigureCanvasAgg(fig)
        plot_front(res, fig.add_subplot())
        assert audit(fig).problems == []


@pytest.mark.parametrize("front", [False, True])
def test_design_picture(res, front):
    with lecture_style():
        fig = draw_design(res, res.compromise, front=front)
        assert audit(fig).problems == []
