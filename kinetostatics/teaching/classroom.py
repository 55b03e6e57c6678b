"""The teacher's loop: a sealed class folder, and the grading of what comes back.

:func:`generate_class` writes, for a class list, ``DIR/students/<id>.ipynb`` (the
student's sealed notebook), ``DIR/handouts/<id>.html``, and for the teacher
``DIR/key.csv``, ``DIR/variants.csv``, ``DIR/answer_form.csv`` and
``DIR/teacher.json`` (the exercise, its seed, the class list, the tolerance rule).
:func:`grade_class` reads notebooks (run in a clean kernel first, see
:mod:`~kinetostatics.teaching.execute`), CSV answer forms and JSON dicts; it takes each
submission's student id from the submission itself, matches ids after trimming and
case-folding, and reports broken submissions, unknown ids and missing students
without stopping: a broken submission and a missing student score 0.
"""

from __future__ import annotations

import datetime
import json
import os
import re
from collections.abc import Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import WorkbenchError
from .answers import notebook_answers, read_answers
from .execute import SubmissionError, run_notebook
from .grading import grade
from .library import exercise as library_exercise
from .questions import TOLERANCE_RULE, normalize_id
from .sheets import handout_html, key_values, leaked_values, student_notebook
from .variants import Exercise

__all__ = ["ClassReport", "generate_class", "grade_class", "read_class_list"]

_BAD_ID = re.compile(r"[/\\:*?\"<>|\x00-\x1f]")


def read_class_list(source: str | Path | Iterable[Any]) -> list[str]:
    """Student ids from a file (one per line; blank lines and ``#`` comments skipped)
    or from a list; each is trimmed.

    Raises
    ------
    WorkbenchError
        An id that cannot be a file name, two ids equal after case-folding, no id.
    """
    if isinstance(source, str | Path):
        p = Path(source)
        if not p.is_file():
            raise WorkbenchError(f"class list {str(p)!r}: no such file")
        try:
            lines = p.read_text(encoding="utf-8-sig").splitlines()
        except UnicodeDecodeError:
            raise WorkbenchError(f"class list {p}: not UTF-8 text; save it as UTF-8") from None
        where = [f"{p}:{k}" for k in range(1, len(lines) + 1)]
    else:
        lines = [str(s) for s in source]
        where = [f"item {k}" for k in range(1, len(lines) + 1)]
    ids, seen = [], {}
    for line, at in zip(lines, where, strict=True):
        sid = line.strip()
        if not sid or sid.startswith("#"):
            continue
        if _BAD_ID.search(sid) or sid.startswith("."):
            raise WorkbenchError(f"{at}: student id {sid!r} cannot be a file name "
                                 "(no / \\ : * ? \" < > |, no leading dot)")
        n = normalize_id(sid)
        if n in seen:
            raise WorkbenchError(f"{at}: student id {sid!r} repeats {seen[n]!r} (ids are "
                                 "matched ignoring case and surrounding spaces)")
        seen[n] = sid
        ids.append(sid)
    if not ids:
        raise WorkbenchError("the class list holds no student id")
    return ids


def generate_class(exercise: str | Exercise, students: str | Path | Iterable[Any],
                   out: str | Path, seed: int | None = None) -> dict[str, Any]:
    """Write a sealed class folder.

    Parameters
    ----------
    exercise : str or Exercise
        A library name (``"four_bar"``, see :func:`list_exercises`) or an exercise.
    students : path or iterable
        The class list (see :func:`read_class_list`).
    out : path
        The folder (must not hold a class already).
    seed : int, optional
        The exercise's seed; None draws a secret one (stored in ``teacher.json``).

    Returns
    -------
    dict
        ``exercise, students, seed_source, folder, files`` (the written paths).
    """
    ids = read_class_list(students)
    if isinstance(exercise, Exercise):
        if seed is not None:
            raise WorkbenchError("give the seed to the Exercise, not to generate_class")
        ex, source = exercise, "the exercise's"
    else:
        ex = library_exercise(exercise, seed)
        source = "random (secret)" if seed is None else "given"
    d = Path(out)
    if (d / "teacher.json").exists():
        raise WorkbenchError(f"{d} already holds a class (teacher.json): choose another "
                             "folder, or delete it first")
    cls = ex.generate(ids)
    (d / "students").mkdir(parents=True, exist_ok=True)
    (d / "handouts").mkdir(parents=True, exist_ok=True)
    import nbformat

    files = []
    for sid in ids:
        v = ex.variant(sid)
        nb_path, html_path = d / "students" / f"{sid}.ipynb", d / "handouts" / f"{sid}.html"
        nbformat.write(student_notebook(ex, sid, v), str(nb_path))
        html_path.write_text(handout_html(ex, sid, v), encoding="utf-8")
        _verify_sealed([nb_path, html_path], v, ex.seed)
        files += [nb_path, html_path]
    for name, df in (("key", cls.key), ("variants", cls.variants),
                     ("answer_form", cls.answer_form())):
        p = d / f"{name}.csv"
        df.to_csv(p, index=False)            # floats as repr: they read back exactly
        files.append(p)
    meta = {"exercise": ex.name, "title": ex.title, "seed": int(ex.seed),
            "seed_source": source, "students": ids, "questions": list(ex.questions),
            "rtol": ex.rtol, "tolerance_rule": TOLERANCE_RULE,
            "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")}
    (d / "teacher.json").write_text(json.dumps(meta, indent=2) + "\n", encoding="utf-8")
    files.append(d / "teacher.json")
    return {"exercise": ex.name, "students": ids, "seed_source": source, "folder": d,
            "files": files}


