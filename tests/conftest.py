"""Test-wide settings.

- Pictures are drawn off-screen (the Agg backend), before any test module imports
  pyplot.
- Hypothesis runs derandomized by default (profile ``repeatable``): the same examples on
  every machine, so CI's verdict does not depend on luck. To search with fresh random
  examples on every run, use ``HYPOTHESIS_PROFILE=explore python -m pytest``.
"""

import os

import matplotlib
from hypothesis import settings

matplotlib.use("Agg")

settings.register_profile("repeatable", derandomize=True, print_blob=True)
settings.register_profile("explore", derandomize=False, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "repeatable"))
