"""Processor time per test phase: a pytest plugin for finding where the suite's CPU goes.

On a shared machine the wall durations (``--durations``) follow the load, not the work;
this plugin records the processor time of each test's setup, call and teardown: this
process's, its reaped children's and that of every live descendant (a Jupyter kernel, a
JupyterLab server, Chromium) with the children each has reaped. A descendant that ends
in a phase takes its time out of that phase's count until its parent reaps it (a
session fixture's server: at the session's end), so single phases can be negative; the
sum over the run is whole.

Usage (serially, from the repository's root)::

    python -m pytest -p no:xdist -p tools.cpu_per_test -m slow     # writes cpu_per_test.jsonl
    python tools/cpu_per_test.py cpu_per_test.jsonl                # the costliest files, tests
    python tools/cpu_per_test.py cpu_per_test.jsonl --over 0.15    # heavy quick tests

``CPU_PER_TEST`` names the output (JSON lines: test id, phase, CPU seconds, wall seconds,
the xdist worker or ``main``, the phase's start in seconds since the epoch, why the test is
a keeper of the quick tier or null), appended to as
the run goes. Under pytest-xdist (``-n 2 -p tools.cpu_per_test``) each worker records its
own tests: the summary then shows each worker's busy time and when it ran out of work (the
run's tail). Needs psutil (installed with ipykernel).
"""

from __future__ import annotations

import collections
import json
import os
import resource
import time

import psutil
import pytest

OUT = os.environ.get("CPU_PER_TEST", "cpu_per_test.jsonl")
_ME = psutil.Process()


def processor_time() -> float:
    """CPU seconds of this process, its reaped children and every live descendant (with
    the children each has reaped)."""
    reaped = resource.getrusage(resource.RUSAGE_CHILDREN)
    total = time.process_time() + reaped.ru_utime + reaped.ru_stime
    for p in _ME.children(recursive=True):
        try:
            t = p.cpu_times()
        except psutil.Error:                # ended meanwhile: counted when reaped
            continue
        total += t.user + t.system + t.children_user + t.children_system
    return total


def _worker(item: pytest.Item) -> str:
    """The xdist worker running ``item`` (from its configuration: the environment's
    PYTEST_XDIST_WORKER reaches the pytest runs a test starts too), else ``main``."""
    return getattr(item.config, "workerinput", {}).get("workerid", "main")


def _measured(item: pytest.Item, phase: str):
    cpu, wall, start = processor_time(), time.perf_counter(), time.time()
    yield
    keeper = item.get_closest_marker("quick_keeper")
    with open(OUT, "a", encoding="utf-8") as f:
        f.write(json.dumps([item.nodeid, phase, processor_time() - cpu,
                            time.perf_counter() - wall, _worker(item), start,
                            keeper.args[0] if keeper else None]) + "\n")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_setup(item: pytest.Item):
    yield from _measured(item, "setup")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_call(item: pytest.Item):
    yield from _measured(item, "call")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_teardown(item: pytest.Item):
    yield from _measured(item, "teardown")


def _workers(rows: list[list]) -> list[str]:
    """Per worker: its tests' CPU and wall, and when its last test ended, counted from the
    first test's start (the worker that ends last is the run's tail), with its last tests."""
    begin = min(r[5] for r in rows)
    lines = ["", "workers (CPU, wall in tests, last test ended at):"]
    for worker in sorted({r[4] for r in rows}):
        mine = [r for r in rows if r[4] == worker]
        end = max(r[5] + r[3] for r in mine) - begin
        lines.append(f"{worker:>8}  {sum(r[2] for r in mine):8.1f}  "
                     f"{sum(r[3] for r in mine):8.1f}  {end:8.1f}")
        last: dict[str, float] = {}
        for r in sorted(mine, key=lambda r: r[5]):
            last[r[0]] = r[5] + r[3] - begin
        for nodeid, t in list(last.items())[-3:]:
            lines.append(f"{'':>18}ended {t:8.1f}  {nodeid}")
    return lines


def summary(path: str, top: int = 30) -> str:
    """The total, then the costliest files and tests (all phases) of a recorded run, and
    each xdist worker's share and tail (records that carry the worker)."""
    files: collections.Counter = collections.Counter()
    tests: collections.Counter = collections.Counter()
    with open(path, encoding="utf-8") as f:
        rows = [json.loads(line) for line in f]
    for nodeid, _phase, cpu, *_rest in rows:
        files[nodeid.split("::")[0]] += cpu
        tests[nodeid] += cpu
    lines = [f"{sum(files.values()):8.1f} s of CPU in {len(tests)} tests", "", "files:"]
    lines += [f"{c:8.1f}  {name}" for name, c in files.most_common(top)]
    lines += ["", "tests:"] + [f"{c:8.1f}  {name}" for name, c in tests.most_common(top)]
    if rows and all(len(r) >= 6 for r in rows):
        lines += _workers(rows)
    return "\n".join(lines)


def over(path: str, budget: float) -> str:
    """The tests of a recorded run (the quick tier) that cost ``budget`` seconds of CPU or
    more and are no keepers of the quick tier (tests/conftest.py, ``keeper``), as lines of
    tests/slow_by_cost.txt; then the keepers' count and CPU."""
    tests: collections.Counter = collections.Counter()
    kept: dict[str, str | None] = {}
    with open(path, encoding="utf-8") as f:
        for row in map(json.loads, f):
            tests[row[0]] += row[2]
            kept[row[0]] = row[6] if len(row) > 6 else None
    lines = [f"{cpu:.2f} {nodeid}" for nodeid, cpu in tests.most_common()
             if cpu >= budget and not kept[nodeid]]
    keepers = [cpu for nodeid, cpu in tests.items() if kept[nodeid]]
    return "\n".join(lines + [f"# keepers: {len(keepers)} tests, {sum(keepers):.1f} s of CPU"])


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", nargs="?", default=OUT, help="the recorded run (JSON lines)")
    ap.add_argument("--over", type=float, metavar="SECONDS",
                    help="list the tests, no keepers, of this CPU or more")
    args = ap.parse_args()
    print(summary(args.run) if args.over is None else over(args.run, args.over))
