"""The command line's pictures, drawn once per test session and shared.

Drawing every figure of ``solve --plot`` for one scene costs 10-20 s of CPU on the CI
machine (the labels are placed on the laid-out figure, several layouts per figure), and
several tests read the same figures: the collision measure, the lecture-size rule and
the overlap check of every picture. :func:`lecture_figures` draws each scene once, in the
lecture style the command line draws with, at one position of its cycle. The figures
are only read by the tests (measured, saved), never changed, and held outside pyplot.
"""

from __future__ import annotations

from collections.abc import Callable

import matplotlib.pyplot as plt
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import kinetostatics as ks
from kinetostatics import plot as kp
from kinetostatics.plot.cli import cli_figures

#: The scenes whose every picture is measured, each at another place of its cycle.
PICTURE_SCENES = ["four_bar", "slider_crank", "slotted_lever", "scotch_yoke",
                  "sliding_driver", "shaper", "four_bar_mm"]


def picture_position(sol, name: str) -> float:
    """The driver position a scene's pictures are drawn at: an eighth, the middle or
    five sixths of its sweep, in turn along :data:`PICTURE_SCENES` (every picture type
    of every scene at one position costs 10-20 s per scene; three positions a minute)."""
    n = sol.positions.size
    which = PICTURE_SCENES.index(name) if name in PICTURE_SCENES else 0
    return float(sol.positions[(n // 7, n // 2, (5 * n) // 6)[which % 3]])


@pytest.fixture(scope="session")
def solved() -> Callable[[str], object]:
    """``solved(name)``: the Solution of a bundled scene, solved once per session."""
    cache: dict[str, object] = {}

    def get(name: str):
        if name not in cache:
            cache[name] = ks.solve(ks.example(name))
        return cache[name]
    return get


@pytest.fixture(scope="session")
def lecture_figures(solved) -> Callable[[str], tuple[object, float, dict[str, Figure]]]:
    """``lecture_figures(name)``: (solution, position, figures of ``solve --plot`` by
    file stem), drawn once per session in the lecture style at
    :func:`picture_position`."""
    cache: dict[str, tuple[object, float, dict[str, Figure]]] = {}

    def get(name: str):
        if name not in cache:
            sol = solved(name)
            pos = picture_position(sol, name)
            with kp.lecture_style():
                figs = cli_figures(sol, [pos])
            for fig in figs.values():
                # out of pyplot (a test's plt.close("all") would take the canvas away),
                # on an off-screen canvas of its own
                plt.close(fig)
                FigureCanvasAgg(fig)
            cache[name] = (sol, pos, figs)
        return cache[name]
    return get
