"""Speed against a baseline measured in the same run: ``python -m kinetostatics bench``.

Every figure is a ratio to its baseline, both timed side by side (alternating runs, in
one process where they can share one), best and median of several runs: the machine
may be shared, so a single run says little.

* ``reference``: :func:`kinetostatics.solve` plus its ``driver`` table against the
  hand-written closed forms ``fourbar_dyad`` and ``slider_dyad`` of
  :mod:`kinetostatics.bench.reference` on the same four-bar and slider-crank, at 2001, 2e5 and 1e6
  positions, with the largest difference of Me (2001 positions also in batches of
  calls, as :mod:`timeit` times);
* ``many``: :func:`kinetostatics.solve_many` on 1000 variants of the bundled four-bar
  (361 positions; every length, ground point and mass within +-10 %) against a loop of
  ``solve``, given as Scene objects and as dicts: the speed-up (the loop's time over
  solve_many's), with the largest difference of any table (0: the same numbers);
* ``start``: ``import kinetostatics``, ``import balance`` and the commands
  ``python -m balance solve rotor_two_plane`` and ``python -m kinetostatics solve
  four_bar --out DIR`` in fresh processes, wall time against ``import numpy``;
* ``tables``: ``python -m kinetostatics solve --out`` at 1e5 positions (wall) and the
  peak memory of a process holding the 1e6-position solution and every table;
* ``crosscheck``: the pymunk cross-check of the shaper and the slotted lever, seconds
  per simulated revolution with its automatic settings against the previous defaults,
  with the largest error of each (:func:`bench_crosscheck`).
"""

from __future__ import annotations

import copy
import gc
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable

import numpy as np
import pandas as pd

from .accuracy import find_reference, fourbar_scene, slider_crank_reference_scene


def side_by_side(jobs: dict[str, Callable[[], object]], repeat: int,
                 batch: int = 1) -> dict[str, list]:
    """Seconds of each job over ``repeat`` alternating rounds, the garbage collected
    before each. ``batch`` > 1: each round times that many calls in a row with the
    collector paused, as :mod:`timeit` does, and gives the time per call (a warm loop:
    what a call costs when it follows others, its code and data in the caches)."""
    times: dict[str, list] = {k: [] for k in jobs}
    for _ in range(repeat):
        for k, f in jobs.items():
            gc.collect()
            was = gc.isenabled()
            if batch > 1:
                gc.disable()
            try:
                t = time.perf_counter()
                for _ in range(batch):
                    f()
                times[k].append((time.perf_counter() - t) / batch)
            finally:
                if was:
                    gc.enable()
    return times


def _row(what: str, n, times: dict, job: str, base: str, **extra) -> dict:
    t, b = times[job], times[base]
    return {"measure": what, "size": n, "seconds_best": min(t), "baseline_best": min(b),
            "ratio_best": min(t) / min(b),
            "ratio_median": statistics.median(t) / statistics.median(b), **extra}


def bench_reference(path: str, sizes=(2_001, 200_001, 1_000_001)) -> list[dict]:
    """solve(scene).driver against ``fourbar_dyad`` of the hand-written baseline."""
    from ..results import solve
    from .accuracy import load_reference
    ref = load_reference(path)
    rows = []
    for n in sizes:
        scene = fourbar_scene(n)
        th = np.deg2rad(np.linspace(0.0, 360.0, n))
        repeat = 25 if n < 10_000 else 7 if n < 500_000 else 3
        times = side_by_side({"reference": lambda th=th: ref.fourbar_dyad(th, 20.0),
                              "solve": lambda s=scene: solve(s).driver}, repeat)
        me = ref.fourbar_dyad(th, 20.0)["Me"]
        err = float(np.abs(solve(scene).Me - me).max() / np.abs(me).max())
        rows.append(_row("solve(scene).driver / hand-written fourbar_dyad", n, times,
                         "solve", "reference", error=err))
        rows += _warm(n, "solve(scene).driver / hand-written fourbar_dyad",
                      {"reference": lambda th=th: ref.fourbar_dyad(th, 20.0),
                       "solve": lambda s=scene: solve(s).driver}, err)
    # the baseline's other mechanism: far fewer operations by hand (a centred slider-crank
    # in closed form), the same general solve
    w2 = ref.SC["w2"]
    for n in sizes:
        scene = slider_crank_reference_scene(n, ref.SC)
        th = np.deg2rad(np.linspace(0.0, 360.0, n))
        repeat = 25 if n < 10_000 else 7 if n < 500_000 else 3
        times = side_by_side({"reference": lambda th=th: ref.slider_dyad(th, w2),
                              "solve": lambda s=scene: solve(s).driver}, repeat)
        me = ref.slider_dyad(th, w2)["Me"]
        err = float(np.abs(solve(scene).Me - me).max() / np.abs(me).max())
        rows.append(_row("solve(scene).driver / hand-written slider_dyad", n, times,
                         "solve", "reference", error=err))
        rows += _warm(n, "solve(scene).driver / hand-written slider_dyad",
                      {"reference": lambda th=th: ref.slider_dyad(th, w2),
                       "solve": lambda s=scene: solve(s).driver}, err)
    return rows


