"""What the result tables cost: ``python -m kinetostatics bench --tables``.

For the benchmark four-bar (:func:`kinetostatics.bench.accuracy.fourbar_scene`: 4 joints,
9 points and cogs, 3 bodies) at 1e4, 1e5 and 1e6 positions, each run in a fresh
process (so that its peak memory is its own):

* ``solve_s``: ``kinetostatics.solve`` (kinematics, loads, reactions, Me);
* ``driver_s, reactions_s, kinematics_s, bodies_s``: building each table, in that
  order (the sweep is solved lean: the first of ``reactions`` and ``kinematics`` solves
  its blocks again once for both, on the numpy path
  :mod:`kinetostatics.results.onepass`, on the compiled path, the default at 1e6
  positions where numba is installed, :mod:`kinetostatics.results.fastpass`, whose
  ``reactions`` pass writes the ``kinematics`` table too; ``bodies`` a pass of its own
  on the compiled path, :func:`kinetostatics.results.fastpass.bodies_frame`, on the
  numpy path the full re-solve), and
  ``long_tables_s`` the three long ones together
  (``long_tables_over_solve`` their ratio to the solve);
* ``tables_MB``: the bytes the ``driver``, ``reactions`` and ``kinematics`` tables hold
  (a column shared by several tables, as ``position``, counted once; a column of one
  value, 8 bytes: 640 MB for the four-bar at 1e6, where the ``reactions`` and
  ``kinematics`` columns written out in full are 758 MB: the floor is the stricter); the
  write floor: those bytes written where the tables have them (:func:`floor_layout`:
  each allocation their columns live in made afresh, as the tables made it, and only the
  bytes they hold written, :func:`fill_layout`), on the pages the tables meet.
  ``warm_*``: after the process's first tables, three rounds of the solve and those
  tables, each round's let go and then its floor measured in the pages they gave back
  (``warm_floor_s``), as the next round's tables meet them; the median round's times
  and, per round, the solve and three tables over the solve and the floor, median
  (``warm_over_floor``; ``_cpu`` in processor time, steadier on a busy machine) and best
  (``_best``). ``first_floor_s``: the same bytes written once in another fresh process
  after its solve (fresh pages, as a process's first tables meet them), and
  ``over_first_floor`` (``_cpu``) the first solve and tables over the first solve and
  that floor;
* ``peak_MB``: the process's peak resident memory with the solution and all four
  tables held;
* ``csv_MB, csv_s, csv_MB_per_s``: writing the four tables as CSV (17 significant
  digits; ``csv_cpu_s`` the CPU time of both writer threads), and ``parquet_s`` as
  Parquet when pyarrow is installed;
* ``cli_out_s, cli_cpu_s, cli_peak_MB``: ``python -m kinetostatics solve SCENE --out
  DIR`` on the bundled ``four_bar`` with that many positions (every table and
  summary.json): wall time, CPU time (user + system) and peak memory;
* ``format_Mvalues_per_s, python_format_Mvalues_per_s``: the vectorised float formatter
  (:func:`kinetostatics.results.csvtext.format_floats`, in the writer's chunks) against Python's
  own ``format(v, ".17g")`` value by value, in CPU time, on ``positions`` random values
  (measured: about 10 M values/s against 4-5 M/s, one core of a loaded machine).

Start-up (:func:`measure_startup`): fresh processes of ``python -c "import numpy"``
(the baseline), ``import kinetostatics``, ``import balance``, ``python -m balance solve
rotor_two_plane`` and ``python -m kinetostatics solve four_bar --out DIR`` (default
positions), taken in turn ``repeat`` times; the best and median wall times and the
best over the best of ``import numpy``.

The machine may be shared: every size runs ``repeat`` times and the best and the
median of each column are printed; on a busy machine the CPU times are the steadier
measure.
"""

from __future__ import annotations

import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

TABLES = ("driver", "reactions", "kinematics", "bodies")
LONG = ("reactions", "kinematics", "bodies")
FLOORED = ("driver", "reactions", "kinematics")     # the tables set against the write floor


WARM_ROUNDS = 3     # rounds of the solve and the floored tables after a process's first


