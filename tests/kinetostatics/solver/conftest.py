"""Fixtures of the solver's tests shared by several modules."""

from __future__ import annotations

import pytest

from kinetostatics.solver import many


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
