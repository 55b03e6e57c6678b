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

ROOT = Path(balance.__file__).resolve().parents[1]


def run(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([sys.executable, "-m", "balance", *args], capture_output=True,
                          text=True, cwd=cwd, env=env, timeout=60)


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
    p = run("solve", "rotor_two_plane")
    assert p.returncode == 0, p.stderr
    assert "plane 1" in p.stdout and "N m" in p.stdout
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
