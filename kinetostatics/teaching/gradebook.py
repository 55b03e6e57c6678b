"""Grading a class folder: every submission on record, one summary row per student.

:func:`grade_class` reads notebooks (run in a clean kernel first, see
:mod:`~kinetostatics.teaching.submissions`), CSV answer forms and JSON dicts; it takes
each submission's student id from the submission itself, matches ids after trimming,
case-folding and Unicode normalisation, and keeps every file it read on record:
unknown ids, broken files and the duplicates not graded each get a row in
``graded`` (with the reason), so nothing handed in is lost. When a student handed in
several files, the one kept is the teacher's ``prefer`` choice, else the newest
readable one by modification time. Unit slips, notebooks that did not run and copies
are flagged (``note``, ``flags``); broken submissions and missing students score 0.
"""

from __future__ import annotations

import dataclasses
import datetime
import math
import os
from collections import defaultdict
from collections.abc import Iterable
from concurrent.futures import Executor, ProcessPoolExecutor
from dataclasses import dataclass, field
from decimal import ROUND_HALF_UP, Decimal
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import WorkbenchError
from ..simulation.batch import run_batch
from .copies import find_copies
from .grading import grade
from .questions import normalize_id
from .sandbox import Limits, sandbox_or_refuse
from .submissions import ON_ERROR, read_one

__all__ = ["COLUMNS", "SUMMARY", "ClassReport", "grade_class", "percent"]

COLUMNS = ["student", "question", "expected", "answer", "unit", "error", "tolerance",
           "passed", "points", "status", "note", "flags", "source"]
"""The columns of ``graded`` (and of ``grades.csv``)."""

SUMMARY = ["student", "score %", "points", "total", "passed", "unit slips", "sign slips",
           "flags", "failed", "source", "sandbox"]
"""The columns of ``scores`` (and of ``grades_students.csv``)."""


@dataclass
class ClassReport:
    """What grading a class found: the graded rows, the summary per student, and the
    problems to read."""

    graded: pd.DataFrame
    scores: pd.DataFrame
    submissions: list[dict] = field(default_factory=list)
    broken: list[dict] = field(default_factory=list)
    unknown: list[dict] = field(default_factory=list)
    missing: list[str] = field(default_factory=list)
    duplicates: list[dict] = field(default_factory=list)
    conflicts: list[dict] = field(default_factory=list)
    flags: dict[str, list[str]] = field(default_factory=dict)
    exercise: str = ""
    sandbox: str = ""


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


def _read_all(tasks: list[tuple], jobs: int | None, executor: Executor | None,
              execute: bool) -> list[dict]:
    if executor is not None:
        return run_batch(read_one, tasks, executor=executor)
    if jobs is None:
        jobs = min(4, os.cpu_count() or 1)
    k = max(1, min(int(jobs), len(tasks)))
    if k < 2 or not execute:                 # reading saved files: no process to pay for
        return [read_one(t) for t in tasks]
    # each notebook runs in its own kernel process; k notebooks at a time
    with ProcessPoolExecutor(k) as pool:
        return run_batch(read_one, tasks, executor=pool)


def _when(t: float) -> str:
    if not math.isfinite(t):
        return "unknown time"
    return datetime.datetime.fromtimestamp(t).strftime("%Y-%m-%d %H:%M:%S")


def _is_preferred(path: str, prefer: list[Path]) -> bool:
    p = Path(path).resolve()
    return any(p == q or q in p.parents for q in prefer)


def _choose(entries: list[dict], prefer: list[Path]) -> tuple[dict, str]:
    """The submission kept for one student, and why (naming the files of the same
    time when the newest is not one alone)."""
    ok = [e for e in entries if e["answers"] is not None]
    pref = [e for e in entries if _is_preferred(e["file"], prefer)]
    if pref:
        pool, why = pref, "the teacher's --prefer"
    elif ok:
        pool, why = ok, "newest by modification time"
        if len(ok) < len(entries):
            why = ("the only readable one" if len(ok) == 1 else
                   "newest readable one by modification time")
    else:
        pool, why = entries, "newest by modification time (none is readable)"
    order = {id(e): k for k, e in enumerate(entries)}

    def when(e):
        return e["mtime"] if math.isfinite(e["mtime"]) else -1e300
    best = max(pool, key=lambda e: (when(e), order[id(e)]))
    tied = [e["file"] for e in pool if e is not best and when(e) == when(best)]
    if tied and not pref:
        why += (f"; {' and '.join(tied)} has the same time: kept the last by name, "
                "choose with --prefer")
    return best, f"{why}, {_when(best['mtime'])}"