WARM_BATCH = 20     # calls per round for the small sizes' warm row


def _warm(n: int, what: str, jobs: dict, err: float) -> list[dict]:
    """A small size timed again in batches of ``WARM_BATCH`` calls (timeit's way)
    beside the single calls after a garbage collection: both rows are given. (Measured
    2026-11-27 for the four-bar at 2001 positions: 3.9-4.0x either way; 3.2-3.5x when
    each is timed in a long loop of its own, not alternating: the solver's far larger
    code, a few hundred small Python and numpy calls, then stays in the caches.)"""
    if n >= 10_000:
        return []
    times = side_by_side(jobs, 15, batch=WARM_BATCH)
    return [_row(f"{what} (warm, batches of {WARM_BATCH} calls)", n, times, "solve",
                 "reference", error=err)]


def four_bar_variants(count: int = 1000, spread: float = 0.10, seed: int = 0) -> list[dict]:
    """``count`` variants of the bundled four-bar that assemble: every local point,
    ground point, mass and inertia scaled within 1 +- spread."""
    from ..model.examples import example
    from ..model.scene import load_scene
    from ..results import solve
    base = load_scene(example("four_bar")).raw
    rng = np.random.default_rng(seed)
    out: list[dict] = []
    while len(out) < count:
        d = copy.deepcopy(base)
        for b in d["bodies"]:
            b["points"] = {p: [x * rng.uniform(1 - spread, 1 + spread) for x in v]
                           for p, v in b["points"].items()}
            b["mass"] *= rng.uniform(1 - spread, 1 + spread)
            b["inertia"] *= rng.uniform(1 - spread, 1 + spread)
        d["ground"] = {p: [x * rng.uniform(1 - spread, 1 + spread) for x in v]
                       for p, v in d["ground"].items()}
        try:
            solve(d)
        except ValueError:      # a variant that cannot assemble: drawn again
            continue
        out.append(d)
    return out


def bench_many(count: int = 1000, repeat: int = 3) -> list[dict]:
    """solve_many against a loop of solve on the four-bar variants: given Scene objects,
    given dicts, and given dicts with each Solution's ``driver`` table built (the
    per-scene arrays of solve_many's Solutions are cut from the stacked ones when first
    read: that cost counted too). ``error``: the largest difference of any table of
    solve_many against solve alone, over the first 50 scenes (0: the same numbers)."""
    from ..model.scene import load_scene
    from ..results import solve, solve_many

    def largest_difference(sols: list, items: list) -> float:
        err = 0.0
        for a, s in zip(sols, items, strict=True):
            b = solve(s)
            for t in ("driver", "reactions", "kinematics", "bodies", "dyads", "frame"):
                x, y = getattr(a, t), getattr(b, t)
                num = x.select_dtypes("number").to_numpy(float)
                err = max(err, float(np.nanmax(np.abs(num - y.select_dtypes("number")
                                                      .to_numpy(float)), initial=0.0)))
        return err

    dicts = four_bar_variants(count)
    scenes = [load_scene(d) for d in dicts]
    rows = []
    for label, items in (("Scene objects", scenes), ("dicts", dicts)):
        times = side_by_side({"loop": lambda it=items: [solve(s) for s in it],
                              "many": lambda it=items: solve_many(it)}, repeat)
        rows.append(_row(f"speed-up: loop of solve / solve_many ({label})",
                         f"{count} x 361", times, "loop", "many",
                         error=largest_difference(solve_many(items[:50]), items[:50])))
    times = side_by_side({"loop": lambda: [solve(d).driver for d in dicts],
                          "many": lambda: [s.driver for s in solve_many(dicts)]}, repeat)
    rows.append(_row("speed-up: loop of solve / solve_many (dicts, each driver table)",
                     f"{count} x 361", times, "loop", "many"))
    return rows


