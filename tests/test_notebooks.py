"""Every sheet in notebooks/ runs top to bottom, headless, without an error.

Each notebook is executed with nbclient in a fresh ``python3`` kernel, from the
notebooks folder (as a student opens it), with ``MPLBACKEND=Agg`` and the checkout on
``PYTHONPATH`` (so it runs from a checkout too, not only after ``pip install -e .``).
A sheet passes when no cell raises, it shows at least one picture and one table, and
its outputs hold no ``nan`` or ``inf`` (a not-applicable cell shows a dash) and nothing
on stderr (no warning). Every interactive cell (a :class:`kinetostatics.notebook.Explorer`
left in the kernel) is exercised after the run through its Python API: each slider,
moved, changes the picture and the key numbers. The topic sheets must have one. The
committed notebooks carry no outputs (they are run here, never stored stale), and the
exercise sheets carry valid nbgrader metadata.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
# s per cell: only stops a hung kernel, never a budget (a test asserts no wall time; the
# slowest cell took 15 s at load 13 on 2 cores)
CELL_TIMEOUT = 600

# the topic sheets: each teaches with one interactive cell (an Explorer)
TOPIC_SHEETS = {"01", "02", "03", "04", "05", "06", "07", "13", "14", "15"}

# a number that is not one, as pandas, numpy and Python print it
_NOT_A_NUMBER = re.compile(r"(?<![A-Za-z0-9_])[-+]?(nan|inf|infinity)(?![A-Za-z0-9_])",
                           re.IGNORECASE)
_DATA_URI = re.compile(r"data:[\w/+.-]+;base64,[A-Za-z0-9+/=\s]*")

# run after the sheet in the same kernel: move every slider of every Explorer
_EXPLORER_CHECK = """
from kinetostatics.notebook import Explorer as _Explorer
_explorers = [v for v in list(globals().values()) if isinstance(v, _Explorer)]
assert _explorers or not {topic}, "this topic sheet has no interactive cell (Explorer)"
for _e in _explorers:
    _e.close()                          # no frontend: the API alone (no widget redraws)
    assert _e.error is None, _e.error
    for _s in _e.sliders:
        _v = _s.value + (_s.max - _s.value) / 2 if _s.value < _s.max else _s.min
        _v = min(max(round(_v / _s.step) * _s.step, _s.min), _s.max)
        _numbers, _png = dict(_e.numbers), _e.png(dpi=30)
        _e.set(**{_s.name: _v})
        assert _e.error is None, f"slider {_s.name} = {_v}: {_e.error}"
        assert _e.png(dpi=30) != _png, f"slider {_s.name} = {_v} does not change the picture"
        assert _e.numbers != _numbers, f"slider {_s.name} = {_v} changes no key number"
        _e.table()                      # every key number is finite (raises otherwise)
"""


def _output_texts(outputs) -> list[str]:
    """Every text a reader sees in the outputs (streams, plain text, HTML), without the
    embedded images."""
    texts = []
    for o in outputs:
        if o.output_type == "stream":
            texts.append(o.text)
        for mime in ("text/plain", "text/html", "text/markdown", "text/latex"):
            if mime in o.get("data", {}):
                texts.append(_DATA_URI.sub("", o["data"][mime]))
    return texts


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


@pytest.mark.slow
@pytest.mark.kernel
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]))
    nb = nbformat.read(path, as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(
        _EXPLORER_CHECK.replace("{topic}", str(path.name[:2] in TOPIC_SHEETS))))
    client = NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}})
    client.execute()            # raises CellExecutionError, naming the cell, on any error
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    errors = [o for o in outputs if o.output_type == "error"]
    assert not errors, errors
    assert any("image/png" in o.get("data", {}) for o in outputs), \
        f"{path.name} shows no picture"
    assert any("<table" in o.get("data", {}).get("text/html", "") for o in outputs), \
        f"{path.name} shows no table"
    stderr = [o.text for o in outputs if o.output_type == "stream" and o.name == "stderr"]
    assert not stderr, f"{path.name} writes to stderr (a warning?): {stderr}"
    bad = sorted({m.group(0) for t in _output_texts(outputs) for m in _NOT_A_NUMBER.finditer(t)})
    assert not bad, f"{path.name} shows {bad} in its outputs: show a dash where no value applies"


EXERCISES = [p for p in NOTEBOOKS if "exercise" in p.stem and "teacher" not in p.stem]


@pytest.mark.parametrize("path", EXERCISES, ids=[p.stem for p in EXERCISES])
def test_exercise_sheets_are_sealed_and_nbgrader_ready(path):
    """A student's sheet: nbgrader metadata on every cell, unique grade ids, one answer
    cell (a solution cell tagged ``answers``, every answer None), no solution and no
    check against a key (tests/kinetostatics/teaching/test_sheets.py grades it)."""
    nb = nbformat.read(path, as_version=4)
    ids, answers = [], 0
    for cell in nb.cells:
        meta = cell.metadata.get("nbgrader")
        assert meta is not None, f"{path.name}: a cell without nbgrader metadata"
        assert meta["schema_version"] == 3 and not meta["grade"]
        ids.append(meta["grade_id"])
        assert "BEGIN SOLUTION" not in cell.source and "expected" not in cell.source
        if meta["grade_id"] == "answers":
            answers += 1
            assert meta["solution"] and "answers" in cell.metadata.get("tags", [])
            assert "None" in cell.source
    assert len(ids) == len(set(ids))
    assert answers == 1