def _tolerance(key: pd.DataFrame) -> np.ndarray:
    return np.where(key["kind"] == "angle", key["atol"],
                    np.maximum(key["atol"], key["rtol"] * key["expected"].abs()))


def grade_class(directory: str | Path, submissions: Iterable[Any], *, execute: bool = True,
                timeout: float | None = None, jobs: int | None = None,
                executor: Executor | None = None, on_error: str = "saved",
                unit_slip_credit: float = 0.0, prefer: Iterable[Any] = (),
                limits: Limits | None = None, unsandboxed: bool = False,
                hide: Iterable[Any] = ()) -> ClassReport:
    """Grade every submission of a class folder written by :func:`generate_class`.

    Parameters
    ----------
    directory : path
        The class folder (``key.csv``, ``teacher.json``).
    submissions : iterable of paths
        Notebooks, CSV answer forms (wide: a ``student`` column and one column per
        question; long: ``student, question, answer``), JSON dicts, or folders of them.
    execute : bool
        Run each notebook in a fresh kernel, in its sandbox, before reading
        ``answers`` (default); with False the answers are read from the saved cell
        (its literal values, or its saved output).
    timeout : float, optional
        Seconds allowed per notebook cell (default: the limits', 60).
    jobs : int, optional
        Notebooks run at the same time, in processes (default: the cores, at most 4).
    executor : concurrent.futures.Executor, optional
        Read the submissions through this executor instead (a dask
        ``Client.get_executor()``); each notebook still runs in its own sandbox.
    on_error : {"saved", "zero"}
        A notebook that does not run (a cell raises, runs too long, hits a limit):
        graded on its answers cell as saved, flagged (default), or broken and 0.
    unit_slip_credit : float
        Credit 0..1 of an answer that is a unit or a sign slip (default 0).
    prefer : iterable of paths
        Files (or folders) to keep when a student handed in several; otherwise the
        newest readable one by modification time is kept.
    limits : Limits, optional
        What a notebook may use in its sandbox (:class:`Limits`).
    unsandboxed : bool
        Run the notebooks as the grader's user, with no isolation (only where
        bubblewrap cannot run; every summary row says so).
    hide : iterable of paths
        More paths no kernel may see (the grades files to be written); the class
        folder and the submissions are hidden always.

    Returns
    -------
    ClassReport
        ``graded`` (:data:`COLUMNS`: one row per student and question, then one row per
        submission not graded: unknown id, broken without an id, duplicate not kept),
        ``scores`` (:data:`SUMMARY`: one row per student of the class, then one per
        unknown id), the lists ``broken, unknown, missing, duplicates, conflicts``
        (ids in one file that disagree), ``flags`` (student -> flags) and
        ``sandbox`` (what the notebooks ran in).

    Raises
    ------
    SandboxUnavailable
        Notebooks are to run and bubblewrap cannot (one line: how to install it, and
        ``unsandboxed``).
    """
    if on_error not in ON_ERROR:
        raise WorkbenchError(f"on_error {on_error!r}: give one of {', '.join(ON_ERROR)}")
    d = Path(directory)
    key, canon = _read_key(d)
    rep = ClassReport(graded=pd.DataFrame(columns=COLUMNS),
                      scores=pd.DataFrame(columns=SUMMARY), exercise=_exercise_name(d))
    own = {(d / n).resolve() for n in ("key.csv", "variants.csv", "teacher.json")}
    subs = list(submissions)
    files = [p for p in _expand(subs) if p.resolve() not in own]   # never the key
    if timeout is not None:
        limits = dataclasses.replace(limits or Limits(), cell_seconds=float(timeout))
    sandbox = None
    if execute and not unsandboxed and any(p.suffix.lower() == ".ipynb" for p in files):
        sandbox = sandbox_or_refuse(limits, [d, *subs, *hide])
    rep.sandbox = ("bubblewrap: " + sandbox.limits.describe() if sandbox else
                   UNSANDBOXED if execute and unsandboxed else "")
    cell = (limits or Limits()).cell_seconds
    results = _read_all([(str(p), execute, cell, on_error, sandbox) for p in files],
                        jobs, executor, execute)
    entries, extra = _entries(results, canon, rep)
    got, failed, flags = _keep(entries, [Path(p).resolve() for p in prefer], rep, extra)
    parts = []
    if got:
        graded = _grade_kept(got, key, unit_slip_credit)
        for s, fl in find_copies(graded, key).items():
            flags.setdefault(s, []).extend(fl)
        parts.append(graded)
    zero = key[~key["student"].isin(list(got))]
    if not zero.empty:
        parts.append(_zero_rows(zero, failed, flags))
    g = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=COLUMNS)
    order = {s: k for k, s in enumerate(canon.values())}
    g = g.sort_values("student", key=lambda c: c.map(order), kind="stable")
    g["flags"] = g["student"].map(lambda s: "; ".join(flags.get(s, [])))
    rec = pd.DataFrame(extra, columns=["student", "source", "status"]).assign(
        question="", passed=False, points=0.0, note="", flags="")
    rep.graded = pd.concat([g, rec], ignore_index=True)[COLUMNS] if extra else g[COLUMNS]
    rep.graded = rep.graded.reset_index(drop=True)
    rep.flags = flags
    rep.missing = [s for s in canon.values() if s not in got and s not in failed]
    ran = {e["student"]: e["sandbox"] for e in [*got.values(), *failed.values()]}
    rep.scores = _summary(g, flags, ran, extra)
    return rep


