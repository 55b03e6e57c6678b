"""Reading students' answers: dicts, tables, CSV and JSON files, filled notebooks."""

from __future__ import annotations

import ast
import json
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from ..model.errors import WorkbenchError
from .questions import ANSWER_TAG, to_float

__all__ = ["AnswerSheet", "fill_answer_cell", "notebook_answers", "read_answers", "record",
           "saved_answers", "write_answer_notebook"]


# ------------------------------------------------------------------ reading answers
@dataclass
class AnswerSheet:
    """A student's answers as shown in a notebook: a table, and a JSON output that
    :func:`read_answers` reads back from the saved notebook."""

    student: str
    answers: dict

    def _clean(self) -> dict:
        return {str(k): (None if (f := to_float(v)) != f else f)
                for k, v in self.answers.items()}

    def _repr_mimebundle_(self, include=None, exclude=None):
        data = {"student_id": self.student, "answers": self._clean()}
        rows = "".join(f"<tr><td>{k}</td><td>{'' if v is None else f'{v:.6g}'}</td></tr>"
                       for k, v in data["answers"].items())
        html = (f"<b>answers of {self.student}</b><table><tr><th>question</th>"
                f"<th>answer</th></tr>{rows}</table>")
        return {"application/json": data, "text/html": html,
                "text/plain": json.dumps(data)}


def record(answers: Mapping[str, Any], student_id: Any) -> AnswerSheet:
    """Show a student's answers in the notebook's answer cell (make it the cell's last
    line): the saved notebook then carries them for :func:`grade`.

    Parameters
    ----------
    answers : dict
        question -> value.
    student_id : str
        The student's id.

    Returns
    -------
    AnswerSheet
        Displays as a table, and as JSON that :func:`read_answers` reads back.
    """
    return AnswerSheet(str(student_id), dict(answers))


def _literal(node: ast.AST) -> Any:
    try:
        return ast.literal_eval(node)
    except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
        raise _NotLiteral from None


class _NotLiteral(Exception):
    pass


def _cell_answers(cell, strict: bool = True) -> tuple | None:
    """(student id, answers) from one answer cell: its JSON output first, else its
    source's literal assignments; with ``strict=False`` (student id, answers, the
    names of the values the cell computes) and no error for computed values."""
    for out in cell.get("outputs", []):
        data = out.get("data", {})
        js = data.get("application/json")
        if isinstance(js, Mapping) and "answers" in js:
            got = (None if js.get("student_id") is None else str(js["student_id"]),
                   dict(js["answers"]))
            return got if strict else (*got, [])
    src = cell.get("source", "")
    src = "".join(src) if isinstance(src, list) else src
    try:
        tree = ast.parse(src)
    except SyntaxError as exc:
        raise WorkbenchError(f"the answer cell is not valid Python ({exc.msg}, line "
                             f"{exc.lineno})") from None
    student, answers, computed = None, {}, []
    for node in tree.body:
        if not isinstance(node, ast.Assign):
            continue
        for target in node.targets:
            if not isinstance(target, ast.Name):
                continue
            try:
                if target.id == "student_id":
                    student = str(_literal(node.value))
                elif target.id == "answers":
                    if isinstance(node.value, ast.Dict):
                        for k, v in zip(node.value.keys, node.value.values, strict=True):
                            kk = _literal(k)
                            try:
                                answers[str(kk)] = _literal(v)
                            except _NotLiteral:
                                computed.append(str(kk))
                    else:
                        answers.update(_literal(node.value))
                else:
                    answers[target.id] = _literal(node.value)
            except _NotLiteral:
                computed.append(target.id)
    if strict and computed and not any(v is not None for v in answers.values()):
        raise WorkbenchError(f"the answer cell computes {', '.join(computed[:3])} instead of "
                             "holding numbers: run the notebook and save it (its output, "
                             "kinetostatics.teaching.record(...), carries the values) or "
                             "write the numbers")
    if not strict:
        return student, answers, computed
    return student, answers


