"""Reading one submission: a notebook (run in a clean kernel, or read as saved), a CSV
answer form, a JSON dict.

:func:`read_one` is a top-level function of plain data, so that a class's submissions
can go through any ``concurrent.futures.Executor`` (processes on this machine, a dask
``Client.get_executor()`` over a cluster): each notebook still runs in its own kernel,
with the network off (:mod:`~kinetostatics.teaching.execute`).

A notebook that does not run to its end (a cell raises, runs too long, the kernel
dies) is graded, by default (``on_error="saved"``), on its answers cell as saved:
its plain numbers count, the values it computes count for nothing, and the
submission carries the flag ``"did not run: cell 5 ('while True:') ran longer than
60 s"``. ``on_error="zero"`` keeps the stricter policy: such a notebook is broken and
scores 0. Read without running (``execute=False``), an answers cell that computes its
values is graded on its plain numbers and on the values its saved output shows (the
``answers`` dict displayed or printed by that cell or a later one, as the student
saved the notebook after running it); a computed value no saved output shows is
flagged and counts for nothing.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

from ..model.errors import WorkbenchError
from .answers import read_answers, saved_answers
from .execute import NotebookRunError, SubmissionError, run_notebook
from .questions import ANSWER_TAG
from .sandbox import Sandbox

__all__ = ["ON_ERROR", "output_answers", "read_one", "read_submission"]

ON_ERROR = ("saved", "zero")
"""What a notebook that does not run is graded on: its saved answers cell, or nothing."""


def _computed_flag(computed: list[str], how: str) -> str:
    few = ", ".join(computed[:4]) + (" ..." if len(computed) > 4 else "")
    return (f"{how}: the answers cell computes {few}; "
            f"{'those count' if how.startswith('ran') else 'those count for nothing'}")


def _as_saved(nb, ids: list[str], literal: dict, computed: list[str], on_error: str) -> dict:
    """A notebook read without running it: the answers cell's numbers, and the values
    it computes as its saved output shows them (the notebook was run before it was
    saved), else flagged: those count for nothing."""
    if not computed:
        return {"ids": ids, "answers": literal, "flags": []}
    shown = output_answers(nb)
    found = [q for q in computed if q in shown]
    answers = {**literal, **{q: shown[q] for q in found}}
    left = [q for q in computed if q not in shown]
    flags = []
    if found:
        flags.append(f"read as saved (not run): {', '.join(found[:4])}"
                     f"{' ...' if len(found) > 4 else ''} read from the saved output")
    if left:
        if on_error == "zero" and not any(v is not None for v in answers.values()):
            raise SubmissionError(_computed_flag(left, "read as saved"), ids)
        flags.append(_computed_flag(left, "read as saved (not run)"))
    return {"ids": ids, "answers": answers, "flags": flags}


_NUMPY = re.compile(r"\bnp\.(?:float|int)\d*\(([^()]*)\)")


def output_answers(nb) -> dict[str, Any]:
    """The ``answers`` dict as the saved outputs show it: the last output, of the
    answers cell or a cell after it, that reads as a dict literal (``np.float64(x)``
    read as x), or ``{}``."""
    import ast

    cells = nb.get("cells", [])
    at = next((k for k, c in enumerate(cells) if c.get("cell_type") == "code" and
               ANSWER_TAG in c.get("metadata", {}).get("tags", [])), None)
    found: dict[str, Any] = {}
    for cell in cells[at or 0:] if at is not None else []:
        for out in cell.get("outputs", []):
            text = out.get("data", {}).get("text/plain") if "data" in out else out.get("text")
            text = "".join(text) if isinstance(text, list) else (text or "")
            if len(text) > 1 << 20:              # no answers dict is a megabyte long
                continue
            for chunk in (text, *text.splitlines()):
                try:
                    got = ast.literal_eval(_NUMPY.sub(r"\1", chunk.strip()))
                except (ValueError, SyntaxError, TypeError, MemoryError, RecursionError):
                    continue
                if isinstance(got, dict) and got and all(isinstance(k, str) for k in got):
                    found = got
                    break
    return found


def read_submission(p: Path, execute: bool = True, timeout: float = 60.0,
                    on_error: str = "saved", sandbox: Sandbox | None = None) -> list[dict]:
    """The parts of one submission file: ``[{ids, answers, flags}]`` (a form may hold
    many students; a notebook is one). A notebook runs in ``sandbox`` (None: as the
    grader's user, no isolation).

    Raises
    ------
    SubmissionError
        The file cannot be read, or (``on_error="zero"``) the notebook did not run; its
        second argument lists the ids it carries.
    """
    if on_error not in ON_ERROR:
        raise WorkbenchError(f"on_error {on_error!r}: give one of {', '.join(ON_ERROR)}")
    if p.suffix.lower() != ".ipynb":
        df = read_answers(p)
        return [{"ids": [sid], "answers": dict(zip(g.question, g.answer, strict=True)),
                 "flags": []}
                for sid, g in df.groupby("student", sort=False)]
    import nbformat

    try:
        nb = nbformat.read(str(p), as_version=4)
    except Exception as exc:        # nbformat raises several kinds on a damaged file
        raise SubmissionError(f"not a readable notebook ({type(exc).__name__})") from None
    meta = nb.get("metadata", {}).get("kinetostatics", {})
    meta_id = meta.get("student_id") if isinstance(meta, dict) else None
    ids = [] if meta_id is None else [str(meta_id)]
    problem = ""
    try:
        _, cell_id, literal, computed = saved_answers(nb)
    except WorkbenchError as exc:
        if "no answer cell" in str(exc):
            raise SubmissionError(str(exc), ids) from None
        if not execute:
            raise SubmissionError(str(exc), ids) from None
        cell_id, literal, computed, problem = None, {}, [], str(exc)
    if cell_id is not None:
        ids.append(cell_id)
    if not execute:
        return [_as_saved(nb, ids, literal, computed, on_error)]
    try:
        run_id, answers = run_notebook(nb, timeout=timeout, sandbox=sandbox)
    except NotebookRunError as exc:
        why = f"did not run: {exc.args[0]}"
        if on_error == "zero":
            raise SubmissionError(why, ids) from None
        if problem:
            flag = f"{why}; the answers cell could not be read either ({problem})"
        elif computed:
            flag = f"{why}; " + _computed_flag(computed, "graded as saved")
        elif any(v is not None for v in literal.values()):
            flag = f"{why}; graded on the answers cell as saved"
        else:
            flag = f"{why}; the answers cell holds no number"
        return [{"ids": ids, "answers": literal, "flags": [flag]}]
    except SubmissionError as exc:
        raise SubmissionError(str(exc.args[0]), ids) from None
    if run_id is not None:
        ids.append(run_id)
    return [{"ids": ids, "answers": answers, "flags": []}]


def read_one(task: tuple) -> dict[str, Any]:
    """One submission file read, whatever it holds: never raises.

    Parameters
    ----------
    task : tuple
        ``(path, execute, timeout, on_error[, sandbox])`` (plain data: any executor
        can run it; the sandbox a notebook runs in, None or left out: no isolation).

    Returns
    -------
    dict
        ``file, mtime, parts`` (None when broken), ``reason`` (why broken), ``ids``
        (the ids a broken file carries) and ``sandbox`` (what a notebook ran in:
        ``"bubblewrap"``, ``"none (--unsandboxed)"``, ``""`` when nothing ran).
    """
    path, execute, timeout, on_error, sandbox = (*task, None)[:5]
    p = Path(path)
    try:
        mtime = os.stat(p).st_mtime
    except OSError:
        mtime = float("nan")
    ran = execute and p.suffix.lower() == ".ipynb"
    out: dict[str, Any] = {"file": str(p), "mtime": mtime, "parts": None, "reason": "",
                           "ids": [], "sandbox": "" if not ran else (
                               "bubblewrap" if sandbox is not None else
                               "none (--unsandboxed)")}
    try:
        out["parts"] = read_submission(p, execute, timeout, on_error, sandbox)
    except SubmissionError as exc:
        out["reason"] = str(exc.args[0])
        out["ids"] = list(exc.args[1]) if len(exc.args) > 1 else []
    except WorkbenchError as exc:
        out["reason"] = str(exc)
    except Exception as exc:     # whatever one submission does, the class goes on
        out["reason"] = f"{type(exc).__name__}: {exc}"
    return out