def _wall(args: list[str], env: dict) -> float:
    t = time.perf_counter()
    subprocess.run(args, env=env, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return time.perf_counter() - t


def bench_start(repeat: int = 7) -> list[dict]:
    """Start-up in fresh processes (wall), against ``import numpy``."""
    env = dict(os.environ)
    py = sys.executable
    with tempfile.TemporaryDirectory() as out:
        jobs = {
            "import numpy": [py, "-c", "import numpy"],
            "import kinetostatics": [py, "-c", "import kinetostatics"],
            "import balance": [py, "-c", "import balance"],
            "python -m balance solve rotor_two_plane": [py, "-m", "balance", "solve",
                                                        "rotor_two_plane"],
            "python -m kinetostatics solve four_bar --out DIR": [
                py, "-m", "kinetostatics", "solve", "four_bar", "--out", out],
        }
        times = side_by_side({k: (lambda a=a: _wall(a, env)) for k, a in jobs.items()},
                             repeat)
    return [_row(k, "", times, k, "import numpy") for k in jobs if k != "import numpy"]


def bench_tables() -> list[dict]:
    """solve --out at 1e5 positions (wall, fresh processes, best of 3, against import
    numpy) and the peak memory at 1e6 positions with every table held."""
    from .tables import fresh_run, measure_cli
    py = sys.executable
    cli, numpy_t = [], []
    for _ in range(3):
        with tempfile.TemporaryDirectory() as tmp:
            cli.append(measure_cli(100_000, tmp)["cli_out_s"])
        numpy_t.append(_wall([py, "-c", "import numpy"], dict(os.environ)))
    rows = [_row("python -m kinetostatics solve four_bar --out DIR (wall)", 100_000,
                 {"cli": cli, "numpy": numpy_t}, "cli", "numpy")]
    with tempfile.TemporaryDirectory() as tmp:
        peak = fresh_run(1_000_000, tmp)["peak_MB"]
    rows.append({"measure": "peak memory with every table (MB)", "size": 1_000_000,
                 "seconds_best": math.nan, "baseline_best": math.nan,
                 "ratio_best": math.nan, "ratio_median": math.nan, "peak_MB": peak})
    return rows


def bench_crosscheck(repeat: int = 3) -> list[dict]:
    """The pymunk cross-check's automatic settings (ballast, lag rule) against the
    previous defaults, seconds per simulated revolution timed side by side, with each
    one's largest error (:func:`kinetostatics.simulation.crosscheck_speed`)."""
    from ..simulation import crosscheck_speed
    keys = ("measure", "size", "seconds_best", "baseline_best", "ratio_best", "ratio_median",
            "error")
    return [{k: r[k] for k in keys} for r in crosscheck_speed(repeat=repeat)]


def run_speed(quick: bool = False, reference: str | None = None) -> pd.DataFrame:
    """Every ratio of this module, printed as one table (``quick``: small sizes)."""
    rows = bench_reference(str(reference or find_reference()),
                           (2_001, 20_001) if quick else (2_001, 200_001, 1_000_001))
    rows += bench_many(100 if quick else 1000)
    rows += bench_start(3 if quick else 7)
    if not quick:
        rows += bench_tables()
        rows += bench_crosscheck()
    df = pd.DataFrame(rows)
    pd.set_option("display.width", 160)
    print(f"\n== speed: ratios to baselines timed side by side ({os.cpu_count()} cores) ==")
    # a cell that does not apply to its row (no error for a start-up time, no ratio for
    # the peak memory) is shown as "-", not as a number
    print(df.to_string(index=False, na_rep="-", float_format=lambda x: f"{x:.4g}"))
    return df
