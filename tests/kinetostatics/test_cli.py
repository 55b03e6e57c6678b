"""The command line: demo, solve, structure, bench; errors are one line with exit code 2."""

import json
import os
import subprocess
import sys

import pandas as pd
import pytest

from tests.helpers import OWN_CASES, ROOT, run_main


def run_process(*args, cwd=None):
    """``python -m kinetostatics`` in a subprocess (the entry point's smoke test)."""
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-m", "kinetostatics", *args], capture_output=True,
                          text=True, cwd=cwd or ROOT, env=env, timeout=300)


def run(*args, cwd=None):
    """``python -m kinetostatics`` through its ``main`` in this process."""
    return run_main("kinetostatics", *args, cwd=cwd)


def test_demo_writes_tables_and_picture(tmp_path, monkeypatch):
    """``demo`` alone: the bundled four-bar's tables and summary, the key numbers
    printed, its pictures drawn once into the run's folder. (The drawing is that of
    ``demo SCENE``: tests/kinetostatics/plot/test_cli.py runs it for real and checks
    these files and every picture; here it is recorded, not drawn again.)"""
    import numpy as np

    from kinetostatics import solve
    from kinetostatics.plot import cli as plot_cli
    drawn = []
    monkeypatch.setattr(plot_cli, "write_pictures",
                        lambda sol, out, positions=None, dpi=150:
                        drawn.append((sol, out, dpi)) or [])
    r = run("demo", "--out", str(tmp_path))
    assert r.returncode == 0, r.stderr
    for name in ("reactions.csv", "driver.csv", "kinematics.csv", "bodies.csv",
                 "summary.json"):
        assert (tmp_path / name).is_file()
    assert "Me mean" in r.stdout
    s = json.loads((tmp_path / "summary.json").read_text())
    for key in ("Me_mean", "Me_max", "Me_min", "reaction_max", "transmission_angle_min",
                "singular_rows"):
        assert key in s
    # drawn once (at 150 dpi), into the run's staging folder inside --out, for the four-bar
    assert len(drawn) == 1 and drawn[0][1].parent == tmp_path and drawn[0][2] == 150
    assert np.array_equal(drawn[0][0].Me, solve("four_bar").Me)


def test_solve_writes_contract_csv(tmp_path):
    r = run_process("solve", str(OWN_CASES / "slider_crank.toml"), "--out", str(tmp_path))
    assert r.returncode == 0, r.stderr
    rx = pd.read_csv(tmp_path / "reactions.csv")
    assert list(rx.columns[:7]) == ["position", "joint", "on", "by", "Fx", "Fy", "F"]
    assert {"N", "M", "offset"} <= set(rx.columns)
    drv = pd.read_csv(tmp_path / "driver.csv")
    assert list(drv.columns) == ["position", "Me", "singular", "undefined_load"]
    assert drv.undefined_load.sum() == 3      # 0, 180 and 360 deg: the piston stands still
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["singular_rows"] == 0
    # full precision in the CSV
    k = pd.read_csv(tmp_path / "kinematics.csv")
    assert set(k.columns) == {"position", "body", "point", "x", "y", "vx", "vy", "ax", "ay"}


