"""Solving a scene: structure (driver + dyads), kinematics, loads, friction,
reactions, reduction, and the pipeline (:func:`kinetostatics.solve`).

The package's ``__init__`` imports none of its modules: importing
``kinetostatics.solver.kinematics`` (as :mod:`kinetostatics.results` does) must not run
the pipeline, which itself builds a :class:`~kinetostatics.results.Solution`. The public
entry point is :func:`kinetostatics.solve` (:mod:`~kinetostatics.solver.pipeline`).
"""
