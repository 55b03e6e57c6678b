"""Outputs written whole or not at all (kinetostatics.model.outputs)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from kinetostatics.model.outputs import FAILED, atomic_file, failure_noted, staged_folder

KIND = ("*.csv", "summary.json")


def _listing(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def test_a_run_is_put_in_place_whole(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with staged_folder(out, KIND) as stage:
        stage.file("a.csv").write_text("1\n")
        stage.file("summary.json").write_text("{}\n")
        assert not (out / "a.csv").exists()        # nothing in place before the end
    assert _listing(out) == {"a.csv": b"1\n", "summary.json": b"{}\n"}


def test_a_failed_run_leaves_the_earlier_files_untouched(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "a.csv").write_text("old\n")
    (out / "summary.json").write_text("old\n")
    (out / "notes.txt").write_text("mine\n")
    before = _listing(out)
    with pytest.raises(RuntimeError), staged_folder(out, KIND) as stage:
        stage.file("a.csv").write_text("new\n")
        raise RuntimeError("halfway")
    assert _listing(out) == before


def test_a_failed_run_into_a_new_folder_leaves_no_folder(tmp_path: Path) -> None:
    out = tmp_path / "deep" / "out"
    with pytest.raises(KeyboardInterrupt), staged_folder(out, KIND) as stage:
        stage.file("a.csv").write_text("new\n")
        raise KeyboardInterrupt
    assert not out.exists()


def test_a_new_run_replaces_the_earlier_one_as_a_whole(tmp_path: Path) -> None:
    """The earlier run's files of the same kind that the new run does not write go; the
    user's other files stay."""
    out = tmp_path / "out"
    out.mkdir()
    for name in ("a.csv", "b.csv", "summary.json", "notes.txt", FAILED):
        (out / name).write_text("old\n")
    with staged_folder(out, KIND) as stage:
        stage.file("a.csv").write_text("new\n")
        stage.file("summary.json").write_text("new\n")
    assert _listing(out) == {"a.csv": b"new\n", "notes.txt": b"old\n",
                             "summary.json": b"new\n"}


def test_failure_noted_marks_earlier_results_only(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with pytest.raises(ValueError), failure_noted(out, KIND, "solve"):
        raise ValueError("bad scene")
    assert not out.exists()                     # no folder made for the note
    out.mkdir()
    (out / "summary.json").write_text("old\n")
    (out / "a.csv").write_text("old\n")
    with pytest.raises(ValueError), failure_noted(out, KIND, "solve"):
        raise ValueError("bad scene")
    note = (out / FAILED).read_text()
    assert "solve" in note and "bad scene" in note and "earlier run" in note
    # no summary stays there looking current; the earlier tables stay, the note beside them
    assert "summary.json was removed" in note and not (out / "summary.json").exists()
    assert (out / "a.csv").read_text() == "old\n"
    with staged_folder(out, KIND) as stage:     # the next good run removes the note
        stage.file("summary.json").write_text("new\n")
    assert not (out / FAILED).exists()


def test_atomic_file(tmp_path: Path) -> None:
    path = tmp_path / "sub" / "report.html"
    with pytest.raises(RuntimeError), atomic_file(path) as tmp:
        tmp.write_text("half")
        raise RuntimeError
    assert not path.parent.exists()
    with atomic_file(path) as tmp:
        assert tmp.parent == path.parent and tmp.suffix == ".html"
        tmp.write_text("whole")
    assert path.read_text() == "whole"
    with pytest.raises(RuntimeError), atomic_file(path) as tmp:
        tmp.write_text("half")
        raise RuntimeError
    assert os.listdir(path.parent) == ["report.html"] and path.read_text() == "whole"


def test_a_killed_run_is_cleared_by_the_next(tmp_path: Path) -> None:
    """A run killed outright leaves its hidden staging folder; the next run removes it."""
    out = tmp_path / "out"
    code = ("import os, sys\nfrom kinetostatics.model.outputs import staged_folder\n"
            f"with staged_folder({str(out)!r}) as s:\n"
            "    s.file('a.csv').write_text('x')\n    os._exit(9)\n")
    subprocess.run([sys.executable, "-c", code], check=False)
    assert [p.name[:9] for p in out.iterdir()] == [".staging-"]
    with staged_folder(out, KIND) as stage:
        stage.file("a.csv").write_text("new\n")
    assert _listing(out) == {"a.csv": b"new\n"}
