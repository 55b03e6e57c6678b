"""What both command lines share: every user mistake is one line ``error: ...`` on
stderr with exit code 2, every warning one line ``warning: ...``."""

from __future__ import annotations

import argparse
import sys
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
