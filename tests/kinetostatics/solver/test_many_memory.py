"""solve_many's memory check (``model/memory.py``'s ``check_memory``): the memory
available read from the system at most every ``FRESH`` seconds for runs well under the
last budget read, and every time for a larger run (a refusal always told on a fresh
reading), never kept where ``WORKBENCH_MEMORY`` sets the budget."""

from __future__ import annotations

import time

import pytest

from kinetostatics.model import memory
from kinetostatics.model.memory import ENV, MemoryBudgetError, check_memory


@pytest.fixture
def reads(monkeypatch: pytest.MonkeyPatch) -> list:
    """The system's memory available as the list's last value (bytes), each reading
    counted in the list's first element; no reading kept at the start."""
    monkeypatch.delenv(ENV, raising=False)
    monkeypatch.setattr(memory, "_READ", [])
    got = [0, 10e9]

    def available() -> float:
        got[0] += 1
        return got[-1]
    monkeypatch.setattr(memory, "available", available)
    return got


def test_a_run_well_under_the_budget_reads_it_once(reads) -> None:
    budget = memory.SHARE * 10e9
    for _ in range(5):
        check_memory(budget / memory.MARGIN, "a run", "fix")
    assert reads[0] == 1
    # (a larger run: read again, and refused on that reading)
    reads.append(1e9)
    with pytest.raises(MemoryBudgetError, match="budget of 600 MB"):
        check_memory(budget / memory.MARGIN * 1.01, "a run", "fix")
    assert reads[0] == 2
    # (the last reading, 600 MB, keeps runs of a quarter of it alone)
    check_memory(memory.SHARE * 1e9 / memory.MARGIN, "a run", "fix")
    with pytest.raises(MemoryBudgetError):
        check_memory(memory.SHARE * 1e9 * 1.01, "a run", "fix")
    assert reads[0] == 3


def test_a_reading_older_than_fresh_is_read_again(reads) -> None:
    check_memory(1e6, "a run", "fix")
    assert reads[0] == 1
    memory._READ[0] = time.monotonic() - memory.FRESH * 1.01
    reads.append(1e6)           # (the memory gone meanwhile)
    with pytest.raises(MemoryBudgetError):
        check_memory(1e6, "a run", "fix")
    assert reads[0] == 2


def test_a_budget_set_by_the_environment_is_never_kept(reads, monkeypatch) -> None:
    check_memory(1e6, "a run", "fix")           # (a reading kept)
    monkeypatch.setenv(ENV, "100M")
    with pytest.raises(MemoryBudgetError, match="set by WORKBENCH_MEMORY=100M"):
        check_memory(2e8, "a run", "fix")
    check_memory(1e6, "a run", "fix")
    assert reads[0] == 1
    assert memory._READ[1] == memory.SHARE * 10e9       # (the system's, not the set one)
