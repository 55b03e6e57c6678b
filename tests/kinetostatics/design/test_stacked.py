"""A population judged from stacked arrays alone (no Scene per design) equals the same
population judged one Solution per design, bit for bit: every quantity of the
vocabulary, the reasons, a partial sweep under full_turn, other kinds of variables; the
designs it leaves to the Solutions and the populations it cannot stack."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.design import stacked
from kinetostatics.design.judging import evaluate_rows, evaluate_scenes
from kinetostatics.design.section import read_design
from kinetostatics.solver.stack import Stacker


def _raw(**design) -> dict:
    raw = tomllib.loads(ks.scene_path("four_bar_design").read_text())
    raw["design"].update(design)
    return raw


EVERY = dict(
    objectives=["min Me_rms", "min reaction_peak", "min frame_force_peak",
                "max stroke:coupler.P", "min path_error:coupler.P", "max stroke:rocker.E@30"],
    constraints=["Me_peak <= 1000", "transmission_min >= 20", "full_turn"],
    targets={"coupler.P": [[0.1, 0.1], [0.2, 0.15], [0.0, 0.2]]})
OTHERS = {"bodies.rocker.mass": [0.5, 3.0], "bodies.coupler.cog.1": [-0.05, 0.05],
          "bodies.crank.inertia": [0.001, 0.01], "ground.A.1": [-0.05, 0.05],
          "bodies.coupler.points.P.1": [0.01, 0.1]}


def _population(spec, seed: int, n: int = 240, spread: float = 0.8) -> np.ndarray:
    rng = np.random.default_rng(seed)
    step = spread * (rng.random((n, len(spec.variables))) - 0.5) * (spec.upper - spec.lower)
    return np.clip(spec.bundled + step, spec.lower, spec.upper)


def _same(a, b) -> None:
    assert a.reasons == b.reasons
    assert a.solved.tolist() == b.solved.tolist()
    assert a.feasible.tolist() == b.feasible.tolist()
    for x, y in ((a.values, b.values), (a.limits, b.limits)):
        assert np.array_equal(x.view(np.int64), y.view(np.int64))      # (NaN too: bits)


def _partial(raw: dict) -> dict:
    raw["driver"].update(start=10.0, stop=130.0, count=121)
    return raw


@pytest.mark.parametrize("raw", [
    _raw(), _raw(**EVERY), _partial(_raw(**EVERY)),
    _raw(**EVERY, variables={**_raw()["design"]["variables"], **OTHERS}),
], ids=["bundled", "every-quantity", "partial-sweep-full-turn", "other-variables"])
def test_stacked_equals_one_solution_each(raw):
    spec = read_design(raw)
    assert spec.stack_plan is not None
    X = _population(spec, 7)
    ev = evaluate_rows(spec, X)
    _same(ev, evaluate_scenes(spec, X))
    # (measured: 90-200 of 240 solved, some refused for each reason the screen gives)
    assert ev.solved.sum() > 50 and (~ev.solved).sum() > 20


def test_the_stack_is_the_stack_of_the_scenes():
    """The stacker laid from the numbers holds what the stacker of the designs' Scenes
    holds, bit for bit (each number shared stays a number)."""
    spec = read_design(_raw(variables={**_raw()["design"]["variables"], **OTHERS}))
    X = _population(spec, 8, n=30)
    made = stacked.stacker_of(spec.stack_plan, spec.set_values(X))
    ref = Stacker([spec.design_scene(x)[1] for x in X])

    def bits(v):
        return ("n", float(v)) if not isinstance(v, np.ndarray) else ("a", v.tobytes())
    for got, want in ((made.ground, ref.ground), (made.near, ref.near)):
        assert {k: tuple(map(bits, p)) for k, p in got.items()} == \
            {k: tuple(map(bits, p)) for k, p in want.items()}
    for name, (m, i, cog, pts) in ref.bodies.items():
        gm, gi, gcog, gpts = made.bodies[name]
        assert (bits(gm), bits(gi)) == (bits(m), bits(i))
        assert tuple(map(bits, gcog)) == tuple(map(bits, cog))
        assert {k: tuple(map(bits, p)) for k, p in gpts.items()} == \
            {k: tuple(map(bits, p)) for k, p in pts.items()}
    assert bits(made.size) == bits(ref.size)


@pytest.mark.usefixtures("numpy_path")      # (the stacked judge's own road)
def test_designs_not_finite_are_judged_one_by_one(monkeypatch):
    """A design whose numbers the stacked pass cannot vouch finite is judged by its own
    Solution (the solve's own check and reason)."""
    spec = read_design("four_bar_design")
    X = _population(spec, 9, n=120)
    real = stacked._RunRows.finite

    def some_not(self):
        out = real(self)
        out[::3] = False
        return out
    monkeypatch.setattr(stacked._RunRows, "finite", some_not)
    seen = []
    monkeypatch.setattr("kinetostatics.design.judging.evaluate_scenes",
                        lambda spec, X: seen.append(len(X)) or evaluate_scenes(spec, X))
    ev = evaluate_rows(spec, X)
    assert seen and 0 < seen[0] < len(X)
    _same(ev, evaluate_scenes(spec, X))


def test_masses_told_apart_are_not_stacked():
    """Designs whose masses the solver's tests tell apart (0 and not) are not one stack:
    judged one by one."""
    spec = read_design(_raw(variables={"bodies.rocker.mass": [0.0, 3.0]}, follow={}))
    X = np.array([[0.0], [1.5], [3.0]])
    assert stacked.stacker_of(spec.stack_plan, spec.set_values(X)) is None
    _same(evaluate_rows(spec, X), evaluate_scenes(spec, X))


@pytest.mark.usefixtures("numpy_path")      # (the stacked judge's own road)
def test_dead_points_between_rows_give_unvouched_reasons(monkeypatch):
    """A dead point between rows, a gap between rows and an end row near a dead point,
    as the solver's search reports them, give the reasons (and the unsolved state)
    :func:`~kinetostatics.design.judging.unvouched` gives a Solution holding them."""
    from types import SimpleNamespace

    from kinetostatics.design.judging import unvouched
    spec = read_design("four_bar_design")
    X = np.repeat(spec.bundled[None, :], 4, axis=0) * np.array([[1.0], [1.001], [1.002],
                                                                 [1.003]])
    pair, none = np.array([[10, 11]]), np.zeros(0, dtype=int)
    empty = np.zeros((0, 2), dtype=int)
    fake = [(pair, none, empty), (empty, none, pair), (empty, np.array([0]), empty),
            (empty, none, empty)]
    real = stacked.dead_points_stacked
    monkeypatch.setattr(stacked, "dead_points_stacked",
                        lambda *a: [f for f, _ in zip(fake, real(*a), strict=True)])
    ev = evaluate_rows(spec, X)
    for i, (between, ends, unassembled) in enumerate(fake[:3]):
        kin = SimpleNamespace(between=between, unassembled=unassembled)
        sol = SimpleNamespace(kin=kin, singular=np.isin(np.arange(361), ends),
                              self_locking=None)
        assert ev.reasons[i] == unvouched(sol)
        assert not ev.solved[i]
    assert ev.solved[3]


def test_a_sliding_driver_stacked():
    """Fe, the frame's force with the driver's reaction along its line, a prismatic
    joint's reactions: the same bits stacked as one Solution each."""
    raw = tomllib.loads(ks.scene_path("sliding_driver").read_text())
    raw["design"] = {
        "objectives": ["min Fe_peak", "min Fe_rms", "min reaction_peak",
                       "min frame_force_peak", "max stroke:crank.B@90"],
        "constraints": ["transmission_min >= 10"],
        "variables": {"bodies.rod.points.B.0": [0.15, 0.35],
                      "bodies.crank.points.B.0": [0.05, 0.14], "ground.S0.1": [-0.05, 0.08]}}
    spec = read_design(raw)
    assert spec.stack_plan is not None
    X = spec.lower + np.random.default_rng(0).random((300, 3)) * (spec.upper - spec.lower)
    ev = evaluate_rows(spec, X)
    _same(ev, evaluate_scenes(spec, X))
    assert ev.solved.sum() > 60          # (measured: 122 of 300)


@pytest.mark.parametrize("setting, stacked_judge", [("auto", True), ("numpy", True),
                                                    ("fast", False)])
def test_auto_judges_on_the_stack_even_with_the_compiled_path_loaded(monkeypatch, setting,
                                                                      stacked_judge):
    """Under ``auto`` the stacked judge stays, whatever ``auto`` does for a long sweep
    (judging one Solution per design from the compiled ``solve_many`` is four times
    slower); only ``fast`` asked for takes the compiled road."""
    from kinetostatics.design import judging
    from kinetostatics.solver.fast import use
    monkeypatch.setattr(judging, "wanted", lambda rows: object())  # (numba loaded)
    seen = []
    real = judging._evaluate_stacked
    monkeypatch.setattr(judging, "_evaluate_stacked",
                        lambda *a: seen.append(1) or real(*a))
    monkeypatch.setattr(judging, "evaluate_scenes", lambda spec, X: "one by one")
    spec = read_design(_raw())
    use(setting)
    try:
        ev = evaluate_rows(spec, _population(spec, 7, n=24))
    finally:
        use(None)
    assert bool(seen) is stacked_judge
    assert (ev == "one by one") is not stacked_judge
