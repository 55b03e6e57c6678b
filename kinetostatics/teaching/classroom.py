"""The teacher's loop: a sealed class folder (and, re-exported from
:mod:`~kinetostatics.teaching.gradebook`, the grading of what comes back).

:func:`generate_class` writes, for a class list, ``DIR/students/<id>.ipynb`` (the
student's sealed notebook), ``DIR/handouts/<id>.html`` (with the student's mechanism
drawn, see :mod:`~kinetostatics.teaching.handouts`; ``pdf=True`` adds
``<id>.pdf``), and for the teacher ``DIR/key.csv``, ``DIR/variants.csv``,
``DIR/answer_form.csv`` and ``DIR/teacher.json`` (the exercise, its seed, the class
list, the tolerance rule). Students are prepared one after another, in ``jobs``
processes, or through any ``concurrent.futures.Executor``. A repeated id in the class
list is dropped with a warning.
"""

from __future__ import annotations

import datetime
import json
import os
import re
from collections.abc import Iterable, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor
from pathlib import Path
from typing import Any

from ..model.errors import WorkbenchError
from ..simulation.batch import run_batch
from .gradebook import ClassReport, grade_class
from .handouts import handout_pdf, picture_figure, picture_uri
from .library import exercise as library_exercise
from .questions import TOLERANCE_RULE, normalize_id
from .sheets import handout_html, key_values, leaked_values, student_notebook
from .variants import Exercise

__all__ = ["ClassReport", "generate_class", "grade_class", "read_class_list"]

_BAD_ID = re.compile(r"[/\\:*?\"<>|\x00-\x1f]")


def read_class_list(source: str | Path | Iterable[Any],
                    warnings: list[str] | None = None) -> list[str]:
    """Student ids from a file (one per line; blank lines and ``#`` comments skipped)
    or from a list; each is trimmed and kept as written (accents and case).

    Parameters
    ----------
    source : path or iterable
        The class list.
    warnings : list, optional
        Receives one line per id dropped because it repeats an earlier one (equal after
        trimming, case-folding and Unicode normalisation), naming both lines.

    Raises
    ------
    WorkbenchError
        An id that cannot be a file name, no id.
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
            first, where_first = seen[n]
            if warnings is not None:
                warnings.append(f"{at}: student id '{sid}' repeats '{first}' ({where_first}); "
                                "dropped")
            continue
        seen[n] = (sid, at)
        ids.append(sid)
    if not ids:
        raise WorkbenchError("the class list holds no student id")
    return ids


def generate_class(exercise: str | Exercise, students: str | Path | Iterable[Any],
                   out: str | Path, seed: int | None = None, *, pdf: bool = False,
                   jobs: int | None = 1, executor: Executor | None = None) -> dict[str, Any]:
    """Write a sealed class folder.

    Parameters
    ----------
    exercise : str or Exercise
        A library name (``"four_bar"``, see :func:`list_exercises`) or an exercise.
    students : path or iterable
        The class list (see :func:`read_class_list`: repeated ids are dropped with a
        warning).
    out : path
        The folder (must not hold a class already).
    seed : int, optional
        The exercise's seed; None draws a secret one (stored in ``teacher.json``).
    pdf : bool
        Write ``handouts/<id>.pdf`` beside each HTML handout.
    jobs : int, optional
        Students prepared at the same time, in processes (default 1: in this process;
        None: one per core).
    executor : concurrent.futures.Executor, optional
        Run the students through this executor instead (a dask ``Client.get_executor()``
        spreads a large class over a cluster); it is not shut down.

    Returns
    -------
    dict
        ``exercise, students, seed_source, folder, files`` (the written paths) and
        ``warnings`` (the repeated ids dropped from the class list).
    """
    warn: list[str] = []
    ids = read_class_list(students, warn)
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
    (d / "students").mkdir(parents=True, exist_ok=True)
    (d / "handouts").mkdir(parents=True, exist_ok=True)
    spec = (ex.name, int(ex.seed)) if isinstance(exercise, str) else ex
    tasks = [(spec, sid, str(d), bool(pdf)) for sid in ids]
    if executor is not None:
        done = run_batch(_student_files, tasks, executor=executor)
    elif jobs == 1 or len(tasks) < 2:
        ex.prepare(ids)                 # the class's first draws solved together
        done = [_student_files(t, ex) for t in tasks]
    else:
        k = max(1, min(len(tasks), int(jobs) if jobs else (os.cpu_count() or 1)))
        with ProcessPoolExecutor(k) as pool:
            done = run_batch(_student_files, tasks, executor=pool)
    files = []
    for sid, (variant, written) in zip(ids, done, strict=True):
        ex.remember(sid, variant)                 # the key below needs no new solve
        files += [Path(f) for f in written]
    cls = ex.generate(ids)
    for name, df in (("key", cls.key), ("variants", cls.variants),
                     ("answer_form", cls.answer_form())):
        p = d / f"{name}.csv"
        df.to_csv(p, index=False)            # floats as repr: they read back exactly
        files.append(p)
    meta = {"exercise": ex.name, "title": ex.title, "seed": int(ex.seed),
            "seed_source": source, "students": ids, "questions": list(ex.questions),
            "rtol": ex.rtol, "tolerance_rule": TOLERANCE_RULE,
            "created": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")}
    (d / "teacher.json").write_text(json.dumps(meta, indent=2, ensure_ascii=False) + "\n",
                                    encoding="utf-8")
    files.append(d / "teacher.json")
    return {"exercise": ex.name, "students": ids, "seed_source": source, "folder": d,
            "files": files, "warnings": warn}


_EXERCISES: dict[tuple, Exercise] = {}


def _student_files(task: tuple, ex: Exercise | None = None) -> tuple[dict, list[str]]:
    """Write one student's notebook and handout (and PDF); return the variant and the
    paths. ``task = (exercise or (name, seed), student, folder, pdf)``: plain data, so
    that a process or a cluster's worker can run it."""
    spec, sid, folder, pdf = task
    if ex is None:
        if isinstance(spec, Exercise):
            ex = spec
        else:
            ex = _EXERCISES.get(spec) or _EXERCISES.setdefault(spec, library_exercise(*spec))
    import nbformat

    d = Path(folder)
    v = ex.variant(sid)
    nb_path, html_path = d / "students" / f"{sid}.ipynb", d / "handouts" / f"{sid}.html"
    nbformat.write(student_notebook(ex, sid, v), str(nb_path))
    fig = picture_figure(ex, v)              # one drawing (and solve) for both handouts
    html_path.write_text(handout_html(ex, sid, v, picture_uri(ex, v, fig)), encoding="utf-8")
    _verify_sealed([nb_path, html_path], v, ex.seed)
    written = [str(nb_path), str(html_path)]
    if pdf:
        handout_pdf(ex, sid, v, d / "handouts" / f"{sid}.pdf", fig)
        written.append(str(d / "handouts" / f"{sid}.pdf"))
    return v, written


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


