"""The compiled path's part of the dead-point screen
(:mod:`~kinetostatics.solver.deadpoints`), without numba at import: its kernels
(:mod:`~kinetostatics.solver.fast.screen_kernels`) are imported once the compiled
kernels are loaded in the process."""

from __future__ import annotations

from collections.abc import Callable

from . import loader
from .choice import path_setting


def compiled_scan() -> Callable | None:
    """:func:`~kinetostatics.solver.fast.screen_kernels.scan_candidates` when the compiled
    kernels are loaded and the numpy path is not asked for, else None (the numpy scan;
    numba is never loaded for it)."""
    if not loader.loaded() or path_setting() == "numpy":
        return None
    from .screen_kernels import scan_candidates
    return scan_candidates
