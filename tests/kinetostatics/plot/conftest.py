"""The command line's pictures, drawn once per test session and shared.

Drawing every figure of ``solve --plot`` for one scene costs 10-20 s of CPU on the CI
machine (the labels are placed on the laid-out figure, several layouts per figure), and
several tests read the same figures: the collision measure, the lecture-size rule, the
overlap check of every picture, and the command line's own tests (``solve --plot
--plot-at`` and ``demo`` write these figures: :func:`cli_pictures`).
:func:`lecture_figures` draws each scene once, in the lecture style the command line
draws with, at :func:`picture_positions`. The figures are only read by the tests
(measured, saved), never changed, and held outside pyplot; each is measured once against
the picture standard (:func:`audited`), and the tests of its collisions, its sizes and
its notation read that one measure.
"""

from __future__ import annotations

from collections.abc import Callable

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import kinetostatics as ks
from kinetostatics import plot as kp
from kinetostatics.plot.audit import PictureAudit, audit
from kinetostatics.plot.cli import cli_figures

#: The scenes whose every picture is measured, each at another place of its cycle.
PICTURE_SCENES = ["four_bar", "slider_crank", "slotted_lever", "scotch_yoke",
                  "sliding_driver", "shaper", "four_bar_mm"]
#: The scene ``demo`` writes in tests/kinetostatics/plot/test_cli.py: its pictures are
#: drawn where the command line draws them by default (where |Me| is largest).
DEMO_SCENE = "slotted_lever"
#: A second position for a scene (deg): ``solve --plot --plot-at`` with two positions
#: in test_cli.py writes these pictures, and every test of the figures reads them too.
SECOND_POSITION = {"slider_crank": 30.0}


def picture_positions(sol, name: str) -> list[float]:
    """The driver positions a scene's pictures are drawn at: an eighth, the middle or
    five sixths of its sweep, in turn along :data:`PICTURE_SCENES` (every picture type
    of every scene at one position costs 10-20 s per scene; three positions a minute),
    then :data:`SECOND_POSITION`; :data:`DEMO_SCENE`'s where |Me| is largest (the command
    line's default)."""
    if name == DEMO_SCENE:
        return [float(sol.positions[int(np.nanargmax(np.abs(sol.Me)))])]
    n = sol.positions.size
    which = PICTURE_SCENES.index(name) if name in PICTURE_SCENES else 0
    first = float(sol.positions[(n // 7, n // 2, (5 * n) // 6)[which % 3]])
    return [first] + ([SECOND_POSITION[name]] if name in SECOND_POSITION else [])


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
def cli_pictures(solved) -> Callable[[str], tuple[object, list[float], dict[str, Figure]]]:
    """``cli_pictures(name)``: (solution, positions, figures of ``solve --plot`` by file
    stem), drawn once per session in the lecture style at :func:`picture_positions`
    (the figures :func:`lecture_figures` gives)."""
    cache: dict[str, tuple[object, list[float], dict[str, Figure]]] = {}

    def get(name: str):
        if name not in cache:
            sol = solved(name)
            positions = picture_positions(sol, name)
            with kp.lecture_style():
                figs = cli_figures(sol, positions)
            for fig in figs.values():
                # out of pyplot (a test's plt.close("all") would take the canvas away),
                # on an off-screen canvas of its own
                plt.close(fig)
                FigureCanvasAgg(fig)
            cache[name] = (sol, positions, figs)
        return cache[name]
    return get


@pytest.fixture(scope="session")
def lecture_figures(cli_pictures) -> Callable[[str], tuple[object, float, dict[str, Figure]]]:
    """``lecture_figures(name)``: (solution, first position, figures of ``solve --plot``
    by file stem), drawn once per session (:func:`cli_pictures`)."""
    def get(name: str):
        sol, positions, figs = cli_pictures(name)
        return sol, positions[0], figs
    return get


@pytest.fixture(scope="session")
def audited(lecture_figures) -> Callable[[str], dict[str, PictureAudit]]:
    """``audited(name)``: every figure of :func:`lecture_figures` measured once against
    the picture standard (:func:`~kinetostatics.plot.audit.audit`, in the lecture style),
    by file stem. The collision test, the lecture-size test and the standard's test read
    this one measure (each measuring again found the collisions two or three times: 0.4-0.6
    s of CPU a scene each time, measured 2026-11-30)."""
    cache: dict[str, dict[str, PictureAudit]] = {}

    def get(name: str):
        if name not in cache:
            _sol, _pos, figs = lecture_figures(name)
            with kp.lecture_style():
                cache[name] = {stem: audit(fig) for stem, fig in figs.items()}
        return cache[name]
    return get
