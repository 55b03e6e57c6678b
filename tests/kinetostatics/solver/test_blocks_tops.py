"""A long sweep whose loads measure a threshold against the sweep's top (``resist``,
``when = "resisting"``) solved in blocks: the tops met block by block
(:class:`~kinetostatics.solver.loads.SweepTops`), the one pass's numbers bit for bit."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.results import onepass
from kinetostatics.solver import blocks, loads
from kinetostatics.solver import pipeline as pl

pytestmark = pytest.mark.usefixtures("numpy_path")

TABLES = ("driver", "kinematics", "reactions", "dyads", "reduced")


def _solve(monkeypatch, scene, positions, blocked: bool, settled: list | None = None):
    with monkeypatch.context() as m:
        if blocked:
            m.setattr(blocks, "BLOCK_ROWS", 50)
            m.setattr(onepass, "BLOCK_ROWS", 50)    # (its tables solved again, in blocks)
        else:
            m.setattr(pl, "blockable", lambda sc, n, tops=False: False)
        if settled is not None:
            real = loads.SweepTops.settle

            def spy(self):
                settled.append(real(self))
                return settled[-1]
            m.setattr(loads.SweepTops, "settle", spy)
        sol = ks.solve(scene, positions)
        return {t: getattr(sol, t) for t in TABLES} | {"summary": repr(sol.summary())}


@pytest.mark.parametrize("name", ["shaper", "slider_crank"])
def test_tops_met_block_by_block_give_the_one_pass(name, monkeypatch) -> None:
    """The shaper (a force acting while the ram resists it) and the slider-crank (a
    resist load) in blocks of 50 rows, each block's top the largest so far: every table
    as in one pass, and no block solved again (the flags settled at once)."""
    sc = load_scene(ks.example(name))
    positions = np.linspace(3.0, 723.0, 1001)       # (two turns: tops met again)
    ref = _solve(monkeypatch, sc, positions, blocked=False)
    settled: list = []
    got = _solve(monkeypatch, sc, positions, blocked=True, settled=settled)
    assert settled == [True]
    for t, x in ref.items():
        if isinstance(x, str):
            assert x == got[t], t
        else:
            pd.testing.assert_frame_equal(x, got[t], check_exact=True, obj=t)


def test_a_flag_that_would_differ_sends_the_sweep_to_one_pass(monkeypatch) -> None:
    """settle() False (a row above its block's threshold, at or below the sweep's): the
    sweep is solved again in one pass, the same tables."""
    sc = load_scene(ks.example("shaper"))
    positions = np.linspace(0.0, 359.0, 400)
    ref = _solve(monkeypatch, sc, positions, blocked=False)
    monkeypatch.setattr(loads.SweepTops, "settle", lambda self: False)
    got = _solve(monkeypatch, sc, positions, blocked=True)
    for t, x in ref.items():
        if not isinstance(x, str):
            pd.testing.assert_frame_equal(x, got[t], check_exact=True, obj=t)


def test_sweep_tops_settle_only_when_every_flag_stands() -> None:
    """A row at 2e-9 of a first block whose top is 1 is not still there; the sweep's
    top 10 makes it still (2e-9 <= 1e-9 x 10): not settled. At 2e-8 it stays moving:
    settled, and the blocks measure against the sweep's top from then on."""
    tops = loads.SweepTops()
    assert not tops.still(0, np.array([1.0, 2e-9]), 0.0).any()
    assert not tops.still(0, np.array([10.0, 5.0]), 0.0).any()
    assert not tops.settle()
    tops = loads.SweepTops()
    tops.still(0, np.array([1.0, 2e-8]), 0.0)
    tops.still(0, np.array([10.0, 5.0]), 0.0)
    tops.still(1, np.array([3.0]), 7.0)     # (another load: its floor 7 its top)
    assert tops.settle()
    assert tops.still(0, np.array([1.0, 1e-8]), 0.0).tolist() == [False, True]
    assert tops.top == {0: 10.0, 1: 7.0}



def _quick_shaper() -> tuple[dict, float, float]:
    """The bundled shaper with its crank's pivot O2 at 0.13 m over the lever's (not 0.3):
    the lever's top speed 33.3 rad/s (10 its crank's), its tip E 20 m/s, over the
    mechanism's own speed scale (6 m/s: 10 rad/s x its size 0.6 m), and a ``resist``
    load at E; with the crank angle (deg) near 230 deg where the lever turns back
    (bisected on the hand form) and how far from it E moves at 5e-10 of its top (1e-8
    m/s: still by the sweep's top, <= 2e-8, not by the floor 6e-9)."""
    from kinetostatics.bench.reference import SH, shaper_kin
    d = load_scene(ks.example("shaper")).raw
    d = {**d, "ground": {**d["ground"], "O2": [0.0, 0.13]},
         "loads": [*d["loads"], {"body": "lever", "point": "E", "resist": 50.0}]}

    def w4(deg: float) -> float:
        return float(shaper_kin(np.radians([deg]), 10.0, dict(SH, h2=0.13))["w4"][0])
    lo, hi = 225.0, 235.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.sign(w4(mid)) == np.sign(w4(lo)) else (lo, mid)
    slope = 0.6 * abs(w4(lo + 1e-4)) / 1e-4         # E's speed a degree from there
    return d, lo, 1e-8 / slope


@pytest.mark.parametrize("fast_first", [True, False])
def test_a_row_still_by_the_sweeps_top_alone(fast_first, monkeypatch) -> None:
    """A block of fast rows (the sweep's top met) and a block about the lever's turn
    back with a row whose speed is 5e-10 of the sweep's top: still in one pass (<=
    1e-9 of the top), not by its own block's top (the floor). Fast rows first: the
    running top keeps the row still, the one pass's tables, settled at once (each
    block's own top would not: checked, the tables then differ); slow rows first: not
    settled, the sweep solved again in one pass, the same tables."""
    d, at, off = _quick_shaper()
    fast = np.linspace(260.0, 280.0, 50)            # (the top at 270 deg)
    slow = np.concatenate([at + np.linspace(-1e-3, 1e-3, 48), [at + 0.01, at + off]])
    blocks_ = [fast, slow] if fast_first else [slow, fast]
    positions = np.concatenate([*blocks_, np.linspace(0.0, 359.0, 100)])
    row = 99 if fast_first else 49
    ref = ks.solve(d, positions)
    assert ref.undefined_load[row] and ref.undefined_load.sum() == 1
    ref = _solve(monkeypatch, d, positions, blocked=False)
    settled: list = []
    got = _solve(monkeypatch, d, positions, blocked=True, settled=settled)
    assert settled == [fast_first]
    for t, x in ref.items():
        if not isinstance(x, str):
            pd.testing.assert_frame_equal(x, got[t], check_exact=True, obj=t)