def _verify_sealed(paths: Sequence[Path], variant: dict, seed: int) -> None:
    """Refuse to leave a student file that shows a key value or the seed."""
    values, angles = key_values(variant)
    for p in paths:
        text = p.read_text(encoding="utf-8")
        leaked = leaked_values(text, values, angles)
        if leaked or (len(str(seed)) >= 6 and str(seed) in text):
            p.unlink()
            what = f"the key of {leaked[0]}" if leaked else "the seed"
            raise WorkbenchError(f"{p}: would show {what}; not written")


# ------------------------------------------------------------------------- grading
@dataclass
class ClassReport:
    """What grading a class found: the graded rows, and the problems to read."""

    graded: pd.DataFrame
    scores: pd.DataFrame
    submissions: list[dict] = field(default_factory=list)
    broken: list[dict] = field(default_factory=list)
    unknown: list[dict] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    duplicates: list[dict] = field(default_factory=list)
    conflicts: list[dict] = field(default_factory=list)


def _expand(submissions: Iterable[Any]) -> list[Path]:
    out = []
    for s in submissions:
        p = Path(s)
        if p.is_dir():
            out += sorted(q for q in p.rglob("*") if q.is_file()
                          and q.suffix.lower() in (".ipynb", ".csv", ".json")
                          and ".ipynb_checkpoints" not in q.parts)
        elif p.is_file():
            out.append(p)
        else:
            raise WorkbenchError(f"submission {str(p)!r}: no such file or folder")
    return out


def _read_submission(p: Path, execute: bool, timeout: float) -> list[dict]:
    """[{ids: [...], answers: {...}}] of one file (a form may hold many students)."""
    if p.suffix.lower() != ".ipynb":
        df = read_answers(p)
        return [{"ids": [sid], "answers": dict(zip(g.question, g.answer, strict=True))}
                for sid, g in df.groupby("student", sort=False)]
    import nbformat

    try:
        nb = nbformat.read(str(p), as_version=4)
    except Exception as exc:        # nbformat raises several kinds on a damaged file
        raise SubmissionError(f"not a readable notebook ({type(exc).__name__})") from None
    meta = nb.get("metadata", {}).get("kinetostatics", {})
    meta_id = meta.get("student_id") if isinstance(meta, dict) else None
    ids = [] if meta_id is None else [str(meta_id)]
    try:
        _, cell_id, literal = notebook_answers(nb)
    except WorkbenchError as exc:
        if "no answer cell" in str(exc) or not execute:
            raise SubmissionError(str(exc), ids) from None
        cell_id, literal = None, {}
    if cell_id is not None:
        ids.append(cell_id)
    if not execute:
        return [{"ids": ids, "answers": literal}]
    try:
        run_id, answers = run_notebook(nb, timeout=timeout)
    except SubmissionError as exc:
        raise SubmissionError(str(exc), ids) from None
    if run_id is not None:
        ids.append(run_id)
    return [{"ids": ids, "answers": answers}]


