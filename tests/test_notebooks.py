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

import json
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
TOPIC_SHEETS = {"01", "02", "03", "04", "05", "06", "07", "13", "14", "15", "16"}

# a number that is not one, as pandas, numpy and Python print it
_NOT_A_NUMBER = re.compile(r"(?<![A-Za-z0-9_])[-+]?(nan|inf|infinity)(?![A-Za-z0-9_])",
                           re.IGNORECASE)
_DATA_URI = re.compile(r"data:[\w/+.-]+;base64,[A-Za-z0-9+/=\s]*")

# run first in the kernel: every figure a cell shows is measured against the picture
# standard (kinetostatics.plot.audit) before the inline backend shows and closes it
# (post_execute callbacks run in the order registered: this one before the backend's)
AUDIT_HOOK = """
def _install_audit():
    import matplotlib.pyplot as plt
    from kinetostatics.plot.audit import audit
    ip = get_ipython()
    found = []

    def measure(where, fig):
        a = audit(fig)
        found.append({"where": where, "dpi": a.dpi, "font": a.smallest_font,
                      "collisions": a.collisions, "not_placed": a.not_placed,
                      "notation": a.notation, "problems": a.problems})

    def before_show():
        code = ip.user_ns["_ih"][-1].strip().splitlines() or [""]
        for k in plt.get_fignums():
            measure(f"cell {code[0][:60]!r} figure {k}", plt.figure(k))

    ip.events.register("post_execute", before_show)
    return found, measure


_AUDITS, _AUDIT = _install_audit()
del _install_audit
"""
AUDIT_REPORT = 'import json as _json; print("AUDITS " + _json.dumps(_AUDITS))'

# run after a sheet, in its kernel: what its text promises about its own output
SHEET_CHECKS = {
    # 02: at every crank length of the slider no singular row is shown as a number:
    # the extremes leave the rows out and say how many, the readout at a singular row
    # says so (the change point at crank + frame = coupler + rocker: 0.15 m)
    "02": """
import numpy as _np
_crank = explorer.slider("crank")
_seen_singular = False
for _c in _np.round(_np.arange(_crank.min, _crank.max + 1e-9, _crank.step), 4):
    _n = explorer.set(crank=float(_c), phi=30.0)
    if explorer.error is not None:
        assert _c > limit, (_c, explorer.error)      # only past the Grashof limit
        continue
    _sol = explorer.result
    _sing = _np.asarray(_sol.singular)
    assert _n["rows near a dead point (left out)"] == int(_sing.sum()), (_c, _n)
    _regular = _np.asarray(_sol.Me)[~_sing]
    assert _n["Me max [N m]"] == _regular.max() and _n["Me min [N m]"] == _regular.min()
    assert ("change point" in _n["turns fully (Grashof)"]) == bool(abs(_c - limit) < 1e-9)
    if _sing.any():
        _seen_singular = True
        _at = float(_sol.positions[_sing][0])
        _n = explorer.set(phi=_at)
        assert _n["Me at φ [N m]"] == "singular (dead point)", (_c, _at, _n)
        explorer.set(phi=30.0)
assert _seen_singular, "the slider never reaches the change point"
""",
}

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
        _AUDIT(f"explorer {_s.name} = {_v}", _e.figure)
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


def run_sheet(path: Path) -> tuple[list, list[dict]]:
    """Run a sheet headless (every Explorer's sliders moved after it), every figure it
    shows measured: (the outputs of its cells, one audit per figure)."""
    nb = nbformat.read(path, as_version=4)
    nb.cells.insert(0, nbformat.v4.new_code_cell(AUDIT_HOOK))
    nb.cells.append(nbformat.v4.new_code_cell(
        _EXPLORER_CHECK.replace("{topic}", str(path.name[:2] in TOPIC_SHEETS))))
    if path.name[:2] in SHEET_CHECKS:
        nb.cells.append(nbformat.v4.new_code_cell(SHEET_CHECKS[path.name[:2]]))
    nb.cells.append(nbformat.v4.new_code_cell(AUDIT_REPORT))
    env = {"MPLBACKEND": "Agg", "PYTHONPATH": os.pathsep.join(
        [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])}
    old = {k: os.environ.get(k) for k in env}
    os.environ.update(env)
    try:
        client = NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                                resources={"metadata": {"path": str(path.parent)}})
        client.execute()        # raises CellExecutionError, naming the cell, on any error
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    report = nb.cells.pop()
    line = next(o.text for o in report.outputs if o.output_type == "stream")
    audits = json.loads(line.split("AUDITS ", 1)[1])
    outputs = [o for c in nb.cells[1:] if c.cell_type == "code" for o in c.outputs]
    return outputs, audits


@pytest.mark.slow
@pytest.mark.kernel
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs(path):
    """The sheet runs; every picture it shows (the Explorer's after each slider move too)
    meets the picture standard: 150 dpi, text >= 10 pt, no collision, at most one label
    not placed, the notation of docs/notation.md."""
    outputs, audits = run_sheet(path)
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
    assert audits, f"{path.name}: no figure measured"
    problems = {a["where"]: a["problems"] for a in audits if a["problems"]}
    assert not problems, f"{path.name}: pictures below the standard: {problems}"


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
