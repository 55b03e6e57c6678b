"""The sheets' interactive cells work without a browser: kinetostatics.notebook."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import kinetostatics as ks
from kinetostatics.notebook import Explorer, Slider, dash_missing, format_number


def _four_bar(crank: float, phi: float):
    raw = ks.load_scene(ks.example("four_bar")).raw
    raw["bodies"][0]["points"]["B"] = [crank, 0.0]
    return ks.solve(raw)


def _draw(sol, fig, crank, phi):
    ax = fig.subplots()
    ax.plot(sol.positions, sol.Me)
    ax.axvline(phi)


def _numbers(sol, crank, phi):
    return {"Me at phi [N m]": float(np.interp(phi, sol.positions, sol.Me)),
            "Me max [N m]": sol.summary()["Me_max"]}


@pytest.fixture
def explorer():
    return Explorer([Slider("crank", "crank AB [m]", 0.06, 0.30, 0.01, 0.10),
                     Slider("phi", "crank angle [deg]", 0.0, 355.0, 5.0, 30.0)],
                    _four_bar, _draw, _numbers, figsize=(5, 3))


def test_setting_a_value_changes_the_picture_and_the_numbers(explorer):
    start, png = dict(explorer.numbers), explorer.png()
    new = explorer.set(crank=0.12)
    assert explorer.values == {"crank": 0.12, "phi": 30.0}
    assert new == explorer.numbers and new != start
    # the numbers are those of the new crank: Me max 33.86 N m (measured) instead of 21.79
    assert explorer.png() != png
    assert new["Me max [N m]"] == pytest.approx(_four_bar(0.12, 30.0).summary()["Me_max"])
    explorer.set(crank=0.10)
    assert explorer.numbers == start              # the same inputs, the same numbers


def test_a_value_that_cannot_be_solved_shows_the_message(explorer):
    # crank 0.30 + frame 0.30 > coupler 0.25 + rocker 0.20: the loop cannot close
    explorer.set(crank=0.30)
    assert explorer.error and explorer.result is None and explorer.numbers == {}
    texts = [t.get_text() for ax in explorer.figure.axes for t in ax.texts]
    assert any(explorer.error in t for t in texts)
    table = explorer.table()
    assert list(table.index) == ["cannot be solved"] and table.value.iloc[0] == explorer.error
    explorer.set(crank=0.10)                       # back to a mechanism that closes
    assert explorer.error is None and explorer.numbers


def test_bad_slider_input_is_refused_with_its_name(explorer):
    with pytest.raises(ValueError, match="slider 'crank'.*outside"):
        explorer.set(crank=0.5)
    with pytest.raises(ValueError, match="no slider 'length'"):
        explorer.set(length=0.1)
    with pytest.raises(ValueError, match="outside"):
        explorer.set(phi=float("nan"))
    with pytest.raises(ValueError, match="distinct names"):
        Explorer([Slider("a", "a", 0, 1, 0.1, 0.5)] * 2, _four_bar, _draw, _numbers)
    with pytest.raises(ValueError, match="min < max"):
        Slider("a", "a", 1.0, 0.0, 0.1, 0.5)
    assert explorer.values == {"crank": 0.10, "phi": 30.0}   # nothing was changed


def test_the_widget_drives_the_explorer(explorer):
    box = explorer.widget()
    crank_slider = box.children[0]
    assert crank_slider.description == "crank AB [m]" and crank_slider.value == 0.10
    before = dict(explorer.numbers)
    crank_slider.value = 0.12                      # what moving the slider does
    assert explorer.values["crank"] == pytest.approx(0.12)
    assert explorer.numbers != before
    explorer.close()                               # the widgets let go, the API works on
    crank_slider.value = 0.10
    assert explorer.values["crank"] == pytest.approx(0.12)
    explorer.set(crank=0.11)
    assert explorer.values["crank"] == pytest.approx(0.11)


def test_key_numbers_are_never_nan():
    assert format_number(None) == "-" and format_number("text") == "text"
    assert format_number(3.0) == "3" and format_number(0.123456) == "0.1235"
    for bad in (float("nan"), float("inf"), -np.inf):
        with pytest.raises(ValueError, match="key number"):
            format_number(bad)


def test_missing_cells_show_a_dash():
    html = dash_missing(pd.DataFrame({"N": [1.5, np.nan], "offset": [None, 0.25]})).to_html()
    assert "–" in html and "nan" not in html.lower() and "none" not in html.lower()
    assert "1.5000" in html and "0.2500" in html
