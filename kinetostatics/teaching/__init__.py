"""Exercises: variants per student, answer keys, reading answers and grading.
"""

from __future__ import annotations

