"""Exercises: variants per student, answer keys, grading.

A teacher writes one *template* scene (a mechanism scene, or a balancing scene with
``[rotor]``, ``[static_test]``, ``[[resonance_test]]``), says which numbers vary and
within which ranges, and which quantities are asked. Each student id gets its own
variant, drawn by a generator seeded from the exercise's seed and the id alone
(SHA-256 of the id): the same id always gets the same variant, whatever the class
list. The answer key is computed with :func:`kinetostatics.solve` or
:func:`balance.solve`; :func:`grade` compares a student's answers (a dict, a CSV file,
a DataFrame or a filled notebook) with it, at stated tolerances, angles modulo 360.

Questions are short strings, ``quantity[argument]@position``:

========================  =====================================================
mechanism                 meaning (unit)
========================  =====================================================
``Me@30``                 equilibrating moment at driver position 30 (N m);
                          ``Fe@0.2`` on a sliding driver (N)
``Me_mean``, ``Me_max``,  mean (trapezoid rule), largest, smallest over the sweep
``Me_min``
``F[B]@30``               magnitude of the reaction in joint B (N); ``Fx[B]@30``,
                          ``Fy[B]@30`` its components on the ``on`` body
``Fmax[B]``               largest |F| in joint B over the sweep (N)
``Fangle[B]@30``          direction of the reaction (deg, an angle)
``N[C-slide]@30``,        normal force (N) and couple (N m) of a prismatic joint
``M[C-slide]@30``
``tau_min``               smallest transmission angle, min(tau, 180 - tau) (deg)
``tau[1]@30``             transmission angle of dyad 1 (deg)
``angle[rocker]@30``      angle of a body (deg, an angle); ``omega[...]``
                          (rad/s), ``alpha[...]`` (rad/s^2)
``x[coupler.P]@30``       coordinates (m), ``v[...]`` speed (m/s), ``a[...]``
                          acceleration magnitude (m/s^2) of a body point
========================  =====================================================

========================  =====================================================
balancing                 meaning (unit)
========================  =====================================================
``mass[1]``, ``angle[1]`` correction mass (kg) and its angle (deg) in plane 1
``U[1]``                  correction unbalance m r (kg m)
``initial_force``, ...    ``initial_force``, ``initial_moment``,
                          ``residual_force``, ``residual_moment``
``eccentricity``,         static device (``[static_test]``)
``correction_mass``
``res_mass[1]``,          amplitude-parallelogram test number 1: correction mass,
``res_angle[1]``,         angle, mirror angle, A, phi, unbalance
``res_mirror[1]``, ...
``shaking_before``,       mechanism balancing (``[balancing]``): largest shaking
``shaking_after``         force (N)
``rotor.corrections.0.U`` any other number of ``balance.solve``'s result, by path
========================  =====================================================

Tolerances: a number passes when |answer - key| <= atol + rtol |key| (rtol 1 % by
default; atol 1e-3 of the quantity's scale over the cycle, so that a value near zero
is not judged by its relative error); an angle passes when the difference, wrapped
into (-180, 180], is at most 0.5 deg.
"""

from __future__ import annotations

import ast
import copy
import hashlib
import json
import math
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ..model.errors import WorkbenchError
from ..model.tomlio import read_source

__all__ = [
    "AnswerSheet", "Exercise", "ExerciseSet", "answer_key", "class_table", "four_bar_exercise",
    "generate", "grade", "read_answers", "record", "rotor_exercise", "var_name",
    "write_answer_notebook",
]

DEFAULT_RTOL = 0.01
ATOL_FRACTION = 1e-3        # atol = this fraction of the quantity's scale over the sweep
ANGLE_ATOL = 0.5            # deg
ANSWER_TAG = "answers"      # cell tag (and nbgrader grade_id) of a notebook's answer cell

_Q = re.compile(r"^(?P<q>[A-Za-z_][A-Za-z0-9_.]*)(?:\[(?P<arg>[^\]]+)\])?"
                r"(?:@(?P<pos>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))?$")


# ------------------------------------------------------------------------ helpers
def var_name(question: str) -> str:
    """A Python identifier for a question, for answer cells written as variables.

    Parameters
    ----------
    question : str
        E.g. ``"Me@30"``.

    Returns
    -------
    str
        ``"Me@30"`` -> ``Me_30``, ``"Fmax[B]"`` -> ``Fmax_B``, ``"x[coupler.P]@30"`` ->
        ``x_coupler_P_30``.
    """
    name = re.sub(r"[^0-9A-Za-z]+", "_", question).strip("_")
    return name if not name[:1].isdigit() else f"q_{name}"


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


