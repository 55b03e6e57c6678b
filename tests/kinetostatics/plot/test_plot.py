"""The pictures: they return Axes / Figures with labelled axes, and draw computed data."""

from __future__ import annotations

import tomllib
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import kinetostatics as ks
from kinetostatics import plot as kp
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.plot import polygon_forces
from kinetostatics.plot.notation import reading
from tests.helpers import SCENES

SCENE_PATHS = [ks.example(n) for n in ks.examples()] + sorted(SCENES.glob("*.toml"))


def _mechanism(path: Path) -> dict:
    """A scene file's mechanism: the scene without its ``[design]`` table (the search's
    settings, which no picture reads)."""
    scene = tomllib.loads(path.read_text(encoding="utf-8"))
    scene.pop("design", None)
    return scene


def _repeats(paths: list[Path]) -> dict[str, str]:
    """Each scene whose mechanism is an earlier scene's (only a ``[design]`` table
    added), to that scene's name."""
    first: dict[str, str] = {}
    out = {}
    for p in paths:
        key = repr(sorted(_mechanism(p).items()))
        if key in first:
            out[p.stem] = first[key]
        first.setdefault(key, p.stem)
    return out


#: the scenes that repeat another's mechanism (four_bar_design: the four-bar with a design
#: search): their pictures are that scene's, drawn once (checked to be the same solution)
REPEATS = _repeats(SCENE_PATHS)
DRAWN = [p.stem for p in SCENE_PATHS if p.stem not in REPEATS]


@pytest.fixture(scope="module")
def sols():
    return {p.stem: ks.solve(p) for p in SCENE_PATHS}


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def _labelled(ax: Axes) -> None:
    assert "[" in ax.get_xlabel() and "]" in ax.get_xlabel(), ax.get_xlabel()
    assert "[" in ax.get_ylabel() and "]" in ax.get_ylabel(), ax.get_ylabel()


