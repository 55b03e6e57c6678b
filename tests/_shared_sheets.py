"""What a run of a sheet must show, for the two tests that run the sheets.

Each sheet is run once in a suite: a sheet with an interactive cell (an Explorer's
widget) in JupyterLab by tests/test_browser.py, which makes the checks below in the same
kernel after its own (the browser's) checks, on the browser's own slider moves
(:data:`MOVES_RECORD`, :data:`MOVES_CHECK`); every other sheet headless with nbclient by
tests/test_notebooks.py, which runs the widget sheets too when the browser test is not
part of the run (Chromium or Playwright missing, the test deselected).

A run passes when no cell raises, the sheet shows at least one picture and one table,
its outputs hold no ``nan`` or ``inf`` (a not-applicable cell shows a dash) and nothing
on stderr (no warning), every figure a cell shows meets the picture standard
(:data:`AUDIT_HOOK`), and every Explorer left in the kernel, moved slider by slider
through its Python API (in the browser: by the browser), changes its picture and key
numbers (:data:`EXPLORER_CHECK`; the browser's picture checked on the page).
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
#: every sheet with an interactive cell (an Explorer's widget): run in the browser
WIDGET_SHEETS = sorted(p.name for p in NOTEBOOKS
                       if "Explorer(" in p.read_text(encoding="utf-8"))
CHROMIUM = Path(os.environ.get("KINETOSTATICS_CHROMIUM", "/usr/bin/chromium"))
# Debian's old headless shell (the package chromium-headless-shell, the same Blink and V8
# as its Chromium 150): driven instead of Chromium where it is installed (and
# KINETOSTATICS_CHROMIUM names no browser), for Chromium's ``--headless`` runs the whole
# browser with its window not shown. With the smaller page (tests/test_browser.py,
# VIEWPORT): the browser test's 11 sheets 182.3 -> 166.9 s of CPU (setup and call, every
# sheet lower; Chromium's processes 71 -> 52 s), two whole runs side by side at load
# 11-14, 2026-11-30 (tools/cpu_per_test.py)
HEADLESS_SHELL = Path("/usr/lib/chromium/chromium-headless-shell")
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
# (first of all, as tests/conftest.py does in the suite's processes: jsonschema, which
# nbformat imports, is declined rfc3987_syntax, whose 38 grammars cost 1.5 s of CPU in a
# kernel that imports nbformat (sheet 12), measured 2026-11-30; nothing in a sheet
# validates an "iri")
AUDIT_HOOK = """
import sys as _sys
_sys.modules.setdefault("rfc3987_syntax", None)
del _sys


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
from kinetostatics.notebook import Explorer as _Explorer


def _check_crank(_e, _c):
    \"\"\"The readouts of explorer _e at crank _c; True where it has singular rows.\"\"\"
    _n = _e.set(crank=_c, phi=30.0)
    if _e.error is not None:
        assert _c > limit, (_c, _e.error)      # only past the Grashof limit
        return True
    _sol = _e.result
    _sing = _np.asarray(_sol.singular)
    assert _n["rows near a dead point (left out)"] == int(_sing.sum()), (_c, _n)
    _regular = _np.asarray(_sol.Me)[~_sing]
    assert _n["Me max [N m]"] == _regular.max() and _n["Me min [N m]"] == _regular.min()
    assert ("change point" in _n["turns fully (Grashof)"]) == bool(abs(_c - limit) < 1e-9)
    if _sing.any():
        _at = float(_sol.positions[_sing][0])
        _n = _e.set(phi=_at)
        assert _n["Me at φ [N m]"] == "singular (dead point)", (_c, _at, _n)
    return bool(_sing.any())                    # (the next call sets phi = 30 again)


# every crank length through a twin of the explorer that draws nothing (the sheet's own
# solve and key numbers; a picture per length was 1.2 s of the kernel's CPU, 16 s in
# all, measured 2026-11-29); the lengths with singular rows or no solution again on the
# sheet's explorer, pictures drawn
_twin = _Explorer(explorer.sliders, four_bar, lambda *_args, **_values: None, key_numbers,
                  limits=explorer.limits)
