"""The ``auto`` rule of the solve paths (kinetostatics.solver.fast.choice): numba loaded
only by a call, or a solve_many group, of at least AUTO_ROWS rows; every call after it
on the compiled path; a fresh process's small solves, and ``import kinetostatics``,
never import numba; without numba, or without a writable cache folder, the numpy path.

The processes that load numba run apart (subprocesses): a test here never leaves the
compiled path loaded in the suite's own process.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics import solve
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.fast import choice, loader

has_numba = importlib.util.find_spec("numba") is not None
needs_numba = pytest.mark.skipif(not has_numba, reason="numba (the [fast] extra) not installed")


def _python(code: str, **env: str) -> list[str]:
    """What ``code`` prints in a fresh process under ``auto`` (``env`` added), in words."""
    full = {**os.environ, **env}
    if "KINETOSTATICS_PATH" not in env:
        full.pop("KINETOSTATICS_PATH", None)        # (unset: auto)
    out = subprocess.run([sys.executable, "-c", code], env=full, capture_output=True,
                         text=True, check=True)
    return out.stdout.split()


SETUP = ("import sys, warnings, kinetostatics as ks\n"
         "from kinetostatics.model.scene import load_scene\n"
         "from kinetostatics.solver.fast import AUTO_ROWS\n"
         "def four_bar(count):\n"
         "    d = load_scene(ks.example('four_bar')).raw\n"
         "    d['driver'] = {**d['driver'], 'count': int(count)}\n"
         "    return d\n")


def test_import_and_small_solves_under_auto_leave_numba_unimported() -> None:
    """A first small solve and a small solve_many group (10 x 361 rows, under AUTO_ROWS)
    stay on numpy and import no numba."""
    words = _python(SETUP + "print('numba' in sys.modules)\n"
                    "s = ks.solve(four_bar(2001))\n"
                    "m = ks.solve_many([four_bar(361) for _ in range(10)])\n"
                    "print(s.path, {x.path for x in m}.pop(), 'numba' in sys.modules)")
    assert words == ["False", "numpy", "numpy", "False"]


@pytest.mark.slow       # (loads the kernels: a machine's first run compiles them, 15 s)
@needs_numba
def test_a_call_of_auto_rows_loads_the_compiled_path_for_every_call_after() -> None:
    """Under auto: a small first call on numpy, a call of AUTO_ROWS rows on the compiled
    path (numba loaded there), then a small call on the compiled path too; a solve_many
    group of AUTO_ROWS rows in a fresh process goes compiled as well."""
    words = _python(SETUP + "a = ks.solve(four_bar(361)).path\n"
                    "b = ks.solve(four_bar(AUTO_ROWS)).path\n"
                    "c = ks.solve(four_bar(361)).path\n"
                    "print(a, b, c)")
    assert words == ["numpy", "fast", "fast"]
    words = _python(SETUP + "n = -(-AUTO_ROWS // 361)\n"
                    "m = ks.solve_many([four_bar(361) for _ in range(n)])\n"
                    "print(sorted({x.path for x in m}), 'numba' in sys.modules)")
    assert words == ["['fast']", "True"]


@needs_numba
def test_auto_without_a_writable_cache_folder_solves_on_numpy_with_one_warning(
        tmp_path) -> None:
    locked = tmp_path / "locked"
    locked.write_text("a file, not a folder")
    words = _python(SETUP + "with warnings.catch_warnings(record=True) as w:\n"
                    "    warnings.simplefilter('always')\n"
                    "    p = {ks.solve(four_bar(AUTO_ROWS)).path for _ in range(2)}\n"
                    "print(p.pop(), len(p), len([x for x in w if 'cache' in str(x.message)]),"
                    " 'numba' in sys.modules)", NUMBA_CACHE_DIR=str(locked / "sub"))
    assert words == ["numpy", "0", "1", "False"]


@pytest.fixture
def auto(monkeypatch):
    """``auto`` set for one test, the loader as if nothing were loaded yet, its loads
    counted (no numba loaded: ``kernels`` stands for the module)."""
    monkeypatch.delenv("KINETOSTATICS_PATH", raising=False)
    choice.use("auto")
    loads: list[int] = []
    kernels = object()

    def load():
        loads.append(1)
        monkeypatch.setitem(loader._STATE, "kernels", kernels)
        return kernels
    monkeypatch.setitem(loader._STATE, "kernels", None)
    monkeypatch.setattr(loader, "kernels", load)
    yield kernels, loads
    choice.use(None)


def test_the_auto_rule(auto) -> None:
    kernels, loads = auto
    assert choice.wanted(1) is None and choice.wanted(choice.AUTO_ROWS - 1) is None
    assert loads == []                          # nothing loaded for small calls
    assert choice.wanted(choice.AUTO_ROWS) is kernels and loads == [1]
    assert choice.wanted(1) is kernels          # once loaded, small calls too
    choice.use("numpy")
    assert choice.wanted(10 * choice.AUTO_ROWS) is None


def test_without_numba_auto_solves_on_numpy_and_says_nothing(monkeypatch, recwarn) -> None:
    monkeypatch.delenv("KINETOSTATICS_PATH", raising=False)
    monkeypatch.setattr(loader, "installed", lambda: False)
    monkeypatch.setitem(loader._STATE, "kernels", None)
    monkeypatch.setitem(choice._OPTION, "told", None)
    choice.use("auto")
    try:
        d = load_scene(ks.example("four_bar")).raw
        d["driver"] = {**d["driver"], "count": choice.AUTO_ROWS}
        assert choice.wanted(10 * choice.AUTO_ROWS) is None
        assert solve(d).path == "numpy"
    finally:
        choice.use(None)
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]


@pytest.mark.slow
@needs_numba
def test_a_small_compiled_solve_wraps_its_arrays_when_first_read() -> None:
    """A compiled sweep of 2001 rows holds the kernels' arrays and wraps them in its
    kinematics and reactions when a table first reads them: whichever table comes first,
    and pickled (every array given), the same tables bit for bit."""
    import pickle

    from kinetostatics.solver.pipeline import solve_arrays
    d = load_scene(ks.example("four_bar")).raw
    d["driver"] = {**d["driver"], "count": 2001}
    choice.use("fast")
    try:
        first, second, sent = solve(d), solve(d), pickle.loads(pickle.dumps(solve(d)))
        # the solver's arrays sent whole (solve_many's executor pickles them)
        arrays = pickle.loads(pickle.dumps(solve_arrays(d)))
    finally:
        choice.use(None)
    arrived = ks.Solution.of(arrays)
    assert first.path == second.path == sent.path == arrived.path == "fast"
    tables = ("driver", "reactions", "kinematics", "dyads", "bodies")
    one = {t: getattr(first, t) for t in tables}                  # the driver table first
    two = {t: getattr(second, t) for t in reversed(tables)}       # the bodies first
    for t in tables:
        assert one[t].equals(two[t]) and one[t].equals(getattr(sent, t)), t
        assert one[t].equals(getattr(arrived, t)), t
    assert np.array_equal(first.loads[0].fx, second.loads[0].fx)  # (let go, made again)
