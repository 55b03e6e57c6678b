"""Text for people, shared by both command lines and the messages: the lowest floor of
the package (it imports nothing of the project).

:mod:`~kinetostatics.text.cli` holds what ``python -m kinetostatics`` and ``python -m
balance`` share: the argument parser whose every mistake is one line, the ``--dpi``
option's type, one-line messages and warnings.
"""

from __future__ import annotations

from .cli import OneLineParser, dpi_argument, one_line, print_warning

__all__ = ["OneLineParser", "dpi_argument", "one_line", "print_warning"]
