"""Answer keys: the asked quantities of one scene, with unit, kind and tolerance.

A mechanism scene is computed with :func:`kinetostatics.solve`, a balancing scene with
:func:`balance.solve`; the question language is described in
:mod:`kinetostatics.teaching.questions`.
"""

from __future__ import annotations

import copy
import math
import warnings
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from ..common.angles import degree_column
from ..model.errors import WorkbenchError
from ..model.tomlio import read_source
from .questions import ANGLE_ATOL, ATOL_FRACTION, Question, is_mechanism, parse_question

__all__ = ["answer_key", "key_rows", "key_rows_many"]

_LIBRARY_NOTICES = (DeprecationWarning, PendingDeprecationWarning, FutureWarning,
                    ResourceWarning)      # about the libraries' future, not this result


def _vouched(solver, raw: dict):
    """``solver(raw)``, refused when it warns: a key must be a result one can vouch for
    (an exercise then draws the variant again)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = solver(raw)
    flag = _flag(caught)
    if flag is not None:
        raise flag
    return out


# --------------------------------------------------------------- mechanism answers
_MECH_UNITS = {"Me": "N m", "Fe": "N", "F": "N", "Fx": "N", "Fy": "N", "Fmax": "N",
               "Fangle": "deg", "N": "N", "M": "N m", "tau": "deg", "tau_min": "deg",
               "angle": "deg", "omega": "rad/s", "alpha": "rad/s^2", "x": "m", "y": "m",
               "v": "m/s", "a": "m/s^2", "Me_mean": "N m", "Me_max": "N m", "Me_min": "N m",
               "Fe_mean": "N", "Fe_max": "N", "Fe_min": "N"}
_ANGLES = {"Fangle", "angle", "res_angle", "res_mirror"}
_PLAIN_DEG = {"tau", "tau_min"}      # transmission angles, min(tau, 180 - tau) in [0, 90]


def _needs_position(q: Question) -> None:
    if q.pos is None:
        raise WorkbenchError(f"question {q.text!r}: give the driver position, e.g. "
                             f"'{q.text}@30'")


def _row_of(sol, q: Question) -> int:
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


def _mechanism_values(raw: dict, questions: Sequence[Question],
                      solved: dict | None = None) -> dict[str, tuple]:
    """question -> (value, unit, kind, atol). ``solved``: ``_vouched(solve, s)`` (the
    Solution or the exception) of the scene and of its sweep with the asked positions
    added, by the scene's id, where already solved (:func:`key_rows_many`)."""
    from ..results import solve

    done = solved.get(id(raw), (None, None)) if solved is not None else (None, None)

    def vouched(scene: dict, got):
        if got is None:
            return _vouched(solve, scene)
        if isinstance(got, Exception):
            raise got
        return got
    sol = vouched(raw, done[0])
    at = [q.pos for q in questions if q.pos is not None]
    aug = _with_positions(raw, at) if at else None
    psol = vouched(aug, done[1]) if aug is not None else sol
    summ = sol.summary()
    out: dict[str, tuple] = {}
    for q in questions:
        unit = _MECH_UNITS.get(q.q, "")
        kind = "angle" if q.q in _ANGLES else "number"
        val, scale, unit = _mechanism_value(q, sol, psol, summ, unit)
        if q.q in _PLAIN_DEG:           # in [0, 90]: a plain number, not modulo 360
            kind, atol = "number", ANGLE_ATOL
        elif kind == "angle" or unit == "deg":
            kind, atol = "angle", ANGLE_ATOL
        else:
            atol = ATOL_FRACTION * (scale or 0.0)
        out[q.text] = (val, unit, kind, atol)
    return out


