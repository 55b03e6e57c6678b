"""An xdist worker's end without the interpreter's teardown.

When its tests are done a worker still tears its interpreter down: every module's
objects freed one by one (the figures the session drew and kept, the solutions, numba's
dispatchers, pandas' and matplotlib's caches), and the controller waits for it before the
run ends. A worker that had run the classroom's and the collisions' tests took 6.2 s
from its exit handlers to its end, 0.01 s so (from its session's end to the run's end:
9.4 s, 4.4 s so); a serial run of the collisions' and the notation's tests spent 2.7 s of
CPU in that teardown (measured 2026-11-30, two runs, beside other sessions' load): CPU
and seconds at the run's tail. Here the worker, once every exit handler
has run (Python's own order: its threads joined first, then the handlers, as at any end),
flushes its output and ends at once (``os._exit``), skipping only that teardown, as a
forked child does.
"""

from __future__ import annotations

import atexit
import os
import sys


def _end_now() -> None:
    """Run the other exit handlers now, flush the output, end the process with status 0
    (registered last, this runs first; see :func:`end_without_teardown`)."""
    atexit.unregister(_end_now)
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr, sys.__stdout__, sys.__stderr__):
        try:
            stream.flush()
        except (AttributeError, OSError, ValueError):
            pass
    os._exit(0)


def end_without_teardown() -> None:
    """At the interpreter's exit, after every exit handler registered so far, end the
    process without its teardown (:func:`_end_now`). Call it last: a handler registered
    after it runs first all the same."""
    atexit.register(_end_now)
