"""Design by optimisation with forces: a multi-objective search over a scene's dimensions.

A mechanism scene with a ``[design]`` section (docs/design.md) names numbers of the scene
by their TOML path, with bounds, and objectives and constraints from one vocabulary
(``Me_peak``, ``Me_rms``, ``reaction_peak``, ``transmission_min``, ``frame_force_peak``,
``stroke:POINT``, ``path_error:POINT``; ``full_turn``). :func:`design` searches it with
pymoo's NSGA-II (the ``[design]`` extra), every generation one stacked solve
(:func:`~kinetostatics.solve_many`'s); a design that cannot be solved and vouched for
over its whole sweep is infeasible, never penalised nor cut short::

    import kinetostatics as ks
    res = ks.design("four_bar_design", population=100, generations=30)
    res.front            # DataFrame: variables by path, objectives by name, scene file
    res.scenes[0]        # the first design's scene (a dict ks.solve takes)
    res.write("out")     # front.csv, designs/*.toml, summary.json, front.png, compromise.png
"""

from __future__ import annotations

import sys
import types
from typing import TYPE_CHECKING

from .errors import DesignError, MissingExtra

if TYPE_CHECKING:
    from .judging import Evaluation, evaluate
    from .optimiser import hypervolume, normalisation, random_search, search
    from .plots import draw_design, plot_front
    from .result import DesignResult, design
    from .section import DesignSpec, read_design
    from .tomltext import toml_text

# imported when first asked for (PEP 562): the command line's parser imports this
# package's cli, which must not load pandas and matplotlib
_LAZY = {"Evaluation": "judging", "evaluate": "judging", "draw_design": "plots",
         "plot_front": "plots", "DesignResult": "result", "design": "result",
         "hypervolume": "optimiser", "normalisation": "optimiser", "random_search": "optimiser",
         "search": "optimiser", "DesignSpec": "section", "read_design": "section",
         "toml_text": "tomltext"}

__all__ = ["DesignError", "DesignResult", "DesignSpec", "Evaluation", "MissingExtra",
           "design", "draw_design", "evaluate", "hypervolume", "normalisation",
           "plot_front", "random_search", "read_design", "search", "toml_text"]


def __getattr__(name: str):
    """The package's public names, imported on first use."""
    where = _LAZY.get(name)
    if where is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(f"{__name__}.{where}"), name)
    globals()[name] = value
    return value


class _Package(types.ModuleType):
    """This package, callable as :func:`design` (``ks.design(scene)``): importing a
    subpackage binds its name on the parent package, so ``kinetostatics.design`` is this
    package once imported, and calling it runs the search."""

    def __call__(self, *args, **kwargs):
        from .result import design
        return design(*args, **kwargs)


sys.modules[__name__].__class__ = _Package