def measure_tables(n: int, out: str, warm_rounds: int = WARM_ROUNDS) -> dict:
    """One run in this process: solve, build the four contract tables, write them; then
    ``warm_rounds`` rounds of the solve and the :data:`FLOORED` tables, each set against
    the write floor of its tables' bytes (:func:`floor_layout`, :func:`fill_layout`)."""
    from ..model.errors import WorkbenchError
    from ..results import solve
    from ..results.output import parquet_available, write_csv, write_parquet
    from .accuracy import fourbar_scene
    row: dict = {"positions": n}
    scene = fourbar_scene(n)
    sol = _timed(row, "solve", lambda: solve(scene))
    for name in TABLES:
        _timed(row, name, lambda name=name, sol=sol: getattr(sol, name))
    row["long_tables_s"] = sum(row[f"{name}_s"] for name in LONG)
    row["long_tables_over_solve"] = row["long_tables_s"] / row["solve_s"]
    row["peak_MB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    layout = floor_layout([getattr(sol, name) for name in FLOORED])
    row["tables_MB"] = sum(sum(b - a for a, b in zip(e[1::2], e[2::2], strict=True))
                           for e in layout) / 1e6
    row["layout"] = layout
    size = 0
    t, cpu = time.perf_counter(), time.process_time()
    for name in TABLES:
        path = write_csv(getattr(sol, name), Path(out) / f"{name}.csv", n)
        size += path.stat().st_size
    row["csv_s"] = time.perf_counter() - t
    row["csv_cpu_s"] = time.process_time() - cpu
    row["csv_MB"] = size / 1e6
    row["csv_MB_per_s"] = row["csv_MB"] / row["csv_s"]
    try:
        parquet_available()
    except WorkbenchError:                 # pyarrow not installed: not measured
        row["parquet_s"] = float("nan")
    else:
        t = time.perf_counter()
        for name in TABLES:
            write_parquet(getattr(sol, name), Path(out) / f"{name}.parquet")
        row["parquet_s"] = time.perf_counter() - t
    row.update(measure_formatter(n))
    del sol
    row.update(warm_rounds_of(scene, warm_rounds))
    return row


def warm_rounds_of(scene, rounds: int) -> dict:
    """``rounds`` rounds of the solve and the :data:`FLOORED` tables, each round's let go
    and then its write floor measured: its tables' bytes (:func:`floor_layout`) written
    into the pages they gave back, as the next round's tables meet them. ``warm_*``: the
    median round's times, and of each round's solve and tables over its solve and floor
    the median (``warm_over_floor``, ``_cpu`` in processor time) and the best (``_best``)."""
    from ..results import solve
    rows = []
    for _ in range(rounds):
        r: dict = {}
        sol = _timed(r, "solve", lambda: solve(scene))
        for name in FLOORED:
            _timed(r, name, lambda name=name, sol=sol: getattr(sol, name))
        layout = floor_layout([getattr(sol, name) for name in FLOORED])
        del sol
        r["floor_s"], r["floor_cpu_s"] = fill_layout(layout)
        spent = [sum(r[f"{k}{cpu}_s"] for k in ("solve", *FLOORED)) for cpu in ("", "_cpu")]
        r["over_floor"] = spent[0] / (r["solve_s"] + r["floor_s"])
        r["over_floor_cpu"] = spent[1] / (r["solve_cpu_s"] + r["floor_cpu_s"])
        rows.append(r)
    out = {f"warm_{k}": float(np.median([r[k] for r in rows])) for k in rows[0]}
    for k in ("over_floor", "over_floor_cpu"):
        out[f"warm_{k}_best"] = min(r[k] for r in rows)
    return out


def first_floor(n: int, layout: list[list[int]]) -> dict:
    """The write floor of a process's first tables: in this process (a fresh one), after
    the solve and the driver table (as the tables met memory), the bytes of ``layout``
    written once into fresh pages (``first_floor_s``, ``first_floor_cpu_s``)."""
    from ..results import solve
    from .accuracy import fourbar_scene
    sol = solve(fourbar_scene(n))
    sol.driver                          # noqa: B018 (the state the tables met)
    wall, cpu = fill_layout(layout)
    return {"first_floor_s": wall, "first_floor_cpu_s": cpu}


def over_first_floor(row: dict) -> dict:
    """A process's first solve and :data:`FLOORED` tables over its first solve and the
    first floor (:func:`first_floor`), in wall and processor time."""
    spent = [sum(row[f"{k}{cpu}_s"] for k in ("solve", *FLOORED)) for cpu in ("", "_cpu")]
    return {"over_first_floor": spent[0] / (row["solve_s"] + row["first_floor_s"]),
            "over_first_floor_cpu": spent[1] / (row["solve_cpu_s"]
                                                + row["first_floor_cpu_s"])}


def _timed(row: dict, name: str, job):
    """``job()``, its wall and processor time into ``row`` (``name_s``, ``name_cpu_s``)."""
    t, cpu = time.perf_counter(), time.process_time()
    out = job()
    row[f"{name}_s"] = time.perf_counter() - t
    row[f"{name}_cpu_s"] = time.process_time() - cpu
    return out


def _column_arrays(frames: list[pd.DataFrame]) -> list[np.ndarray]:
    """Each column's array (a categorical's codes, the table's own: ``Series.cat.codes``
    is a new Series, a copy under pandas 3, 30 MB for the four-bar at 1e6 rows, whose
    addresses are not the table's) of every table in ``frames``."""
    out = []
    for df in frames:
        for c in df.columns:
            col = df[c]
            out.append(col.array.codes if isinstance(col.dtype, pd.CategoricalDtype)
                       else col.to_numpy())
    return out


def _spans(arrays: list[np.ndarray]) -> list[tuple[int, int]]:
    """The union of the address ranges ``arrays`` hold (a column of one value, a view of
    one number: 8 bytes), as sorted disjoint ``(start, end)`` pairs."""
    spans = []
    for a in arrays:
        start = a.__array_interface__["data"][0]
        size = a.itemsize if a.ndim and a.strides[0] == 0 else a.nbytes
        spans.append((start, start + size))
    out: list[tuple[int, int]] = []
    for a, b in sorted(spans):
        if out and a <= out[-1][1]:
            out[-1] = (out[-1][0], max(out[-1][1], b))
        else:
            out.append((a, b))
    return out


def held_bytes(frames: list[pd.DataFrame]) -> int:
    """The bytes the tables' columns hold: each column's array (a categorical's codes),
    memory that several columns share counted once, a column of one value (a view of one
    number) as 8 bytes."""
    arrays = _column_arrays(frames)     # (kept alive: a freed copy's address is reused)
    return sum(b - a for a, b in _spans(arrays))


def _owner(a: np.ndarray) -> np.ndarray:
    """The array that owns ``a``'s memory (the end of its chain of views)."""
    while isinstance(a.base, np.ndarray):
        a = a.base
    return a


def floor_layout(frames: list[pd.DataFrame]) -> list[list[int]]:
    """Where the tables' bytes (:func:`held_bytes`) lie: per allocation their columns
    live in, its size and the byte ranges held in it, ``[size, start, end, ...]`` (from
    its first byte). The floor then allocates as the tables did (a table's float block
    allocated whole, only its rows written touched) and writes those bytes."""
    arrays = _column_arrays(frames)
    owners: dict[int, np.ndarray] = {}
    for a in arrays:
        o = _owner(a)
        owners.setdefault(o.__array_interface__["data"][0], o)
    ranges = sorted((k, k + max(o.nbytes, 1)) for k, o in owners.items())
    layout: dict[int, list[int]] = {}
    for a, b in _spans(arrays):
        for lo, hi in ranges:           # the allocation holding the span
            if lo <= a < hi:
                entry = layout.setdefault(lo, [hi - lo])
                entry += [a - lo, min(b, hi) - lo]
                break
    return list(layout.values())


def fill_layout(layout: list[list[int]]) -> tuple[float, float]:
    """Wall and processor time of writing the bytes of ``layout`` (:func:`floor_layout`):
    each allocation made afresh (``np.empty``, as the tables' arrays) and its ranges
    filled, all held till the end (as the tables are held together)."""
    held = []
    t, cpu = time.perf_counter(), time.process_time()
    for size, *ranges in layout:
        a = np.empty(size, dtype=np.uint8)
        for lo, hi in zip(ranges[::2], ranges[1::2], strict=True):
            a[lo:hi] = 1
        held.append(a)
    return time.perf_counter() - t, time.process_time() - cpu


def measure_formatter(n: int) -> dict:
    """Values per second (millions, CPU time) of the vectorised float formatter, in the
    writer's chunks, and of Python's ``format(v, ".17g")`` value by value, on ``n``
    standard normal values; each the best of three."""
    from ..results.csvtext import format_floats
    from ..results.output import CHUNK
    x = np.random.default_rng(3).standard_normal(n)

    def best(f) -> float:
        times = []
        for _ in range(3):
            t = time.process_time()
            f()
            times.append(time.process_time() - t)
        return max(min(times), 1e-9)

    ours = best(lambda: [format_floats(x[s:s + CHUNK]) for s in range(0, n, CHUNK)])
    python = best(lambda: "\n".join(format(v, ".17g") for v in x.tolist()))
    return {"format_Mvalues_per_s": n / ours / 1e6,
            "python_format_Mvalues_per_s": n / python / 1e6}


def fresh_run(n: int, out: str) -> dict:
    """:func:`measure_tables` in a fresh process, then :func:`first_floor` of its tables'
    layout in another (both meet a fresh process's pages) and :func:`over_first_floor`."""
    code = ("import json, sys; from kinetostatics.bench.tables import measure_tables; "
            f"print(json.dumps(measure_tables({n}, {out!r})))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       check=True)
    row = json.loads(r.stdout.strip().splitlines()[-1])
    code = ("import json, sys; from kinetostatics.bench.tables import first_floor; "
            f"print(json.dumps(first_floor({n}, json.load(sys.stdin))))")
    r = subprocess.run([sys.executable, "-c", code], input=json.dumps(row.pop("layout")),
                       capture_output=True, text=True, check=True)
    row.update(json.loads(r.stdout.strip().splitlines()[-1]))
    row.update(over_first_floor(row))
    return row


def measure_cli(n: int, folder: str) -> dict:
    """``solve --out`` on the bundled four_bar with ``n`` positions, in a fresh process."""
    from ..model.examples import example
    text = Path(example("four_bar")).read_text()
    text, k = re.subn(r"(?m)^count\s*=\s*\d+", f"count = {n}", text)
    if k != 1:
        raise RuntimeError("the bundled four_bar has no 'count = ...' line to change")
    scene = Path(folder) / "four_bar.toml"
    scene.write_text(text)
    code = ("import resource, sys; from kinetostatics.cli import main; "
            "rc = main(sys.argv[1:]); "
            "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr); "
            "sys.exit(rc)")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", code, "solve", str(scene), "--out",
                        str(Path(folder) / "out")], capture_output=True, text=True, check=True)
    seconds = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return {"cli_out_s": seconds, "cli_cpu_s": cpu,
            "cli_peak_MB": int(r.stderr.strip().splitlines()[-1]) / 1024}


