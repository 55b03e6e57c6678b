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

``CPU_PER_TEST`` names the output (JSON lines: test id, phase, CPU seconds, wall seconds,
the xdist worker or ``main``, the phase's start in seconds since the epoch), appended to as
the run goes. Under pytest-xdist (``-n 2 -p tools.cpu_per_test``) each worker records its
own tests: the summary then shows each worker's busy time and when it ran out of work (the
run's tail). Needs psutil (installed with ipykernel).
"""

from __future__ import annotations

import collections
import json
import os
import resource
import sys
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
    with open(OUT, "a", encoding="utf-8") as f:
        f.write(json.dumps([item.nodeid, phase, processor_time() - cpu,
                            time.perf_counter() - wall, _worker(item), start]) + "\n")


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


if __name__ == "__main__":
    print(summary(sys.argv[1] if len(sys.argv) > 1 else OUT))
