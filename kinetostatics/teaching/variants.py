"""Variants per student: the exercise, its draws, the class set.

A teacher writes one *template* scene (a mechanism scene, or a balancing scene with
``[rotor]``, ``[static_test]``, ``[[resonance_test]]``), says which numbers vary and
within which ranges, and which quantities are asked. Each student id gets its own
variant, drawn by a generator seeded from the exercise's seed and the id alone
(SHA-256 of the id): the same id always gets the same variant, whatever the class
list.
"""

from __future__ import annotations

import copy
import hashlib
import math
import re
import secrets
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import WorkbenchError
from ..model.tomlio import read_source
from .grading import grade
from .keys import key_rows, key_rows_many
from .questions import DEFAULT_RTOL, normalize_id, parse_question, wrap_angle
from .sheets import data_rows, key_values, leaked_values, visible_text

__all__ = ["Exercise", "ExerciseSet", "generate"]


def _student_seed(seed: int, student: Any) -> np.random.Generator:
    """A generator that depends on the exercise's seed and the student id only."""
    digest = hashlib.sha256(str(student).strip().encode("utf-8")).digest()
    return np.random.default_rng([int(seed), int.from_bytes(digest[:8], "little")])


def _round_sig(x: float, sig: int = 4) -> float:
    if x == 0 or not math.isfinite(x):
        return float(x)
    return float(round(x, sig - 1 - int(math.floor(math.log10(abs(x))))))


def _draw(rng: np.random.Generator, name: str, spec: Any) -> Any:
    """One value from a range spec: (lo, hi), (lo, hi, step), a list of choices, or a
    dict {low, high[, step]} / {choices}."""
    if isinstance(spec, Mapping):
        if "choices" in spec:
            spec = list(spec["choices"])
        else:
            spec = tuple(spec[k] for k in ("low", "high", "step") if k in spec)
    if isinstance(spec, list):
        if not spec:
            raise WorkbenchError(f"range {name!r}: the list of choices is empty")
        return copy.deepcopy(spec[int(rng.integers(len(spec)))])
    if isinstance(spec, tuple) and len(spec) in (2, 3):
        lo, hi = float(spec[0]), float(spec[1])
        if not hi >= lo:
            raise WorkbenchError(f"range {name!r}: high {hi:g} < low {lo:g}")
        if len(spec) == 3:
            step = float(spec[2])
            if not step > 0:
                raise WorkbenchError(f"range {name!r}: step must be > 0, not {step:g}")
            k = int(rng.integers(int(math.floor((hi - lo) / step + 1e-9)) + 1))
            return float(round(lo + k * step, 12))
        return _round_sig(float(rng.uniform(lo, hi)))
    raise WorkbenchError(f"range {name!r}: give (low, high), (low, high, step), a list of "
                         f"choices or a dict; got {spec!r}")


def _set_path(scene: dict, path: str, value: Any) -> None:
    """Set ``scene[path]`` for a dotted path; list items by index or by their ``name``:
    ``"bodies.crank.mass"``, ``"ground.D.0"``, ``"rotor.unbalance.1.angle"``."""
    parts = path.split(".")
    node: Any = scene
    for k, part in enumerate(parts):
        last = k == len(parts) - 1
        where = ".".join(parts[:k + 1])
        if isinstance(node, list):
            if re.fullmatch(r"-?\d+", part):
                idx = int(part)
                if not -len(node) <= idx < len(node):
                    raise WorkbenchError(f"range {path!r}: no item {idx} at {where!r}")
            else:
                hits = [i for i, it in enumerate(node)
                        if isinstance(it, Mapping) and it.get("name") == part]
                if not hits:
                    raise WorkbenchError(f"range {path!r}: no item named {part!r} at {where!r}")
                idx = hits[0]
            if last:
                node[idx] = value
            else:
                node = node[idx]
        elif isinstance(node, dict):
            if last:
                node[part] = value
            elif part not in node:
                raise WorkbenchError(f"range {path!r}: the template has no {where!r}")
            else:
                node = node[part]
        else:
            raise WorkbenchError(f"range {path!r}: {'.'.join(parts[:k])!r} is a number, not a "
                                 "table or a list")


