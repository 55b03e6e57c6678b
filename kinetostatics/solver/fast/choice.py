"""Which path solves: the switch (an option, and ``KINETOSTATICS_PATH`` for a process or a
test suite) and the rule for ``auto`` (no numba here).

``numpy``: always the numpy path. ``fast``: the compiled path for every call it covers
(numba loaded on the first). ``auto`` (the default): while :data:`AUTO_COMPILED` is off,
the numpy path; on, the compiled path for a call (or a ``solve_many`` group) of at
least :data:`AUTO_ROWS` rows, and for every call once it is loaded in the process; a
first small solve never imports numba. Without numba, or
without a writable cache folder, every setting solves on the numpy path.
"""

from __future__ import annotations

import os
import warnings

from . import loader

PATHS = ("auto", "numpy", "fast")
AUTO_ROWS = 20_000      # below, numba's import and first call (0.2-0.3 s) outweigh the gain
# Whether ``auto`` takes the compiled path at all. Off: the kernels, vectorised in tiles,
# win on long four-bar sweeps but not yet elsewhere (measured 2026-11-29 on the 2-core
# machine in processor time, solve + driver table against the hand form: four-bar at
# 2e5 / 1e6 rows 0.57x / 0.61x against numpy's 1.00x / 0.89x; slider-crank 2.3x / 0.80x
# against 2.1x / 0.79x; at 2001 rows 4.7x against 4.2x; solve_many of 1000 x 361 rows
# 1.6x numpy's time), so the compiled path runs only when asked for (``fast``).
# docs/solve-paths.md, "Speed", says where the time goes.
AUTO_COMPILED = False
AUTO_SMALL = False
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
