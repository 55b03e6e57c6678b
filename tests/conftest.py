"""Test-wide settings.

- Pictures are drawn off-screen (the Agg backend), before any test module imports
  pyplot.
- Hypothesis runs derandomized by default (profile ``repeatable``): the same examples on
  every machine, so CI's verdict does not depend on luck. To search with fresh random
  examples on every run, use ``HYPOTHESIS_PROFILE=explore python -m pytest``.
- The solve path: ``KINETOSTATICS_PATH=fast python -m pytest`` runs the suite on the
  compiled path (numba), ``numpy`` (or unset) on the numpy path. A test of the numpy
  path's own workings takes the fixture ``numpy_path``.
"""

import os

import matplotlib
import pytest
from hypothesis import settings

matplotlib.use("Agg")

settings.register_profile("repeatable", derandomize=True, print_blob=True)
settings.register_profile("explore", derandomize=False, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))


@pytest.fixture
def numpy_path():
    """The numpy solve path for one test, whatever ``KINETOSTATICS_PATH`` says (a test of
    the numpy path's own workings: what it lets go, its blocks, its traps)."""
    from kinetostatics.solver.fast import use
    use("numpy")
    yield
    use(None)