def _mechanism_value(q: Question, sol, psol, summ: dict, unit: str
                     ) -> tuple[float, float | None, str]:
    """One question's (value, scale of the quantity over the cycle, unit)."""
    dq = sol.driver_quantity
    if q.q in ("Me", "Fe"):
        if q.q != dq:
            raise WorkbenchError(f"question {q.text!r}: this driver has {dq}, not {q.q}")
        _needs_position(q)
        return float(psol.Me[_row_of(psol, q)]), float(np.abs(sol.Me).max()), unit
    if q.q in ("Me_mean", "Me_max", "Me_min", "Fe_mean", "Fe_max", "Fe_min"):
        if q.q[:2] != dq:
            raise WorkbenchError(f"question {q.text!r}: this driver has {dq}, not "
                                 f"{q.q[:2]}")
        return float(summ[q.q]), float(np.abs(sol.Me).max()), unit
    if q.q in ("F", "Fx", "Fy", "Fmax", "Fangle", "N", "M"):
        return (*_reaction_value(q, sol, psol, summ), unit)
    if q.q == "tau_min":
        val = summ["transmission_angle_min"]
        if val is None:
            raise WorkbenchError(f"question {q.text!r}: the mechanism has no dyad")
        return float(val), None, "deg"
    if q.q == "tau":
        _needs_position(q)
        t = psol.dyads
        g = t[t.dyad == int(q.arg or 1)]
        if g.empty:
            raise WorkbenchError(f"question {q.text!r}: no dyad {q.arg}")
        t = float(g.transmission_angle.to_numpy()[_row_of(psol, q)]) % 180.0
        return min(t, 180.0 - t), None, unit   # the summary's definition, min(tau, 180 - tau)
    if q.q in ("angle", "omega", "alpha"):
        return (*_body_value(q, sol, psol), unit)
    if q.q in ("x", "y", "v", "a"):
        return (*_point_value(q, sol, psol), unit)
    raise WorkbenchError(f"question {q.text!r}: unknown mechanism quantity {q.q!r}; "
                         f"known: {', '.join(sorted(_MECH_UNITS))}")


def _reaction_value(q: Question, sol, psol, summ: dict) -> tuple[float, float]:
    """A joint's reaction asked for (F, Fx, Fy, Fmax, Fangle, N, M) and its scale."""
    if q.arg not in sol.scene.joints:
        raise WorkbenchError(f"question {q.text!r}: no joint {q.arg!r}; joints: "
                             f"{', '.join(sol.scene.joints)}")
    fx, fy = sol.reaction(q.arg)
    scale = float(np.hypot(fx, fy).max())
    if q.q == "Fmax":
        return float(summ["reaction_max"][q.arg]["F"]), scale
    _needs_position(q)
    i = _row_of(psol, q)
    px, py = psol.reaction(q.arg)
    if q.q in ("N", "M"):
        r = psol.joint_reactions[q.arg]
        if r.N is None:
            raise WorkbenchError(f"question {q.text!r}: joint {q.arg!r} is "
                                 "revolute: it has no N or M")
        arr = r.N if q.q == "N" else r.M
        val = float(np.broadcast_to(arr, (psol.positions.size,))[i])
        s0 = sol.joint_reactions[q.arg]
        full = np.broadcast_to(s0.N if q.q == "N" else s0.M, sol.positions.shape)
        return val, float(np.abs(full).max())
    return {"F": float(np.hypot(px[i], py[i])), "Fx": float(px[i]), "Fy": float(py[i]),
            "Fangle": float(degree_column(np.arctan2(py[i], px[i])) % 360.0)}[q.q], scale


def _body_value(q: Question, sol, psol) -> tuple[float, float | None]:
    """A body's angle (modulo 360), omega or alpha asked for, and its scale."""
    _needs_position(q)
    if q.arg not in sol.scene.bodies:
        raise WorkbenchError(f"question {q.text!r}: no body {q.arg!r}; bodies: "
                             f"{', '.join(sol.scene.bodies)}")
    t = psol.bodies
    g = t[t.body == q.arg]
    val = float(g[q.q].to_numpy()[_row_of(psol, q)])
    if q.q == "angle":
        return val % 360.0, None
    full = sol.bodies[sol.bodies.body == q.arg][q.q].to_numpy()
    return val, float(np.abs(full).max())


def _point_value(q: Question, sol, psol) -> tuple[float, float]:
    """A point's x, y, speed or acceleration asked for, and its scale."""
    _needs_position(q)
    b, _, p = (q.arg or "").partition(".")
    k = psol.kinematics
    g = k[(k.body == b) & (k.point == p)]
    if g.empty:
        raise WorkbenchError(f"question {q.text!r}: no point {q.arg!r} (write "
                             "'body.point', e.g. 'coupler.P')")
    row = g.iloc[_row_of(psol, q)]
    val = float({"x": row.x, "y": row.y, "v": math.hypot(row.vx, row.vy),
                 "a": math.hypot(row.ax, row.ay)}[q.q])
    k0 = sol.kinematics
    g0 = k0[(k0.body == b) & (k0.point == p)]
    scale = float({"x": np.ptp(g0.x.to_numpy()) + np.abs(g0.x).max(),
                   "y": np.ptp(g0.y.to_numpy()) + np.abs(g0.y).max(),
                   "v": np.hypot(g0.vx, g0.vy).max(),
                   "a": np.hypot(g0.ax, g0.ay).max()}[q.q])
    return val, scale


