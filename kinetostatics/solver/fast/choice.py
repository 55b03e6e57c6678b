"""Which path solves: the switch (an option, and ``KINETOSTATICS_PATH`` for a process or a
test suite) and the rule for ``auto`` (no numba here).

``numpy``: always the numpy path. ``fast``: the compiled path for every call it covers
(numba loaded on the first). ``auto`` (the default): the numpy path until a call, or a
``solve_many`` group, of at least :data:`AUTO_ROWS` rows: that call loads numba and
solves on the compiled path, and so does every call after it in the process, small ones
too (:data:`AUTO_SMALL`: once loaded, the compiled path wins at 2001 rows as well). A
first small solve never imports numba, nor does ``import kinetostatics``. Without numba,
or without a writable cache folder (one warning), every setting solves on the numpy
path.
"""

from __future__ import annotations

import os
import warnings

from . import loader

PATHS = ("auto", "numpy", "fast")
AUTO_ROWS = 20_000      # below, numba's import and first call (0.2-0.3 s) outweigh the gain
# Whether ``auto`` takes the compiled path: for a call (or a solve_many group) of
# AUTO_ROWS rows or more, and then (AUTO_SMALL) for every call of the process, once numba
# is loaded. Measured 2026-11-29 on the 2-core machine (shared, load 4-8), processor
# time, bench_reference's rounds, solve(dict).driver against the hand form, compiled
# against numpy: four-bar at 2001 rows 1.50-1.61x against 2.98-3.21x (single calls,
# fast/short.py's fused kernel; 2.11-2.33x before it), 0.73-0.90x against 2.48-2.80x
# (batches of 20); slider-crank at 2001 2.16-2.36x against 3.96-4.07x; four-bar at 2e5
# 0.51-0.55x against 0.75-0.81x, at 1e6 0.57x against 0.77x;
# slider-crank at 2e5 2.19-2.38x against 2.03-2.15x (the one loss, 5-10 %), at 1e6 1.07x
# against 1.15x; solve_many of 1000 four-bars x 361 (a group over AUTO_ROWS) 7.3x a loop
# of solve against 5.9x (docs/solve-paths.md, "Speed"). A fresh process's small calls
# stay on numpy: numba's import and its kernels' first load (0.2-1.2 s of processor time
# from the cache, 15 s of compiling per kind of mechanism on a new machine) outweigh a
# small call's gain.
AUTO_COMPILED = True
AUTO_SMALL = True
_OPTION: dict[str, str | None] = {"path": None, "told": None}


def use(path: str | None) -> None:
    """Set the solve path for this process: ``"auto"``, ``"numpy"`` or ``"fast"`` (None:
    back to ``KINETOSTATICS_PATH``, else ``auto``)."""
    if path is not None and path not in PATHS:
        raise ValueError(f"solve path {path!r}: expected one of {', '.join(PATHS)}")
    _OPTION["path"] = path


def path_setting() -> str:
    """The setting in force: the option, else ``KINETOSTATICS_PATH``, else ``auto`` (an
    unknown value of the variable is named once and taken as ``auto``)."""
    if _OPTION["path"] is not None:
        return _OPTION["path"]
    env = os.environ.get("KINETOSTATICS_PATH", "").strip().lower()
    if env in PATHS:
        return env
    if env and _OPTION["told"] != env:
        _OPTION["told"] = env
        warnings.warn(f"KINETOSTATICS_PATH={env!r} is not one of {', '.join(PATHS)}: "
                      "taken as auto", RuntimeWarning, stacklevel=3)
    return "auto"


def wanted(rows: int):
    """The kernels module when a call of ``rows`` rows goes the compiled path, else None
    (numba imported here, on the first call that qualifies)."""
    setting = path_setting()
    if setting == "numpy":
        return None
    if setting == "auto" and not (AUTO_COMPILED and (
            rows >= AUTO_ROWS or (AUTO_SMALL and loader.loaded()))):
        return None
    if loader.loaded():
        return loader.kernels()
    if setting == "fast" and not loader.installed() and _OPTION["told"] != "numba":
        _OPTION["told"] = "numba"
        warnings.warn("KINETOSTATICS_PATH=fast but numba is not installed (pip install "
                      "'mechanisms-workbench[fast]'): solving on the numpy path",
                      RuntimeWarning, stacklevel=3)
    return loader.kernels()
