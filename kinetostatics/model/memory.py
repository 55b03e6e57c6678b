"""The memory budget of a run: its peak known before it is spent.

Every run that allocates arrays over its rows (a solve, a batch of solves, a cam, a
motion, a mechanism's balancing) estimates its peak from its rows and columns before it
allocates (:func:`check_memory`), and refuses in one line when the estimate is over the
budget: the estimate, the budget and the memory available, and what to change.

The budget is ``SHARE`` of the memory available to this process: the system's available
memory (``MemAvailable``), or what an address-space limit (``ulimit -v``) leaves, the
smaller. It can be set with the environment variable ``WORKBENCH_MEMORY`` (``"2G"``,
``"1500M"``, ``"3e9"`` bytes) or, for one command, with ``--memory`` (docs/limits.md).
"""

from __future__ import annotations

import os
import re
import time

from .errors import WorkbenchError

SHARE = 0.6                     # of the memory available, when no budget is set
ENV = "WORKBENCH_MEMORY"        # the budget, as a size ("2G", "1500M", bytes)
FLOAT = 8                       # bytes of a float64
_UNITS = {"": 1, "B": 1, "K": 1e3, "KB": 1e3, "M": 1e6, "MB": 1e6, "G": 1e9, "GB": 1e9,
          "T": 1e12, "TB": 1e12, "KIB": 2**10, "MIB": 2**20, "GIB": 2**30, "TIB": 2**40}


class MemoryBudgetError(WorkbenchError):
    """A run whose estimated peak memory is over the budget (refused before it starts)."""


def parse_size(text: str, where: str = ENV) -> float:
    """Bytes of a size written ``"2G"``, ``"1500M"``, ``"512MiB"`` or ``"3e9"``."""
    m = re.fullmatch(r"\s*([0-9.]+(?:[eE][+-]?\d+)?)\s*([A-Za-z]*)\s*", str(text))
    unit = m.group(2).upper() if m else None
    if m is None or unit not in _UNITS:
        raise WorkbenchError(f"{where} = {text!r}: give a size such as 2G, 1500M or 3e9 "
                             "(bytes)")
    try:
        size = float(m.group(1)) * _UNITS[unit]
    except ValueError:
        size = -1.0
    if not 1e6 <= size <= 1e15:
        raise WorkbenchError(f"{where} = {text!r}: give a size from 1M to 1000T")
    return size


def available() -> float:
    """Bytes of memory this process can still take: the system's available memory, or
    what the address-space limit leaves (the smaller); a large number when neither is
    known."""
    free = _meminfo("MemAvailable")
    if free is None:
        try:
            free = os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
        except (AttributeError, ValueError, OSError):
            free = 1e12
    try:
        import resource
        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
        if soft != resource.RLIM_INFINITY:
            free = min(free, max(soft - _address_space(), 0))
    except (ImportError, OSError, ValueError):
        pass
    return float(free)


def budget() -> tuple[float, str]:
    """The memory budget in bytes and where it comes from (for the messages)."""
    text = os.environ.get(ENV)
    if text:
        return parse_size(text), f"set by {ENV}={text}"
    free = available()
    return SHARE * free, f"{SHARE:.0%} of the {free / 1e9:.2g} GB available"


# a budget read from the system (no ENV) is trusted for a run well under it for a short
# while: the memory available is read (``/proc/meminfo``, and ``/proc/self/statm`` under
# an address-space limit) at most every FRESH seconds for runs of at most 1 / MARGIN of
# the last budget read, and every time for a larger one (a refusal is always told on a
# fresh reading). Measured 2026-11-30: 0.17 ms a call of solve_many (1000 four-bars x
# 361, 288 MB against a budget of 12 GB) reading it every call.
FRESH = 0.5         # seconds a reading holds
MARGIN = 4.0        # a run of at most a quarter of the last budget read: not read again
_READ: list[float] = []         # (when the budget was last read from the system, and it)


def _well_under(need: float) -> bool:
    """Whether ``need`` is at most 1 / MARGIN of the budget read from the system less than
    FRESH seconds ago (none set by ENV)."""
    read = _READ
    if not read or os.environ.get(ENV):
        return False
    when, limit = read
    return need * MARGIN <= limit and time.monotonic() - when < FRESH


def check_memory(need: float, what: str, fix: str) -> None:
    """Refuse a run whose estimated peak ``need`` (bytes) is over the budget.

    Parameters
    ----------
    need : float
        The estimate, in bytes.
    what : str
        The run, e.g. ``"solve of four_bar at 10,000,000 positions"``.
    fix : str
        What to change, e.g. ``"use fewer positions (driver.count)"``.

    Raises
    ------
    MemoryBudgetError
        One line: the estimate, the budget and where it comes from, and the fixes.
    """
    if _well_under(need):
        return
    limit, source = budget()
    if not os.environ.get(ENV):
        _READ[:] = [time.monotonic(), limit]
    if need > limit:
        raise MemoryBudgetError(
            f"{what} needs about {_size(need)} of memory, more than the budget of "
            f"{_size(limit)} ({source}); {fix}, or set a larger budget with {ENV} "
            "(docs/limits.md)")


def _size(b: float) -> str:
    return f"{b / 1e9:.2f} GB" if b >= 1e9 else f"{b / 1e6:.0f} MB"


def _meminfo(key: str) -> float | None:
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith(key + ":"):
                    return float(line.split()[1]) * 1024
    except OSError:
        return None
    return None


def _address_space() -> float:
    """Bytes of address space this process holds now (its virtual size)."""
    try:
        with open("/proc/self/statm", encoding="ascii") as fh:
            return float(fh.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0.0
