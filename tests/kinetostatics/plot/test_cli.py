"""``solve SCENE --plot DIR`` and ``demo SCENE``: pictures written, units in the console,
one-line errors."""

from __future__ import annotations

import json

import matplotlib.pyplot as plt
import pytest

from kinetostatics.cli import main
from kinetostatics.plot import cli as plot_cli


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def drawn_once(monkeypatch, sol, positions, figs) -> list:
    """The command line draws its pictures with the figures :func:`cli_pictures` drew
    once per session for the same scene, in the same style, at the same positions (the
    same call, asserted here: the tests of the figures measure them, these the files
    and the console); the positions asked for, as the command line passed them."""
    asked = []

    def drawn(s, positions_asked=None):
        asked.append(positions_asked)
        assert s.scene.title == sol.scene.title and list(positions_asked) == positions
        assert plt.rcParams["figure.dpi"] == 150        # in the lecture style
        return dict(figs)
    monkeypatch.setattr(plot_cli, "cli_figures", drawn)
    return asked


@pytest.mark.slow
@pytest.mark.parametrize("name", ["slider_crank"])
def test_solve_plot_writes_the_pictures(name, cli_pictures, tmp_path, capsys, monkeypatch):
    sol, positions, figs = cli_pictures(name)
    assert len(positions) == 2
    asked = drawn_once(monkeypatch, sol, positions, figs)
    out = tmp_path / "pics"
    at = [f"{p:g}" for p in positions]
    assert main(["solve", name, "--plot", str(out), "--plot-at", *at]) == 0
    assert asked == [positions]
    printed = capsys.readouterr().out
    names = {p.name for p in out.glob("*.png")}
    expect = {"overview.png", "driver.png", "polar_A.png", "polar_B.png", "polar_C.png"}
    for t in at:
        expect |= {f"mechanism_{t}deg.png", f"velocity_plan_{t}deg.png",
                   f"acceleration_plan_{t}deg.png", f"instant_centres_{t}deg.png",
                   f"free_body_{t}deg_driver.png", f"free_body_{t}deg_dyad1.png"}
    assert expect <= names, expect - names
    assert all((out / n).stat().st_size > 10_000 for n in expect)
    from PIL import Image
    for n in names:                                    # at 150 dpi, the lecture size
        with Image.open(out / n) as im:
            assert round(im.info["dpi"][0]) == 150, n
    assert str(out / "overview.png") in printed
    assert "Me mean" in printed and "warnings: none" in printed    # the summary follows


def test_solve_plot_default_position_and_errors(tmp_path, capsys, monkeypatch):
    # no --plot-at: the default position (where |Me| is largest) is write_pictures'
    # choice; the pictures it draws there are checked by test_demo_scene (same call)
    calls = []
    real = plot_cli.write_pictures
    monkeypatch.setattr(plot_cli, "write_pictures",
                        lambda sol, out, positions=None, dpi=150:
                        calls.append((positions, dpi)) or [])
    assert main(["solve", "four_bar", "--plot", str(tmp_path)]) == 0
    assert calls == [(None, 150)]
    capsys.readouterr()
    monkeypatch.setattr(plot_cli, "write_pictures", real)
    assert main(["solve", "four_bar", "--plot", str(tmp_path), "--plot-at", "400"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --plot-at 400: outside the sweep [0, 360] deg")
    f = tmp_path / "file"
    f.write_text("x")
    assert main(["solve", "four_bar", "--plot", str(f)]) == 2
    assert "is a file, not a folder" in capsys.readouterr().err


@pytest.mark.slow
@pytest.mark.parametrize("name", ["slotted_lever"])
def test_demo_scene(name, cli_pictures, tmp_path, capsys, monkeypatch):
    sol, positions, figs = cli_pictures(name)
    # every picture at one stated position (where |Me| is largest), the overview too
    asked = drawn_once(monkeypatch, sol, positions, figs)
    assert main(["demo", name, "--out", str(tmp_path)]) == 0
    assert asked == [positions]
    out = capsys.readouterr().out
    assert out.startswith("Crank and slotted lever")
    assert " deg\n" in out and "max |F| =" in out and " N at " in out
    # the tables and summary beside the pictures (``demo`` alone, the four-bar, is
    # checked the same way in tests/kinetostatics/test_cli.py with its drawing recorded)
    for stem in ("reactions.csv", "driver.csv", "kinematics.csv", "bodies.csv",
                 "summary.json", "overview.png"):
        assert (tmp_path / stem).is_file(), stem
    assert "Me mean" in out
    s = json.loads((tmp_path / "summary.json").read_text())
    assert {"Me_mean", "Me_max", "Me_min", "reaction_max", "transmission_angle_min",
            "singular_rows"} <= set(s)
    # the driver's free-body diagram named "driver", the dyads numbered from 1
    import numpy as np
    at = float(sol.positions[int(np.argmax(np.abs(sol.Me)))])
    assert positions == [at]
    assert f"pictures at φ = {at:g} deg, where |Me| is largest" in out
    names = {p.name for p in tmp_path.glob("*.png")}
    assert {f"free_body_{at:g}deg_driver.png", f"free_body_{at:g}deg_dyad1.png"} <= names
    assert not any("dyad0" in n for n in names)
    # the old form still works (its pictures are the same code as above: not drawn again,
    # a sliding driver's figures are drawn in test_pictures and test_collisions)
    drawn = []
    monkeypatch.setattr(plot_cli, "write_pictures",
                        lambda sol, out, positions=None, dpi=150: drawn.append(out) or [])
    assert main(["demo", "--example", "sliding_driver", "--out", str(tmp_path / "s")]) == 0
    assert " m\n" in capsys.readouterr().out           # a sliding driver's position unit
    # drawn once, into the run's staging folder inside s (kinetostatics.model.outputs)
    assert len(drawn) == 1 and drawn[0].parent == tmp_path / "s"
    assert (tmp_path / "s" / "reactions.csv").exists()
    assert [p.name for p in (tmp_path / "s").iterdir() if p.name.startswith(".")] == []


def test_demo_of_a_cam_scene_points_to_the_cam_command(tmp_path, capsys):
    assert main(["demo", "translating_roller", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.strip() == ("error: translating_roller is a cam scene: run "
                           "python -m kinetostatics cam translating_roller")
    assert main(["demo", "--example", "translating_roller", "--out", str(tmp_path)]) == 2
