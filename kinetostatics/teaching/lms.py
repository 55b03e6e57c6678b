"""Per-student totals in the column layout of a learning platform's gradebook import.

- Moodle (Grades > Import > CSV file): an identifier column and a grade column; in the
  import dialog map ``ID number`` to the user field holding the class list's ids
  (ID number, username or email) and the grade column to the assignment.
- Canvas (Grades > Import): ``Student, ID, SIS User ID, Section`` and then one column
  per assignment; the class list's id goes into ``SIS User ID`` (``ID``, Canvas's own
  number, is left empty: Canvas matches on either).

The grade is the score in percent (0-100, one decimal): set the assignment's maximum
to 100 points.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pandas as pd

from ..model.errors import WorkbenchError
from ..model.outputs import atomic_file

__all__ = ["LMS", "lms_table", "write_lms"]

LMS = ("moodle", "canvas")


def lms_table(scores: pd.DataFrame, lms: str, assignment: str) -> pd.DataFrame:
    """The gradebook import table of one assignment.

    Parameters
    ----------
    scores : DataFrame
        ``ClassReport.scores`` (``student`` and ``score %``).
    lms : {"moodle", "canvas"}
        The platform.
    assignment : str
        The grade column's name (the assignment's name in the gradebook).

    Returns
    -------
    DataFrame
        Moodle: ``ID number, <assignment>``; Canvas: ``Student, ID, SIS User ID,
        Section, <assignment>``. One row per student of the class.
    """
    kind = str(lms).strip().lower()
    if kind not in LMS:
        raise WorkbenchError(f"--lms {lms!r}: give one of {', '.join(LMS)}")
    ids = scores["student"].astype(str).tolist()
    grade = [round(float(x), 1) for x in scores["score %"]]
    if kind == "moodle":
        return pd.DataFrame({"ID number": ids, assignment: grade})
    return pd.DataFrame({"Student": ids, "ID": [""] * len(ids), "SIS User ID": ids,
                         "Section": [""] * len(ids), assignment: grade})


def write_lms(scores: pd.DataFrame, lms: str, path: Any, assignment: str) -> Path:
    """Write :func:`lms_table` as a UTF-8 CSV file (ids with accents kept)."""
    p = Path(path)
    with atomic_file(p) as tmp:             # the whole file, or the earlier one kept
        lms_table(scores, lms, assignment).to_csv(tmp, index=False, encoding="utf-8")
    return p
