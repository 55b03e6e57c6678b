"""Test-wide settings: pictures are drawn off-screen (the Agg backend), before any test
module imports pyplot."""

import matplotlib

matplotlib.use("Agg")
