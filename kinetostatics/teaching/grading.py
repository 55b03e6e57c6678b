"""Grading: answers against a key, at stated tolerances, angles modulo 360.

A number passes when |answer - key| <= max(rtol |key|, atol) (rtol 1 % by default; the
key's atol is 1e-3 of the quantity's largest magnitude over the cycle, so that a value
near zero is not judged by its relative error alone); an angle passes when the
difference, wrapped into (-180, 180], is at most 0.5 deg.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from decimal import ROUND_HALF_UP, Decimal
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import WorkbenchError
from .answers import read_answers
from .questions import ANGLE_ATOL, DEFAULT_RTOL, normalize_id, var_name, wrap_angle
from .slips import answer_value, slip_note, slip_status

__all__ = ["class_table", "grade"]


# ------------------------------------------------------------------------- grading
def _is_exercise(key: Any) -> bool:
    """An :class:`~kinetostatics.teaching.Exercise` (computes the key of given ids)."""
    return callable(getattr(key, "answer_key", None)) and callable(getattr(key, "key", None))


def _key_table(key: Any, students: Sequence[str]) -> pd.DataFrame:
    if _is_exercise(key):
        return key.key(students)
    if isinstance(getattr(key, "key", None), pd.DataFrame):     # an ExerciseSet
        return key.key
    if isinstance(key, pd.DataFrame):
        k = key.copy()
        if "expected" not in k.columns:
            raise WorkbenchError("key table: needs columns question, expected (and student)")
        if "student" not in k.columns:
            k["student"] = ""
        return k
    if isinstance(key, Mapping):
        sid = students[0] if len(students) == 1 else ""
        return pd.DataFrame([{"student": sid, "question": q, "expected": float(v)}
                             for q, v in key.items()])
    raise WorkbenchError(f"key must be an Exercise, an ExerciseSet, a DataFrame or a dict, not "
                         f"{type(key).__name__}")


def grade(answers: Any, key: Any, *, rtol: float | None = None, atol: float | None = None,
          angle_keys: Iterable[str] = (), angle_atol: float | None = None,
          student: Any = None, unit_slip_credit: float = 0.0) -> tuple[pd.DataFrame, dict]:
    """Grade answers against a key.

    Parameters
    ----------
    answers : dict, DataFrame, path or list
        See :func:`read_answers`.
    key : Exercise, ExerciseSet, DataFrame or dict
        An :class:`Exercise` (the key of every student who answered is computed), a
        set or key table (``student, question, expected`` and optionally ``kind, rtol,
        atol``), or a dict ``{question: value}`` for one student.
    rtol, atol : float, optional
        Override the key's tolerances for numbers: pass when |answer - key| <=
        max(rtol |key|, atol) (defaults: the key's, else rtol 1 %, atol 0).
    angle_keys : iterable of str
        Questions to compare as angles, besides those the key marks ``kind == "angle"``.
    angle_atol : float, optional
        Tolerance of angles in degrees (default: the key's, else 0.5); the difference
        is wrapped into (-180, 180] first, so 330 and -30 are the same answer.
    student : optional
        The id, when ``answers`` is one student's dict without ``student_id``.
    unit_slip_credit : float
        Credit (0..1) of a wrong answer that is a unit slip (see
        :mod:`~kinetostatics.teaching.slips`): 1000x the key of a moment in N m, an
        angle in rad for deg, a flipped sign... (default 0: named, not credited).

    Returns
    -------
    graded : DataFrame
        One row per student and question: ``student, question, expected, answer, unit,
        error`` (answer - expected, wrapped for angles), ``tolerance, passed, points``
        (1 when passed, ``unit_slip_credit`` for a unit slip, else 0), ``status``
        (``ok``, ``wrong``, ``unit slip``, ``missing``, ``not a number``) and ``note``
        (the slip named, an answer read with its unit). Answers written with a unit
        (``"300800 N mm"``) are converted to the key's unit first.
    summary : dict
        ``students, items, passed, failed, missing, score`` (fraction passed),
        ``per_student`` {id: {passed, total, score, failed: [questions]}},
        ``missing_students`` (in the key, no answer), ``unknown_students`` (answers
        but not in the key), ``unknown_questions`` (answered but not asked).
    """
    if not 0.0 <= float(unit_slip_credit) <= 1.0:
        raise WorkbenchError(f"unit slip credit {unit_slip_credit!r}: give a number in 0..1")
    ans = read_answers(answers, student)
    kt, ans = _matched(key, ans, set(angle_keys))
    key_students = list(dict.fromkeys(kt["student"]))
    students = list(dict.fromkeys(ans["student"]))
    graded_students = [s for s in key_students if s in set(ans["student"])]
    kt = kt[kt["student"].isin(graded_students)]
    m = kt.merge(ans, on=["student", "question"], how="left")
    exp = m["expected"].to_numpy(dtype=float)
    units = m["unit"].fillna("").astype(str)
    read = [answer_value(a, u) for a, u in zip(m["answer"], units, strict=True)]
    got = np.array([r[0] for r in read], dtype=float)
    notes = [r[1] for r in read]
    is_angle = (m["kind"] == "angle").to_numpy()
    tol = _tolerance(m, is_angle, rtol, atol, angle_atol)
    err = np.where(is_angle, wrap_angle(got - exp), got - exp)
    with np.errstate(invalid="ignore"):
        passed = np.abs(err) <= tol
    passed &= ~np.isnan(got)
    missing = m["answer"].isna().to_numpy() | np.array(
        [isinstance(x, float) and math.isnan(x) for x in m["answer"]], dtype=bool)
    status = np.where(passed, "ok", np.where(missing, "missing",
                                             np.where(np.isnan(got), "not a number", "wrong")))
    status = np.where([("the question asks for" in n) for n in notes], "wrong unit", status)
    status = status.astype(object)
    points = passed.astype(float)
    kinds = np.where(is_angle, "angle", "number")
    for i in np.flatnonzero(status == "wrong"):
        slip = slip_note(str(m["question"].iat[i]), str(units.iat[i]), str(kinds[i]),
                         float(got[i]), float(exp[i]), float(tol[i]))
        if slip:
            status[i], points[i] = slip_status(slip), float(unit_slip_credit)
            notes[i] = "; ".join(filter(None, [slip, notes[i]]))
    graded = pd.DataFrame({
        "student": m["student"], "question": m["question"], "expected": exp,
        "answer": got, "unit": m["unit"].fillna(""), "error": err, "tolerance": tol,
        "passed": passed, "points": points, "status": status.astype(str), "note": notes})
    st = graded.status
    summary = {
        "students": len(graded_students), "items": int(len(graded)),
        "passed": int(graded.passed.sum()),
        "failed": int(st.isin(["wrong", "not a number", "wrong unit", *SLIP_STATUSES]).sum()),
        "missing": int((st == "missing").sum()),
        "unit_slips": int(st.isin(["unit slip", "unit and sign slip"]).sum()),
        "sign_slips": int(st.isin(["sign slip", "unit and sign slip"]).sum()),
        "score": float(graded.points.mean()) if len(graded) else 0.0,
        "per_student": _per_student(graded),
        "missing_students": [s for s in key_students if s not in set(ans["student"])],
        "unknown_students": [s for s in students if s not in set(key_students)],
        "unknown_questions": sorted({q for q in ans["question"]
                                     if q not in set(kt["question"])}),
    }
    return graded, summary


SLIP_STATUSES = ("unit slip", "sign slip", "unit and sign slip")
"""The statuses of a slip (credited ``unit_slip_credit``)."""


def _matched(key: Any, ans: pd.DataFrame, angle_keys: set[str]
             ) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The key table (kind, unit, tolerances filled) and the answers, their questions
    and ids matched to the key's."""
    students = list(dict.fromkeys(ans["student"].astype(str)))
    if isinstance(key, Mapping) and not isinstance(key, pd.DataFrame) and len(students) > 1:
        raise WorkbenchError("a dict key is one student's: grade one student at a time, or "
                             "give an Exercise / key table")
    if _is_exercise(key):
        known = [s for s in students if s]
        if not known:
            raise WorkbenchError("the answers carry no student id: give student=..., or a "
                                 "'student_id' in the answers")
        kt = _key_table(key, known)
    else:
        kt = _key_table(key, students)
    kt = kt.copy()
    kt["student"] = kt["student"].astype(str)
    if isinstance(key, Mapping) and len(students) == 1:
        kt["student"] = students[0]
    if (kt["student"] == "").all() and len(students) == 1:
        kt["student"] = students[0]
    if "kind" not in kt.columns:
        kt["kind"] = "number"
    kt.loc[kt["question"].isin(angle_keys), "kind"] = "angle"
    for c, default in (("unit", ""), ("rtol", np.nan), ("atol", np.nan)):
        if c not in kt.columns:
            kt[c] = default
    # answers given as variables named by var_name(question)
    names = {var_name(q): q for q in kt["question"].unique()}
    ans = ans.copy()
    ans["question"] = [names.get(q, q) if q not in set(kt["question"]) else q
                       for q in ans["question"].astype(str)]
    # ids match after trimming and case-folding: " S001" answers for "s001"
    canon = {normalize_id(k): k for k in kt["student"]}
    ans["student"] = [canon.get(normalize_id(a), a) for a in ans["student"].astype(str)]
    return kt, ans.drop_duplicates(["student", "question"], keep="last")


def _tolerance(m: pd.DataFrame, is_angle: np.ndarray, rtol, atol, angle_atol) -> np.ndarray:
    """Each row's tolerance: max(rtol |key|, atol) for numbers, the angle's atol."""
    exp = m["expected"].to_numpy(dtype=float)
    key_atol = m["atol"].to_numpy(dtype=float)
    r = np.where(np.isnan(m["rtol"].to_numpy(dtype=float)), DEFAULT_RTOL,
                 m["rtol"].to_numpy(dtype=float))
    a = np.where(np.isnan(key_atol), 0.0, key_atol)
    if rtol is not None:
        r = np.full_like(r, float(rtol))
    if atol is not None:
        a = np.full_like(a, float(atol))
    a_ang = np.where(np.isnan(key_atol), ANGLE_ATOL, key_atol)
    if angle_atol is not None:
        a_ang = np.full_like(a_ang, float(angle_atol))
    return np.where(is_angle, a_ang, np.maximum(a, r * np.abs(exp)))


def _per_student(graded: pd.DataFrame) -> dict[str, dict]:
    per = {}
    for s, g in graded.groupby("student", sort=False):
        per[s] = {"passed": int(g.passed.sum()), "total": int(len(g)),
                  "points": float(g.points.sum()),
                  "score": float(g.points.mean()) if len(g) else 0.0,
                  "failed": g.loc[~g.passed, "question"].tolist()}
    return per


def _percent(passed: int, total: int) -> float:
    """Percent to one decimal, half up (the gradebooks' rule)."""
    if not total:
        return float("nan")
    return float((Decimal(100 * passed) / total).quantize(Decimal("0.1"), ROUND_HALF_UP))


def class_table(graded: pd.DataFrame) -> pd.DataFrame:
    """The class at a glance.

    Parameters
    ----------
    graded : DataFrame
        The first result of :func:`grade`.

    Returns
    -------
    DataFrame
        One row per student: ``passed, total, score %`` and the ``failed`` questions.
    """
    rows = []
    for s, g in graded.groupby("student", sort=False):
        rows.append({"student": s, "passed": int(g.passed.sum()), "total": int(len(g)),
                     "score %": _percent(int(g.passed.sum()), len(g)),
                     "failed": ", ".join(g.loc[~g.passed, "question"])})
    return pd.DataFrame(rows, columns=["student", "passed", "total", "score %", "failed"])