def _to_float(x: Any) -> float:
    """A student's answer as a float: numbers, '12.5', '12,5', '330°'; NaN if none."""
    if x is None:
        return math.nan
    if isinstance(x, bool):
        return math.nan
    if isinstance(x, int | float | np.integer | np.floating):
        return float(x)
    if isinstance(x, str):
        t = x.strip().replace("°", "").replace("deg", "").replace(" ", "")
        if t.count(",") == 1 and "." not in t:
            t = t.replace(",", ".")
        try:
            return float(t)
        except ValueError:
            return math.nan
    return math.nan


def _wrap(d: np.ndarray) -> np.ndarray:
    """Angle differences into (-180, 180]."""
    return 180.0 - np.mod(180.0 - np.asarray(d, dtype=float), 360.0)


# ------------------------------------------------------------------ question parse
@dataclass(frozen=True)
class _Question:
    text: str
    q: str
    arg: str | None
    pos: float | None


def _parse(question: str) -> _Question:
    m = _Q.match(question.strip())
    if not m:
        raise WorkbenchError(f"question {question!r}: write quantity[argument]@position, e.g. "
                             "'Me@30', 'Fmax[B]', 'angle[rocker]@30', 'mass[1]'")
    pos = m.group("pos")
    return _Question(question.strip(), m.group("q"), m.group("arg"),
                     None if pos is None else float(pos))


def _is_mechanism(raw: Mapping) -> bool:
    return "bodies" in raw or "driver" in raw


# --------------------------------------------------------------- mechanism answers
_MECH_UNITS = {"Me": "N m", "Fe": "N", "F": "N", "Fx": "N", "Fy": "N", "Fmax": "N",
               "Fangle": "deg", "N": "N", "M": "N m", "tau": "deg", "tau_min": "deg",
               "angle": "deg", "omega": "rad/s", "alpha": "rad/s^2", "x": "m", "y": "m",
               "v": "m/s", "a": "m/s^2", "Me_mean": "N m", "Me_max": "N m", "Me_min": "N m",
               "Fe_mean": "N", "Fe_max": "N", "Fe_min": "N"}
_ANGLES = {"Fangle", "angle", "res_angle", "res_mirror"}


def _needs_position(q: _Question) -> None:
    if q.pos is None:
        raise WorkbenchError(f"question {q.text!r}: give the driver position, e.g. "
                             f"'{q.text}@30'")


def _row_of(sol, q: _Question) -> int:
    hits = np.flatnonzero(np.abs(sol.positions - q.pos) <= 1e-9 * max(1.0, abs(q.pos)))
    if hits.size == 0:
        raise WorkbenchError(f"question {q.text!r}: position {q.pos:g} is not in the sweep "
                             f"[{sol.positions[0]:g}, {sol.positions[-1]:g}]")
    return int(hits[0])


def _with_positions(raw: dict, extra: Sequence[float]) -> dict | None:
    """The scene with the asked positions added to the sweep (None if all are in it)."""
    drv = raw.get("driver", {})
    if "positions" in drv:
        base = np.asarray(drv["positions"], dtype=float)
        start, stop = base[0], base[-1]
    else:
        start, stop = float(drv["start"]), float(drv["stop"])
        base = np.linspace(start, stop, int(drv["count"]))
    missing = [p for p in extra
               if not np.any(np.abs(base - p) <= 1e-9 * max(1.0, abs(p)))]
    if not missing:
        return None
    lo, hi = min(start, stop), max(start, stop)
    for p in missing:
        if not lo - 1e-12 <= p <= hi + 1e-12:
            raise WorkbenchError(f"asked position {p:g} lies outside the sweep "
                                 f"[{start:g}, {stop:g}]")
    allp = np.unique(np.concatenate([base, missing]))
    if stop < start:
        allp = allp[::-1]
    out = copy.deepcopy(raw)
    d = {k: v for k, v in out["driver"].items() if k not in ("start", "stop", "count")}
    d["positions"] = [float(p) for p in allp]
    out["driver"] = d
    return out


