"""What a student receives: the sealed notebook and the printable handout.

A student's notebook holds the student's own data, the task, and one code cell tagged
``answers`` (an nbgrader solution cell too) that assigns ``answers = {question: None,
...}``; it holds no solution, no expected value and no seed. The handout is one HTML
page with the same data (rounded to the digits that were drawn, with units) and the
questions with their units and tolerances. :func:`leaked_values` says which key
values (to 4 significant digits) can be read in a text: a variant whose sheets would
show one is drawn again (see :class:`~kinetostatics.teaching.Exercise`).
"""

from __future__ import annotations

import html
import json
import math
import re
from collections.abc import Mapping
from typing import Any

import numpy as np

from .questions import ANSWER_TAG, TOLERANCE_RULE, describe, tolerance_text, wrap_angle

__all__ = ["data_rows", "format_value", "handout_html", "key_values", "leaked_values",
           "question_rows", "student_notebook", "visible_text"]

_NUM = re.compile(r"\d+(?:\.\d*)?(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?")


def format_value(v: Any) -> str:
    """A datum with the digits it was drawn with: the shortest positional form that reads
    back as the same float (``0.115``, ``250``, ``0.002``); ``.6g`` if that is long."""
    if isinstance(v, str):
        return v
    x = float(v)
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    s = np.format_float_positional(x, trim="-")
    return s if len(s) <= 12 else f"{x:.6g}"


def _sig4(x: float) -> str:
    return f"{abs(x):.4g}"


def leaked_values(text: str, values: Mapping[str, float],
                  angles: frozenset[str] | set[str] = frozenset()) -> list[str]:
    """The questions whose key value can be read in ``text`` to 4 significant digits.

    Parameters
    ----------
    text : str
        What the student sees (the notebook's JSON, the handout's HTML).
    values : dict
        question -> key value.
    angles : set of str
        Questions that are angles: their value minus 360 counts too.

    Returns
    -------
    list of str
        A question leaks when a number written in the text equals its value to 4
        significant digits, or when the value's 4-digit form (``f"{abs(v):.4g}"``)
        appears anywhere in the text, even inside a longer number.
    """
    shown = set()
    for tok in set(_NUM.findall(text)):     # each distinct token once (a PNG's base64
        try:                                # text repeats short digit runs many times)
            shown.add(_sig4(float(tok)))
        except (ValueError, OverflowError):
            continue
    out = []
    for q, v in values.items():
        forms = {_sig4(v)}
        if q in angles:
            forms.add(_sig4(float(wrap_angle(v))))
        for s in forms:
            if s in shown or s in text:
                out.append(q)
                break
    return out


def data_rows(exercise, variant: Mapping) -> list[dict]:
    """The data a student sees: ``symbol, value, unit, meaning`` per row."""
    if exercise.data is not None:
        rows = exercise.data(dict(variant["params"]), variant["scene"])
    else:
        rows = [(k, v, "", "") for k, v in variant["params"].items()]
    return [{"symbol": str(r[0]), "value": r[1], "unit": str(r[2]),
             "meaning": str(r[3]) if len(r) > 3 else ""} for r in rows]


def question_rows(exercise, variant: Mapping) -> list[dict]:
    """The questions as a student reads them: ``question, asked, unit, tolerance``."""
    out = []
    for q in exercise.questions:
        _, unit, kind, _ = variant["rows"][q]
        words = exercise.labels.get(q) or describe(q, exercise.position)
        rtol = 0.0 if kind == "angle" else exercise.rtol
        out.append({"question": q, "asked": words, "unit": unit,
                    "tolerance": tolerance_text(q, unit, rtol, kind)})
    return out