_crank = explorer.slider("crank")
_special = [float(_c) for _c in _np.round(_np.arange(_crank.min, _crank.max + 1e-9,
                                                    _crank.step), 4)
            if _check_crank(_twin, float(_c))]
assert any(_c <= limit for _c in _special), "the slider never reaches the change point"
for _c in _special:
    _check_crank(explorer, _c)
""",
}

# run after the sheet in the same kernel: move every slider of every Explorer (from the
# sliders' starting values: a browser may have moved them before)
# (an Explorer is there only where the sheet imported kinetostatics.notebook: the check
# does not import it into a sheet without one, 0.1-0.17 s of its kernel's CPU, measured
# 2026-11-30)
EXPLORER_CHECK = """
import sys as _sys
_module = _sys.modules.get("kinetostatics.notebook")
_explorers = [v for v in list(globals().values())
              if _module is not None and isinstance(v, _module.Explorer)]
assert _explorers or not {topic}, "this topic sheet has no interactive cell (Explorer)"
for _e in _explorers:
    _e.close()                          # no frontend: the API alone (no widget redraws)
    _start = {_s.name: _s.value for _s in _e.sliders}
    if _e.values != _start:
        _e.set(**_start)
    assert _e.error is None, _e.error
    _png = _e.png(dpi=30)               # (each state drawn once: the last move's is the next's
    for _s in _e.sliders:               # before)
        _v = _s.value + (_s.max - _s.value) / 2 if _s.value < _s.max else _s.min
        _v = min(max(round(_v / _s.step) * _s.step, _s.min), _s.max)
        _numbers = dict(_e.numbers)
        _e.set(**{_s.name: _v})
        assert _e.error is None, f"slider {_s.name} = {_v}: {_e.error}"
        _before, _png = _png, _e.png(dpi=30)
        assert _png != _before, f"slider {_s.name} = {_v} does not change the picture"
        assert _e.numbers != _numbers, f"slider {_s.name} = {_v} changes no key number"
        _e.table()                      # every key number is finite (raises otherwise)
        _AUDIT(f"explorer {_s.name} = {_v}", _e.figure)
"""


# the browser test's record of its own slider moves, in the kernel: MOVES_RECORD is run
# (through a kernel client) once the sheet has run and again after each slider move of the
# browser, whose update has ended; MOVES_CHECK, after the moves, holds them to what
# EXPLORER_CHECK holds its own moves to (so the browser's run moves every slider once, not
# once in the browser and again through the API: each move was a whole update, 1-3 s of
# the kernel's CPU, measured 2026-11-30)
MOVES_RECORD = """
def _record_moves():
    from kinetostatics.notebook import Explorer
    moves = globals().setdefault("_MOVES", [])
    found = {id(v): v for v in list(globals().values()) if isinstance(v, Explorer)}
    moves.append([(dict(e.values), dict(e.numbers), e.error, e.updates)
                  for e in found.values()])
    for k, e in enumerate(found.values()):
        if len(moves) > 1 and moves[-2][k][0] != e.values:    # moved: measured as shown
            moved = {n: v for n, v in e.values.items() if moves[-2][k][0][n] != v}
            e.table()                   # every key number is finite (raises otherwise)
            _AUDIT(f"explorer {moved} (browser)", e.figure)


_record_moves()
"""
MOVES_CHECK = """
from kinetostatics.notebook import Explorer as _Explorer
_explorers = list({id(v): v for v in list(globals().values()) if isinstance(v, _Explorer)}
                  .values())
assert _explorers or not {topic}, "this topic sheet has no interactive cell (Explorer)"
assert len(_MOVES) > 1 and all(len(_m) == len(_explorers) for _m in _MOVES), _MOVES
for _before, _after in zip(_MOVES, _MOVES[1:]):
    # each move: one slider of one explorer, its value in the kernel, one update computed
    _moved = [(_k, _n) for _k, (_b, _a) in enumerate(zip(_before, _after))
              for _n in _a[0] if _a[0][_n] != _b[0][_n]]
    assert len(_moved) == 1, f"a move changed {_moved} (one slider each)"
    _k, _n = _moved[0]
    _v = _after[_k][0][_n]
    assert _after[_k][3] > _before[_k][3], f"slider {_n} = {_v}: no update computed"
    assert _after[_k][2] is None, f"slider {_n} = {_v}: {_after[_k][2]}"
    assert _after[_k][1] != _before[_k][1], f"slider {_n} = {_v} changes no key number"
