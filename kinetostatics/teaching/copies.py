"""Copies: answers that belong to another student's variant.

Two signs, both flagged, never penalised (the teacher decides):

- a submission whose *wrong* answers match another student's key, within that key's
  tolerance, for at least half of the questions (and at least two): the numbers were
  computed for the other student's variant;
- two submissions with the same answers (to 6 significant digits, at least two of
  them) for different variants.
"""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np
import pandas as pd

from .questions import wrap_angle

__all__ = ["find_copies"]


def _tolerances(key: pd.DataFrame) -> pd.Series:
    rtol = key["rtol"].fillna(0.0).to_numpy(dtype=float)
    atol = key["atol"].fillna(0.0).to_numpy(dtype=float)
    exp = key["expected"].to_numpy(dtype=float)
    ang = (key["kind"] == "angle").to_numpy()
    return pd.Series(np.where(ang, atol, np.maximum(atol, rtol * np.abs(exp))), index=key.index)


def find_copies(graded: pd.DataFrame, key: pd.DataFrame, *,
                share: float = 0.5) -> dict[str, list[str]]:
    """Flags of copied work, per student.

    Parameters
    ----------
    graded : DataFrame
        Graded rows (``student, question, answer, passed``) of the submissions.
    key : DataFrame
        The class's key (``student, question, expected, kind, rtol, atol``).
    share : float
        The fraction of the questions whose wrong answers must match another key.

    Returns
    -------
    dict
        student -> flags, e.g. ``["copy? 7 of 8 answers are the key of 'ana', not
        their own"]``, ``["same answers as 'ion' (another variant)"]``.
    """
    out: dict[str, list[str]] = defaultdict(list)
    if graded.empty or key.empty:
        return {}
    key = key.assign(tol=_tolerances(key))
    questions = list(dict.fromkeys(key["question"]))
    ks = list(dict.fromkeys(key["student"]))
    K = key.pivot(index="student", columns="question", values="expected").reindex(
        index=ks, columns=questions).to_numpy(dtype=float)
    T = key.pivot(index="student", columns="question", values="tol").reindex(
        index=ks, columns=questions).to_numpy(dtype=float)
    kinds = key.drop_duplicates("question").set_index("question")["kind"]
    ang = np.array([kinds.get(q) == "angle" for q in questions])
    subs = list(dict.fromkeys(graded["student"]))
    A = graded.pivot_table(index="student", columns="question", values="answer",
                           aggfunc="last", dropna=False).reindex(index=subs, columns=questions)
    A = A.to_numpy(dtype=float)
    P = graded.pivot_table(index="student", columns="question", values="passed",
                           aggfunc="last").reindex(index=subs, columns=questions)
    P = P.fillna(False).to_numpy(dtype=bool)
    nq = len(questions)
    need = max(2, math.ceil(share * nq))
    row = {s: k for k, s in enumerate(ks)}
    for i, s in enumerate(subs):
        wrong = ~P[i] & np.isfinite(A[i])
        if wrong.sum() < need:
            continue
        d = A[i][None, :] - K
        d = np.where(ang[None, :], wrap_angle(d), d)
        with np.errstate(invalid="ignore"):
            hit = (np.abs(d) <= T) & wrong[None, :]
        count = hit.sum(axis=1)
        if s in row:
            count[row[s]] = 0
        t = int(np.argmax(count))
        if count[t] >= need:
            out[s].append(f"copy? {int(count[t])} of {nq} answers are the key of "
                          f"{ks[t]!r}, not their own")
    # the same answers for different variants
    groups: dict[tuple, list[str]] = defaultdict(list)
    for i, s in enumerate(subs):
        ok = np.isfinite(A[i])
        if ok.sum() < 2:
            continue
        sig = tuple(float(f"{v:.6g}") if f else None for v, f in zip(A[i], ok, strict=True))
        groups[sig].append(s)
    for members in groups.values():
        if len(members) < 2:
            continue
        for s in members:
            others = [t for t in members if t != s and not _same_variant(K, T, row, s, t)]
            if others:
                out[s].append("same answers as " + ", ".join(repr(t) for t in others)
                              + " (another variant)")
    return dict(out)


def _same_variant(K: np.ndarray, T: np.ndarray, row: dict, s: str, t: str) -> bool:
    if s not in row or t not in row:
        return False
    a, b = K[row[s]], K[row[t]]
    return bool(np.all(np.abs(a - b) <= np.minimum(T[row[s]], T[row[t]]) * 1e-6))