STARTUP = {
    "import numpy": ["-c", "import numpy"],
    "import kinetostatics": ["-c", "import kinetostatics"],
    "import balance": ["-c", "import balance"],
    "balance solve rotor_two_plane": ["-m", "balance", "solve", "rotor_two_plane"],
    "kinetostatics solve four_bar --out": ["-m", "kinetostatics", "solve", "four_bar",
                                           "--out", "{out}"],
}


def measure_startup(repeat: int = 7) -> pd.DataFrame:
    """Wall time of fresh processes (:data:`STARTUP`), each command in turn ``repeat``
    times: ``best_s``, ``median_s`` and ``over_numpy`` (best over the best of ``import
    numpy``, measured in the same rounds)."""
    times: dict[str, list[float]] = {k: [] for k in STARTUP}
    for _ in range(repeat):
        for name, args in STARTUP.items():
            with tempfile.TemporaryDirectory() as tmp:
                t = time.perf_counter()
                subprocess.run([sys.executable, *(a.format(out=tmp) for a in args)],
                               capture_output=True, check=True)
                times[name].append(time.perf_counter() - t)
    numpy_best = min(times["import numpy"])
    return pd.DataFrame([{"command": k, "best_s": min(v), "median_s": float(np.median(v)),
                          "over_numpy": min(v) / numpy_best} for k, v in times.items()])