def notebook_answers(nb) -> tuple[str | None, str | None, dict]:
    """The answers a notebook holds as saved, without running it.

    Parameters
    ----------
    nb : nbformat.NotebookNode
        The notebook.

    Returns
    -------
    metadata_id : str or None
        ``metadata.kinetostatics.student_id`` (written by the teacher's generator).
    cell_id : str or None
        ``student_id = ...`` in the answer cell (or in a cell tagged ``student_id``).
    answers : dict
        question -> value: the answer cell's :func:`record` output, else its literal
        ``answers = {...}`` (or one variable per question).

    Raises
    ------
    WorkbenchError
        No answer cell, or an answer cell that is not valid Python or that computes
        its values (run the notebook first).
    """
    meta_id, student, answers, _ = saved_answers(nb, strict=True)
    return meta_id, student, answers


def saved_answers(nb, strict: bool = False) -> tuple[str | None, str | None, dict, list]:
    """Like :func:`notebook_answers`, and the questions whose value the answers cell
    computes (an expression, not a number written down); with ``strict=False`` (the
    default) an answers cell that only computes is no error: its answers are empty.

    Returns
    -------
    metadata_id, cell_id, answers, computed
        ``computed`` lists the questions (or variable names) the cell computes.
    """
    meta = nb.get("metadata", {}).get("kinetostatics", {})
    meta_id = meta.get("student_id") if isinstance(meta, Mapping) else None
    answers: dict = {}
    computed: list = []
    student = None
    found = False
    for cell in nb.cells:
        if cell.get("cell_type") != "code":
            continue
        md = cell.get("metadata", {})
        tags = md.get("tags", [])
        gid = md.get("nbgrader", {}).get("grade_id")
        if ANSWER_TAG not in tags and gid != ANSWER_TAG and gid != "student_id" and \
                "student_id" not in tags:
            continue
        found = True
        got = _cell_answers(cell, strict)
        if got is None:
            continue
        sid, ans = got[0], got[1]
        if not strict:
            computed += got[2]
        student = sid or student
        answers.update(ans)
    if not found:
        raise WorkbenchError(f"no answer cell (a code cell tagged {ANSWER_TAG!r} or with "
                             f"nbgrader grade_id {ANSWER_TAG!r})")
    return (None if meta_id is None else str(meta_id)), student, answers, computed


def _read_notebook(path: Path) -> pd.DataFrame:
    import nbformat

    nb = nbformat.read(str(path), as_version=4)
    try:
        meta_id, cell_id, answers = notebook_answers(nb)
    except WorkbenchError as exc:
        raise WorkbenchError(f"{path}: {exc}") from None
    df = pd.DataFrame([{"question": k, "answer": v} for k, v in answers.items()],
                      columns=["question", "answer"])
    sid = cell_id if cell_id is not None else meta_id
    df.insert(0, "student", "" if sid is None else sid)
    return df