def _md_table(head: list[str], rows: list[list[str]]) -> str:
    esc = [[str(c).replace("|", "\\|") for c in r] for r in rows]
    return "\n".join(["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
                     + ["| " + " | ".join(r) + " |" for r in esc])


def _literal(obj: Any) -> str:
    """A Python literal of JSON-like data: a dict one key per line, a list of tables one
    table per line, everything else compact."""
    one = repr
    if not isinstance(obj, dict):
        return one(obj)
    lines = ["{"]
    for k, v in obj.items():
        if isinstance(v, list) and v and all(isinstance(i, dict) for i in v):
            lines.append(f"    {one(k)}: [")
            lines += [f"        {one(i)}," for i in v]
            lines.append("    ],")
        else:
            lines.append(f"    {one(k)}: {one(v)},")
    lines.append("}")
    return "\n".join(lines)


def _cell(kind: str, source: str, grade_id: str, *, locked: bool = True,
          solution: bool = False, tags: list[str] | None = None):
    import nbformat

    new = nbformat.v4.new_code_cell if kind == "code" else nbformat.v4.new_markdown_cell
    cell = new(source)
    cell["id"] = grade_id.replace("_", "-")
    cell.metadata["nbgrader"] = {"grade": False, "grade_id": grade_id, "locked": locked,
                                 "schema_version": 3, "solution": solution, "task": False}
    if tags:
        cell.metadata["tags"] = list(tags)
    return cell


def _statement(exercise, student: str, variant: Mapping) -> str:
    data = data_rows(exercise, variant)
    qs = question_rows(exercise, variant)
    return "\n\n".join([
        f"# {exercise.title}", f"Student: **{student}**", exercise.text,
        "## Your data",
        _md_table(["symbol", "value", "unit", "meaning"],
                  [[d["symbol"], format_value(d["value"]), d["unit"], d["meaning"]]
                   for d in data]),
        "## Questions",
        _md_table(["#", "key in `answers`", "asked", "unit", "tolerance"],
                  [[str(k), f"`{q['question']}`", q["asked"], q["unit"] or "-",
                    q["tolerance"]] for k, q in enumerate(qs, 1)]),
        f"**How the answers are graded.** {TOLERANCE_RULE}",
        "Replace each `None` in the cell marked *answers* by your number (or by the "
        "expression that computes it), run the whole notebook, save it and hand in this "
        "file. Do not change `student_id`."])


def _answers_source(exercise, student: str, variant: Mapping) -> str:
    lines = [f"student_id = {json.dumps(student, ensure_ascii=False)}      # do not change",
             "answers = {"]
    for q in question_rows(exercise, variant):
        unit = f"{q['unit']}: " if q["unit"] else ""
        key = json.dumps(q["question"], ensure_ascii=False)
        lines.append(f"    {key}: None,    # {unit}{q['asked']}")
    lines.append("}")
    return "\n".join(lines)


def student_notebook(exercise, student: str, variant: Mapping):
    """The sealed notebook of one student (an ``nbformat`` notebook, unrun).

    Parameters
    ----------
    exercise : Exercise
        The exercise.
    student : str
        The id.
    variant : dict
        The student's variant (``params, scene, rows``).

    Returns
    -------
    nbformat.NotebookNode
        Cells: statement with data and questions; imports; the data (and the scene, if
        the exercise gives it) with a table; a picture if the exercise has one; a cell
        for the student's work; the ``answers`` cell. Metadata ``kinetostatics``:
        ``student_id`` and ``exercise``.
    """
    import nbformat

    mech = "bodies" in variant["scene"] or "driver" in variant["scene"]
    data = {d["symbol"]: d["value"] for d in data_rows(exercise, variant)}
    units = {d["symbol"]: d["unit"] for d in data_rows(exercise, variant)}
    imports = ["import pandas as pd", "", "import kinetostatics as ks"]
    if not mech:
        imports.append("import balance")
    data_src = [f"data = {_literal(data)}", f"units = {_literal(units)}"]
    if exercise.give_scene:
        data_src.append(f"scene = {_literal(variant['scene'])}   # your "
                        + ("mechanism: ks.solve(scene)" if mech else
                           "scene: balance.solve(scene)"))
    data_src.append('pd.DataFrame({"value": data, "unit": units})')
    cells = [_cell("markdown", _statement(exercise, student, variant), "statement"),
             _cell("code", "\n".join(imports), "imports"),
             _cell("code", "\n".join(data_src), "data")]
    if exercise.picture and exercise.give_scene:
        cells.append(_cell("code", exercise.picture, "picture"))
    cells += [
        _cell("markdown", "## Your work", "work_help"),
        _cell("code", "# your work here", "work", locked=False, solution=True),
        _cell("markdown", "## Your answers", "answers_help"),
        _cell("code", _answers_source(exercise, student, variant), ANSWER_TAG,
              locked=False, solution=True, tags=[ANSWER_TAG]),
    ]
    nb = nbformat.v4.new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"display_name": "Python 3", "language": "python",
                                 "name": "python3"}
    nb.metadata["kinetostatics"] = {"student_id": student, "exercise": exercise.name}
    return nb


