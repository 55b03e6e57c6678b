"""Rows flagged singular are never shown as ordinary numbers (issue 33, item 4): the
summary's extremes and mean leave them out and say how many (scene-format.md), and the
pictures of forces say so instead of drawing them.

The case: the four-bar with a 0.15 m crank is a change-point linkage (crank + frame =
coupler + rocker, Grashof's equality): at 180 deg the four links lie on one line and the
dyad's equations are singular (Me there: 2.5e8 N m, measured).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics import plot as kp
from kinetostatics.plot.base import SINGULAR_NOTE


@pytest.fixture(scope="module")
def change_point():
    raw = ks.load_scene(ks.example("four_bar")).raw
    raw["bodies"][0]["points"]["B"] = [0.15, 0.0]
    raw["bodies"][0]["cog"] = [0.075, 0.0]
    return ks.solve(raw)


def test_summary_leaves_singular_rows_out_of_the_extremes(change_point):
    sol = change_point
    sing = np.asarray(sol.singular, dtype=bool)
    assert sing.any() and np.abs(sol.Me[sing]).max() > 1e6      # the meaningless number
    s = sol.summary()
    assert s["singular_rows"] == int(sing.sum()) == s["rows_left_out"]
    assert s["Me_max"] == pytest.approx(sol.Me[~sing].max(), rel=0, abs=0)
    assert s["Me_min"] == pytest.approx(sol.Me[~sing].min(), rel=0, abs=0)
    for j, r in s["reaction_max"].items():
        fx, fy = sol.reaction(j)
        assert r["F"] == np.hypot(fx, fy)[~sing].max(), j


def test_regular_scene_summary_unchanged():
    s = ks.solve(ks.example("four_bar")).summary()
    assert s["singular_rows"] == 0 and s["rows_left_out"] == 0


def test_force_pictures_say_singular_instead_of_drawing(change_point):
    sol = change_point
    at = float(sol.positions[np.asarray(sol.singular)][0])
    ax = kp.draw_mechanism(sol, at, forces=True, loads=True)
    assert SINGULAR_NOTE in ax.get_title()
    assert not [t for t in ax.texts if t.arrow_patch is not None and not t.get_text()]
    fig = kp.dyad_free_body(sol, 1, at)
    assert SINGULAR_NOTE in fig.axes[0].get_title()
    assert any("singular" in t.get_text() for t in fig.axes[1].texts)
    ax = kp.plot_driver(sol)
    y = ax.lines[0].get_ydata()
    assert np.isnan(y[np.asarray(sol.singular)]).all()      # a gap, shaded
    assert np.nanmax(np.abs(y)) < 1e3
    plt.close("all")