UNSANDBOXED = ("none (--unsandboxed): the notebooks ran as the teacher, with no isolation")


def _read_key(d: Path) -> tuple[pd.DataFrame, dict[str, str]]:
    if not (d / "key.csv").is_file():
        raise WorkbenchError(f"{d}: no key.csv; give the folder written by "
                             "'exercises generate'")
    key = pd.read_csv(d / "key.csv", dtype={"student": str}, keep_default_na=False,
                      na_values={"expected": [""], "atol": [""], "rtol": [""]})
    return key, {normalize_id(s): s for s in dict.fromkeys(key["student"])}


def _exercise_name(d: Path) -> str:
    meta = d / "teacher.json"
    if not meta.is_file():
        return ""
    import json

    return str(json.loads(meta.read_text(encoding="utf-8")).get("exercise", ""))


def _entries(results: list[dict], canon: dict[str, str], rep: ClassReport
             ) -> tuple[list[dict], list[dict]]:
    """One entry per graded part or broken file of a known student, and the rows of
    the submissions not graded (unknown ids, broken without a known id)."""
    def known_of(ids):
        return list(dict.fromkeys(canon[normalize_id(i)] for i in ids
                                  if i is not None and normalize_id(i) in canon))

    entries: list[dict] = []
    extra: list[dict] = []
    for res in results:
        ran = res.get("sandbox", "")
        if res["parts"] is None:
            known = known_of(res["ids"])
            sid = known[0] if known else None
            rep.broken.append({"file": res["file"], "student": sid, "reason": res["reason"]})
            if sid is None:
                extra.append({"student": (res["ids"] or [""])[0], "source": res["file"],
                              "status": f"broken, not graded (no known id): {res['reason']}"})
            else:
                entries.append({"file": res["file"], "mtime": res["mtime"], "student": sid,
                                "answers": None, "flags": [], "reason": res["reason"],
                                "sandbox": ran})
            continue
        for part in res["parts"]:
            ids = [str(i) for i in part["ids"] if i is not None and str(i).strip()]
            known = known_of(ids)
            rep.submissions.append({"file": res["file"], "ids": ids})
            if len(known) > 1 or (known and len({normalize_id(i) for i in ids}) > 1):
                rep.conflicts.append({"file": res["file"], "ids": ids,
                                      "graded_as": known[0] if known else None})
            if not known:
                who = ids[0] if ids else "(no id)"
                rep.unknown.append({"file": res["file"], "student": who})
                extra.append({"student": who, "source": res["file"],
                              "status": "unknown id: not in the class list, not graded"})
                continue
            entries.append({"file": res["file"], "mtime": res["mtime"], "student": known[0],
                            "answers": part["answers"], "flags": list(part["flags"]),
                            "reason": "", "sandbox": ran})
    return entries, extra


