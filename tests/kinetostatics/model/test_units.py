"""Guards for likely unit slips: a warning (Python and a ``warning:`` line on the command
line), never a change of the exit code or of the numbers."""

from __future__ import annotations

import json
import math
import tomllib
import warnings

import pytest

import kinetostatics as ks
from tests.helpers import run_main, to_toml


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
    assert any("'coupler'.points.cog" in m and "millimetres" in m for m in msgs)
    d = four_bar()
    d["bodies"][1]["points"]["P"] = [100.0, 60.0]    # a coupler point in mm
    assert any("points.P = [100, 60] m" in m for m in _warnings(d))


def test_the_cli_prints_a_warning_line_and_keeps_exit_code_0(tmp_path) -> None:
    d = four_bar(start=0.0, stop=6.2832, count=20)
    path = tmp_path / "slip.toml"
    path.write_text(to_toml(d))
    out = run_main("kinetostatics", "solve", str(path), "--out", str(tmp_path / "out"))
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


# ---------------------------------------------------------------- issue 18: [units], slips
def _all_warnings(fn, *args) -> list[str]:
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        fn(*args)
    return [str(w.message) for w in seen if issubclass(w.category, ks.UnitWarning)]


def _positions(values: list[float], units: dict | None = None) -> dict:
    d = four_bar()
    for k in ("start", "stop", "count"):
        d["driver"].pop(k)
    d["driver"]["positions"] = values
    if units:
        d["units"] = units
    return d


def test_positions_typed_in_radians_warn_under_degrees() -> None:
    rad = [0.0, 0.7854, 1.5708, 3.1416]             # 0, 45, 90, 180 deg typed in radians
    msgs = _warnings(_positions(rad))
    assert len(msgs) == 1 and "driver.positions" in msgs[0] and "radians" in msgs[0]
    assert _warnings(_positions(rad, {"angle": "rad"})) == []          # said so: no slip
    assert _warnings(_positions([0.0, 45.0, 90.0, 180.0])) == []
    assert _warnings(_positions([0.0, 1.0, 2.0, 3.0])) == []            # whole degrees


def test_positions_in_radians_are_converted_once() -> None:
    """angle = "rad": the tables give degrees (hand conversion: pi/4 rad = 45 deg)."""
    sol = ks.solve(_positions([0.0, math.pi / 4, math.pi / 2], {"angle": "rad"}))
    ref = ks.solve(_positions([0.0, 45.0, 90.0]))
    assert sol.driver["position"].to_numpy() == pytest.approx([0.0, 45.0, 90.0], abs=1e-13)
    assert sol.driver["Me"].to_numpy() == pytest.approx(ref.driver["Me"].to_numpy(),
                                                        rel=1e-12)   # measured 4e-16


def test_motion_slips_warn() -> None:
    with open(ks.example("four_bar_motion"), "rb") as fh:
        d = tomllib.load(fh)
    d["motion"]["omega0"] = 30000.0                 # rpm typed in rad/s
    msgs = _all_warnings(ks.load_scene, d)
    assert any("motion.omega0" in m and "rpm" in m for m in msgs)
    d["motion"]["omega0"] = 20.0
    d["motion"].pop("motor"), d["motion"].pop("target_delta")
    d["motion"]["motor_table"] = [[0.0, 40.0], [1.5708, 60.0], [3.1416, 50.0]]
    assert any("motor_table" in m and "radians" in m for m in _all_warnings(ks.load_scene, d))


def test_cam_slips_warn() -> None:
    from kinetostatics.cams import load_cam_scene
    with open(ks.scene_path("translating_roller"), "rb") as fh:
        d = tomllib.load(fh)
    d["cam"].pop("speed_rpm")
    d["cam"]["speed"] = 30000.0
    assert any("cam.speed" in m for m in _all_warnings(load_cam_scene, d))
    d["cam"]["speed"] = 30.0
    for seg in d["cam"]["segments"]:
        seg["angle"] = math.radians(seg["angle"])
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        with pytest.raises(ks.WorkbenchError, match="add up to"):
            load_cam_scene(d)
    assert any("radians" in str(w.message) for w in seen)
    d["units"] = {"angle": "rad"}                    # said so: converted, solved, no warning
    d["cam"]["transmission_angle"] = math.radians(d["cam"]["transmission_angle"])
    assert _all_warnings(load_cam_scene, d) == []