def _mechanism_values(raw: dict, questions: Sequence[_Question]) -> dict[str, tuple]:
    """question -> (value, unit, kind, atol)."""
    from ..solver.pipeline import solve

    sol = solve(raw)
    at = [q.pos for q in questions if q.pos is not None]
    aug = _with_positions(raw, at) if at else None
    psol = solve(aug) if aug is not None else sol
    summ = sol.summary()
    dq = sol.driver_quantity
    out: dict[str, tuple] = {}
    n = psol.positions.size
    for q in questions:
        unit = _MECH_UNITS.get(q.q, "")
        kind = "angle" if q.q in _ANGLES else "number"
        if q.q in ("Me", "Fe"):
            if q.q != dq:
                raise WorkbenchError(f"question {q.text!r}: this driver has {dq}, not {q.q}")
            _needs_position(q)
            val = float(psol.Me[_row_of(psol, q)])
            scale = float(np.abs(sol.Me).max())
        elif q.q in ("Me_mean", "Me_max", "Me_min", "Fe_mean", "Fe_max", "Fe_min"):
            if q.q[:2] != dq:
                raise WorkbenchError(f"question {q.text!r}: this driver has {dq}, not "
                                     f"{q.q[:2]}")
            val = float(summ[q.q])
            scale = float(np.abs(sol.Me).max())
        elif q.q in ("F", "Fx", "Fy", "Fmax", "Fangle", "N", "M"):
            if q.arg not in sol.scene.joints:
                raise WorkbenchError(f"question {q.text!r}: no joint {q.arg!r}; joints: "
                                     f"{', '.join(sol.scene.joints)}")
            fx, fy = sol.reaction(q.arg)
            scale = float(np.hypot(fx, fy).max())
            if q.q == "Fmax":
                val = float(summ["reaction_max"][q.arg]["F"])
            else:
                _needs_position(q)
                i = _row_of(psol, q)
                px, py = psol.reaction(q.arg)
                if q.q in ("N", "M"):
                    r = psol.joint_reactions[q.arg]
                    if r.N is None:
                        raise WorkbenchError(f"question {q.text!r}: joint {q.arg!r} is "
                                             "revolute: it has no N or M")
                    arr = r.N if q.q == "N" else r.M
                    val = float(np.broadcast_to(arr, (n,))[i])
                    s0 = sol.joint_reactions[q.arg]
                    full = np.broadcast_to(s0.N if q.q == "N" else s0.M,
                                           sol.positions.shape)
                    scale = float(np.abs(full).max())
                else:
                    val = {"F": float(np.hypot(px[i], py[i])), "Fx": float(px[i]),
                           "Fy": float(py[i]),
                           "Fangle": float(np.degrees(np.arctan2(py[i], px[i])) % 360.0)
                           }[q.q]
        elif q.q == "tau_min":
            val = summ["transmission_angle_min"]
            if val is None:
                raise WorkbenchError(f"question {q.text!r}: the mechanism has no dyad")
            val, scale, unit = float(val), None, "deg"
        elif q.q == "tau":
            _needs_position(q)
            t = psol.dyads
            g = t[t.dyad == int(q.arg or 1)]
            if g.empty:
                raise WorkbenchError(f"question {q.text!r}: no dyad {q.arg}")
            val = float(g.transmission_angle.to_numpy()[_row_of(psol, q)])
            scale = None
        elif q.q in ("angle", "omega", "alpha"):
            _needs_position(q)
            if q.arg not in sol.scene.bodies:
                raise WorkbenchError(f"question {q.text!r}: no body {q.arg!r}; bodies: "
                                     f"{', '.join(sol.scene.bodies)}")
            t = psol.bodies
            g = t[t.body == q.arg]
            val = float(g[q.q].to_numpy()[_row_of(psol, q)])
            if q.q == "angle":
                val %= 360.0
                scale = None
            else:
                full = sol.bodies[sol.bodies.body == q.arg][q.q].to_numpy()
                scale = float(np.abs(full).max())
        elif q.q in ("x", "y", "v", "a"):
            _needs_position(q)
            b, _, p = (q.arg or "").partition(".")
            k = psol.kinematics
            g = k[(k.body == b) & (k.point == p)]
            if g.empty:
                raise WorkbenchError(f"question {q.text!r}: no point {q.arg!r} (write "
                                     "'body.point', e.g. 'coupler.P')")
            i = _row_of(psol, q)
            row = g.iloc[i]
            val = {"x": row.x, "y": row.y, "v": math.hypot(row.vx, row.vy),
                   "a": math.hypot(row.ax, row.ay)}[q.q]
            val = float(val)
            k0 = sol.kinematics
            g0 = k0[(k0.body == b) & (k0.point == p)]
            scale = float({"x": np.ptp(g0.x.to_numpy()) + np.abs(g0.x).max(),
                           "y": np.ptp(g0.y.to_numpy()) + np.abs(g0.y).max(),
                           "v": np.hypot(g0.vx, g0.vy).max(),
                           "a": np.hypot(g0.ax, g0.ay).max()}[q.q])
        else:
            raise WorkbenchError(f"question {q.text!r}: unknown mechanism quantity {q.q!r}; "
                                 f"known: {', '.join(sorted(_MECH_UNITS))}")
        if kind == "angle" or unit == "deg":
            atol = ANGLE_ATOL
        else:
            atol = ATOL_FRACTION * (scale or 0.0)
        out[q.text] = (val, unit, kind, atol)
    return out


