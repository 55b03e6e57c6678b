"""``python -m balance``: JSON output, text report, one-line errors with exit code 2."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import balance
from tests.balance._balance_cases import CASE_NAMES, EXPECTED, SCENES, assert_matches
from tests.helpers import run_main

ROOT = Path(balance.__file__).resolve().parents[1]


def run_process(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    """``python -m balance`` in a subprocess (the smoke test of the entry point)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([sys.executable, "-m", "balance", *args], capture_output=True,
                          text=True, cwd=cwd, env=env, timeout=60)


def run(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    """``python -m balance`` through its ``main`` in this process (no 1.5 s of imports)."""
    return run_main("balance", *args, cwd=cwd)


@pytest.fixture(scope="module")
def scene_files(tmp_path_factory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("scenes")
    out = {}
    for name in CASE_NAMES:
        out[name] = folder / f"{name}.toml"
        out[name].write_text(SCENES[name])
    bad = folder / "bad.toml"
    bad.write_text(SCENES["resonance_example"].replace("A3 = 495.0", "A3 = 10.0"))
    out["bad"] = bad
    typo = folder / "typo.toml"
    typo.write_text(SCENES["static_device"].replace("alpha", "alpah"))
    out["typo"] = typo
    return out


@pytest.mark.parametrize("name", CASE_NAMES)
def test_json_output(scene_files, name: str) -> None:
    p = run("solve", str(scene_files[name]), "--json")
    assert p.returncode == 0, p.stderr
    got = json.loads(p.stdout)
    assert_matches(got, EXPECTED[name])
    assert got == balance.solve(scene_files[name])     # the CLI prints solve()'s dict


def test_text_report_and_bundled_names() -> None:
    p = run_process("solve", "rotor_two_plane")      # the smoke test of `python -m balance`
    assert p.returncode == 0, p.stderr
    assert "plane 1" in p.stdout and "N m" in p.stdout
    assert p.stdout == run("solve", "rotor_two_plane").stdout
    p = run("solve", "four_run")
    assert p.returncode == 0 and "mirror" in p.stdout
    p = run("examples")
    assert p.returncode == 0 and "four_run" in p.stdout
    p = run("solve", "four_bar_balancing")
    assert p.returncode == 0, p.stderr
    assert "counterweight on crank about A" in p.stdout and "shaking force" in p.stdout


@pytest.mark.parametrize("key", ["bad", "typo", "missing"])
def test_bad_scene_exits_2_with_one_line(scene_files, key: str) -> None:
    path = scene_files.get(key, Path("/no/such/scene.toml"))
    p = run("solve", str(path), "--json")
    assert p.returncode == 2
    assert p.stdout == ""
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:")
    assert "Traceback" not in p.stderr


def test_usage_errors_are_one_line() -> None:
    for args in ([], ["frobnicate"], ["solve"]):
        p = run(*args)
        assert p.returncode == 2
        lines = p.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error:"), p.stderr


def test_warning_is_one_line_and_exit_0(scene_files, tmp_path) -> None:
    f = tmp_path / "clip.toml"
    f.write_text("[[resonance_test]]\ntrial_mass = 0.01\ntrial_radius = 0.1\n"
                 "correction_radius = 0.1\nA1 = 1.0\nA2 = 3.00000000015\nA3 = 1.0\n")
    p = run("solve", str(f), "--json")
    assert p.returncode == 0, p.stderr
    assert p.stderr.startswith("warning:") and "Traceback" not in p.stderr
    assert json.loads(p.stdout)["resonance_test"][0]["phi"] == 0.0


# ------------------------------------------------------------ field sections, report
ILL = """
[[influence]]
name = "nearly parallel planes"
initial = [[2.0, 30.0], [2.002, 30.05]]
noise = { relative = 0.01 }
phase_noise = 0.0
runs = [
  { plane = 1, mass = 1.0, angle = 0.0, readings = [[2.8, 20.0], [2.802, 20.04]] },
  { plane = 2, mass = 1.0, angle = 0.0, readings = [[2.81, 20.0], [2.813, 20.05]] },
]
"""


def test_field_examples_listed_and_readable() -> None:
    p = run("examples")
    for name in ("influence_two_plane", "influence_speeds", "trim_run", "iso_tolerance",
                 "split_combine"):
        assert name in p.stdout
    p = run("solve", "influence_two_plane")
    assert p.returncode == 0 and p.stderr == ""
    assert "plane 1: add 1.979 g at 236.2 deg" in p.stdout
    assert "on 12 positions" in p.stdout
    p = run("solve", "iso_tolerance")
    assert "U_per = 200.5 g mm" in p.stdout and "within tolerance" in p.stdout


def test_result_warnings_are_warning_lines_exit_0(tmp_path) -> None:
    f = tmp_path / "ill.toml"
    f.write_text(ILL)
    p = run("solve", str(f), "--json")
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    warns = out["influence"][0]["warnings"]
    assert warns and any("condition number" in w for w in warns)
    lines = p.stderr.strip().splitlines()
    assert len(lines) == len(warns)
    assert all(line.startswith("warning: influence[0]: ") for line in lines)


def test_bad_field_input_is_one_error_line(tmp_path) -> None:
    f = tmp_path / "bad.toml"
    f.write_text('[units]\nmass = "pound"\n' + ILL)
    p = run("solve", str(f))
    assert p.returncode == 2 and p.stdout == ""
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and "pound" in lines[0]
    p = run("solve", "trim_run", "--report", str(tmp_path / "r.txt"))
    assert p.returncode == 2 and p.stderr.startswith("error:") and ".html or .pdf" in p.stderr


def _html_check(text: str) -> list[bytes]:
    """Tags balanced (a small stack parser) and the embedded PNGs decoded."""
    import base64
    import re
    from html.parser import HTMLParser

    class Checker(HTMLParser):
        def __init__(self) -> None:
            super().__init__()
            self.stack: list[str] = []
            self.bad = 0

        def handle_starttag(self, tag, attrs) -> None:
            if tag not in ("meta", "img", "br"):
                self.stack.append(tag)

        def handle_endtag(self, tag) -> None:
            if self.stack and self.stack[-1] == tag:
                self.stack.pop()
            else:
                self.bad += 1

    c = Checker()
    c.feed(text)
    assert text.startswith("<!DOCTYPE html>") and c.stack == [] and c.bad == 0
    return [base64.b64decode(b, validate=True)
            for b in re.findall(r'src="data:image/png;base64,([^"]+)"', text)]


# the quick tier draws one report (iso_tolerance), the slow tier every kind (0.7-2.5 s each)
@pytest.mark.parametrize("name, n_pictures", [
    pytest.param("influence_two_plane", 1, marks=pytest.mark.slow),
    pytest.param("four_run", 2, marks=pytest.mark.slow),
    pytest.param("rotor_two_plane", 1, marks=pytest.mark.slow), ("iso_tolerance", 1)])
def test_html_report(tmp_path, name: str, n_pictures: int) -> None:
    import io

    import matplotlib.image as mpimg

    f = tmp_path / f"{name}.html"
    p = run("solve", name, "--report", str(f))
    assert p.returncode == 0, p.stderr
    text = f.read_text(encoding="utf-8")
    pngs = _html_check(text)
    assert len(pngs) == n_pictures
    for png in pngs:
        img = mpimg.imread(io.BytesIO(png), format="png")
        assert img.shape[0] > 300 and img.shape[1] > 300
        assert img[..., :3].std() > 0.01                   # not a blank picture
    assert "Data (the scene)" in text and "Warnings" in text
    if name == "iso_tolerance":
        assert "ISO 21940-11 check: the residual unbalance is within tolerance" in text


@pytest.mark.slow     # a PDF report through the command line (test_html_report keeps the smoke)
def test_html_report_lists_the_warnings_and_pdf(tmp_path) -> None:
    f = tmp_path / "ill.toml"
    f.write_text(ILL)
    p = run("solve", str(f), "--report", str(tmp_path / "ill.html"))
    assert p.returncode == 0 and p.stderr.startswith("warning:")
    text = (tmp_path / "ill.html").read_text(encoding="utf-8")
    assert 'class="warn">influence[0]: the correction is not determined' in text
    p = run("solve", "influence_two_plane", "--report", str(tmp_path / "r.pdf"))
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "r.pdf").read_bytes()[:5] == b"%PDF-"


def test_report_from_python(tmp_path) -> None:
    from balance import example_path
    from balance.report import report_scene

    f = report_scene(example_path("trim_run"), tmp_path / "sub" / "trim.html")
    pngs = _html_check(f.read_text(encoding="utf-8"))
    assert len(pngs) == 1 and pngs[0][:8] == b"\x89PNG\r\n\x1a\n"
