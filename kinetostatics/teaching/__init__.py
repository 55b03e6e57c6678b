"""Exercises: variants per student, answer keys, reading answers and grading.

``questions`` (the question language, units, tolerances), ``keys`` (answer keys with
:func:`kinetostatics.solve` or :func:`balance.solve`), ``variants`` (an exercise's
draws per student and the class set), ``answers`` (reading dicts, tables and notebooks),
``grading`` (answers against the key), ``slips`` (unit slips, answers with units),
``library`` (the ready exercises), ``sheets`` (what a student receives), ``handouts``
(the handout's picture and PDF), ``execute`` (running a submitted notebook),
``sandbox`` (the bubblewrap sandbox a graded kernel runs in, and its limits),
``kernels`` (the grader's side of a graded kernel), ``submissions`` (reading one
submission), ``copies`` (answers of another variant),
``gradebook`` (grading a class folder), ``lms`` (gradebook imports), ``classroom``
(the teacher's class folder) and ``cli`` (the ``exercises`` command).
"""

from __future__ import annotations

from .answers import (
    AnswerSheet,
    fill_answer_cell,
    notebook_answers,
    read_answers,
    record,
    saved_answers,
    write_answer_notebook,
)
from .classroom import ClassReport, generate_class, grade_class, read_class_list
from .copies import find_copies
from .grading import class_table, grade
from .keys import answer_key
from .library import (
    EXERCISES,
    exercise,
    four_bar_exercise,
    list_exercises,
    resonance_exercise,
    rotor_exercise,
    slider_crank_exercise,
    slotted_lever_exercise,
)
from .lms import lms_table, write_lms
from .questions import (
    ANGLE_ATOL,
    ANSWER_TAG,
    ATOL_FRACTION,
    DEFAULT_RTOL,
    TOLERANCE_RULE,
    normalize_id,
    to_float,
    var_name,
    wrap_angle,
)
from .sandbox import Limits, Sandbox, SandboxUnavailable, sandbox_or_refuse
from .slips import answer_value, slip_note
from .variants import Exercise, ExerciseSet, generate

__all__ = [
    "ANGLE_ATOL", "ANSWER_TAG", "ATOL_FRACTION", "DEFAULT_RTOL", "EXERCISES", "ClassReport",
    "generate_class", "grade_class", "read_class_list", "answer_value", "find_copies",
    "lms_table", "saved_answers", "slip_note", "write_lms", "Limits", "Sandbox",
    "SandboxUnavailable", "sandbox_or_refuse",
    "TOLERANCE_RULE", "answer_key", "AnswerSheet", "class_table", "Exercise", "exercise",
    "ExerciseSet", "fill_answer_cell", "four_bar_exercise", "generate", "grade",
    "list_exercises", "normalize_id", "notebook_answers", "read_answers", "record",
    "resonance_exercise", "rotor_exercise", "slider_crank_exercise",
    "slotted_lever_exercise", "to_float", "var_name", "wrap_angle", "write_answer_notebook",
]