def _keep(entries: list[dict], prefer: list[Path], rep: ClassReport, extra: list[dict]
          ) -> tuple[dict[str, dict], dict[str, dict], dict[str, list[str]]]:
    """The submission kept per student (readable, or broken), and the flags so far;
    the duplicates not kept are put on record in ``extra`` and named in the flags."""
    by: dict[str, list[dict]] = defaultdict(list)
    for e in entries:
        by[e["student"]].append(e)
    got: dict[str, dict] = {}
    failed: dict[str, dict] = {}
    flags: dict[str, list[str]] = {}
    for sid, es in by.items():
        kept, why = _choose(es, prefer)
        if len(es) > 1:
            rep.duplicates.append({"student": sid, "files": [e["file"] for e in es],
                                   "kept": kept["file"], "why": why})
            flags.setdefault(sid, []).append(f"{len(es)} submissions: kept {kept['file']} "
                                             f"({why})")
            for e in es:
                if e is not kept:
                    extra.append({"student": sid, "source": e["file"],
                                  "status": f"duplicate, not graded: kept {kept['file']} "
                                            f"({why})"})
        (got if kept["answers"] is not None else failed)[sid] = kept
        flags.setdefault(sid, []).extend(kept["flags"])
        if kept["answers"] is None:
            flags[sid].append(f"did not run: {kept['reason']} (graded 0)")
    return got, failed, {s: f for s, f in flags.items() if f}


def _grade_kept(got: dict[str, dict], key: pd.DataFrame, credit: float) -> pd.DataFrame:
    # one empty row per student too: an answers cell that holds nothing is graded
    # (every question missing), not dropped
    long = pd.DataFrame([{"student": s, "question": q, "answer": a}
                         for s, e in got.items()
                         for q, a in [("", None), *e["answers"].items()]],
                        columns=["student", "question", "answer"])
    graded, _ = grade(long, key[key["student"].isin(list(got))], unit_slip_credit=credit)
    graded["source"] = graded["student"].map({s: e["file"] for s, e in got.items()})
    return graded


def _zero_rows(zero: pd.DataFrame, failed: dict[str, dict],
               flags: dict[str, list[str]]) -> pd.DataFrame:
    status = [("broken: " + failed[s]["reason"]) if s in failed else "no submission"
              for s in zero["student"]]
    for s in dict.fromkeys(zero["student"]):
        if s not in failed:
            flags.setdefault(s, []).append("no submission")
    return pd.DataFrame({
        "student": zero["student"], "question": zero["question"],
        "expected": zero["expected"], "answer": np.nan, "unit": zero["unit"],
        "error": np.nan, "tolerance": _tolerance(zero), "passed": False, "points": 0.0,
        "status": status, "note": "",
        "source": [failed[s]["file"] if s in failed else "" for s in zero["student"]]})


def _slip_flags(grp: pd.DataFrame) -> list[str]:
    out = []
    for kind in ("unit", "sign"):
        hit = grp[grp.status.str.contains(kind + " slip") |
                  (grp.status == "unit and sign slip")]
        if len(hit):
            out.append(f"{kind} slip: " + ", ".join(hit.question))
    return out


def _summary(g: pd.DataFrame, flags: dict[str, list[str]], ran: dict[str, str],
             extra: list[dict]) -> pd.DataFrame:
    rows = []
    for s, grp in g.groupby("student", sort=False):
        bad = grp.loc[~grp.passed.astype(bool)]
        st = grp.status.astype(str)
        rows.append({"student": s, "score %": percent(grp.points.sum(), len(grp)),
                     "points": float(grp.points.sum()), "total": int(len(grp)),
                     "passed": int(grp.passed.sum()),
                     "unit slips": int(st.isin(["unit slip", "unit and sign slip"]).sum()),
                     "sign slips": int(st.isin(["sign slip", "unit and sign slip"]).sum()),
                     "flags": "; ".join(_slip_flags(grp) + flags.get(s, [])),
                     "failed": ", ".join(f"{q} ({n})" if n else q
                                         for q, n in zip(bad.question, bad.note, strict=True)),
                     "source": grp["source"].iloc[0], "sandbox": ran.get(s, "")})
    for x in extra:
        if not x["status"].startswith("duplicate"):
            rows.append({"student": x["student"], "score %": np.nan, "points": np.nan,
                         "total": 0, "passed": 0, "unit slips": 0, "sign slips": 0,
                         "flags": x["status"], "failed": "", "source": x["source"],
                         "sandbox": ""})
    return pd.DataFrame(rows, columns=SUMMARY)


def percent(points: float, total: int) -> float:
    """``100 points / total`` rounded to one decimal half up (the gradebooks' rule:
    62.25 -> 62.3, where Python's round gives 62.2), from the decimal value of the
    points, not its binary neighbour."""
    if total <= 0:
        return float("nan")
    x = Decimal(repr(float(points))) * 100 / Decimal(int(total))
    return float(x.quantize(Decimal("0.1"), rounding=ROUND_HALF_UP))
