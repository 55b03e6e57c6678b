"""Module paths of earlier versions, kept working after the move into subpackages.

``import kinetostatics.scene`` (and ``from kinetostatics.crosscheck import study``) load the
module at its new home; the table below is the one place that says where each went.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys

MOVED = {
    "errors": "model.errors", "scene": "model.scene", "tomlio": "model.tomlio",
    "structure": "solver.structure", "kinematics": "solver.kinematics",
    "loads": "solver.loads", "friction": "solver.friction", "reactions": "solver.reactions",
    "reduction": "solver.reduction", "_arith": "solver._arith",
    "concentration": "topics.concentration", "gears": "topics.gears",
    "efficiency": "topics.efficiency", "motion_scene": "motion.scene",
    "crosscheck": "simulation", "sim_cli": "simulation.cli",
    "exercises": "teaching",
}


class _Alias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds ``kinetostatics.<old>`` and hands back the module at its new path."""

    def find_spec(self, fullname, path=None, target=None):
        pkg, _, leaf = fullname.partition(".")
        if pkg != __package__ or leaf not in MOVED:
            return None
        return importlib.machinery.ModuleSpec(fullname, self)

    def create_module(self, spec):
        return importlib.import_module(f"{__package__}.{MOVED[spec.name.split('.', 1)[1]]}")

    def exec_module(self, module):
        return None


def install() -> None:
    """Register the alias finder once."""
    if not any(isinstance(f, _Alias) for f in sys.meta_path):
        sys.meta_path.append(_Alias())