_CSS = ("body{font-family:sans-serif;max-width:46em;margin:2em auto;line-height:1.4}"
        "table{border-collapse:collapse;margin:0.5em 0}"
        "td,th{border:1px solid #999;padding:0.2em 0.6em;text-align:left}"
        "td.v{text-align:right;font-family:monospace}img{max-width:100%}")


def handout_html(exercise, student: str, variant: Mapping, picture: str | None = None) -> str:
    """The printable handout of one student: one HTML page (data with units, the
    picture of the student's mechanism when ``picture`` (a ``data:`` URI) is given, the
    questions with units and tolerances, the tolerance rule)."""
    e = html.escape
    # the picture's markup holds no number: the page without it (what the variant's
    # leak check reads, visible_text) shows every number the page with it shows
    fig = "" if not picture else (
        "<h2>Your mechanism</h2>\n<p><img alt='your mechanism at its first position, "
        f"with its dimensions' src='{picture}'></p>\n")
    data = "".join(f"<tr><td>{e(d['symbol'])}</td><td class='v'>{e(format_value(d['value']))}"
                   f"</td><td>{e(d['unit'])}</td><td>{e(d['meaning'])}</td></tr>"
                   for d in data_rows(exercise, variant))
    qs = "".join(f"<tr><td>{k}</td><td><code>{e(q['question'])}</code></td>"
                 f"<td>{e(q['asked'])}</td><td>{e(q['unit'] or '-')}</td>"
                 f"<td>{e(q['tolerance'])}</td><td style='width:8em'></td></tr>"
                 for k, q in enumerate(question_rows(exercise, variant), 1))
    return (f"<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>{e(exercise.title)}"
            f" - {e(student)}</title><style>{_CSS}</style></head><body>\n"
            f"<h1>{e(exercise.title)}</h1>\n<p>Student: <b>{e(student)}</b></p>\n"
            f"<p>{e(exercise.text)}</p>\n<h2>Your data</h2>\n<table><tr><th>symbol</th>"
            f"<th>value</th><th>unit</th><th>meaning</th></tr>{data}</table>\n{fig}"
            f"<h2>Questions</h2>\n<table><tr><th>#</th><th>key</th><th>asked</th>"
            f"<th>unit</th><th>tolerance</th><th>your answer</th></tr>{qs}</table>\n"
            f"<p><b>How the answers are graded.</b> {e(TOLERANCE_RULE)}</p>\n"
            "</body></html>\n")


def visible_text(exercise, student: str, variant: Mapping) -> str:
    """Everything the student receives, as text: the notebook's JSON and the handout."""
    import nbformat

    return nbformat.writes(student_notebook(exercise, student, variant)) + \
        handout_html(exercise, student, variant)


def key_values(variant: Mapping) -> tuple[dict[str, float], set[str]]:
    """question -> key value, and the set of angle questions, of a variant."""
    rows = variant["rows"]
    return ({q: float(v[0]) for q, v in rows.items() if np.isfinite(v[0])},
            {q for q, v in rows.items() if v[2] == "angle"})
