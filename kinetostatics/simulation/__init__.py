"""pymunk simulations built from the same scenes, and the cross-check of the joint
reactions against :func:`kinetostatics.solve`.

The names load lazily: importing this package (or its ``cli``) does not import pymunk
until a simulation name is used.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from ..common.lazy import lazy_names

_NOT_EXPORTED = ("__init__", "cli")
"""The package itself, and the command line's module (``kinetostatics.cli`` imports it)."""


def _read_home() -> dict[str, str]:
    """``name -> module`` for the names in the ``__all__`` of every module here, read
    from the source text (importing the modules would import pymunk): each module
    declares ``__all__ = [...]`` as a literal list (tests/kinetostatics/simulation checks
    the result against the imported modules' ``__all__``)."""
    home: dict[str, str] = {}
    for path in sorted(Path(__file__).parent.glob("*.py")):
        if path.stem in _NOT_EXPORTED:
            continue
        found = re.search(r"^__all__(?:: list\[str\])? = (\[.*?\])", path.read_text(),
                          re.MULTILINE | re.DOTALL)
        if found is None:
            raise ImportError(f"kinetostatics.simulation.{path.stem} declares no __all__")
        for name in ast.literal_eval(found.group(1)):
            home[name] = path.stem
    return home


_HOME = _read_home()

__all__ = sorted(_HOME)


# each name loaded from its module on first use (PEP 562)
__getattr__, __dir__ = lazy_names(__name__, _HOME, globals(), __all__, subpackages=False)
