"""A kernel that dies drops its output connection a moment before it can be reaped: the
grader must not blame that drop on the output limit (seen on CI beside two busy loops,
2026-12-01: a notebook that killed its own sandbox was flagged "printed a message larger
than the output limit")."""

from __future__ import annotations

import time
from types import SimpleNamespace

from kinetostatics.teaching.kernels import GradingClient


def _kernel(dies_after: float | None) -> SimpleNamespace:
    """A stand-in whose ``exit_code`` turns from None to 137 ``dies_after`` seconds from
    now (never, with None)."""
    t0 = time.monotonic()

    def exit_code():
        if dies_after is None or time.monotonic() - t0 < dies_after:
            return None
        return 137
    return SimpleNamespace(exit_code=exit_code)


def test_a_kernel_reaped_late_is_not_blamed_on_its_output():
    # dead 0.2 s after the drop: seen dead within the wait
    assert not GradingClient._still_alive(_kernel(0.2), wait=2.0)


def test_a_kernel_that_lives_on_is_blamed():
    t0 = time.monotonic()
    assert GradingClient._still_alive(_kernel(None), wait=0.2)
    assert time.monotonic() - t0 >= 0.2          # it waited the whole time


def test_a_kernel_already_dead_is_not_waited_for():
    assert not GradingClient._still_alive(_kernel(0.0), wait=5.0)