# ---------------------------------------------------------------- balance answers
def _balance_values(raw: dict, questions: Sequence[_Question]) -> dict[str, tuple]:
    import balance

    res = balance.solve(raw)
    rot = res.get("rotor")
    force_units = ("N", "N m") if rot is not None and \
        raw.get("rotor", {}).get("speed_rpm") is not None else ("kg m", "kg m^2")
    out: dict[str, tuple] = {}

    def need(section: str, q: _Question):
        if section not in res:
            raise WorkbenchError(f"question {q.text!r}: the scene has no [{section}] section")
        return res[section]

    for q in questions:
        kind, unit = "number", ""
        k = int(q.arg) if q.arg and q.arg.isdigit() else 1
        if q.q in ("mass", "angle", "U"):
            cor = need("rotor", q)["corrections"]
            if not 1 <= k <= len(cor):
                raise WorkbenchError(f"question {q.text!r}: the rotor has {len(cor)} "
                                     "correction plane(s)")
            val = cor[k - 1][q.q]
            unit = {"mass": "kg", "angle": "deg", "U": "kg m"}[q.q]
            kind = "angle" if q.q == "angle" else "number"
            scale = max(c[q.q] for c in cor) if q.q != "angle" else None
        elif q.q in ("initial_force", "initial_moment", "residual_force", "residual_moment"):
            r = need("rotor", q)
            val = r[q.q]
            unit = force_units[0] if q.q.endswith("force") else force_units[1]
            scale = r["initial_force" if q.q.endswith("force") else "initial_moment"]
        elif q.q in ("eccentricity", "correction_mass"):
            val = need("static_test", q)[q.q]
            unit = "m" if q.q == "eccentricity" else "kg"
            scale = abs(val)
        elif q.q.startswith("res_"):
            tests = need("resonance_test", q)
            if not 1 <= k <= len(tests):
                raise WorkbenchError(f"question {q.text!r}: the scene has {len(tests)} "
                                     "resonance test(s)")
            key = {"res_mass": "correction_mass", "res_angle": "angle",
                   "res_mirror": "mirror_angle", "res_A": "A", "res_phi": "phi",
                   "res_unbalance": "unbalance"}.get(q.q)
            if key is None:
                raise WorkbenchError(f"question {q.text!r}: unknown resonance quantity; "
                                     "known: res_mass, res_angle, res_mirror, res_A, res_phi, "
                                     "res_unbalance")
            val = tests[k - 1][key]
            unit = {"correction_mass": "kg", "angle": "deg", "mirror_angle": "deg", "A": "",
                    "phi": "deg", "unbalance": "kg m"}[key]
            kind = "angle" if q.q in _ANGLES else "number"
            scale = abs(val) if isinstance(val, int | float) else None
        elif q.q in ("shaking_before", "shaking_after"):
            b = need("balancing", q)
            val = b[f"shaking_force_{q.q.split('_')[1]}"]
            unit, scale = "N", b["shaking_force_before"]
        else:
            node: Any = res
            for part in q.text.split("."):
                try:
                    node = node[int(part)] if isinstance(node, list) else node[part]
                except (KeyError, IndexError, ValueError, TypeError):
                    raise WorkbenchError(f"question {q.text!r}: not a quantity of this "
                                         "balancing scene") from None
            val, scale = node, None
        if val is None:
            raise WorkbenchError(f"question {q.text!r}: undefined for this variant")
        val = float(val)
        atol = ANGLE_ATOL if kind == "angle" or unit == "deg" else \
            ATOL_FRACTION * abs(scale or val)
        out[q.text] = (val, unit, kind, atol)
    return out


