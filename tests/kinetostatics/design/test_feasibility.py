"""Feasibility: full_turn on a sweep shorter than a turn, and a population spread
through an executor judged as in one process."""

from __future__ import annotations

import tomllib
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.design import evaluate, read_design


def _spec(constraints):
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    raw["driver"].update(start=0.0, stop=120.0, count=121)
    raw["design"]["constraints"] = constraints
    return read_design(raw)


# frame 0.30, crank 0.12, coupler 0.20, rocker 0.20: 0.12 + 0.30 > 0.20 + 0.20, not a
# Grashof crank: it closes from 0 to 120 deg (|BD| <= 0.375 < 0.40) but not near 180 deg
NOT_GRASHOF = [0.30, 0.12, 0.20, 0.20]


def test_full_turn_checks_the_whole_turn():
    x = np.array([NOT_GRASHOF, [0.30, 0.10, 0.25, 0.20]])
    free = evaluate(_spec([]), x)
    assert free.feasible.tolist() == [True, True]          # the 120 deg sweep is fine
    turn = evaluate(_spec(["full_turn"]), x)
    assert turn.feasible.tolist() == [False, True]
    assert turn.reasons[0].startswith("full_turn: ")
    # the objectives stay those of the sweep
    assert turn.values[1].tolist() == free.values[1].tolist()
    spec = _spec(["full_turn"])
    assert spec.turn_dict(spec.scene_dict(x[0]))["driver"] == {
        **spec.raw["driver"], "start": 0.0, "stop": 360.0, "count": 361}
    assert read_design("four_bar_design").turn_dict({}) is None   # a whole turn already


def test_an_executor_gives_the_same_numbers():
    spec = read_design("four_bar_design")
    X = spec.lower + np.random.default_rng(9).random((120, 4)) * (spec.upper - spec.lower)
    one = evaluate(spec, X)
    with ThreadPoolExecutor(2) as pool:
        parts = evaluate(spec, X, pool, parts=4)
    assert np.array_equal(one.values, parts.values, equal_nan=True)
    assert one.reasons == parts.reasons and (one.feasible == parts.feasible).all()


@pytest.mark.slow     # two whole design runs written (1.8 s)
def test_a_second_run_replaces_the_first_whole(tmp_path):
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    raw["design"]["constraints"] = ["transmission_min >= 45", "full_turn"]
    a = ks.design(raw, population=12, generations=3, seed=2)
    b = ks.design(raw, population=12, generations=2, seed=3)
    assert len(a.front) != len(b.front)
    a.write(tmp_path)
    b.write(tmp_path)
    names = sorted(p.name for p in (tmp_path / "designs").iterdir())
    assert names == [s.split("/")[1] for s in b.front.scene]
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "compromise.png", "designs", "front.csv", "front.png", "summary.json"]