def _mid(sol) -> float:
    return float(sol.positions[len(sol.positions) // 7])


@pytest.mark.parametrize("name", [p.stem for p in SCENE_PATHS])
def test_force_polygons_close(name, sols):
    """Every dyad's polygon (and the driver's) sums to zero at several positions."""
    sol = sols[name]
    n = sol.positions.size
    for i in (0, n // 3, 2 * n // 3):
        for d in [None, *(dm.dyad for dm in sol.kin.dyads)]:
            forces, split = polygon_forces(sol, d, i, True)
            total = np.sum([f[1] for f in forces], axis=0)
            scale = max(np.hypot(*f[1]) for f in forces)
            assert np.hypot(*total) <= 1e-9 * scale, (name, d, i, total)


# (the quick tier draws the four-bar's; every other scene's in the full suite, a scene
# repeating another's mechanism once: test_a_repeated_mechanism_draws_as_its_first)
@pytest.mark.parametrize("name", [pytest.param(n, marks=() if n == "four_bar" else
                                               pytest.mark.slow) for n in DRAWN])
def test_every_picture_of_every_scene(name, sols):
    sol = sols[name]
    pos = _mid(sol)
    for d in range(len(sol.kin.dyads) + 1):
        ax = kp.force_polygon(sol, d, pos)
        assert isinstance(ax, Axes)
        _labelled(ax)
        assert ax.get_xlabel() == "Fx [N]"
        assert "closing error |ΣF| = " in ax.get_title()
        hits = kp.overlapping_texts(ax.figure)      # no two labels overlap
        assert not hits, (d, hits)
        plt.close("all")
    for f in (kp.velocity_plan, kp.acceleration_plan):
        ax = f(sol, pos)
        _labelled(ax)
        assert ax.get_legend() is not None
        plt.close("all")
    ax = kp.draw_mechanism(sol, pos, forces=True, loads=True)
    _labelled(ax)
    assert ax.get_aspect() == 1.0


@pytest.mark.parametrize("name", sorted(REPEATS))
def test_a_repeated_mechanism_draws_as_its_first(name, sols):
    """A scene repeating another's mechanism (a ``[design]`` table added) is solved to
    the same bit, under the same title: every picture, drawn from the solution, is the
    other scene's (drawn by test_every_picture_of_every_scene)."""
    sol, first = sols[name], sols[REPEATS[name]]
    assert name in {p.stem for p in SCENE_PATHS} - set(DRAWN)
    assert sol.scene.title == first.scene.title
    assert np.array_equal(sol.positions, first.positions) and np.array_equal(sol.Me, first.Me)
    for table in ("kinematics", "reactions"):
        pd.testing.assert_frame_equal(getattr(sol, table), getattr(first, table),
                                      check_exact=True)


def test_plans_show_the_computed_vectors(sols):
    sol = sols["four_bar"]
    i = 30
    ax = kp.velocity_plan(sol, row=i)
    k = sol.kinematics
    b = k[(k.body == "crank") & (k.point == "B")].iloc[i]
    tips = [a.xy for a in ax.texts if a.get_text() == "b"]
    assert tips and np.allclose(tips[0], (b.vx, b.vy))
    assert ax.get_xlabel() == "$v_x$ [m/s]"
    legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert f"{np.hypot(b.vx, b.vy):.3g} m/s" in legend and "ω(coupler)" in legend
    ax = kp.acceleration_plan(sol, row=i)
    c = k[(k.body == "coupler") & (k.point == "C")].iloc[i]
    tips = [a.xy for a in ax.texts if a.get_text() == "c"]
    assert np.allclose(tips[0], (c.ax, c.ay))
    assert ax.get_ylabel() == "$a_y$ [m/s²]"
    # the slotted lever: the guide's coincident point and the Coriolis term
    ax = kp.acceleration_plan(sols["slotted_lever"], 40)
    legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert "Coriolis" in legend and "a3" in legend


def test_force_polygon_arguments(sols):
    sol = sols["shaper"]
    a = kp.force_polygon(sol, "RRT", 30)
    b = kp.force_polygon(sol, ("ram", "link"), 30)
    assert a.get_title() == b.get_title() and "dyad 2 RRT" in a.get_title()
    assert "Me =" in kp.force_polygon(sol, "driver", 30).get_title()
    with pytest.raises(WorkbenchError, match="no dyad"):
        kp.force_polygon(sol, 7)
    # a sliding driver's polygon holds Fe
    ax = kp.force_polygon(sols["sliding_driver"], 0, 0.25)
    assert any("F_{e}" in t.get_text() for t in ax.get_legend().get_texts())


@pytest.mark.slow
def test_curves(sols):
    sol = sols["four_bar"]
    for f in (kp.plot_speeds, kp.plot_accelerations):
        ax = f(sol, ["coupler.P", "rocker.C"])
        _labelled(ax)
        assert len(ax.lines) == 2
        assert ax.get_xlabel() == "crank angle φ [deg]"
    ax = kp.plot_speeds(sols["slider_crank"], "piston.C", component="x")
    assert ax.get_ylabel() == "speed vx [m/s]"
    with pytest.raises(WorkbenchError, match="body.point"):
        kp.plot_speeds(sol, "P")
    with pytest.raises(WorkbenchError, match="component"):
        kp.plot_speeds(sol, component="z")
    fig = kp.plot_angular(sol)
    assert isinstance(fig, Figure) and len(fig.axes) == 3
    assert [a.get_ylabel() for a in fig.axes] == ["angle θ [deg]", "ω [rad/s]", "ε [rad/s²]"]
    for f in (kp.plot_driver, kp.plot_polar, kp.plot_transmission, kp.plot_trajectories):
        _labelled(f(sol))
    assert isinstance(kp.overview(sol), Figure)
    assert kp.plot_driver(sols["sliding_driver"]).get_ylabel() == "equilibrating force Fe [N]"


@pytest.mark.slow
def test_animation(sols):
    anim = kp.animate(sols["shaper"], frames=4)
    assert isinstance(anim, FuncAnimation)
    ax = anim._fig.axes[0]
    _labelled(ax)
    for f in range(4):
        anim._func(f)
    assert "shaper" in ax.get_title().lower() and "360" in ax.get_title()
    assert "<img" in anim.to_jshtml()
    with pytest.raises(WorkbenchError, match="frames"):
        kp.animate(sols["shaper"], frames=0)


def test_draw_gear_pair(monkeypatch):
    from kinetostatics.transmission.gears import gear_pair

    monkeypatch.setattr(plt, "show", lambda *a, **k: pytest.fail("plt.show called"))
    for internal in (False, True):
        pair = gear_pair([120.0, 60.0], 0.05, 0.15, 20.0, internal, centre_angle_deg=30.0)
        ax = kp.draw_gear_pair(pair)
        assert isinstance(ax, Axes)
        _labelled(ax)
        assert ax.get_xlabel() == "x [m]" and ax.get_ylabel() == "y [m]"
        assert ax.get_aspect() == 1.0
        assert ("internal" if internal else "external") in ax.get_title()
        assert f"$i_{{12}}$ = {reading(pair.i12)}" in ax.get_title()
        # two arrows from the pitch point: F12 along the computed force, F21 against it
        arrows = [t for t in ax.texts if t.arrow_patch is not None and not t.get_text()]
        assert len(arrows) == 2
        f = np.array([pair.F12x[0], pair.F12y[0]])
        for a, sign in zip(arrows, (1.0, -1.0), strict=True):
            np.testing.assert_allclose(a.xyann, pair.P, atol=1e-12)
            d = np.subtract(a.xy, a.xyann)
            np.testing.assert_allclose(d / np.hypot(*d), sign * f / np.hypot(*f), atol=1e-12)
        assert any(f"{reading(pair.F[0])} N" in t.get_text() for t in ax.texts)
        # pitch circles through P around each axis
        pitch = [ln for ln in ax.lines if ln.get_label().startswith("gear ")]
        for o, line in zip((pair.O1, pair.O2), pitch, strict=True):
            r = np.hypot(line.get_xdata() - o[0], line.get_ydata() - o[1])
            np.testing.assert_allclose(r, np.hypot(pair.P[0] - o[0], pair.P[1] - o[1]))
    # no load: the circles without arrows, on a given Axes
    _, ax0 = plt.subplots()
    assert kp.draw_gear_pair(gear_pair(0.0, 0.05, 0.15), ax=ax0) is ax0
    assert not [t for t in ax0.texts if t.arrow_patch is not None]
    with pytest.raises(WorkbenchError, match="GearPair"):
        kp.draw_gear_pair((0.05, 0.15))
