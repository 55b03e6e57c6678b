"""The balancing pictures return labelled matplotlib objects (Agg backend)."""

from __future__ import annotations

import cmath
import math

import matplotlib.pyplot as plt
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import balance
from balance import plot


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def labelled(ax: Axes) -> None:
    assert isinstance(ax, Axes) and isinstance(ax.figure, Figure)
    assert ax.get_xlabel() and ax.get_ylabel() and ax.get_title()
    assert "(" in ax.get_xlabel() and ")" in ax.get_xlabel()          # a unit


def rotor(name: str):
    return balance.solve_results(balance.example_path(name))["rotor"]


@pytest.mark.parametrize("name", ["rotor_two_plane",
                                  pytest.param("rotor_static", marks=pytest.mark.slow)])
def test_polygons(name: str, tmp_path) -> None:
    res = rotor(name)
    ax = plot.plot_unbalance_polygon(res)
    labelled(ax)
    assert ax.get_aspect() == 1.0
    unit = "N" if res.speed_rpm else "kg m"
    assert f"({unit})" in ax.get_xlabel()
    ax.figure.savefig(tmp_path / "poly.png")
    ax2 = plot.plot_moment_polygon(res)
    labelled(ax2)
    ax2.figure.savefig(tmp_path / "moment.png")


def test_given_axes_are_used() -> None:
    fig, (a, b) = plt.subplots(1, 2)
    res = rotor("rotor_two_plane")
    assert plot.plot_unbalance_polygon(res, ax=a) is a
    assert plot.plot_moment_polygon(res, ax=b, force=False) is b
    assert "kg m" in b.get_xlabel()


def test_parallelogram_and_circles(tmp_path) -> None:
    r = balance.solve_results(balance.example_path("resonance_example"))["resonance_test"][0]
    ax = plot.plot_parallelogram(r, unit="um")
    labelled(ax)
    texts = " ".join(t.get_text() for t in ax.texts)
    assert f"{r.angle:.1f}" in texts and f"{r.mirror_angle:.1f}" in texts   # both candidates
    ax.figure.savefig(tmp_path / "par.png")
    labelled(plot.plot_amplitude_circles(r, unit="um"))


def test_run_comparison(tmp_path) -> None:
    U = cmath.rect(1.5e-4, math.radians(200.0))
    k, q = 500 / 1.5e-4, 1.2e-4

    def a(mark):
        return k * abs(U + (0 if mark is None else cmath.rect(q, math.radians(mark))))

    three = balance.parallelogram(a(None), a(0.0), a(180.0), 0.002, 0.06, 0.05)
    four = balance.four_run(a(None), a(0.0), a(120.0), a(240.0), 0.002, 0.06, 0.05)
    fig = plot.plot_run_comparison(three, four, unit="um")
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    for ax in fig.axes:
        labelled(ax)
    fig.savefig(tmp_path / "cmp.png")
    labelled(plot.plot_parallelogram(four))


def test_nothing_to_draw_is_an_error() -> None:
    r = balance.parallelogram(0.0, 5.0, 5.0, 0.002, 0.06, 0.05)
    with pytest.raises(balance.BalanceError):
        plot.plot_parallelogram(r)
    with pytest.raises(balance.BalanceError):
        plot.plot_unbalance_polygon(rotor("rotor_static"), force=True)
