"""Speed against a baseline measured in the same run: ``python -m kinetostatics bench``.

Every figure is a ratio to its baseline, both timed side by side (alternating runs, in
one process where they can share one), best and median of several runs, in processor
time (wall time for fresh processes): the machine may be shared, so a single run says
little.

* ``reference``: :func:`kinetostatics.solve` plus its ``driver`` table, on each solve
  path (``numpy``, and ``fast`` when the compiled kernels load: column ``path``), against
  the hand-written closed forms ``fourbar_dyad`` and ``slider_dyad`` of
  :mod:`kinetostatics.bench.reference` on the same four-bar and slider-crank (and
  ``shaper_dyad`` on the bundled shaper), at 2001, 2e5 and 1e6
  positions, with the largest difference of Me (2001 positions also in batches of
  calls, as :mod:`timeit` times);
* ``many``: :func:`kinetostatics.solve_many` on 1000 variants of the bundled four-bar
  (361 positions; every length, ground point and mass within +-10 %) against a loop of
  ``solve``, on each path (the compiled one also against the numpy path's loop),
  given as Scene objects (the same ones every round, and new ones each round) and as
  dicts, and on as many variants of the slider-crank, the shaper and the slotted lever:
  the speed-up (the loop's time over solve_many's), with
  the largest difference of any table (0: the same numbers);
* ``design``: :func:`kinetostatics.design` on the bundled ``four_bar_design`` (1000
  designs, 10 generations, 361 rows) against ``solve_many`` of as many four-bars: its
  kinetostatic rows per second (:func:`bench_design`; needs pymoo);
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

from ..common.angles import radian_column
from .accuracy import (
    find_reference,
    fourbar_scene,
    frozen_heap,
    slider_crank_reference_scene,
)


def side_by_side(jobs: dict[str, Callable[[], object]], repeat: int,
                 batch: int = 1, clock: Callable[[], float] = time.process_time
                 ) -> dict[str, list]:
    """Seconds of each job over ``repeat`` alternating rounds, the garbage collected
    before each. ``batch`` > 1: each round times that many calls in a row with the
    collector paused, as :mod:`timeit` does, and gives the time per call (a warm loop:
    what a call costs when it follows others, its code and data in the caches).

    ``clock``: the process's processor time (user and system: page faults counted) by
    default, which other processes sharing the machine do not lengthen (measured
    2026-11-28 on the 2-core machine at a load of 8-11: wall-clock ratios of one job
    to another varied 2-3x from run to run, processor-time ratios by about 10 %); a
    job that waits on another process (a start-up in a fresh one) is timed by the
    wall clock, ``time.perf_counter``."""
    times: dict[str, list] = {k: [] for k in jobs}
    with frozen_heap():
        for _ in range(repeat):
            for k, f in jobs.items():
                gc.collect()
                was = gc.isenabled()
                if batch > 1:
                    gc.disable()
                try:
                    t = clock()
                    for _ in range(batch):
                        f()
                    times[k].append((clock() - t) / batch)
                finally:
                    if was:
                        gc.enable()
    return times


def _row(what: str, n, times: dict, job: str, base: str, **extra) -> dict:
    t, b = times[job], times[base]
    return {"measure": what, "size": n, "seconds_best": min(t), "baseline_best": min(b),
            "ratio_best": min(t) / min(b),
            "ratio_median": statistics.median(t) / statistics.median(b), **extra}


def solve_paths() -> list[str]:
    """The solve paths this process can time: ``numpy``, and ``fast`` when the compiled
    kernels load (numba installed, a writable cache folder) unless the numpy path is
    asked for (``KINETOSTATICS_PATH=numpy``, or ``use("numpy")``: then numba is not
    loaded, nor its kernels compiled, the test suite's case)."""
    from ..solver.fast import loader, path_setting
    if path_setting() == "numpy":
        return ["numpy"]
    return ["numpy", "fast"] if loader.kernels() is not None else ["numpy"]


def on_path(path: str, job: Callable[[], object]) -> Callable[[], object]:
    """``job`` run with the solve path set to ``path`` (put back after)."""
    from ..solver.fast import use

    def run():
        use(path)
        try:
            return job()
        finally:
            use(None)
    return run


def bench_reference(path: str, sizes=(2_001, 200_001, 1_000_001),
                    repeat: int | None = None) -> list[dict]:
    """solve(scene).driver on each solve path against ``fourbar_dyad`` (and
    ``slider_dyad``, and ``shaper_dyad`` when the baseline has it) of the hand-written
    baseline, all timed side by side in one run
    (``repeat``: the rounds of every size and of the warm rows; None: 25 below 10^4
    positions, 7 below 5 10^5, else 3, and 15 for the warm rows)."""
    from ..results import solve
    from .accuracy import load_reference
    ref = load_reference(path)
    w2 = ref.SC["w2"]
    rows = []
    # the baseline's other mechanism: far fewer operations by hand (a centred slider-crank
    # in closed form), the same general solve
    mechanisms = [("fourbar_dyad", fourbar_scene, lambda th: ref.fourbar_dyad(th, 20.0)),
                  ("slider_dyad", lambda n: slider_crank_reference_scene(n, ref.SC),
                   lambda th: ref.slider_dyad(th, w2))]
    if hasattr(ref, "shaper_dyad"):     # (a six-bar: two dyads, RTR and RRT; a baseline
        # given with --reference may have none)
        mechanisms.append(("shaper_dyad", shaper_scene,
                           lambda th: ref.shaper_dyad(th, ref.SH["w2"])))
    for name, make, hand in mechanisms:
        for n in sizes:
            scene = make(n)
            th = radian_column(np.linspace(0.0, 360.0, n))
            rounds = repeat or (25 if n < 10_000 else 7 if n < 500_000 else 3)
            jobs = {"reference": lambda th=th, hand=hand: hand(th)}
            for p in solve_paths():
                jobs[p] = on_path(p, lambda s=scene: solve(s).driver)
                jobs[p]()                   # (the compiled kernels loaded before timing)
            times = side_by_side(jobs, rounds)
            me = hand(th)["Me"]
            what = f"solve(scene).driver / hand-written {name}"
            for p in solve_paths():
                sol = on_path(p, lambda s=scene: solve(s))()
                err = float(np.abs(sol.Me - me).max() / np.abs(me).max())
                rows.append(_row(what, n, times, p, "reference", path=p, error=err))
                rows += _warm(n, what, {"reference": jobs["reference"], "solve": jobs[p]},
                              err, rounds=repeat or 15, path=p)
    return rows


def shaper_scene(count: int) -> dict:
    """The bundled shaper (the baseline's ``shaper_dyad``'s mechanism) over ``count``
    positions of a turn."""
    from ..model.examples import example
    from ..model.scene import load_scene
    d = copy.deepcopy(load_scene(example("shaper")).raw)
    d["driver"].update(start=0.0, stop=360.0, count=int(count))
    return d


WARM_BATCH = 20     # calls per round for the small sizes' warm row


def _warm(n: int, what: str, jobs: dict, err: float, rounds: int = 15,
          **extra) -> list[dict]:
    """A small size timed again in batches of ``WARM_BATCH`` calls (timeit's way)
    beside the single calls after a garbage collection: both rows are given. (Measured
    2026-11-27 for the four-bar at 2001 positions: 3.9-4.0x either way; 3.2-3.5x when
    each is timed in a long loop of its own, not alternating: the solver's far larger
    code, a few hundred small Python and numpy calls, then stays in the caches.)"""
    if n >= 10_000:
        return []
    times = side_by_side(jobs, rounds, batch=WARM_BATCH)
    return [_row(f"{what} (warm, batches of {WARM_BATCH} calls)", n, times, "solve",
                 "reference", error=err, **extra)]


def four_bar_variants(count: int = 1000, spread: float = 0.10, seed: int = 0) -> list[dict]:
    """``count`` variants of the bundled four-bar that assemble: every local point,
    ground point, mass and inertia scaled within 1 +- spread."""
    return example_variants("four_bar", count, spread, seed)


def example_variants(name: str, count: int = 1000, spread: float = 0.10, seed: int = 0
                     ) -> list[dict]:
    """``count`` variants of the bundled example ``name`` that assemble, as
    :func:`four_bar_variants`."""
    from ..model.examples import example
    from ..model.scene import load_scene
    from ..results import solve
    base = load_scene(example(name)).raw
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


OTHER_MANY = ("slider_crank", "shaper", "slotted_lever")   # (bench_many's other mechanisms)


MANY_ROUNDS = 7     # (bench_many's rounds: see there)


def bench_many(count: int = 1000, repeat: int = MANY_ROUNDS, others: tuple = OTHER_MANY,
               checked: int = 50) -> list[dict]:
    """solve_many against a loop of solve on the four-bar variants: given Scene objects
    (the same every round, and new ones each round: :func:`_fresh_row`), given dicts,
    and given dicts with each Solution's ``driver`` table built (the per-scene arrays of
    solve_many's Solutions are cut from the stacked ones when first read: that cost
    counted too); and given Scene objects, on the variants of each of
    ``others`` (a ``resist`` load, a six-bar with a force ``when = "resisting"``, a
    slotted lever). ``error``: the largest difference of any table of solve_many against
    solve alone, over the first ``checked`` scenes (0: the same numbers).

    Both jobs of a row given the same Scene objects every round run once on all of them
    before the clock starts: solve_many tells what it stacks of a scene once per scene
    object (``solver.stack.stack_record``, ``solver.many.kept_assemblies``), so a first
    round after a warm-up on a few of them was a first sight of the others (measured
    2026-11-30, 1000 four-bars x 361, the compiled path, process time at a load of 7-8:
    40-70 ms against 20-25 ms, about 18 ms of it those records; what a first sight
    costs is the row of new objects each round). ``repeat`` rounds, 7 by default: the
    median of 3 was the middle of a slow first round and two others, and each job's
    rounds spread by 20-50 % on the shared 2-core machine (the loop 465-726 ms over 14
    rounds, solve_many 21-37 ms, neither in step with the other): over four runs of 10
    alternating rounds, the ratio of the medians of any 3 rounds in a row took
    18.0-25.4x, of any 7 19.6-23.3x."""
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
    for p in solve_paths():
        for label, items in (("Scene objects", scenes), ("dicts", dicts)):
            jobs = {"loop": on_path(p, lambda it=items: [solve(s) for s in it]),
                    "many": on_path(p, lambda it=items: solve_many(it))}
            warm_up(jobs)
            if p != "numpy":        # (the compiled solve_many against the numpy loop too)
                jobs["numpy loop"] = on_path("numpy", lambda it=items: [solve(s) for s in it])
            times = side_by_side(jobs, repeat)
            err = on_path(p, lambda it=items: largest_difference(
                solve_many(it[:checked]), it[:checked]))()
            rows.append(_row(f"speed-up: loop of solve / solve_many ({label})",
                             f"{count} x 361", times, "loop", "many", path=p, error=err))
            if p != "numpy":
                rows.append(_row(f"speed-up: numpy loop of solve / solve_many ({label})",
                                 f"{count} x 361", times, "numpy loop", "many", path=p))
        rows.append(_fresh_row(p, scenes, repeat))
        times = side_by_side({"loop": on_path(p, lambda: [solve(d).driver for d in dicts]),
                              "many": on_path(p, lambda: [s.driver for s in
                                                          solve_many(dicts)])}, repeat)
        rows.append(_row("speed-up: loop of solve / solve_many (dicts, each driver table)",
                         f"{count} x 361", times, "loop", "many", path=p))
    for name in others:
        items = [load_scene(d) for d in example_variants(name, count)]
        for p in solve_paths():
            jobs = {"loop": on_path(p, lambda it=items: [solve(s) for s in it]),
                    "many": on_path(p, lambda it=items: solve_many(it))}
            warm_up(jobs)
            times = side_by_side(jobs, repeat)
            err = on_path(p, lambda it=items: largest_difference(
                solve_many(it[:checked]), it[:checked]))()
            rows.append(_row(f"speed-up: loop of solve / solve_many ({name}, Scene objects)",
                             f"{count} x 361", times, "loop", "many", path=p, error=err))
    return rows


def warm_up(jobs: dict[str, Callable[[], object]]) -> None:
    """Each job run once, untimed: the kernels loaded and compiled, and what solve_many
    keeps per scene object told for every scene the rounds will give it
    (:func:`bench_many`)."""
    for job in jobs.values():
        job()


def _fresh_row(path: str, scenes: list, repeat: int) -> dict:
    """The loop of solve over solve_many, each round on new Scene objects (shallow copies
    of ``scenes``, made before the clock starts): what a first call costs, with nothing
    told once per scene object kept from an earlier call (the solver's per-scene records,
    ``solver.stack.stack_record``)."""
    from ..results import solve, solve_many
    sets = {k: [[copy.copy(s) for s in scenes] for _ in range(repeat)]
            for k in ("loop", "many")}
    times = side_by_side({"loop": on_path(path, lambda: [solve(s) for s in sets["loop"].pop()]),
                          "many": on_path(path, lambda: solve_many(sets["many"].pop()))},
                         repeat)
    return _row("speed-up: loop of solve / solve_many (Scene objects, new ones each round)",
                f"{len(scenes)} x 361", times, "loop", "many", path=path)


def bench_design(population: int = 1000, generations: int = 10, repeat: int = 2
                 ) -> list[dict]:
    """``design`` on the bundled four_bar_design (``population`` x ``generations`` x 361
    rows, seed 1, nothing written) against ``solve_many`` of as many scenes of that
    mechanism as dicts (its variants within +-10 %: the bare stacked solve, no screen,
    no optimiser), on each solve path (column ``path``): the seconds of each, their
    ratio, and ``design``'s rows per second. Needs pymoo (the ``[design]`` extra);
    without it, no row."""
    try:
        import pymoo  # noqa: F401
    except ImportError:
        return []
    from ..design.result import design
    from ..results import solve_many
    dicts = four_bar_variants(population)
    rows = population * generations * 361
    out = []
    for p in solve_paths():
        times = side_by_side({
            "design": on_path(p, lambda: design("four_bar_design", population=population,
                                                generations=generations, seed=1)),
            "many": on_path(p, lambda: [solve_many(dicts) for _ in range(generations)])},
            repeat)
        out.append(_row("design: rows per second (NSGA-II, one stacked solve a generation)",
                        f"{population} x {generations} x 361", times, "design", "many",
                        path=p, rows_per_second=rows / min(times["design"])))
    return out


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
                             repeat, clock=time.perf_counter)
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


