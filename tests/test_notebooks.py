"""Every sheet in notebooks/ runs top to bottom, headless, without an error.

Each notebook is executed with nbclient in a fresh ``python3`` kernel, from the
notebooks folder (as a student opens it), with ``MPLBACKEND=Agg`` and the checkout on
``PYTHONPATH`` (so it runs from a checkout too, not only after ``pip install -e .``).
A sheet passes when no cell raises, it shows at least one picture and one table, and
its outputs hold no ``nan`` or ``inf`` (a not-applicable cell shows a dash) and nothing
on stderr (no warning). Every interactive cell (a :class:`kinetostatics.notebook.Explorer`
left in the kernel) is exercised after the run through its Python API: each slider,
moved, changes the picture and the key numbers. The topic sheets must have one (the
checks: tests/_shared_sheets.py). A sheet with a widget is run once, in JupyterLab by
tests/test_browser.py, which makes the same checks on that run; here only when the
browser test is not in the session. The committed notebooks carry no outputs (they are
run here, never stored stale), and the exercise sheets carry valid nbgrader metadata.

Where the heaviest headless sheets' CPU goes (their kernels, per cell; 2026-11-30, load
~12): 08_simulation_crosscheck 15.0 s (the shaper's cross-check at its default settings,
whose iteration search runs the simulation several times, 4.3 s; the two comparison plots
1.7 and 1.4 s; the convergence study 1.6 s), 12_teacher_exercises 11.3 s (generating the
class of 12 students 7.3 s: each handout's picture drawn, decluttered and saved as PNG,
kinetostatics/teaching/handouts.py); every kernel ~1.8 s to start and import matplotlib,
pandas and kinetostatics before its sheet's first picture. Neither sheet offers a lighter
setting for a test, and the test runs each sheet as a student does. The kernels are
forked from one process that imported those once (tests/_kernel_fork.py: the module's
``forker``): sheets 09-12 headless 18.7 -> 9.0 s of CPU, 08 13.2 -> 13.6 s with the
forker's own start (one run each, load 5-10, 2026-12-01).
"""

from __future__ import annotations

import os
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

from tests import _shared_sheets as sheets
from tests._kernel_fork import Forker

NOTEBOOKS = sheets.NOTEBOOKS


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


def _kernel_env() -> dict[str, str]:
    """What a sheet's kernel has in its environment, beyond this process's."""
    return {"MPLBACKEND": "Agg", "PYTHONPATH": os.pathsep.join(
        [str(sheets.ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])}


@pytest.fixture(scope="module")
def forker(tmp_path_factory):
    """The kernels' forker (tests/_kernel_fork.py) for this module's sheets: each kernel
    forked from one process that imported the sheets' libraries once."""
    f = Forker(tmp_path_factory.mktemp("forker"), env={**os.environ, **_kernel_env()})
    yield f
    f.close()


def run_sheet(path: Path, forker: Forker | None = None) -> tuple[list, list[dict]]:
    """Run a sheet headless (every Explorer's sliders moved after it), every figure it
    shows measured: (the outputs of its cells, one audit per figure). ``forker``: its
    kernel forked from there (tests/_kernel_fork.py), else started as Jupyter does."""
    nb = nbformat.read(path, as_version=4)
    nb.cells.insert(0, nbformat.v4.new_code_cell(sheets.AUDIT_HOOK))
    nb.cells += [nbformat.v4.new_code_cell(code) for code in sheets.checks_after(path.name)]
    nb.cells.append(nbformat.v4.new_code_cell(sheets.AUDIT_REPORT))
    env = _kernel_env()
    if forker is not None:
        env["JUPYTER_PATH"] = forker.first_on(os.environ.get("JUPYTER_PATH"))
    old = {k: os.environ.get(k) for k in env}
    os.environ.update(env)
    try:
        # the kernel stopped at once when the run is over (its outputs are in): a graceful
        # exit tore its interpreter down, 0.5 s of CPU for a kernel that drew a picture,
        # 0.03 s so (measured 2026-11-30)
        client = NotebookClient(nb, timeout=sheets.CELL_TIMEOUT, kernel_name="python3",
                                shutdown_kernel="immediate",
                                resources={"metadata": {"path": str(path.parent)}})
        client.execute()        # raises CellExecutionError, naming the cell, on any error
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    report = nb.cells.pop()
    audits = sheets.audits_of(next(o.text for o in report.outputs
                                   if o.output_type == "stream"))
    outputs = [o for c in nb.cells[1:] if c.cell_type == "code" for o in c.outputs]
    return outputs, audits


def _in_the_browser(session: pytest.Session, name: str) -> bool:
    """True when tests/test_browser.py runs the sheet in this session (with every check
    of :func:`test_notebook_runs`): Chromium and Playwright are there and its test of
    the sheet is selected."""
    return sheets.browser_ready() and any(
        item.path.name == "test_browser.py" and
        getattr(item, "callspec", None) is not None and
        item.callspec.params.get("sheet") == name for item in session.items)


@pytest.mark.slow
@pytest.mark.kernel
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path, request):
    """The sheet runs; every picture it shows (the Explorer's after each slider move too)
    meets the picture standard: 150 dpi, text >= 10 pt, no collision, at most one label
    not placed, the notation of docs/notation.md. A sheet with a widget is run (once) in
    the browser test, which makes these checks on its run, when that test is in the
    session; here otherwise."""
    if _in_the_browser(request.session, path.name):
        pytest.skip("run in JupyterLab by tests/test_browser.py, with these checks")
    outputs, audits = run_sheet(path, request.getfixturevalue("forker"))
    sheets.check_run(path.name, outputs, audits)


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