@pytest.mark.parametrize("table, text", [
    ({"length": "km"}, "unknown unit 'km'"),
    ({"lenght": "mm"}, "unknown quantity 'lenght'"),
    ({"unbalance": "g mm"}, "unknown quantity 'unbalance'"),
    ("mm", "[units] must be a table"),
])
def test_bad_units_are_one_line_errors(table, text, tmp_path) -> None:
    d = four_bar()
    d["units"] = table
    with pytest.raises(ks.SceneError) as exc:
        ks.load_scene(d)
    assert text in str(exc.value) and "\n" not in str(exc.value)
    if isinstance(table, dict):
        path = tmp_path / "bad.toml"
        path.write_text(to_toml(d))
        out = run_main("kinetostatics", "solve", str(path))
        assert out.returncode == 2 and out.stderr.startswith("error: ")
        assert len(out.stderr.strip().splitlines()) == 1


def test_summary_json_repeats_the_units(tmp_path) -> None:
    out = run_main("kinetostatics", "solve", "four_bar_mm", "--out", str(tmp_path))
    assert out.returncode == 0, out.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    # the numbers are SI, said plainly with a unit per key; the scene's [units] stand
    # under a key that says they are the scene's
    assert summary["units"] == "SI (angles in degrees)"
    assert summary["unit_of"]["Me_max"] == "N m"
    assert summary["unit_of"]["reaction_max"] == {"F": "N", "position": "deg"}
    assert summary["scene_units"] == {"length": "mm", "mass": "g", "angle": "deg",
                                      "speed": "rpm", "force": "N"}
    assert summary["positions"] == 361 and summary["warnings"] == []
    plain = json.loads(run_main("kinetostatics", "solve", "four_bar",
                                "--json").stdout)      # stdout is the JSON alone
    assert plain["scene_units"]["length"] == "m"


def test_the_unit_checks_use_the_scenes_length_unit() -> None:
    """A cog typed in metres in a millimetre scene: 0.125 mm is no slip, but a point typed
    in micrometres is (the message gives the scene's unit)."""
    with open(ks.example("four_bar_mm"), "rb") as fh:
        d = tomllib.load(fh)
    assert _warnings(d) == []
    d["bodies"][1]["points"]["P"] = [100000.0, 60000.0]
    msgs = _warnings(d)
    assert any("points.P = [100000, 60000] mm" in m for m in msgs)


def test_a_line_angle_in_degrees_under_radians_warns() -> None:
    """A single small line angle cannot be told from a slip (a 0.2618 deg guide is real):
    silent. Degrees under angle = "rad" put it beyond two turns: warned."""
    with open(ks.example("slider_crank"), "rb") as fh:
        d = tomllib.load(fh)
    slide = next(j for j in d["joints"] if j["kind"] == "T")
    slide["line_angle"] = 0.2618
    assert _all_warnings(ks.load_scene, d) == []
    d["units"] = {"angle": "rad"}
    d["driver"]["start"], d["driver"]["stop"] = 0.0, 2 * math.pi
    slide["line_angle"] = 90.0                       # degrees typed under rad
    msgs = _all_warnings(ks.load_scene, d)
    assert len(msgs) == 1 and "line_angle" in msgs[0] and "quiet" in msgs[0]


def test_a_small_cam_swing_is_not_warned() -> None:
    """A real 4.5 deg swing of an oscillating follower is silent (a single angle is never
    judged alone); 200 deg typed under angle = "rad" is warned."""
    from kinetostatics.cams import load_cam_scene
    with open(ks.scene_path("oscillating_roller"), "rb") as fh:
        d = tomllib.load(fh)
    d["cam"]["follower"]["stroke_angle"] = 4.5
    assert _all_warnings(load_cam_scene, d) == []
    d["cam"]["follower"]["stroke_angle"] = 200.0
    d["units"] = {"angle": "rad"}
    for seg in d["cam"]["segments"]:
        seg["angle"] = math.radians(seg["angle"])
    d["cam"].pop("transmission_angle", None)
    msgs = [m for m in _all_warnings(_quietly(load_cam_scene), d) if "stroke_angle" in m]
    assert len(msgs) == 1 and "two turns" in msgs[0]


def _quietly(fn):
    """fn, its WorkbenchError (a cam that cannot be built) swallowed: only warnings count."""
    def run(*args):
        try:
            fn(*args)
        except ks.WorkbenchError:
            pass
    return run
