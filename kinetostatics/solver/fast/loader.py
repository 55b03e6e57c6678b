"""Loading the compiled kernels: numba imported on first use, its cache folder settled
first (no numba here at import).

numba reads its cache folder when a kernel is decorated (``cache=True`` raises there when
no folder is writable), so the folder is chosen before numba loads: ``NUMBA_CACHE_DIR``
when set, else ``$XDG_CACHE_HOME/kinetostatics/numba`` (``~/.cache/...``), and in it a
folder named by the kernels' sources (:func:`sources_key`). When nothing is writable the
compiled path is off for the process, with one warning: the numpy path solves
everything. The project ships no caches; the first use on a machine compiles each
kernel once (0.5-4 s each), later processes load them from the folder.

Why a folder per version of the sources: numba checks a cached kernel against its own
file's time stamp and size only, so a kernel whose inlined helpers (another module of
this package) changed would load stale from the cache, a wrong number with no warning.
A new version of any file the kernels are compiled from (:func:`kernel_sources`) gets a
folder of its own.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import re
import sys
import tempfile
import warnings
from pathlib import Path
from types import ModuleType

_STATE: dict[str, object] = {"kernels": None, "off": None}


def installed() -> bool:
    """Whether numba can be imported (the ``[fast]`` extra), without importing it."""
    return importlib.util.find_spec("numba") is not None


def loaded() -> bool:
    """Whether the kernels are loaded in this process."""
    return _STATE["kernels"] is not None


def _writable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=folder):
            pass
    except OSError:
        return False
    return True


def kernel_sources() -> list[Path]:
    """The files numba compiles: the kernels modules (the composed kernels,
    ``solve_many``'s fused ones, the RTR guide's and the dead-point screen's) and the
    modules of this package they import, and theirs (the composing code, in Python, is
    left out: a change there compiles nothing again)."""
    here = Path(__file__).parent
    seen: list[Path] = []
    todo = ["kernels", "fused_kernels", "guide_kernels", "fused_tables", "screen_kernels"]
    while todo:
        path = here / f"{todo.pop()}.py"
        if path in seen:
            continue
        seen.append(path)
        todo += _RELATIVE.findall(path.read_text(encoding="utf-8"))
    return sorted(seen)


_RELATIVE = re.compile(r"^\s*from \.(\w+) import", re.MULTILINE)


def sources_key() -> str:
    """A short hash of the kernels' source files (:func:`kernel_sources`): the name of
    the cache's folder for this version of the kernels."""
    digest = hashlib.sha256()
    for path in kernel_sources():
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return "kernels-" + digest.hexdigest()[:16]


def cache_folder() -> Path | None:
    """The folder numba caches the compiled kernels in (a folder per version of their
    sources, :func:`sources_key`), or None when none is writable."""
    given = os.environ.get("NUMBA_CACHE_DIR")
    if given:
        base = Path(given)
    else:
        home = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"),
                                                                ".cache")
        base = Path(home) / "kinetostatics" / "numba"
    key = sources_key()
    # (a process this one starts inherits NUMBA_CACHE_DIR as :func:`kernels` set it, the
    # folder of this version already: taken as it is, not nested one folder deeper,
    # where every kernel would be compiled again)
    folder = base if base.name == key else base / key
    return folder if _writable(folder) else None


def kernels() -> ModuleType | None:
    """The kernels module (numba loaded on the first call), or None: numba is not
    installed, or no cache folder is writable (warned once)."""
    if _STATE["kernels"] is not None:
        return _STATE["kernels"]      # type: ignore[return-value]
    if _STATE["off"] is not None or not installed():
        return None
    folder = cache_folder()
    if folder is None:
        _STATE["off"] = "no writable cache folder"
        warnings.warn("the compiled solve path is off: no writable folder for numba's cache "
                      "(set NUMBA_CACHE_DIR); solving on the numpy path", RuntimeWarning,
                      stacklevel=3)
        return None
    os.environ["NUMBA_CACHE_DIR"] = str(folder)
    if "numba" in sys.modules:          # (loaded by someone else: its config read already)
        sys.modules["numba"].config.CACHE_DIR = str(folder)
    from ..stack import SWEEP_TURN
    from . import kernels as module
    from .trig_kernels import turned
    SWEEP_TURN[:] = [turned]            # (solve_many's runs: the kernels' cos and sin)
    _STATE["kernels"] = module
    return module