# --------------------------------------------------------------------- exercises
@dataclass
class Exercise:
    """An exercise: a template scene, the ranges of its varying numbers, the questions.

    Parameters
    ----------
    template : dict, path, TOML text or callable
        The scene. A callable receives the drawn parameters (a dict) and returns the
        scene (dict, path or TOML text); otherwise the range names are dotted paths
        into the scene (``"bodies.crank.mass"``, ``"rotor.unbalance.0.angle"``: list
        items by index or by their ``name``).
    ranges : dict
        name -> (low, high) (uniform, rounded to 4 significant digits), (low, high,
        step), or a list of choices.
    questions : list of str
        What is asked (see the module's table).
    seed : int, optional
        The exercise's seed: with the student id it fixes the variant. None (the
        default) draws a secret one (``secrets.randbits(63)``; keep ``.seed`` private).
    title, text : str
        Title and statement shown on the sheets.
    check : callable, optional
        ``check(scene_dict, key_dict) -> bool``: refuse a variant (e.g. a transmission
        angle below 30 deg). Variants whose scene cannot be solved (a four-bar that
        does not assemble) are refused too; a refused variant is drawn again from the
        same student's generator (``max_tries`` times).
    rtol : float
        Relative tolerance of the numbers (angles: 0.5 deg absolute).
    max_tries : int
        Draws per student before giving up.
    name : str
        The exercise's name in the library (``"four_bar"``).
    data : callable, optional
        ``data(params, scene) -> [(symbol, value, unit, meaning), ...]``: what the
        student's sheets show as data (default: the drawn parameters).
    labels, units : dict, optional
        question -> words, question -> unit, replacing the defaults on the sheets.
    picture : str, optional
        Code of a notebook cell that draws the student's ``scene`` (no answer in it).
    give_scene : bool
        Write the student's scene into the notebook (for ``ks.solve(scene)``).
    position : str
        How a driver position reads in a question (``{pos}`` is the number).
    discriminate : float or None
        Refuse a variant where an error of this fraction of an asked value would pass
        (a value too near zero to be judged); default 5 %.

    A variant is also refused when one of its key values, to 4 significant digits, can
    be read in the student's notebook or handout (see
    :func:`~kinetostatics.teaching.sheets.leaked_values`).
    """

    template: Any
    ranges: Mapping[str, Any]
    questions: Sequence[str]
    seed: int | None = None
    title: str = "exercise"
    text: str = ""
    check: Callable[[dict, dict], bool] | None = None
    rtol: float = DEFAULT_RTOL
    max_tries: int = 200
    name: str = ""
    data: Callable[[dict, dict], list] | None = None
    labels: Mapping[str, str] = field(default_factory=dict)
    units: Mapping[str, str] = field(default_factory=dict)
    picture: str | None = None
    give_scene: bool = True
    position: str = "phi = {pos:g} deg"
    discriminate: float | None = 0.05
    _cache: dict = field(default_factory=dict, repr=False, compare=False)
    _first: dict = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self):
        if self.seed is None:
            self.seed = secrets.randbits(63)
        if self.discriminate is not None and not 2 * self.rtol < self.discriminate:
            raise WorkbenchError(f"rtol {self.rtol:g} must be below half of discriminate "
                                 f"{self.discriminate:g} (or set discriminate=None)")
        self.questions = [str(q) for q in self.questions]
        for q in self.questions:
            parse_question(q)
        if not callable(self.template):
            self._raw = read_source(self.template, "exercise template")
        if not self.ranges:
            raise WorkbenchError("an exercise needs at least one range (else every student "
                                 "gets the same numbers)")

    def _build(self, params: dict) -> dict:
        if callable(self.template):
            return read_source(self.template(dict(params)), "exercise template")
        raw = copy.deepcopy(self._raw)
        for name, value in params.items():
            _set_path(raw, name, value)
        return raw

    def _variant(self, student: Any) -> dict:
        sid = str(student).strip()
        if not sid:
            raise WorkbenchError("a student id must not be empty")
        if sid in self._cache:
            return self._cache[sid]
        rng = _student_seed(self.seed, sid)
        first = self._first.pop(sid, None)      # the first draw, solved by prepare
        last = None
        for attempt in range(1, self.max_tries + 1):
            params = {name: _draw(rng, name, self.ranges[name]) for name in sorted(self.ranges)}
            try:
                if attempt == 1 and first is not None:
                    raw, rows = first
                    if isinstance(rows, Exception):
                        raise rows
                else:
                    raw = self._build(params)
                    rows = key_rows(raw, self.questions)
            except (ValueError, ArithmeticError) as exc:     # WorkbenchError is a ValueError
                last = str(exc)
                continue
            rows = {q: (r[0], self.units.get(q, r[1]), r[2], r[3]) for q, r in rows.items()}
            if self.check is not None and \
                    not self.check(raw, {k: v[0] for k, v in rows.items()}):
                last = "refused by the exercise's check"
                continue
            v = {"student": sid, "attempt": attempt, "params": params, "scene": raw,
                 "rows": rows}
            if (vague := self._not_judged(rows)) or (seen := self._leaks(sid, v)):
                last = (f"a {100 * self.discriminate:g} % error in {vague[0]} would pass"
                        if vague else f"the key of {seen[0]} can be read on the sheets")
                continue
            self._cache[sid] = v
            return v
        raise WorkbenchError(f"exercise {self.title!r}: no valid variant for student {sid!r} "
                             f"in {self.max_tries} draws (last: {last}); widen the ranges or "
                             "relax the check")

    def remember(self, student: Any, variant: dict) -> None:
        """Keep a variant of ``student`` drawn elsewhere (by this exercise in another
        process or on a cluster's worker: the same seed draws the same numbers), so
        that the key needs no new solve; a variant already drawn here is kept."""
        self._cache.setdefault(str(student).strip(), variant)

    def prepare(self, students: Iterable[Any]) -> None:
        """Draw the first variant of each student not drawn yet and solve them all
        together (:func:`~kinetostatics.teaching.keys.key_rows_many`:
        :func:`kinetostatics.solve_many` over the class): the variants are those drawn
        one by one, with the same numbers; a student whose first draw is refused draws
        again alone."""
        todo = []
        for s in students:
            sid = str(s).strip()
            if sid and sid not in self._cache and sid not in self._first and sid not in todo:
                todo.append(sid)
        if len(todo) < 2:
            return
        raws = []
        for sid in todo:
            rng = _student_seed(self.seed, sid)
            raws.append(self._build({name: _draw(rng, name, self.ranges[name])
                                     for name in sorted(self.ranges)}))
        for sid, raw, rows in zip(todo, raws, key_rows_many(raws, self.questions),
                                  strict=True):
            if isinstance(rows, Exception) and not isinstance(rows, ValueError | ArithmeticError):
                continue                # not a refusal of the draw: _variant raises it
            self._first[sid] = (raw, rows)

    def _not_judged(self, rows: Mapping[str, tuple]) -> list[str]:
        """Questions whose value a ``discriminate`` error would not fail."""
        if self.discriminate is None:
            return []
        out = []
        for q, (val, _, kind, atol) in rows.items():
            off = self.discriminate * val
            if kind == "angle":
                miss, tol = abs(float(wrap_angle(off))), atol
            else:
                miss, tol = abs(off), max(self.rtol * abs(val), atol)
            if not miss >= 2.0 * tol:
                out.append(q)
        return out

    def _leaks(self, student: str, variant: dict) -> list[str]:
        values, angles = key_values(variant)
        return leaked_values(visible_text(self, student, variant), values, angles)

    def variant(self, student: Any) -> dict:
        """A student's variant: ``params``, ``scene``, ``attempt`` and ``rows``
        (question -> (value, unit, kind, atol))."""
        return copy.deepcopy(self._variant(student))

    def params(self, student: Any) -> dict:
        """The drawn parameters of a student's variant."""
        return dict(self._variant(student)["params"])

    def scene(self, student: Any) -> dict:
        """The student's scene (a dict: ``kinetostatics.solve`` or ``balance.solve`` it)."""
        return copy.deepcopy(self._variant(student)["scene"])

    def answer_key(self, student: Any) -> dict[str, float]:
        """question -> the right value, for one student."""
        return {q: v[0] for q, v in self._variant(student)["rows"].items()}

    def key(self, students: Iterable[Any]) -> pd.DataFrame:
        """The answer key of several students: one row per student and question, with
        ``expected, unit, kind, rtol, atol``."""
        students = list(students)
        self.prepare(students)
        rows = []
        for s in students:
            v = self._variant(s)
            for q in self.questions:
                val, unit, kind, atol = v["rows"][q]
                rows.append({"student": v["student"], "question": q, "expected": val,
                             "unit": unit, "kind": kind,
                             "rtol": 0.0 if kind == "angle" or unit == "deg" else self.rtol,
                             "atol": atol})
        return pd.DataFrame(rows, columns=["student", "question", "expected", "unit", "kind",
                                           "rtol", "atol"])

    def variants(self, students: Iterable[Any]) -> pd.DataFrame:
        """One row per student: the drawn parameters (and the draw that was kept)."""
        students = list(students)
        self.prepare(students)
        rows = []
        for s in students:
            v = self._variant(s)
            shown = {} if self.data is None else {
                f"{d['symbol']} [{d['unit']}]" if d["unit"] else d["symbol"]: d["value"]
                for d in data_rows(self, v)}
            rows.append({"student": v["student"], **v["params"], **shown,
                         "attempt": v["attempt"]})
        return pd.DataFrame(rows)

    def answer_form(self, students: Iterable[Any]) -> pd.DataFrame:
        """An empty answer sheet: a ``student`` column and one column per question."""
        return pd.DataFrame([{"student": str(s), **{q: np.nan for q in self.questions}}
                             for s in students])

    def generate(self, students: Iterable[Any]) -> ExerciseSet:
        """The variants and the key of a class list."""
        ids = [str(s).strip() for s in students]
        norm = [normalize_id(s) for s in ids]
        if len(set(norm)) != len(norm):
            dup = sorted({s for s, n in zip(ids, norm, strict=True) if norm.count(n) > 1})
            raise WorkbenchError(f"duplicate student ids: {', '.join(dup)}")
        return ExerciseSet(self, ids, self.variants(ids), self.key(ids))

    def grade(self, answers: Any, **kwargs) -> tuple[pd.DataFrame, dict]:
        """:func:`grade` against the keys of the students who answered."""
        return grade(answers, self, **kwargs)


