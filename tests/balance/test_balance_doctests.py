"""The docstring examples of the balance package run and hold."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = ["balance.rotor.design", "balance.rotor.static_device", "balance.resonance.methods",
           "balance.field.influence",
           "balance.field.iso", "balance.api"]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name: str) -> None:
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.failed == 0


def test_public_api_is_complete() -> None:
    import balance

    for name in balance.__all__:
        assert hasattr(balance, name), name
    # the notebook-facing functions named in the design
    for name in ("solve", "balance_rotor", "static_device", "parallelogram", "four_run",
                 "trial_runs", "influence_two_plane", "influence_single_plane",
                 "iso_permissible_unbalance"):
        assert callable(getattr(balance, name))


def test_import_does_not_load_matplotlib() -> None:
    import subprocess
    import sys

    code = "import sys, balance; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "False"
