"""The xdist controller's start: the bytecode every worker reads, made once before the
workers start.

On a fresh clone (CI) no module has its bytecode yet, and the workers, started at the
same moment, each compiled every module of the packages and rewrote the asserts of every
test module (pytest's rewritten ``.pyc``): 10.3 s of CPU a process against 4.0 s with the
bytecode there (``pytest --collect-only -p no:xdist``, measured 2026-11-30), three times
over. Here the controller writes that bytecode once, on two processes, before xdist starts
the workers (its ``pytest_sessionstart`` runs last): the workers then only read it.

pytest offers no public call for its rewritten bytecode: this uses the functions its
import hook uses (``_pytest.assertion.rewrite``), and where they are not there (another
pytest) it writes nothing, and the workers rewrite as before.
"""

from __future__ import annotations

import compileall
import multiprocessing
import sys
from pathlib import Path

import pytest

#: The packages whose bytecode the workers read (besides the tests).
PACKAGES = ("kinetostatics", "balance", "tools")


def rewritten(config: pytest.Config, files: list[Path]) -> int:
    """Write pytest's rewritten bytecode of ``files`` where it is missing or stale, as
    pytest's import hook writes it (the same name, the same code); the count written."""
    from _pytest.assertion import rewrite
    state = config.stash[rewrite.assertstate_key]
    done = 0
    for fn in files:
        cache = rewrite.get_cache_dir(fn)
        if not rewrite.try_makedirs(cache):
            continue
        pyc = cache / (fn.name[:-3] + rewrite.PYC_TAIL)
        if rewrite._read_pyc(fn, pyc, state.trace) is None:
            try:
                source_hash, co = rewrite._rewrite_test(fn, config)
            except (SyntaxError, ValueError, OSError):
                continue        # the worker that collects it reports it, as before
            done += rewrite._write_pyc(state, co, source_hash, pyc)
    return done


def rewritten_files(config: pytest.Config) -> list[Path]:
    """The modules pytest rewrites under the test paths: the test files (the
    ``python_files`` patterns) and the conftest files."""
    root = config.rootpath
    patterns = config.getini("python_files")
    found: set[Path] = set()
    for where in config.getini("testpaths") or ["."]:
        for pattern in [*patterns, "conftest.py"]:
            found.update((root / where).rglob(pattern))
    return sorted(p for p in found if p.suffix == ".py")


def _half(config: pytest.Config, files: list[Path]) -> None:
    """A forked helper's share: its files' rewritten bytecode, then the packages'."""
    rewritten(config, files)
    root = config.rootpath
    for package in PACKAGES:
        if (root / package).is_dir():
            compileall.compile_dir(root / package, quiet=2)


def warm_bytecode(config: pytest.Config) -> None:
    """Every worker's bytecode written once (:mod:`tests.prewarm`): half the test files
    here, the other half and the packages in a forked process at the same time.
    Nothing where bytecode is not written (``sys.dont_write_bytecode``), or where
    pytest's hook is not the one this knows."""
    if sys.dont_write_bytecode or "fork" not in multiprocessing.get_all_start_methods():
        return
    try:
        from _pytest.assertion import rewrite
        needed = (rewrite.assertstate_key, rewrite.get_cache_dir, rewrite.try_makedirs,
                  rewrite.PYC_TAIL, rewrite._read_pyc, rewrite._rewrite_test,
                  rewrite._write_pyc)
        config.stash[needed[0]]
    except (ImportError, AttributeError, KeyError):
        return
    files = rewritten_files(config)
    helper = multiprocessing.get_context("fork").Process(
        target=_half, args=(config, files[1::2]), daemon=True)
    helper.start()
    try:
        rewritten(config, files[::2])
    except Exception:   # noqa: BLE001 (pytest's private functions changed: the workers
        pass            # rewrite their modules themselves, as without this module)
    helper.join()
