"""Guards for likely unit slips: a warning (Python and a ``warning:`` line on the command
line), never a change of the exit code or of the numbers."""

from __future__ import annotations

import subprocess
import sys
import tomllib
import warnings

import pytest

import kinetostatics as ks
from tests.helpers import to_toml


def four_bar(**driver) -> dict:
    with open(ks.example("four_bar"), "rb") as fh:
        d = tomllib.load(fh)
    d["driver"].update(driver)
    return d


def _warnings(d: dict) -> list[str]:
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        ks.solve(d)
    return [str(w.message) for w in seen if issubclass(w.category, ks.UnitWarning)]


def test_a_sweep_of_two_pi_degrees_warns() -> None:
    assert any("2 pi" in m for m in _warnings(four_bar(start=0.0, stop=6.2832, count=50)))
    assert _warnings(four_bar(start=0.0, stop=360.0, count=50)) == []
    assert _warnings(four_bar(start=0.0, stop=10.0, count=50)) == []


def test_a_speed_in_rpm_warns() -> None:
    assert any("rpm" in m for m in _warnings(four_bar(speed=1500.0 * 30)))
    assert _warnings(four_bar(speed=900.0)) == []


def test_millimetres_among_metres_warn() -> None:
    d = four_bar()
    d["bodies"][1]["cog"] = [125.0, 20.0]            # typed in mm
    msgs = _warnings(d)
    assert any("coupler" in m and "cog" in m and "millimetres" in m for m in msgs)
    d = four_bar()
    d["bodies"][1]["points"]["P"] = [100.0, 60.0]    # a coupler point in mm
    assert any("point P" in m for m in _warnings(d))


def test_the_cli_prints_a_warning_line_and_keeps_exit_code_0(tmp_path) -> None:
    d = four_bar(start=0.0, stop=6.2832, count=20)
    path = tmp_path / "slip.toml"
    path.write_text(to_toml(d))
    out = subprocess.run([sys.executable, "-m", "kinetostatics", "solve", str(path), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    warn = [ln for ln in out.stderr.splitlines() if ln.startswith("warning:")]
    assert len(warn) == 1 and "degrees" in warn[0]
    assert "Traceback" not in out.stderr and "UnitWarning" not in out.stderr


@pytest.mark.parametrize("name", ["four_bar", "shaper", "slider_crank", "sliding_driver"])
def test_bundled_scenes_do_not_warn(name) -> None:
    assert _warnings(ks.load_scene(ks.example(name))) == []


def test_scene_sources_say_what_is_wrong(tmp_path) -> None:
    """A path that is not a file, a directory, a non-UTF-8 file, a bundled name."""
    assert ks.solve("four_bar").summary()["positions"] == 361          # a bundled name
    with pytest.raises(ks.SceneError, match=r"nope\.toml: no such scene file"):
        ks.solve(str(tmp_path / "nope.toml"))
    with pytest.raises(ks.SceneError, match=r"nope: no such scene file, and not a bundled"):
        ks.solve("nope")
    with pytest.raises(ks.SceneError, match="is a directory"):
        ks.solve(str(tmp_path))
    bad = tmp_path / "latin1.toml"
    bad.write_bytes('title = "ok"\n\n# r\u00e9glage\n'.encode("latin-1"))
    with pytest.raises(ks.SceneError, match=r"save it as UTF-8 \(line 3\)"):
        ks.load_scene(bad)