def run_speed(quick: bool = False, reference: str | None = None,
              repeat: int | None = None) -> pd.DataFrame:
    """Every ratio of this module, printed as one table (``quick``: small sizes;
    ``repeat``: the rounds of every row, None: each row's own)."""
    ref = str(reference or find_reference())
    # quick: every row once more than a smoke run, 3 rounds each (25 and 7, and 15 warm
    # rounds, took 68 s of the command's 120 s at a load of 12); solve_many of 20 scenes
    # (100: bench_many took 21 s of the 28 s of CPU of `bench --quick --repeat 1`, 20:
    # 5 s, measured 2026-11-30), its tables checked against solve on 5 of them (all 20,
    # the 6 tables of 2 x 20 solves on each of 10 rows: bench_many 6.0-6.3 s of CPU; 5:
    # 1.9-2.2 s, measured 2026-11-30; the suite checks every table bit for bit)
    with frozen_heap():             # (one walk of the heap, not one a timing loop)
        rows = (bench_reference(ref, (2_001, 20_001), repeat=repeat or 3) if quick
                else bench_reference(ref, repeat=repeat))
        rows += (bench_many(20, repeat=repeat or 3, checked=5) if quick
                 else bench_many(repeat=repeat or MANY_ROUNDS))
        rows += bench_start(repeat or (3 if quick else 7))
        rows += (bench_design(50, 2, repeat=1) if quick else
                 bench_design(repeat=repeat or 2))
        if not quick:
            rows += bench_tables()
            rows += bench_crosscheck(repeat or 3)
    df = pd.DataFrame(rows)
    pd.set_option("display.width", 160)
    print(f"\n== speed: ratios to baselines timed side by side ({os.cpu_count()} cores) ==")
    # a cell that does not apply to its row (no error for a start-up time, no ratio for
    # the peak memory) is shown as "-", not as a number
    print(df.to_string(index=False, na_rep="-", float_format=lambda x: f"{x:.4g}"))
    return df