for _k, _e in enumerate(_explorers):
    _left = {_s.name for _s in _e.sliders} - {_n for _b, _a in zip(_MOVES, _MOVES[1:])
                                             for _n in _a[_k][0] if _a[_k][0][_n] != _b[_k][0][_n]}
    assert not _left, f"sliders never moved in the browser: {sorted(_left)}"
    _e.close()                          # no frontend from here: the API alone
"""


def checks_after(name: str, browser: bool = False) -> list[str]:
    """The code run in a sheet's kernel after the sheet (each a cell): every Explorer's
    sliders moved (``browser``: the browser's moves, recorded by :data:`MOVES_RECORD`,
    checked), the sheet's own checks; then :data:`AUDIT_REPORT` gives the audits."""
    check = MOVES_CHECK if browser else EXPLORER_CHECK
    cells = [check.replace("{topic}", str(name[:2] in TOPIC_SHEETS))]
    if name[:2] in SHEET_CHECKS:
        cells.append(SHEET_CHECKS[name[:2]])
    return cells


def audits_of(report: str) -> list[dict]:
    """The audits printed by :data:`AUDIT_REPORT`."""
    return json.loads(report.split("AUDITS ", 1)[1])


def output_texts(outputs) -> list[str]:
    """Every text a reader sees in the outputs (streams, plain text, HTML), without the
    embedded images."""
    texts = []
    for o in outputs:
        if o.get("output_type") == "stream":
            texts.append(o["text"])
        for mime in ("text/plain", "text/html", "text/markdown", "text/latex"):
            if mime in o.get("data", {}):
                texts.append(_DATA_URI.sub("", o["data"][mime]))
    return texts


def check_run(name: str, outputs: list, audits: list[dict]) -> None:
    """The sheet ran; every picture it shows (the Explorer's after each slider move too)
    meets the picture standard: 150 dpi, text >= 10 pt, no collision, at most one label
    not placed, the notation of docs/notation.md. ``outputs``: the outputs of the sheet's
    cells (nbformat), ``audits``: :func:`audits_of` the kernel's report."""
    errors = [o for o in outputs if o.get("output_type") == "error"]
    assert not errors, f"{name}: {errors}"
    assert any("image/png" in o.get("data", {}) for o in outputs), \
        f"{name} shows no picture"
    assert any("<table" in o.get("data", {}).get("text/html", "") for o in outputs), \
        f"{name} shows no table"
    stderr = [o["text"] for o in outputs
              if o.get("output_type") == "stream" and o.get("name") == "stderr"]
    assert not stderr, f"{name} writes to stderr (a warning?): {stderr}"
    bad = sorted({m.group(0) for t in output_texts(outputs) for m in _NOT_A_NUMBER.finditer(t)})
    assert not bad, f"{name} shows {bad} in its outputs: show a dash where no value applies"
    assert audits, f"{name}: no figure measured"
    problems = {a["where"]: a["problems"] for a in audits if a["problems"]}
    assert not problems, f"{name}: pictures below the standard: {problems}"


def browser_binary() -> Path:
    """The browser tests/test_browser.py drives: :data:`HEADLESS_SHELL` where it is
    installed and ``KINETOSTATICS_CHROMIUM`` is not set, else :data:`CHROMIUM`."""
    if "KINETOSTATICS_CHROMIUM" not in os.environ and HEADLESS_SHELL.exists():
        return HEADLESS_SHELL
    return CHROMIUM


def browser_ready() -> bool:
    """Chromium and Playwright's Python package are there (tests/test_browser.py can
    run)."""
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return False
    return CHROMIUM.exists()
