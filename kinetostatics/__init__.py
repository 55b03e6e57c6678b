"""Kinetostatics of planar mechanisms: a driver plus dyads, over the whole cycle.

The public API::

    import kinetostatics as ks
    scene = ks.load_scene("four_bar.toml")     # or TOML text, or a dict
    sol = ks.solve(scene)                      # kinematics, reactions, Me
    sol.driver, sol.reactions, sol.kinematics, sol.bodies, sol.summary()

Bundled examples: ``ks.example("four_bar")`` (also ``slider_crank``, ``slotted_lever``,
``scotch_yoke``, ``sliding_driver``, ``shaper``).

More of the course, one subpackage per topic: :mod:`~kinetostatics.concentration` (mass
concentration s. 2.2), :mod:`~kinetostatics.transmission` (gears s. 2.3.3, efficiency
s. 4.3), :mod:`~kinetostatics.solver`
(structure, kinematics, loads, friction s. 2.4, reactions, reduction s. 2.5, dead points),
:mod:`~kinetostatics.motion` and :func:`simulate_motion` (motion under forces, ch. 4),
:mod:`~kinetostatics.cams` (ch. 1), :mod:`~kinetostatics.design` and :func:`design` (a
search over a scene's dimensions with forces, its ``[design]`` section; pymoo),
:mod:`~kinetostatics.teaching` (exercises for a class and grading),
:mod:`~kinetostatics.plot` (pictures), :mod:`~kinetostatics.notebook` (the
sheets' interactive cells). The pymunk cross-check is :mod:`kinetostatics.simulation`
(``crosscheck``, ``study``; its names load pymunk lazily, so ``import kinetostatics`` does
not). The scene model (reading, checking, exceptions, bundled scenes) is
:mod:`~kinetostatics.model`.
"""

from __future__ import annotations

from .common.lazy import group, lazy_names
from .model.errors import (
    AssemblyError,
    SceneError,
    SelfLockingError,
    StructureError,
    UnitWarning,
    WorkbenchError,
)

# Imported when first asked for (PEP 562), so that ``import kinetostatics`` costs little
# more than ``import numpy``: pandas, matplotlib, scipy and pymunk load with the first
# table, picture, motion or cross-check that needs them.
_LAZY = {
    **group(("cam_examples", "example", "examples", "scene_path"), "model.examples"),
    **group(("Scene", "load_scene"), "model.scene"),
    **group(("simulate_motion",), "motion.scene"),
    **group(("Solution",), "results"),
    **group(("Kinematics", "solve_kinematics"), "solver.kinematics"),
    **group(("solve", "solve_many"), "results.solving"),
    **group(("Dyad", "Structure", "analyse"), "solver.structure"),
    **group(("design",), "design.result"),
}

__all__ = [
    "AssemblyError", "Dyad", "Kinematics", "Scene", "SceneError", "SelfLockingError",
    "Solution", "Structure", "StructureError", "UnitWarning", "WorkbenchError", "analyse",
    "cam_examples", "design", "example", "examples", "load_scene", "scene_path",
    "simulate_motion", "solve", "solve_kinematics", "solve_many",
]


# modules moved into subpackages: their old names import the new module with a
# DeprecationWarning, for one release
_MOVED = {"output": "results.output", "csvtext": "results.csvtext",
          "longtable": "results.longtable", "bench_speed": "bench.speed",
          "bench_tables": "bench.tables"}


class _MovedModules:
    """Import finder of the moved modules' old names (``kinetostatics.output``, ...)."""

    @staticmethod
    def find_spec(fullname: str, path=None, target=None):
        package, _, name = fullname.rpartition(".")
        if package != __name__ or name not in _MOVED:
            return None
        from importlib.util import spec_from_loader
        return spec_from_loader(fullname, _MovedModules)

    @staticmethod
    def create_module(spec):
        import importlib
        import warnings

        new = f"{__name__}.{_MOVED[spec.name.rpartition('.')[2]]}"
        warnings.warn(f"{spec.name} is now {new}; the old name goes in the next release",
                      DeprecationWarning, stacklevel=2)
        module = importlib.import_module(new)
        spec.loader_state = module.__spec__      # put back in exec_module
        return module

    @staticmethod
    def exec_module(module) -> None:
        module.__spec__ = module.__spec__.loader_state


if not any(f is _MovedModules for f in __import__("sys").meta_path):
    __import__("sys").meta_path.insert(0, _MovedModules)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals(), __all__)
