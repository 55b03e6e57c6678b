"""The compiled solve path: numba kernels per dyad kind and per driver kind (the
optional ``[fast]`` extra).

The numpy path stays the reference and solves everything; the compiled path solves the
same formulas row by row (:mod:`~kinetostatics.solver.fast.kernels`, each with its seed
equation) for the scenes it covers (:func:`~kinetostatics.solver.fast.geometry.not_covered`:
all but joint friction). Importing this package never imports numba: it is loaded on
the first call that qualifies (:func:`~kinetostatics.solver.fast.choice.wanted`).
"""

from .choice import AUTO_ROWS, PATHS, path_setting, use, wanted
from .solve import solve_compiled, solve_run_compiled
from .stacked import solve_run_stacked

__all__ = ["AUTO_ROWS", "PATHS", "path_setting", "solve_compiled", "solve_run_compiled",
           "solve_run_stacked", "use", "wanted"]