def run_table_bench(quick: bool = False, repeat: int = 3,
                    sizes: tuple[int, ...] | None = None) -> pd.DataFrame:
    """Run every size ``repeat`` times; print and return the best and median rows
    (``quick``: 1000 positions alone, a smoke run of every column: each size costs three
    fresh processes, 10 000 positions 2.5 s of CPU, measured 2026-11-30)."""
    sizes = sizes or ((1_000,) if quick else (10_000, 100_000, 1_000_000))
    runs = []
    for n in sizes:
        for _ in range(repeat):
            with tempfile.TemporaryDirectory() as tmp:
                row = fresh_run(n, tmp)
            with tempfile.TemporaryDirectory() as tmp:
                row.update(measure_cli(n, tmp))
            runs.append(row)
    df = pd.DataFrame(runs)
    higher_better = ["csv_MB_per_s", "format_Mvalues_per_s", "python_format_Mvalues_per_s"]
    lower_better = [c for c in df.columns if c not in ("positions", *higher_better)]
    best = df.groupby("positions").agg({**dict.fromkeys(lower_better, "min"),
                                        **dict.fromkeys(higher_better, "max")})
    median = df.groupby("positions").median()
    out = pd.concat({"best": best, "median": median}, names=["stat"]).reset_index()
    out = out.sort_values(["positions", "stat"]).reset_index(drop=True)
    pd.set_option("display.width", 200)
    print(f"== result tables (four-bar; {repeat} runs per size, "
          f"{os.cpu_count()} cores) ==")
    print(out.T.to_string(header=False, float_format=lambda x: f"{x:.4g}"))
    rounds = 1 if quick else 7
    start = measure_startup(rounds)
    print(f"== start-up (fresh processes, best and median of {rounds}, "
          f"{os.cpu_count()} cores) ==")
    print(start.to_string(index=False, float_format=lambda x: f"{x:.3f}"))
    return out
