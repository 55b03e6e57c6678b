"""Exercises: variants per student, answer keys, reading answers and grading.

``questions`` (the question language, units, tolerances), ``keys`` (answer keys with
:func:`kinetostatics.solve` or :func:`balance.solve`), ``variants`` (an exercise's
draws per student and the class set), ``answers`` (reading dicts, tables and notebooks),
``grading`` (answers against the key) and ``library`` (the ready exercises).
"""

from __future__ import annotations

from .answers import AnswerSheet, read_answers, record, write_answer_notebook
from .grading import class_table, grade
from .keys import answer_key
from .library import four_bar_exercise, rotor_exercise
from .questions import (
    ANGLE_ATOL,
    ANSWER_TAG,
    ATOL_FRACTION,
    DEFAULT_RTOL,
    to_float,
    var_name,
    wrap_angle,
)
from .variants import Exercise, ExerciseSet, generate

__all__ = [
    "ANGLE_ATOL", "ANSWER_TAG", "ATOL_FRACTION", "DEFAULT_RTOL", "AnswerSheet", "Exercise",
    "ExerciseSet", "answer_key", "class_table", "four_bar_exercise", "generate", "grade",
    "read_answers", "record", "rotor_exercise", "to_float", "var_name", "wrap_angle",
    "write_answer_notebook",
]