@dataclass
class ExerciseSet:
    """The variants of a class: ``variants`` (parameters per student) and ``key`` (the
    answer key, one row per student and question)."""

    exercise: Exercise
    students: list[str]
    variants: pd.DataFrame
    key: pd.DataFrame

    def scene(self, student: Any) -> dict:
        """A student's scene."""
        return self.exercise.scene(student)

    def answer_form(self) -> pd.DataFrame:
        """An empty wide answer sheet for the class (fill it, save it as CSV, grade it)."""
        return self.exercise.answer_form(self.students)

    def to_csv(self, directory: str | Path) -> list[Path]:
        """Write ``variants.csv``, ``key.csv`` and an empty ``answers.csv`` form."""
        d = Path(directory)
        d.mkdir(parents=True, exist_ok=True)
        out = []
        for name, df in (("variants", self.variants), ("key", self.key),
                         ("answers", self.answer_form())):
            p = d / f"{name}.csv"
            df.to_csv(p, index=False, float_format="%.17g")
            out.append(p)
        return out


def generate(template_scene: Any, ranges: Mapping[str, Any], student_ids: Iterable[Any],
             seed: int | None = None, *, questions: Sequence[str] = (), **kwargs) -> ExerciseSet:
    """Variants of an exercise, one per student id, deterministic from (seed, id).

    Parameters
    ----------
    template_scene : dict, path, TOML text or callable
        See :class:`Exercise`.
    ranges : dict
        name -> (low, high), (low, high, step) or a list of choices.
    student_ids : iterable
        The class list (any values; their ``str`` is the id).
    seed : int, optional
        The exercise's seed (None: a secret one is drawn).
    questions : sequence of str
        The quantities asked (the key's rows).
    **kwargs
        ``title``, ``text``, ``check``, ``rtol``, ``max_tries`` of :class:`Exercise`.

    Returns
    -------
    ExerciseSet
        ``.variants`` (DataFrame), ``.key`` (DataFrame), ``.scene(id)``, ``.to_csv``.
    """
    if not questions:
        raise WorkbenchError("generate: give the questions, e.g. questions=['Me@30', "
                             "'Fmax[B]']")
    ex = Exercise(template_scene, ranges, list(questions), seed=seed, **kwargs)
    return ex.generate(student_ids)

