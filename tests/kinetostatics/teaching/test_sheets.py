"""Sheets 10 and 11 are sealed student sheets, exactly as the generator writes them.

Each is the notebook ``exercises generate`` writes for the student ``demo-student``
with the seed below (the seed lives here, in the tests, never in a sheet). Run
unchanged, a sheet scores 0 against that student's key.
"""

from __future__ import annotations

from pathlib import Path

import nbformat
import pytest

from kinetostatics import teaching as T

ROOT = Path(__file__).resolve().parents[3]
SHEETS = {"10_exercise_four_bar": ("four_bar", 20261125),
          "11_exercise_rotor": ("rotor_two_plane", 20261126)}
STUDENT = "demo-student"


def _cells(nb) -> list[tuple]:
    return [(c.cell_type, c.source, c.get("id"), dict(c.metadata)) for c in nb.cells]


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """The class of each sheet's student (its folder), generated once for the two tests
    that read it (0.2-0.4 s of CPU each, measured 2026-11-30)."""
    made: dict[str, Path] = {}

    def make(stem: str) -> Path:
        if stem not in made:
            kind, seed = SHEETS[stem]
            made[stem] = tmp_path_factory.mktemp(stem) / "class"
            T.generate_class(kind, [STUDENT], made[stem], seed=seed)
        return made[stem]
    return make


@pytest.mark.parametrize("stem", SHEETS)
def test_sheet_is_the_generated_student_notebook(stem, generated):
    kind, seed = SHEETS[stem]
    made = nbformat.read(generated(stem) / "students" / f"{STUDENT}.ipynb", as_version=4)
    sheet = nbformat.read(ROOT / "notebooks" / f"{stem}.ipynb", as_version=4)
    assert _cells(sheet) == _cells(made), \
        f"regenerate notebooks/{stem}.ipynb with generate_class({kind!r}, seed={seed})"
    assert sheet.metadata["kinetostatics"] == {"student_id": STUDENT, "exercise": kind}
    text = (ROOT / "notebooks" / f"{stem}.ipynb").read_text(encoding="utf-8")
    assert str(seed) not in text and "BEGIN SOLUTION" not in text


@pytest.mark.parametrize("stem", SHEETS)
def test_sheet_handed_in_unchanged_scores_zero(stem, generated):
    """Read as handed in (not run: each sheet is run once in the suite, by
    tests/test_notebooks.py; the grader's run of an untouched generated sheet, which the
    test above shows these are, scores 0 in test_classroom.py::test_executed_notebooks)."""
    rep = T.grade_class(generated(stem), [ROOT / "notebooks" / f"{stem}.ipynb"],
                        execute=False)
    assert not rep.broken and not rep.unknown and not rep.missing
    assert rep.scores.set_index("student").loc[STUDENT, "score %"] == 0.0
    assert (rep.graded.status == "missing").all()