def answer_key(scene: Any, questions: Iterable[str]) -> dict[str, float]:
    """The values of the asked quantities for one scene.

    Parameters
    ----------
    scene : dict, path or TOML text
        A mechanism scene (computed with :func:`kinetostatics.solve`) or a balancing
        scene (:func:`balance.solve`).
    questions : iterable of str
        See the module's table (``"Me@30"``, ``"Fmax[B]"``, ``"mass[1]"``, ...).

    Returns
    -------
    dict
        question -> value.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> key = answer_key(ks.example("four_bar"), ["Me@30", "Fmax[B]"])
    >>> sorted(key)
    ['Fmax[B]', 'Me@30']
    """
    return {k: v[0] for k, v in _key_rows(read_source(scene), list(questions)).items()}


def _key_rows(raw: dict, questions: Sequence[str]) -> dict[str, tuple]:
    qs = [_parse(q) for q in questions]
    if _is_mechanism(raw):
        return _mechanism_values(raw, qs)
    return _balance_values(raw, qs)


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
    seed : int
        The exercise's seed: with the student id it fixes the variant.
    title, text : str
        Title and statement shown on the sheets.
    check : callable, optional
        ``check(scene_dict, key_dict) -> bool``: refuse a variant (e.g. a transmission
        angle below 30 deg). Variants whose scene cannot be solved (a four-bar that
        does not assemble) are refused too; a refused variant is drawn again from the
        same student's generator (``max_tries`` times).
    rtol : float
        Relative tolerance of the numbers (angles: 0.5 deg absolute).
    """

    template: Any
    ranges: Mapping[str, Any]
    questions: Sequence[str]
    seed: int = 0
    title: str = "exercise"
    text: str = ""
    check: Callable[[dict, dict], bool] | None = None
    rtol: float = DEFAULT_RTOL
    max_tries: int = 200
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self):
        self.questions = [str(q) for q in self.questions]
        for q in self.questions:
            _parse(q)
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
        last = None
        for attempt in range(1, self.max_tries + 1):
            params = {name: _draw(rng, name, self.ranges[name]) for name in sorted(self.ranges)}
            raw = self._build(params)
            try:
                rows = _key_rows(raw, self.questions)
            except (ValueError, ArithmeticError) as exc:     # WorkbenchError is a ValueError
                last = str(exc)
                continue
            if self.check is not None and \
                    not self.check(raw, {k: v[0] for k, v in rows.items()}):
                last = "refused by the exercise's check"
                continue
            v = {"student": sid, "attempt": attempt, "params": params, "scene": raw,
                 "rows": rows}
            self._cache[sid] = v
            return v
        raise WorkbenchError(f"exercise {self.title!r}: no valid variant for student {sid!r} "
                             f"in {self.max_tries} draws (last: {last}); widen the ranges or "
                             "relax the check")

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
        rows = []
        for s in students:
            v = self._variant(s)
            rows.append({"student": v["student"], **v["params"], "attempt": v["attempt"]})
        return pd.DataFrame(rows)

    def answer_form(self, students: Iterable[Any]) -> pd.DataFrame:
        """An empty answer sheet: a ``student`` column and one column per question."""
        return pd.DataFrame([{"student": str(s), **{q: np.nan for q in self.questions}}
                             for s in students])

    def generate(self, students: Iterable[Any]) -> ExerciseSet:
        """The variants and the key of a class list."""
        ids = [str(s).strip() for s in students]
        if len(set(ids)) != len(ids):
            dup = sorted({s for s in ids if ids.count(s) > 1})
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
             seed: int = 0, *, questions: Sequence[str] = (), **kwargs) -> ExerciseSet:
    """Variants of an exercise, one per student id, deterministic from (seed, id).

    Parameters
    ----------
    template_scene : dict, path, TOML text or callable
        See :class:`Exercise`.
    ranges : dict
        name -> (low, high), (low, high, step) or a list of choices.
    student_ids : iterable
        The class list (any values; their ``str`` is the id).
    seed : int
        The exercise's seed.
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


