"""Fixtures of the solver's tests shared by several modules."""

from __future__ import annotations

import pytest

from kinetostatics.solver import many
from kinetostatics.solver.fast import loader


@pytest.fixture
def alone_calls(monkeypatch):
    """The scenes solve_many solves alone (not stacked)."""
    calls = []
    solo = many._alone

    def spy(sc):
        calls.append(sc.title)
        return solo(sc)
    monkeypatch.setattr(many, "_alone", spy)
    return calls


@pytest.fixture
def kernels():
    """The compiled path's kernels, loaded (skips where they cannot load: no writable
    cache folder; the modules using it skip without numba)."""
    k = loader.kernels()
    if k is None:
        pytest.skip("no writable cache folder")
    return k
