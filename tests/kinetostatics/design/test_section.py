"""The [design] section: paths, bounds, the vocabulary, and one line for every mistake."""

from __future__ import annotations

import sys
import tomllib

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import kinetostatics as ks
from kinetostatics.design import DesignError, read_design, toml_text
from kinetostatics.design.paths import resolve, with_values
from tests.helpers import run_main


def _scene(**design) -> dict:
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    if "variables" in design:
        design.setdefault("follow", {})     # (the bundled followers follow its variables)
    raw["design"].update(design)
    return raw


def test_bundled_section():
    spec = read_design("four_bar_design")
    assert spec.names == ["ground.D.0", "bodies.crank.points.B.0",
                          "bodies.coupler.points.C.0", "bodies.rocker.points.C.0"]
    assert spec.bundled.tolist() == [0.30, 0.10, 0.25, 0.20]
    assert np.allclose(spec.lower, 0.6 * spec.bundled) and np.allclose(spec.upper,
                                                                       1.4 * spec.bundled)
    assert [o.text for o in spec.objectives] == ["min Me_peak", "max transmission_min"]
    assert [c.text for c in spec.constraints] == ["transmission_min >= 60",
                                                  "stroke:rocker.C@90 >= 0.11"]
    assert spec.full_turn and (spec.seed, spec.population, spec.generations) == (1, 100, 60)
    # a follower keeps its ratio: the crank's cog stays at its middle
    d = spec.scene_dict(np.array([0.3, 0.08, 0.25, 0.2]))
    assert d["bodies"][0]["cog"] == [0.04, 0.0] and d["bodies"][0]["points"]["B"] == [0.08, 0.0]
    assert "design" not in d


def test_paths_copy_only_what_they_change():
    raw = tomllib.loads(ks.scene_path("four_bar").read_text())
    before = toml_text(raw)
    p = [resolve(raw, "bodies.rocker.points.C.0", "t"), resolve(raw, "ground.D.1", "t"),
         resolve(raw, "loads.0.force.1", "t"), resolve(raw, "bodies.2.mass", "t")]
    assert [x.value for x in p] == [0.20, 0.0, -150.0, 1.6]
    d = with_values(raw, p, [0.21, 0.01, -100.0, 2.0])
    assert toml_text(raw) == before                    # the scene as typed is untouched
    assert d["bodies"][2]["points"]["C"] == [0.21, 0.0] and d["ground"]["D"] == [0.30, 0.01]
    assert d["loads"][0]["force"] == [0.0, -100.0] and d["bodies"][2]["mass"] == 2.0
    assert d["bodies"][0] is raw["bodies"][0]          # what is not changed is shared


@pytest.mark.parametrize("name", ks.examples())
def test_toml_text_reads_back(name):
    raw = tomllib.loads(ks.scene_path(name).read_text())
    assert tomllib.loads(toml_text(raw, "a header\nof two lines")) == raw


BAD = [
    ({"variables": {"ground.X.0": [0, 1]}}, "'ground.X.0' names nothing: ground has no 'X'"),
    ({"variables": {"bodies.crank.points.Q.0": [0, 1]}}, "has no 'Q'"),
    ({"variables": {"bodies.lever.mass": [0, 1]}}, "bodies has no item 'lever'"),
    ({"variables": {"bodies.crank.points.B": [0, 1]}}, "is not a number in the scene"),
    ({"variables": {"title": [0, 1]}}, "is not a number in the scene"),
    ({"variables": {"ground.D.0": [0.4, 0.2]}}, "the bounds are reversed"),
    ({"variables": {"ground.D.0": ["a", 0.2]}}, "give the bounds as [low, high]"),
    ({"variables": {"bodies.crank.points.B.0": [-0.05, 0.1]}}, "would reach zero or turn "
                                                                 "negative"),
    ({"variables": {"bodies.crank.mass": [-1.0, 2.0]}}, "the bound -1 is outside what the "
                                                         "scene allows"),
    ({"objectives": ["min Me_top"]}, "unknown quantity 'Me_top'"),
    ({"objectives": ["lower Me_peak"]}, "write 'min NAME' or 'max NAME'"),
    ({"objectives": ["min Fe_peak"]}, "Fe_peak needs a sliding driver"),
    ({"objectives": ["max stroke:coupler.Z"]}, "body 'coupler' has no point 'Z'"),
    ({"objectives": ["min path_error:coupler.P"]}, "needs target points"),
    ({"constraints": ["transmission_min > 40"]}, "unknown constraint"),
    ({"constraints": ["full_circle"]}, "unknown constraint 'full_circle'"),
    ({"population": 2}, "[design] population = 2: give a whole number >= 4"),
    ({"follow": {"bodies.crank.cog.0": "ground.D.0x"}}, "follow one of the variables"),
    ({"speed": 3}, "unknown key"),
]


@pytest.mark.parametrize(("change", "message"), BAD)
def test_mistakes_are_one_line(change, message):
    with pytest.raises(ks.SceneError) as e:     # (DesignError is one)
        read_design(_scene(**change))
    text = str(e.value)
    assert message in text and "\n" not in text, text


def test_no_section():
    with pytest.raises(DesignError, match="no \\[design\\] section"):
        read_design("four_bar")


def test_no_feasible_design_says_how_many_and_why():
    with pytest.raises(DesignError) as e:
        ks.design(_scene(constraints=["transmission_min >= 89"]), population=8,
                  generations=2)
    assert str(e.value).startswith("no feasible design among the 16 tried; the commonest "
                                   "reason: transmission_min >= 89 not kept"), str(e.value)


def test_cli_mistake_exit_2(tmp_path):
    scene = _scene(variables={"ground.D.0": [0.4, 0.2]})
    path = tmp_path / "bad.toml"
    path.write_text(toml_text(scene))
    r = run_main("kinetostatics", "design", str(path), "--out", str(tmp_path / "out"))
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("error: [design.variables] "
                                                            "'ground.D.0' = [0.4, 0.2]")


def test_missing_extra_one_line(monkeypatch):
    monkeypatch.setitem(sys.modules, "pymoo", None)
    with pytest.raises(DesignError, match=r"pip install -e '\.\[design\]'"):
        ks.design("four_bar_design", population=4, generations=1)


@given(st.lists(st.floats(allow_nan=False, width=64), min_size=1, max_size=6),
       st.text(min_size=1, max_size=8))
def test_toml_text_keeps_every_float(values, name):
    """Every float (subnormals, -0.0, infinities) reads back with the same bits."""
    raw = {"title": name, "ground": {"a.b": values[:2]},
           "bodies": [{"name": name, "points": {"P": values}}]}
    back = tomllib.loads(toml_text(raw))
    got = back["bodies"][0]["points"]["P"]
    assert np.array(got).tobytes() == np.array(values).tobytes() and back["title"] == name
