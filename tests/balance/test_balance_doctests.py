"""The balance package's public names (its docstring examples: tests/test_doctests.py)."""

from __future__ import annotations


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
