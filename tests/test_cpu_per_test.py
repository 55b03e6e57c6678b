"""tools/cpu_per_test.py: the processor time of each test phase, a child process's too."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from tests.helpers import ROOT

TESTS = '''
import subprocess, sys

def test_busy_child():
    # about 0.5 s of CPU in a child process (the plugin counts what the test starts)
    subprocess.run([sys.executable, "-c", "import time\\nt = time.process_time()\\n"
                    "while time.process_time() - t < 0.5: pass"], check=True)

def test_idle():
    import time
    time.sleep(0.3)
'''


@pytest.mark.slow
def test_a_childs_processor_time_is_its_tests(tmp_path) -> None:
    (tmp_path / "test_cases.py").write_text(TESTS)
    out = tmp_path / "cpu.jsonl"
    env = dict(os.environ, CPU_PER_TEST=str(out), PYTHONPATH=os.pathsep.join(
        [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]))
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                        "-p", "no:xdist", "-p", "tools.cpu_per_test", "test_cases.py"],
                       cwd=tmp_path, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    rows = [json.loads(line) for line in out.read_text().splitlines()]
    assert [(n.split("::")[1], p) for n, p, *_ in rows] == [
        (t, p) for t in ("test_busy_child", "test_idle") for p in ("setup", "call", "teardown")]
    cpu = {(n.split("::")[1], p): c for n, p, c, *_ in rows}
    wall = {(n.split("::")[1], p): w for n, p, _, w, *_ in rows}
    # the child's 0.5 s (and its interpreter's start) counted; the sleep is wall, not CPU
    assert cpu["test_busy_child", "call"] >= 0.5
    assert cpu["test_idle", "call"] < 0.1 <= 0.3 <= wall["test_idle", "call"]
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "cpu_per_test.py"), str(out)],
                       capture_output=True, text=True, check=True)
    tests = r.stdout.split("tests:\n", 1)[1].splitlines()
    assert tests[0].endswith("test_cases.py::test_busy_child"), r.stdout
    # one process (no xdist worker): its two tests' wall in its line, the idle one last
    assert {row[4] for row in rows} == {"main"}
    main = r.stdout.split("workers", 1)[1].splitlines()[1].split()
    assert main[0] == "main" and float(main[2]) >= 0.3, r.stdout
    assert r.stdout.rstrip().endswith("test_cases.py::test_idle"), r.stdout


def test_over_lists_the_heavy_tests_that_are_no_keepers(tmp_path) -> None:
    """``--over``: the tests of a recorded run at or over the budget (all phases summed),
    heaviest first, as lines of tests/slow_by_cost.txt; the keepers left out and counted."""
    rows = [["t.py::test_a", "setup", 0.05, 0.0, "gw0", 1.0, None],
            ["t.py::test_a", "call", 0.12, 0.0, "gw0", 1.0, None],
            ["t.py::test_b", "call", 0.4, 0.0, "gw1", 1.0, None],
            ["t.py::test_c", "call", 0.1, 0.0, "gw1", 1.0, None],
            ["t.py::test_p", "call", 2.0, 0.0, "gw0", 1.0, "property"]]
    run = tmp_path / "run.jsonl"
    run.write_text("".join(json.dumps(r) + "\n" for r in rows))
    # (in this process: the command line's start cost 0.35 s of CPU, over the quick
    # tier's budget; `--over` only hands its arguments on)
    from tools.cpu_per_test import over
    assert over(str(run), 0.15).splitlines() == ["0.40 t.py::test_b", "0.17 t.py::test_a",
                                                 "# keepers: 1 tests, 2.0 s of CPU"]
