"""Every sheet in notebooks/ runs top to bottom, headless, without an error.

Each notebook is executed with nbclient in a fresh ``python3`` kernel, from the
notebooks folder (as a student opens it), with ``MPLBACKEND=Agg`` and the checkout on
``PYTHONPATH`` (so it runs from a checkout too, not only after ``pip install -e .``).
A sheet passes when no cell raises, and it shows at least one picture and one table.
The committed notebooks carry no outputs (they are run here, never stored stale), and
the exercise sheets carry valid nbgrader metadata.
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
CELL_TIMEOUT = 120          # s per cell
TOTAL_BUDGET = 300          # s for all the sheets together (the limit)
_times: dict[str, float] = {}


def test_there_are_sheets():
    assert len(NOTEBOOKS) >= 7, [p.name for p in NOTEBOOKS]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_committed_without_outputs(path):
    nb = nbformat.read(path, as_version=4)
    nbformat.validate(nb)
    for k, cell in enumerate(nb.cells):
        if cell.cell_type == "code":
            assert not cell.outputs, f"{path.name}: cell {k} has stored outputs; strip them"
            assert cell.execution_count is None, f"{path.name}: cell {k} has an execution count"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]))
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}})
    t = time.perf_counter()
    client.execute()            # raises CellExecutionError, naming the cell, on any error
    _times[path.name] = time.perf_counter() - t
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    errors = [o for o in outputs if o.output_type == "error"]
    assert not errors, errors
    assert any("image/png" in o.get("data", {}) for o in outputs), \
        f"{path.name} shows no picture"
    assert any("<table" in o.get("data", {}).get("text/html", "") for o in outputs), \
        f"{path.name} shows no table"


def test_total_time():
    """All the sheets together within the budget (measured by the runs above)."""
    if len(_times) < len(NOTEBOOKS):
        pytest.skip("not every notebook ran in this session")
    total = sum(_times.values())
    assert total < TOTAL_BUDGET, f"the sheets took {total:.0f} s: {_times}"


EXERCISES = [p for p in NOTEBOOKS if "exercise" in p.stem and "teacher" not in p.stem]


@pytest.mark.parametrize("path", EXERCISES, ids=[p.stem for p in EXERCISES])
def test_exercise_sheets_are_nbgrader_ready(path):
    """Solution cells hold the BEGIN/END SOLUTION markers, autograded cells have points,
    grade ids are unique, the answer cell is tagged for kinetostatics.exercises."""
    nb = nbformat.read(path, as_version=4)
    ids, graded, answers = [], 0, 0
    for cell in nb.cells:
        meta = cell.metadata.get("nbgrader")
        assert meta is not None, f"{path.name}: a cell without nbgrader metadata"
        assert meta["schema_version"] == 3
        ids.append(meta["grade_id"])
        if meta["grade"]:
            assert meta["locked"] and meta["points"] > 0 and "assert" in cell.source
            graded += 1
        if meta["grade_id"] == "answers":
            answers += 1
            assert meta["solution"] and "answers" in cell.metadata.get("tags", [])
            assert "### BEGIN SOLUTION" in cell.source and "### END SOLUTION" in cell.source
    assert len(ids) == len(set(ids))
    assert answers == 1 and graded >= 3