def read_answers(source: Any, student: Any = None) -> pd.DataFrame:
    """Students' answers as a long table ``student, question, answer``.

    Parameters
    ----------
    source : dict, DataFrame, path or list of these
        - a dict ``{question: value}`` (one student: give ``student``, or put a
          ``"student_id"`` item in it), or ``{student: {question: value}}``;
        - a DataFrame or CSV file, long (columns ``student, question, answer``) or wide
          (a ``student`` column and one column per question);
        - a filled notebook (``.ipynb``): the code cell tagged ``answers`` (or with
          nbgrader ``grade_id = "answers"``): its :func:`record` output, or the literal
          ``student_id = ...`` and ``answers = {...}`` (or one variable per question,
          named by :func:`var_name`) in its source; the id is the cell's
          ``student_id``, else the notebook's ``metadata.kinetostatics.student_id``
          (never the file name);
        - a JSON file holding one of the dicts above;
        - a list of any of these (e.g. every submitted notebook).
    student : optional
        The id of a single student's dict.

    Returns
    -------
    DataFrame
    """
    cols = ["student", "question", "answer"]
    if isinstance(source, list | tuple):
        parts = [read_answers(s) for s in source]
        return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=cols)
    if isinstance(source, str | Path):
        p = Path(source)
        if not p.is_file():
            raise WorkbenchError(f"answers file {str(p)!r} does not exist")
        suffix = p.suffix.lower()
        if suffix == ".ipynb":
            return _read_notebook(p)
        if suffix == ".json":
            return read_answers(json.loads(p.read_text(encoding="utf-8")), student)
        try:
            df = pd.read_csv(p, dtype={"student": str, "student_id": str})
        except (pd.errors.ParserError, UnicodeDecodeError) as exc:
            raise WorkbenchError(f"{p}: not a readable CSV file ({exc})") from None
        return read_answers(df, student)
    if isinstance(source, pd.DataFrame):
        df = source.copy()
        if "student_id" in df.columns and "student" not in df.columns:
            df = df.rename(columns={"student_id": "student"})
        if {"question", "answer"} <= set(df.columns):
            if "student" not in df.columns:
                df["student"] = "" if student is None else str(student)
            df["student"] = df["student"].astype(str)
            return df[cols].reset_index(drop=True)
        if "student" not in df.columns:
            if student is None:
                raise WorkbenchError("answers table: a wide table needs a 'student' column "
                                     "(or long columns student, question, answer)")
            df["student"] = str(student)
        long = df.melt(id_vars=["student"], var_name="question", value_name="answer")
        long["student"] = long["student"].astype(str)
        return long[cols]
    if isinstance(source, Mapping):
        d = dict(source)
        if d and all(isinstance(v, Mapping) for v in d.values()):
            return pd.DataFrame([{"student": str(s), "question": str(q), "answer": a}
                                 for s, ans in d.items() for q, a in ans.items()],
                                columns=cols)
        sid = d.pop("student_id", None) if student is None else student
        if isinstance(d.get("answers"), Mapping):
            d = dict(d["answers"])
        return pd.DataFrame([{"student": "" if sid is None else str(sid), "question": str(q),
                              "answer": a} for q, a in d.items()], columns=cols)
    raise WorkbenchError(f"answers must be a dict, a DataFrame, a CSV/JSON/notebook path or a "
                         f"list of these, not {type(source).__name__}")


def write_answer_notebook(path: str | Path, student_id: Any, answers: Mapping[str, Any]
                          ) -> Path:
    """Write a minimal filled answer sheet: what a student hands in, for tests and demos.

    Parameters
    ----------
    path : str or Path
        The ``.ipynb`` file to write.
    student_id : str
        The student's id.
    answers : dict
        question -> value.

    Returns
    -------
    Path
        The notebook: one code cell, tagged ``answers`` (nbgrader solution cell
        ``answers``), holding ``student_id = ...`` and ``answers = {...}`` as literals.
    """
    import nbformat

    body = ",\n".join(f"    {str(q)!r}: {to_float(v)!r}" for q, v in answers.items())
    src = f"student_id = {str(student_id)!r}\nanswers = {{\n{body},\n}}"
    cell = nbformat.v4.new_code_cell(src)
    cell.metadata["tags"] = [ANSWER_TAG]
    cell.metadata["nbgrader"] = {"grade": False, "grade_id": ANSWER_TAG, "locked": False,
                                 "schema_version": 3, "solution": True, "task": False}
    nb = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_markdown_cell(f"Answers of {student_id}"), cell])
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, str(p))
    return p



def fill_answer_cell(nb, answers: Mapping[str, Any]):
    """Type values into a student notebook's ``answers`` cell, as a student does:
    each line ``'question': None,`` becomes ``'question': value,``.

    Parameters
    ----------
    nb : nbformat.NotebookNode
        A notebook written by the teacher's generator (changed in place).
    answers : dict
        question -> value (numbers are written with ``repr``, text as it is).

    Returns
    -------
    nbformat.NotebookNode
        The same notebook.
    """
    cell = next((c for c in nb.cells if ANSWER_TAG in c.get("metadata", {}).get("tags", [])),
                None)
    if cell is None:
        raise WorkbenchError(f"no cell tagged {ANSWER_TAG!r}")
    lines = cell.source.split("\n")
    for q, v in answers.items():
        heads = [f"    {json.dumps(str(q), ensure_ascii=False)}: ", f"    {str(q)!r}: "]
        hits = [(k, h) for k, ln in enumerate(lines) for h in heads if ln.startswith(h)]
        if not hits:
            raise WorkbenchError(f"the answers cell asks no {q!r}")
        (k, head), value = hits[0], v if isinstance(v, str) else repr(float(v))
        rest = lines[k][len(head):].split(",", 1)
        lines[k] = head + value + "," + (rest[1] if len(rest) > 1 else "")
    cell.source = "\n".join(lines)
    return nb
