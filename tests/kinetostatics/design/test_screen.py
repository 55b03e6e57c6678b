"""The screen sets aside only designs the solve itself refuses or flags: a population
judged with it equals the same population solved whole, design by design."""

from __future__ import annotations

import numpy as np

from kinetostatics.design.judging import evaluate, unvouched
from kinetostatics.design.screen import loaded
from kinetostatics.design.section import read_design
from kinetostatics.solver.many import solve_outcomes


def test_screen_agrees_with_the_solve():
    spec = read_design("four_bar_design")
    X = spec.lower + np.random.default_rng(3).random((300, 4)) * (spec.upper - spec.lower)
    dicts = [spec.scene_dict(x) for x in X]
    scenes, why = loaded(dicts)
    whole = solve_outcomes(scenes)              # every design, none set aside
    told = [unvouched(s) is not None for s in whole]
    aside = [w is not None for w in why]
    assert sum(aside) > 50                      # (measured: 119 of 300)
    # set aside: the solve refuses it or flags a row; passed: mostly feasible to solve
    assert all(t for t, a in zip(told, aside, strict=True) if a)
    ev = evaluate(spec, X)
    assert ev.solved.tolist() == [not t for t in told]
    for i in np.flatnonzero(ev.solved):
        assert ev.values[i, 0] == np.max(np.abs(whole[i].Me))
