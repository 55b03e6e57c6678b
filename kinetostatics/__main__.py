"""Command line: ``python -m kinetostatics {demo,solve,structure,bench,...}``."""

from .cli import main

raise SystemExit(main())
