"""Bad input at the extremes: a full disk, memory over the budget, TOML nested too deep.
Each ends in one WorkbenchError line (exit 2 on the command line) with earlier results
whole, never a traceback or a half-written folder."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.memory import ENV, MemoryBudgetError, budget, parse_size
from kinetostatics.model.outputs import FAILED
from tests.helpers import ROOT

# the command line under a file-size limit (a full disk): SIGXFSZ ignored, so that a
# write past the limit fails with EFBIG instead of killing the process
FULL_DISK = """
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
limit = int(sys.argv.pop(1))
resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
from kinetostatics.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _run(*args: str, limit: int | None = None, env: dict | None = None):
    code = ["-c", FULL_DISK, str(limit)] if limit is not None else ["-m", "kinetostatics"]
    return subprocess.run([sys.executable, *code, *args], capture_output=True, text=True,
                          cwd=ROOT, env=dict(os.environ, MPLBACKEND="Agg", **(env or {})),
                          timeout=300)


def _files(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def _one_error_line(r) -> None:
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    assert "internal error" not in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow     # whole runs written and broken on purpose (1.6 s)
@pytest.mark.skipif(not hasattr(os, "fork") or sys.platform == "darwin",
                    reason="RLIMIT_FSIZE as a full disk: Linux")
def test_a_full_disk_leaves_earlier_results_whole(tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert _run("solve", "four_bar", "--out", str(out)).returncode == 0
    before = _files(out)
    # kinematics.csv (about 460 kB at 361 rows) passes the 200 kB limit: the run fails
    r = _run("solve", "four_bar", "--out", str(out), "--format", "csv", limit=200_000)
    _one_error_line(r)
    assert "File too large" in r.stderr and str(out) in r.stderr
    after = _files(out)
    note = after.pop(FAILED).decode()
    # every earlier table as it was; no summary.json left looking current
    assert before.pop("summary.json") and after == before
    assert "failed" in note and "earlier run" in note
    # a new folder: none left behind
    r = _run("solve", "four_bar", "--out", str(tmp_path / "new"), limit=200_000)
    _one_error_line(r)
    assert not (tmp_path / "new").exists()
    # a cam run under the same limit (its tables are about 100 kB each at 361 rows)
    r = _run("cam", "translating_roller", "--out", str(tmp_path / "cam"), limit=50_000)
    _one_error_line(r)
    assert not (tmp_path / "cam").exists()


@pytest.mark.slow     # whole runs written and broken on purpose (1.3 s)
def test_a_failed_run_marks_the_earlier_results(tmp_path: Path) -> None:
    """Issue #30 item 8: a bad scene into a folder of earlier results leaves their tables
    with FAILED.txt beside them and no summary.json looking current; the next good run
    removes the note."""
    out = tmp_path / "out"
    assert _run("solve", "four_bar", "--out", str(out)).returncode == 0
    before = _files(out)
    bad = tmp_path / "bad.toml"
    bad.write_text("x = 1\n")
    r = _run("solve", str(bad), "--out", str(out))
    _one_error_line(r)
    after = _files(out)
    assert "unknown key 'x'" in after.pop(FAILED).decode()
    assert before.pop("summary.json") and after == before
    assert _run("solve", "four_bar", "--out", str(out)).returncode == 0
    assert not (out / FAILED).exists()
    # a bad scene into a new folder makes no folder
    _one_error_line(_run("solve", str(bad), "--out", str(tmp_path / "none")))
    assert not (tmp_path / "none").exists()


def test_parquet_after_csv_replaces_the_run_whole(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    sol = ks.solve(ks.example("four_bar"))
    sol.write(tmp_path, "csv")
    (tmp_path / "mine.txt").write_text("kept")
    sol.write(tmp_path, "parquet")
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted([f"{n}.parquet" for n in sol.FILES] + ["summary.json", "mine.txt"])


def test_the_budget_is_read_and_told(monkeypatch: pytest.MonkeyPatch) -> None:
    assert parse_size("2G") == 2e9 and parse_size("1500M") == 1.5e9
    assert parse_size("512MiB") == 512 * 2**20 and parse_size("3e9") == 3e9
    for bad in ("x", "2Q", "0", "-1G", "1e400"):
        with pytest.raises(ks.WorkbenchError, match="give a size"):
            parse_size(bad)
    monkeypatch.delenv(ENV, raising=False)
    limit, source = budget()
    assert limit > 0 and "available" in source
    monkeypatch.setenv(ENV, "700M")
    assert budget() == (7e8, f"set by {ENV}=700M")


def test_a_solve_over_the_budget_is_refused_before_it_starts(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(ENV, "100M")
    raw = ks.load_scene(ks.example("four_bar")).raw
    raw["driver"] = {**raw["driver"], "count": 10_000_000}
    with pytest.raises(MemoryBudgetError, match=r"10,000,000 positions needs about 6\.\d+ GB"
                       r".*budget of 100 MB \(set by WORKBENCH_MEMORY=100M\); use fewer"):
        ks.solve(raw)
    # a list of 1e7 positions
    with pytest.raises(MemoryBudgetError, match="10,000,000 positions"):
        ks.solve(ks.example("four_bar"), positions=np.linspace(0.0, 359.0, 10_000_000))
    with pytest.raises(MemoryBudgetError, match="solving 2 scene"):
        ks.solve_many([raw, ks.example("four_bar")])
    # within the budget it runs
    monkeypatch.setenv(ENV, "2G")
    raw["driver"]["count"] = 200_000
    assert ks.solve(raw).positions.size == 200_000


def test_cam_and_motion_over_the_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    from kinetostatics.cams import solve_cam
    from kinetostatics.model.tomlio import read_source
    monkeypatch.setenv(ENV, "500M")
    raw = read_source(ks.scene_path("translating_roller"))
    raw["cam"] = {**raw["cam"], "count": 10_000_000}
    with pytest.raises(MemoryBudgetError, match="the cam at 10,000,000 angles"):
        solve_cam(raw)
    raw = ks.load_scene(ks.example("four_bar_motion")).raw
    raw["motion"] = {**raw["motion"], "cycles": 100_000}
    with pytest.raises(MemoryBudgetError, match="100,000 cycles"):
        ks.simulate_motion(raw)


def test_the_command_line_refuses_in_one_line(tmp_path: Path) -> None:
    scene = tmp_path / "big.toml"
    text = (ROOT / "kinetostatics" / "scenes" / "four_bar.toml").read_text()
    scene.write_text(text.replace("count = 361", "count = 10000000"))
    r = _run("solve", str(scene), "--out", str(tmp_path / "out"), "--memory", "1G")
    _one_error_line(r)
    assert "budget of 1.00 GB" in r.stderr and not (tmp_path / "out").exists()
    _one_error_line(_run("solve", "four_bar", "--memory", "lots"))


@pytest.mark.parametrize("text", [
    "x = " + "[" * 2000 + "]" * 2000,                       # RecursionError before
    "x = " + "{a = " * 2000 + "1" + "}" * 2000,
    "a" + ".a" * 99_999 + " = 1",                           # 3.3 GB and 100 s before
    "[" + "a." * 5000 + "a]\nx = 1",
    "x = " + "[" * 150,                                     # invalid and deep
])
def test_deep_toml_is_one_line(text: str) -> None:
    with pytest.raises(ks.SceneError, match="levels deep; a scene needs a few"):
        ks.load_scene(text)


def test_moderate_nesting_and_brackets_in_strings_pass_the_depth_check() -> None:
    from kinetostatics.model.tomlio import parse_toml
    assert parse_toml("x = " + "[" * 99 + "]" * 99)["x"] is not None
    text = 'x = "' + "[" * 500 + '"  # ' + "{" * 300 + "\n" + "y = '" + "a." * 200 + "'\n"
    assert parse_toml(text) == {"x": "[" * 500, "y": "a." * 200}
    with pytest.raises(ks.SceneError, match="not valid TOML"):
        parse_toml("x = [1, 2", "scene")
