"""Solving a scene: structure (driver + dyads), kinematics, loads, friction,
reactions, reduction, and the one road of every solve (:mod:`~kinetostatics.solver.pipeline`:
a :class:`~kinetostatics.solver.pipeline.Sweep`; :mod:`~kinetostatics.solver.many` for
many scenes stacked).

The solver gives arrays (:mod:`~kinetostatics.solver.solved`) and never imports the
results: :mod:`kinetostatics.results` stands above it and wraps them in a
:class:`~kinetostatics.results.Solution` (:func:`kinetostatics.solve`,
:func:`kinetostatics.solve_many`). The package's ``__init__`` imports none of its
modules.
"""