def test_sliding_driver_table_has_fe(tmp_path):
    r = run("solve", str(OWN_CASES / "sliding_driver.toml"), "--out", str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert "Fe" in pd.read_csv(tmp_path / "driver.csv").columns
    assert "Fe_mean" in json.loads((tmp_path / "summary.json").read_text())


@pytest.mark.parametrize("text,word", [
    ("[driver]\nbody = 'x'\n", "missing"),
    ("this is not toml", "TOML"),
])
def test_bad_scene_exit_2_one_line(tmp_path, text, word):
    p = tmp_path / "bad.toml"
    p.write_text(text)
    r = run("solve", str(p))
    assert r.returncode == 2
    assert r.stderr.startswith("error: ") and word in r.stderr
    assert "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


@pytest.mark.parametrize("package,args", [
    ("kinetostatics", ["solve", "four_bar", "--dpi", "x"]),
    ("kinetostatics", ["solve", "four_bar", "--no-such-option"]),
    ("kinetostatics", ["no-such-command"]),
    ("balance", ["solve", "rotor_two_plane", "--dpi", "x"]),
])
def test_bad_option_is_one_error_line(package, args):
    """argparse's mistakes too: one ``error:`` line (no usage lines above it), exit 2."""
    r = run_main(package, *args)
    assert r.returncode == 2
    assert r.stderr.startswith("error: ") and r.stderr.count("\n") == 1, r.stderr
    assert "--help" in r.stderr


def test_missing_file_exit_2():
    r = run("solve", "no/such/scene.toml")
    assert r.returncode == 2 and r.stderr.startswith("error:")


def test_structure_command():
    r = run("structure", str(OWN_CASES / "slotted_lever.toml"))
    assert r.returncode == 0 and "RTR" in r.stdout


def _bench(*args: str):
    """``python -m kinetostatics bench ARGS`` in this process (its start-up rows time
    fresh processes of their own; test_solve_writes_contract_csv keeps the ``python -m``
    entry), pandas' display options as they were (the tables widen them)."""
    with pd.option_context("display.width", pd.get_option("display.width")):
        return run("bench", *args)


@pytest.mark.slow
def test_bench_quick():
    """``bench --quick`` prints its tables; one round of every timed row (``--repeat 1``:
    18 s of CPU against 33 s at the rows' own 3 to 25 rounds on a warm numba cache,
    measured 2026-11-29; 4.3 s since the timing loops freeze the heap and the quick
    solve_many rows check 5 scenes' tables, 2026-11-30; the ratios are not checked
    here, only that every row runs)."""
    r = _bench("--quick", "--repeat", "1")
    assert r.returncode == 0, r.stderr
    assert "positions_per_s" in r.stdout and "max_rel_error" in r.stdout
    for row in ("speed-up: loop of solve / solve_many", "hand-written fourbar_dyad",
                "import balance", "design: rows per second"):
        assert row in r.stdout, row


def test_cam_command(tmp_path):
    """The [cam] scene of docs/cam-scenes.md through the command line."""
    text = (ROOT / "docs" / "cam-scenes.md").read_text()
    scene = text.split("```toml\n", 1)[1].split("```", 1)[0]
    p = tmp_path / "cam.toml"
    p.write_text(scene)
    r = run("cam", str(p), "--out", str(tmp_path / "out"))
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    assert s["transmission_angle_min"] >= 45.0 - 1e-9
    assert (tmp_path / "out" / "geometry.csv").is_file()
    bad = tmp_path / "bad.toml"
    bad.write_text(scene.replace("stroke", "strok"))
    r = run("cam", str(bad))
    assert r.returncode == 2 and r.stderr.startswith("error:") and "stroke" in r.stderr


@pytest.mark.slow
def test_bundled_names_work_in_every_command():
    """The CLI takes a bundled example's name as well as a path: the mechanism, motion
    and cam examples all run; an unknown name lists the known ones."""
    import kinetostatics as ks
    assert {"four_bar_motion"} <= set(ks.examples())
    assert {"translating_roller", "oscillating_roller"} <= set(ks.cam_examples())
    p = run("structure", "shaper")
    assert p.returncode == 0 and "RTR" in p.stdout and "RRT" in p.stdout
    p = run("motion", "four_bar_motion", "--json")
    assert p.returncode == 0, p.stderr
    summary = json.loads(p.stdout)["summary"]
    assert summary["steady"] and 0.0 < summary["delta"] < 1.0
    assert summary["flywheel_for_target"] > 0.02          # delta 0.02 needs a bigger one
    for name in ks.cam_examples():
        p = run("cam", name)
        assert p.returncode == 0, p.stderr
        assert json.loads(p.stdout)["transmission_angle_min"] >= 45.0 - 1e-9
    p = run("solve", "no_such_example")
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and "four_bar" in p.stderr
    # the wrong kind of scene for a command says which kind it needs
    p = run("cam", "four_bar")
    assert p.returncode == 2 and "mechanism scene" in p.stderr and "[cam]" in p.stderr
    p = run("motion", "four_bar")
    assert p.returncode == 2 and "four_bar_motion" in p.stderr


def test_solve_parquet_and_help(tmp_path):
    """--format parquet writes the tables as Parquet; --help says what count costs."""
    pytest.importorskip("pyarrow")
    r = run("solve", str(OWN_CASES / "slider_crank.toml"), "--out", str(tmp_path),
            "--format", "parquet")
    assert r.returncode == 0, r.stderr
    k = pd.read_parquet(tmp_path / "kinematics.parquet")
    assert list(k.columns) == ["position", "body", "point", "x", "y", "vx", "vy", "ax", "ay"]
    assert str(k.body.dtype) == "category" and (tmp_path / "summary.json").is_file()
    h = run("solve", "--help")
    assert "What count costs" in h.stdout and "--format" in h.stdout


def test_solve_warns_on_long_tables(tmp_path, monkeypatch, capsys):
    """A table over the warning's row count is announced on stderr with its size and
    time (the threshold lowered here to keep the run small)."""
    from kinetostatics import cli
    from kinetostatics.results import output
    monkeypatch.setattr(output, "WARN_ROWS", 1000)
    rc = cli.main(["solve", str(OWN_CASES / "four_bar.toml"), "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert rc == 0
    lines = [x for x in err.splitlines() if x.startswith("warning: kinematics.csv")]
    assert len(lines) == 1 and " MB of CSV and " in lines[0] and " rows" in lines[0]
    assert "driver.csv" not in err                       # 361 rows: no warning


def test_parquet_without_pyarrow_is_one_error_line(tmp_path, monkeypatch, capsys):
    from kinetostatics import cli
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    rc = cli.main(["solve", str(OWN_CASES / "four_bar.toml"), "--out", str(tmp_path),
                   "--format", "parquet"])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("error: ") and "pyarrow" in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.slow
def test_bench_tables_quick():
    """bench --tables reports solve, table and CSV times with peak memory (small sizes)."""
    r = _bench("--tables", "--quick", "--repeat", "1")
    assert r.returncode == 0, r.stderr
    for word in ("solve_s", "kinematics_s", "long_tables_over_solve", "csv_MB_per_s",
                 "peak_MB", "cli_out_s", "best", "median", "start-up", "over_numpy",
                 "import balance", "balance solve rotor_two_plane"):
        assert word in r.stdout, word


def test_a_mean_that_is_rounding_is_said_as_zero():
    """The four-bar's Me over a whole cycle of conservative loads averages to rounding
    (6.3e-16 N m beside a 21.8 N m peak): the text says 0, the JSON keeps the number."""
    from kinetostatics import solve
    from kinetostatics.results.output import summary_with_units
    from kinetostatics.results.text import summary_text

    sol = solve("four_bar")
    s = summary_with_units(sol.summary(), sol.scene.units, sol.scene.warnings, "deg")
    assert 0 < abs(s["Me_mean"]) < 1e-12 * s["Me_max"]
    assert "Me mean 0 (to rounding), min -16.6826 N m" in summary_text(s)
    s["Me_mean"] = 1e-3                 # a small mean that is not rounding stays a number
    assert "Me mean 0.001 N m, min" in summary_text(s)


@pytest.mark.parametrize("module, args", [("kinetostatics", ["solve", "four_bar", "--json"]),
                                          ("balance", ["solve", "rotor_two_plane"])])
def test_a_reader_that_goes_away_gets_no_error(module, args):
    """``... | head -1``: the rest of the output is dropped without an error line or a
    traceback (was: "error: [Errno 32] Broken pipe", exit 2)."""
    env = dict(os.environ, MPLBACKEND="Agg")
    p = subprocess.Popen([sys.executable, "-m", module, *args], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, cwd=ROOT, env=env)
    p.stdout.readline()
    p.stdout.close()            # the reader goes away before the writer is done
    err = p.stderr.read().decode()
    assert p.wait(timeout=120) == 0 and err == "", err