# ------------------------------------------------------------------ reading answers
@dataclass
class AnswerSheet:
    """A student's answers as shown in a notebook: a table, and a JSON output that
    :func:`read_answers` reads back from the saved notebook."""

    student: str
    answers: dict

    def _clean(self) -> dict:
        return {str(k): (None if (f := _to_float(v)) != f else f)
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


def _cell_answers(cell) -> tuple[str | None, dict] | None:
    """(student id, answers) from one answer cell: its JSON output first, else its
    source's literal assignments."""
    for out in cell.get("outputs", []):
        data = out.get("data", {})
        js = data.get("application/json")
        if isinstance(js, Mapping) and "answers" in js:
            return (None if js.get("student_id") is None else str(js["student_id"]),
                    dict(js["answers"]))
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
    if computed and not any(v is not None for v in answers.values()):
        raise WorkbenchError(f"the answer cell computes {', '.join(computed[:3])} instead of "
                             "holding numbers: run the notebook and save it (its output, "
                             "kinetostatics.exercises.record(...), carries the values) or "
                             "write the numbers")
    return student, answers


def _read_notebook(path: Path) -> pd.DataFrame:
    import nbformat

    nb = nbformat.read(str(path), as_version=4)
    rows: list[dict] = []
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
        got = _cell_answers(cell)
        if got is None:
            continue
        sid, ans = got
        student = sid or student
        rows += [{"question": k, "answer": v} for k, v in ans.items()]
    if not found:
        raise WorkbenchError(f"{path}: no answer cell (a code cell tagged {ANSWER_TAG!r} or "
                             f"with nbgrader grade_id {ANSWER_TAG!r})")
    df = pd.DataFrame(rows, columns=["question", "answer"])
    df.insert(0, "student", student if student is not None else path.stem)
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
          named by :func:`var_name`) in its source;
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