def grade_class(directory: str | Path, submissions: Iterable[Any], *, execute: bool = True,
                timeout: float = 60.0, jobs: int | None = None) -> ClassReport:
    """Grade every submission of a class folder written by :func:`generate_class`.

    Parameters
    ----------
    directory : path
        The class folder (``key.csv``, ``teacher.json``).
    submissions : iterable of paths
        Notebooks, CSV answer forms (wide: a ``student`` column and one column per
        question; long: ``student, question, answer``), JSON dicts, or folders of them.
    execute : bool
        Run each notebook in a clean kernel before reading ``answers`` (default); with
        False the answers are read from the saved cell (its literal values).
    timeout : float
        Seconds allowed per notebook cell.
    jobs : int, optional
        Notebooks run at the same time (default: the number of cores, at most 4).

    Returns
    -------
    ClassReport
        ``graded`` (one row per student and question: ``student, question, expected,
        answer, unit, error, tolerance, passed, status, source``), ``scores`` (one row
        per student), and the lists ``broken, unknown, missing, duplicates,
        conflicts`` (id in the metadata and in the answer cell disagree).
    """
    d = Path(directory)
    if jobs is None:
        jobs = min(4, os.cpu_count() or 1)
    if not (d / "key.csv").is_file():
        raise WorkbenchError(f"{d}: no key.csv; give the folder written by "
                             "'exercises generate'")
    key = pd.read_csv(d / "key.csv", dtype={"student": str}, keep_default_na=False,
                      na_values={"expected": [""], "atol": [""], "rtol": [""]})
    canon = {normalize_id(s): s for s in dict.fromkeys(key["student"])}
    rep = ClassReport(graded=pd.DataFrame(), scores=pd.DataFrame())
    got: dict[str, tuple[dict, str]] = {}
    failed: dict[str, tuple[str, str]] = {}
    own = {(d / n).resolve() for n in ("key.csv", "variants.csv", "teacher.json")}
    files = [p for p in _expand(submissions) if p.resolve() not in own]   # never the key

    def read(p: Path) -> tuple[list | None, str, list]:
        try:
            return _read_submission(p, execute, timeout), "", []
        except SubmissionError as exc:
            return None, str(exc.args[0]), list(exc.args[1]) if len(exc.args) > 1 else []
        except WorkbenchError as exc:
            return None, str(exc), []
        except Exception as exc:     # whatever one submission does, the class goes on
            return None, f"{type(exc).__name__}: {exc}", []

    # each notebook runs in its own kernel process: a few at a time, results in order
    with ThreadPoolExecutor(max(1, int(jobs))) as pool:
        results = list(pool.map(read, files))
    for p, (parts, reason, ids) in zip(files, results, strict=True):
        if parts is None:
            known = [canon[normalize_id(i)] for i in ids if normalize_id(i) in canon]
            sid = known[0] if known else None
            rep.broken.append({"file": str(p), "student": sid, "reason": reason})
            if sid in got:
                rep.duplicates.append({"student": sid, "files": [got[sid][1], str(p)],
                                       "kept": got[sid][1]})
            elif sid is not None:
                failed[sid] = (reason, str(p))
            continue
        for part in parts:
            ids = [i for i in part["ids"] if i is not None and str(i).strip()]
            known = list(dict.fromkeys(canon[normalize_id(i)] for i in ids
                                       if normalize_id(i) in canon))
            rep.submissions.append({"file": str(p), "ids": ids})
            if len(known) > 1 or (known and len({normalize_id(i) for i in ids}) > 1):
                rep.conflicts.append({"file": str(p), "ids": ids,
                                      "graded_as": known[0] if known else None})
            if not known:
                rep.unknown.append({"file": str(p),
                                    "student": ids[0] if ids else "(no id)"})
                continue
            sid = known[0]
            if sid in got or sid in failed:
                before = got[sid][1] if sid in got else failed[sid][1]
                rep.duplicates.append({"student": sid, "files": [before, str(p)],
                                       "kept": str(p)})
            got[sid] = (part["answers"], str(p))
            failed.pop(sid, None)
    long = pd.DataFrame([{"student": s, "question": q, "answer": a}
                         for s, (ans, _) in got.items() for q, a in ans.items()],
                        columns=["student", "question", "answer"])
    parts = []
    if got:
        graded, _ = grade(long, key[key["student"].isin(list(got))])
        graded["source"] = graded["student"].map({s: f for s, (_, f) in got.items()})
        parts.append(graded)
    zero = key[~key["student"].isin(list(got))]
    if not zero.empty:
        tol = np.where(zero["kind"] == "angle", zero["atol"],
                       np.maximum(zero["atol"], zero["rtol"] * zero["expected"].abs()))
        status = [("broken: " + failed[s][0]) if s in failed else "no submission"
                  for s in zero["student"]]
        parts.append(pd.DataFrame({
            "student": zero["student"], "question": zero["question"],
            "expected": zero["expected"], "answer": np.nan, "unit": zero["unit"],
            "error": np.nan, "tolerance": tol, "passed": False, "status": status,
            "source": [failed[s][1] if s in failed else "" for s in zero["student"]]}))
    rep.graded = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame()
    order = {s: k for k, s in enumerate(canon.values())}
    rep.graded = rep.graded.sort_values("student", key=lambda c: c.map(order),
                                        kind="stable").reset_index(drop=True)
    rep.missing = [s for s in canon.values() if s not in got and s not in failed]
    rows = []
    for s, g in rep.graded.groupby("student", sort=False):
        rows.append({"student": s, "passed": int(g.passed.sum()), "total": int(len(g)),
                     "score %": round(100.0 * float(g.passed.mean()), 1),
                     "failed": ", ".join(g.loc[~g.passed.astype(bool), "question"]),
                     "source": g["source"].iloc[0]})
    rep.scores = pd.DataFrame(rows, columns=["student", "passed", "total", "score %",
                                             "failed", "source"])
    return rep
