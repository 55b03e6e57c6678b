"""Command line: ``python -m kinetostatics {demo,solve,structure,bench,...}``."""

from .cli import main
from .common.cli import run_command

raise SystemExit(run_command(main))
