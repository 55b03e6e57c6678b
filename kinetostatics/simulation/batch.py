"""Batches of simulation runs through an executor.

Batches of runs (a study's settings, many scenes, a balancing machine's runs) go
through :func:`run_batch`: one process per core by default, in this process with
``executor="serial"``, or through any ``concurrent.futures.Executor``.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from concurrent.futures import Executor, ProcessPoolExecutor
from typing import Any

from .errors import SimulationError

__all__ = ["SERIAL", "run_batch"]

SERIAL = "serial"
"""``executor=SERIAL``: run a batch one item after another in this process."""


def run_batch(fn: Callable[[Any], Any], items: Iterable[Any], *,
              executor: Executor | str | None = None) -> list[Any]:
    """``[fn(item) for item in items]``, in order, run through an executor.

    The batches of the cross-check (:func:`kinetostatics.simulation.study`,
    :func:`kinetostatics.simulation.crosscheck_many`) and of the balancing machine
    (:meth:`balance.machine.BalancingMachine.runs`) go through here. Their ``fn`` is a
    top-level function and their items plain data (scene dicts, settings dicts,
    tuples), so any executor that pickles them can run them: a
    ``concurrent.futures.ProcessPoolExecutor``, or a dask.distributed
    ``Client.get_executor()`` that spreads them over a cluster.

    Parameters
    ----------
    fn : callable
        A picklable (top-level) function of one item.
    items : iterable
        The work items.
    executor : Executor, ``"serial"`` or None
        None (default): a ``ProcessPoolExecutor`` with ``min(len(items), cpu_count)``
        workers, created for the batch and shut down after it; a batch of one item,
        or a machine with one core, runs in this process (no pool to pay for).
        ``"serial"`` (:data:`SERIAL`): in this process, one after another. An
        ``Executor``: its ``map`` (it is not shut down: the caller owns it).

    Returns
    -------
    list
        The results in the order of ``items``.

    Raises
    ------
    SimulationError
        ``executor`` is none of these.
    """
    work = list(items)
    if isinstance(executor, str):
        if executor != SERIAL:
            raise SimulationError(f"executor = {executor!r}: give a concurrent.futures "
                                  f"Executor, None (processes) or {SERIAL!r}")
        return [fn(x) for x in work]
    if executor is None:
        workers = min(len(work), os.cpu_count() or 1)
        if workers < 2:
            return [fn(x) for x in work]
        with ProcessPoolExecutor(max_workers=workers) as pool:
            return list(pool.map(fn, work))
    if not isinstance(executor, Executor) and not callable(getattr(executor, "map", None)):
        raise SimulationError(f"executor = {executor!r}: give a concurrent.futures Executor, "
                              f"None (processes) or {SERIAL!r}")
    return list(executor.map(fn, work))
