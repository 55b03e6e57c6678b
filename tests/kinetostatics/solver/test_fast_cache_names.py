"""numba's on-disk cache of the compiled kernels: one index file per kernel.

numba names a cached function's index by its module, qualified name and first line. A
factory's kernels (one per dyad kind) would share one index, and two processes compiling
two kinds at once (xdist workers, a class's machines on a cold cache) could then save
into one data file, one kind's machine code loading for the other's without a warning.
``jitbase.jit_as`` names each kind's kernel apart; this test guards that every cached
kernel of every kernel module has an index of its own."""

from __future__ import annotations

import importlib

import pytest

from kinetostatics.solver.fast import loader

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


def cached_kernels() -> list:
    """Every cached kernel (a numba dispatcher that is not an inlined helper) the kernel
    modules hold, in their globals and in their tables of kinds."""
    from numba.core.registry import CPUDispatcher

    if loader.kernels() is None:
        pytest.skip("no writable cache folder")
    found = []
    for path in loader.kernel_sources():
        module = importlib.import_module(f"kinetostatics.solver.fast.{path.stem}")
        for value in vars(module).values():
            for item in value.values() if isinstance(value, dict) else (value,):
                if (isinstance(item, CPUDispatcher)
                        and not item.targetoptions.get("forceinline")
                        and item.py_func.__module__ == module.__name__):
                    found.append(item)
    return found


def test_every_cached_kernel_has_an_index_of_its_own() -> None:
    kernels = cached_kernels()
    # (measured 2026-11-29: 42 kernels; each table of kinds (MOTION, REACTIONS, KEPT,
    # AFTER_RTR, TABLES) made by a factory, one source)
    assert len(kernels) >= 30
    names = [(k.py_func.__module__, k.py_func.__qualname__, k.py_func.__code__.co_firstlineno)
             for k in kernels]
    shared = sorted({n for n in names if names.count(n) > 1})
    assert not shared, f"kernels sharing one cache index: {shared}"
