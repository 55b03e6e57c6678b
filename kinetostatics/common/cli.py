"""What both command lines share: every user mistake is one line ``error: ...`` on
stderr with exit code 2, every warning one line ``warning: ...``."""

from __future__ import annotations

import argparse
import contextlib
import os
import signal
import sys
import threading
from collections.abc import Iterator
from typing import NoReturn


def one_line(message: object) -> str:
    """``message`` as text on one line (its runs of white space, new lines included, one
    space each)."""
    return " ".join(str(message).split())


class OneLineParser(argparse.ArgumentParser):
    """An argument parser whose every mistake is one line ``error: ...`` on stderr and
    exit code 2, without argparse's usage lines (the parser class of both CLIs and of
    all their subcommands)."""

    def error(self, message: str) -> NoReturn:
        print(f"error: {one_line(message)} (see {self.prog} --help)", file=sys.stderr)
        raise SystemExit(2)


def dpi_argument(text: str) -> float:
    """A --dpi value: a number from 50 to 600 (the argparse type of both CLIs)."""
    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not 50.0 <= v <= 600.0:
        raise argparse.ArgumentTypeError(f"{text!r}: give a number from 50 to 600")
    return v


def print_warning(message, category=None, filename=None, lineno=None, file=None,
                  line=None) -> None:
    """A Python warning (a unit slip, a negative concentrated mass, ...) as one line
    ``warning: ...`` on stderr; the signature of :func:`warnings.showwarning`."""
    print(f"warning: {one_line(message)}", file=sys.stderr)


MEMORY_HELP = ("memory budget of the run, e.g. 2G or 1500M (default: 60%% of the memory "
               "available, or WORKBENCH_MEMORY); a run estimated above it is refused")


# a run that ran out of memory although its estimate was within the budget (another
# process took memory meanwhile, or an estimate fell short): one line, never a traceback
MEMORY_LINE = ("the run ran out of memory; give fewer positions (count), or a smaller "
               "budget (--memory, WORKBENCH_MEMORY) so that it is refused before it starts "
               "(docs/limits.md)")


def memory_argument(text: str) -> str:
    """A --memory value: a size (``2G``, ``1500M``); set as the run's budget."""
    from ..model.errors import WorkbenchError
    from ..model.memory import ENV, parse_size
    try:
        parse_size(text, "--memory")
    except WorkbenchError as exc:
        raise argparse.ArgumentTypeError(str(exc).removeprefix("--memory = ")) from None
    os.environ[ENV] = text
    return text


def add_memory_option(parser: argparse.ArgumentParser) -> None:
    """``--memory SIZE``, the run's memory budget (every command that solves)."""
    parser.add_argument("--memory", type=memory_argument, metavar="SIZE", help=MEMORY_HELP)


def add_dpi_option(parser: argparse.ArgumentParser, help: str) -> None:
    """``--dpi``, the pictures' dots per inch (50 to 600, default 150)."""
    parser.add_argument("--dpi", type=dpi_argument, default=150, help=help)


class Terminated(BaseException):
    """The run was asked to stop (SIGTERM: ``kill``, a time limit): raised in the main
    thread so that every writer cleans up as after an interrupt (its staging files
    removed, the earlier results kept: :mod:`kinetostatics.model.outputs`)."""


TERMINATED_LINE = ("stopped by SIGTERM; the files being written were removed and earlier "
                   "results kept as they were")


@contextlib.contextmanager
def stopped_cleanly() -> Iterator[None]:
    """SIGTERM raised as :class:`Terminated` while the body runs (in the main thread;
    elsewhere nothing changes). The command lines print :data:`TERMINATED_LINE` and exit
    with 143 (128 + SIGTERM), the code a shell gives a run stopped by the signal."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def stop(signum, frame):
        raise Terminated(signum)
    try:
        before = signal.signal(signal.SIGTERM, stop)
    except (ValueError, OSError):           # (no signals here)
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, before)


def failure_code(exc: BaseException) -> int:
    """Print the one ``error: ...`` line of a run stopped by ``exc`` (a stop by SIGTERM,
    memory run out, a user's mistake or an unwritable file) and return its exit code:
    143 after SIGTERM, 2 otherwise."""
    if isinstance(exc, Terminated):
        print(f"error: {TERMINATED_LINE}", file=sys.stderr)
        return 143
    print(f"error: {MEMORY_LINE if isinstance(exc, MemoryError) else one_line(exc)}",
          file=sys.stderr)
    return 2


def run_command(main, argv: list[str] | None = None) -> int:
    """``main(argv)``'s exit code, as a program's entry point runs it: when the reader
    of standard output goes away (``... | head``), the rest of the output is dropped
    without a word and the exit code is 0 (what was read was whole lines), not an
    ``error: [Errno 32] Broken pipe`` line or a traceback at exit."""
    try:
        code = main(argv)
        sys.stdout.flush()
    except BrokenPipeError:
        code = 0
    else:
        return code
    # the interpreter flushes standard output again at exit: send it nowhere
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    return code