# ------------------------------------------------------------------------- grading
def _key_table(key: Any, students: Sequence[str]) -> pd.DataFrame:
    if isinstance(key, Exercise):
        return key.key(students)
    if isinstance(key, ExerciseSet):
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
          student: Any = None) -> tuple[pd.DataFrame, dict]:
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
        Override the key's tolerances for numbers: pass when |answer - key| <= atol +
        rtol |key| (defaults: the key's, else rtol 1 %, atol 0).
    angle_keys : iterable of str
        Questions to compare as angles, besides those the key marks ``kind == "angle"``.
    angle_atol : float, optional
        Tolerance of angles in degrees (default: the key's, else 0.5); the difference
        is wrapped into (-180, 180] first, so 330 and -30 are the same answer.
    student : optional
        The id, when ``answers`` is one student's dict without ``student_id``.

    Returns
    -------
    graded : DataFrame
        One row per student and question: ``student, question, expected, answer, unit,
        error`` (answer - expected, wrapped for angles), ``tolerance, passed, status``
        (``ok``, ``wrong``, ``missing``, ``not a number``).
    summary : dict
        ``students, items, passed, failed, missing, score`` (fraction passed),
        ``per_student`` {id: {passed, total, score, failed: [questions]}},
        ``missing_students`` (in the key, no answer), ``unknown_students`` (answers
        but not in the key), ``unknown_questions`` (answered but not asked).
    """
    ans = read_answers(answers, student)
    students = list(dict.fromkeys(ans["student"].astype(str)))
    if isinstance(key, Mapping) and not isinstance(key, pd.DataFrame) and len(students) > 1:
        raise WorkbenchError("a dict key is one student's: grade one student at a time, or "
                             "give an Exercise / key table")
    if isinstance(key, Exercise):
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
    angle_keys = set(angle_keys)
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
    ans = ans.drop_duplicates(["student", "question"], keep="last")
    key_students = list(dict.fromkeys(kt["student"]))
    graded_students = [s for s in key_students if s in set(ans["student"])]
    unknown_students = [s for s in students if s not in set(key_students)]
    kt = kt[kt["student"].isin(graded_students)]
    m = kt.merge(ans, on=["student", "question"], how="left")
    exp = m["expected"].to_numpy(dtype=float)
    got = np.array([_to_float(a) for a in m["answer"]], dtype=float)
    is_angle = (m["kind"] == "angle").to_numpy()
    r = np.where(np.isnan(m["rtol"].to_numpy(dtype=float)), DEFAULT_RTOL,
                 m["rtol"].to_numpy(dtype=float))
    a = np.where(np.isnan(m["atol"].to_numpy(dtype=float)), 0.0,
                 m["atol"].to_numpy(dtype=float))
    if rtol is not None:
        r = np.full_like(r, float(rtol))
    if atol is not None:
        a = np.full_like(a, float(atol))
    a_ang = np.where(np.isnan(m["atol"].to_numpy(dtype=float)), ANGLE_ATOL,
                     m["atol"].to_numpy(dtype=float))
    if angle_atol is not None:
        a_ang = np.full_like(a_ang, float(angle_atol))
    err = np.where(is_angle, _wrap(got - exp), got - exp)
    tol = np.where(is_angle, a_ang, a + r * np.abs(exp))
    with np.errstate(invalid="ignore"):
        passed = np.abs(err) <= tol
    passed &= ~np.isnan(got)
    missing = m["answer"].isna().to_numpy() | np.array(
        [isinstance(x, float) and math.isnan(x) for x in m["answer"]], dtype=bool)
    status = np.where(passed, "ok", np.where(missing, "missing",
                                             np.where(np.isnan(got), "not a number", "wrong")))
    graded = pd.DataFrame({
        "student": m["student"], "question": m["question"], "expected": exp,
        "answer": got, "unit": m["unit"].fillna(""), "error": err, "tolerance": tol,
        "passed": passed, "status": status})
    per = {}
    for s, g in graded.groupby("student", sort=False):
        per[s] = {"passed": int(g.passed.sum()), "total": int(len(g)),
                  "score": float(g.passed.mean()) if len(g) else 0.0,
                  "failed": g.loc[~g.passed, "question"].tolist()}
    asked = set(kt["question"])
    summary = {
        "students": len(per), "items": int(len(graded)), "passed": int(graded.passed.sum()),
        "failed": int((graded.status == "wrong").sum() + (graded.status == "not a number").sum()),
        "missing": int((graded.status == "missing").sum()),
        "score": float(graded.passed.mean()) if len(graded) else 0.0,
        "per_student": per,
        "missing_students": [s for s in key_students if s not in set(ans["student"])],
        "unknown_students": unknown_students,
        "unknown_questions": sorted({q for q in ans["question"] if q not in asked}),
    }
    return graded, summary


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
                     "score %": round(100.0 * float(g.passed.mean()), 1),
                     "failed": ", ".join(g.loc[~g.passed, "question"])})
    return pd.DataFrame(rows, columns=["student", "passed", "total", "score %", "failed"])


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

    body = ",\n".join(f"    {str(q)!r}: {_to_float(v)!r}" for q, v in answers.items())
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


# ---------------------------------------------------------------- ready exercises
def _four_bar_scene(p: Mapping[str, float]) -> dict:
    """A crank-rocker four-bar A-B-C-D from the lengths a (crank), b (coupler), c
    (rocker), d (frame), with mid-link centres of mass, a force resisting the motion of
    the rocker's point E and gravity."""
    a, b, c, d = (float(p[k]) for k in ("a", "b", "c", "d"))
    ma, mb, mc = 7.8 * a, 7.8 * b, 7.8 * c          # kg: 7.8 kg/m, steel bars
    return {
        "title": "Four-bar crank-rocker (exercise)",
        "gravity": [0.0, -9.81],
        "ground": {"A": [0.0, 0.0], "D": [d, 0.0]},
        "driver": {"body": "crank", "joint": "A", "speed_rpm": float(p["rpm"]),
                   "start": 0.0, "stop": 360.0, "count": 361},
        "bodies": [
            {"name": "crank", "mass": ma, "inertia": ma * a * a / 12, "cog": [a / 2, 0.0],
             "points": {"A": [0.0, 0.0], "B": [a, 0.0]}},
            {"name": "coupler", "mass": mb, "inertia": mb * b * b / 12, "cog": [b / 2, 0.0],
             "points": {"B": [0.0, 0.0], "C": [b, 0.0]}},
            {"name": "rocker", "mass": mc, "inertia": mc * c * c / 12, "cog": [c / 2, 0.0],
             "points": {"D": [0.0, 0.0], "C": [c, 0.0], "E": [0.6 * c, 0.0]}},
        ],
        "joints": [
            {"name": "A", "kind": "R", "bodies": ["ground", "crank"]},
            {"name": "B", "kind": "R", "bodies": ["crank", "coupler"]},
            {"name": "C", "kind": "R", "bodies": ["coupler", "rocker"]},
            {"name": "D", "kind": "R", "bodies": ["ground", "rocker"]},
        ],
        "loads": [{"body": "rocker", "point": "E", "resist": float(p["load"])}],
        "near": {"C": [d, 0.8 * c]},
    }


def _grashof_crank_rocker(scene: dict, key: dict) -> bool:
    return key.get("tau_min", 90.0) >= 25.0


def four_bar_exercise(seed: int = 2024) -> Exercise:
    """The four-bar exercise of the sheets: a crank-rocker with lengths, speed and load
    drawn per student; asked: Me at 30 deg, the mean and largest Me, |F_B| max, |F_C|
    at 30 deg, the rocker's angle and angular velocity at 30 deg, the smallest
    transmission angle. Variants with a transmission angle below 25 deg are redrawn.

    Parameters
    ----------
    seed : int
        The exercise's seed (keep it private for marked work).

    Returns
    -------
    Exercise
    """
    text = ("A crank-rocker four-bar ABCD (crank AB = a, coupler BC = b, rocker CD = c, frame "
            "AD = d; bars of 7.8 kg/m with their centres of mass at mid-length) turns at n "
            "rpm, counter-clockwise. A force P resists the motion of the rocker's point E (DE = "
            "0.6 c); gravity acts. Find, by kinetostatics (seed 002 s. 2.3): the equilibrating "
            "moment Me at φ = 30°, its mean and largest values over the cycle, the largest "
            "reaction in B, the reaction in C at φ = 30°, the rocker's angle and angular "
            "velocity at φ = 30°, and the smallest transmission angle.")
    return Exercise(
        template=_four_bar_scene,
        ranges={"a": (0.08, 0.12, 0.005), "b": (0.26, 0.34, 0.01), "c": (0.20, 0.28, 0.01),
                "d": (0.28, 0.34, 0.01), "rpm": (150.0, 400.0, 10.0),
                "load": (100.0, 300.0, 10.0)},
        questions=["Me@30", "Me_mean", "Me_max", "Fmax[B]", "F[C]@30", "angle[rocker]@30",
                   "omega[rocker]@30", "tau_min"],
        seed=seed, title="Kinetostatics of a four-bar", text=text,
        check=_grashof_crank_rocker)


def rotor_exercise(seed: int = 2024) -> Exercise:
    """The rotor exercise of the sheets: three eccentric masses in three planes, two
    correction planes (dynamic balancing by design, seed 002 eqs 3.9-3.14); masses,
    radii and angles drawn per student; asked: both correction masses and angles and
    the initial resultant force. Variants with a correction mass below 1 g are redrawn.

    Parameters
    ----------
    seed : int
        The exercise's seed.

    Returns
    -------
    Exercise
    """
    template = {
        "title": "Rotor, dynamic balancing (exercise)",
        "rotor": {
            "speed_rpm": 1500.0,
            "unbalance": [
                {"mass": 0.020, "radius": 0.10, "angle": 30.0, "z": 0.05},
                {"mass": 0.015, "radius": 0.12, "angle": 150.0, "z": 0.15},
                {"mass": 0.010, "radius": 0.08, "angle": 260.0, "z": 0.25},
            ],
            "planes": [{"z": 0.0, "radius": 0.12}, {"z": 0.30, "radius": 0.12}],
        },
    }
    ranges = {}
    for k in range(3):
        ranges[f"rotor.unbalance.{k}.mass"] = (0.005, 0.030, 0.001)
        ranges[f"rotor.unbalance.{k}.radius"] = (0.06, 0.14, 0.01)
        ranges[f"rotor.unbalance.{k}.angle"] = (0.0, 355.0, 5.0)
    text = ("A rigid rotor turning at 1500 rpm carries three eccentric masses m_k at radii "
            "r_k, angles θ_k, in planes z_k. Balance it in the planes z = 0 and z = 0.30 m "
            "with masses fixed at 0.12 m (seed 002 eqs 3.9-3.14): give both correction masses "
            "and their angles, and the resultant inertia force before balancing.")

    def big_enough(scene: dict, key: dict) -> bool:      # angles of tiny masses mean little
        return min(key["mass[1]"], key["mass[2]"]) >= 1e-3

    return Exercise(template=template, ranges=ranges,
                    questions=["mass[1]", "angle[1]", "mass[2]", "angle[2]", "initial_force"],
                    seed=seed, title="Dynamic balancing of a rotor", text=text,
                    check=big_enough)