# ---------------------------------------------------------------- balance answers
def _balance_values(raw: dict, questions: Sequence[Question]) -> dict[str, tuple]:
    import balance

    res = _vouched(balance.solve, raw)
    rot = res.get("rotor")
    force_units = ("N", "N m") if rot is not None and \
        raw.get("rotor", {}).get("speed_rpm") is not None else ("kg m", "kg m^2")
    out: dict[str, tuple] = {}

    def need(section: str, q: Question):
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
        if unit == "deg":
            kind = "angle"
        atol = ANGLE_ATOL if kind == "angle" else ATOL_FRACTION * abs(scale or val)
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
    return {k: v[0] for k, v in key_rows(read_source(scene), list(questions)).items()}


def key_rows_many(raws: Sequence[dict], questions: Sequence[str]) -> list[dict | Exception]:
    """:func:`key_rows` of each scene, or the exception it raises, in order; the
    mechanism scenes (and their sweeps with the asked positions added) solved together
    by :func:`~kinetostatics.results.solving.solve_outcomes`, each with exactly the numbers
    and the refusals (an error, a warning) of its own solve."""
    qs = [parse_question(q) for q in questions]
    at = [q.pos for q in qs if q.pos is not None]
    scenes, augs = [], []
    for raw in raws:
        if is_mechanism(raw):
            try:
                aug = _with_positions(raw, at) if at else None
            except Exception:           # raised again, in its turn, by key_rows below
                aug = None
            scenes.append(raw)
            augs.append(aug)
    done = _vouched_many(scenes + [a for a in augs if a is not None])
    more = iter(done[len(scenes):])
    solved = {id(raw): (got, None if aug is None else next(more))
              for raw, aug, got in zip(scenes, augs, done, strict=False)}
    out: list[Any] = []
    for raw in raws:
        try:
            out.append(_mechanism_values(raw, qs, solved) if is_mechanism(raw)
                       else _balance_values(raw, qs))
        except Exception as exc:        # the caller takes it as key_rows' own
            out.append(exc)
    return out


def _vouched_many(raws: list[dict]) -> list:
    """``_vouched(solve, raw)`` of each scene (its Solution or exception), solved
    together; a warning that the batch cannot pin on one scene sends each back to
    :func:`_vouched` alone."""
    from ..model.scene import load_scene
    from ..results import solve, solve_outcomes

    flags: list[Any] = []
    loaded: list[Any] = []
    for raw in raws:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                loaded.append(load_scene(raw))
            except Exception as exc:
                loaded.append(exc)
        flags.append(_flag(caught))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        # (every key reads the summary, so every table: the runs kept whole)
        sols = solve_outcomes([sc for sc in loaded if not isinstance(sc, Exception)],
                              lean=False)
    if _flag(caught) is not None:
        return [_outcome(_vouched, solve, raw) for raw in raws]
    it = iter(sols)
    out = []
    for sc, flag in zip(loaded, flags, strict=True):
        got = sc if isinstance(sc, Exception) else next(it)
        out.append(flag if flag is not None and not isinstance(got, Exception) else got)
    return out


def _flag(caught: list) -> WorkbenchError | None:
    """The refusal :func:`_vouched` makes of these warnings, or None."""
    caught = [w for w in caught if not issubclass(w.category, _LIBRARY_NOTICES)]
    if not caught:
        return None
    msg = " ".join(str(caught[0].message).split())
    return WorkbenchError(f"the solver flags this scene: {msg}")


def _outcome(f, *args):
    try:
        return f(*args)
    except Exception as exc:
        return exc


def key_rows(raw: dict, questions: Sequence[str]) -> dict[str, tuple]:
    qs = [parse_question(q) for q in questions]
    if is_mechanism(raw):
        return _mechanism_values(raw, qs)
    return _balance_values(raw, qs)


