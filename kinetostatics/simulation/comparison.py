"""A simulated run against kinetostatics: the comparison tables (:class:`CrossCheck`).

Two kinds of simulated values are compared. pymunk's own readings, the magnitudes of
the constraint impulses over dt (every joint's |F| and the driver's |Me| or |Fe|),
make the headline ``errors`` and ``max_error``. The values derived from the momentum
balance of the bodies (:mod:`.signed`: the reactions' components, the normal forces
and couples of prismatic joints, the signed driving moment) go to ``derived_errors``:
they rest on the balance's own arithmetic as well as on pymunk.

Error of a quantity: the largest |simulated - computed| over the compared rows,
divided by the largest |computed| there. Compared rows: after the first revolution
(a full turn is simulated ``revolutions`` times), or, for a sweep shorter than a
turn (and for a sliding driver), the sweep after its first 1 %; rows that
kinetostatics flags ``singular`` or ``undefined_load``, or where a ``resist`` point is
nearly still in the simulation, are left out.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from ..model.scene import Scene
from .errors import SimulationError
from .friction import near_reversals
from .stepper import SimRecord

__all__ = ["CrossCheck", "ZERO_COUPLE", "compare"]

ZERO_COUPLE = 1e-9
"""A prismatic joint's couple below this times max|F| x the mechanism's size counts as
zero in kinetostatics (it is compared on that scale, not on its own)."""


@dataclass
class CrossCheck:
    """A simulated run compared with kinetostatics.

    Attributes
    ----------
    scene : Scene
    record : SimRecord
        The simulation's readings.
    reference : Solution
        Kinetostatics at the simulated driver positions (its first row, the scene's
        first position, is dropped from every comparison).
    rows : pandas.DataFrame
        Long table ``position, time, quantity, source, simulated, computed, used``: one
        row per sample and quantity (``F[joint]`` and ``|Me|`` (``|Fe|``): pymunk's
        readings, ``source = "pymunk"``; ``M[joint]``, the signed couple of a prismatic
        joint where kinetostatics does not find it zero, and ``Me`` (``Fe``), signed:
        ``source = "momentum balance"``).
    errors : dict
        pymunk's readings: quantity -> relative error over the compared rows.
    derived_errors : dict
        The same for the values derived from the momentum balance (``Fx[j]``,
        ``Fy[j]``, ``N[j]``, ``M[j]``, ``Me`` or ``Fe``).
    settings : dict
        dt, iterations, error_bias, steps per revolution, revolutions, samples.
    notes : list of str
        What the reader should know (translating bodies, couples that are zero, mass
        models, rows left out...).
    """

    scene: Scene
    record: SimRecord
    reference: Any
    rows: pd.DataFrame
    errors: dict[str, float]
    derived_errors: dict[str, float]
    settings: dict[str, Any]
    notes: list[str] = field(default_factory=list)

    @property
    def max_error(self) -> float:
        """The largest error of pymunk's readings: every joint's |F| and the driver's |Me|
        (|Fe|)."""
        return max(self.errors.values()) if self.errors else float("nan")

    @property
    def vector_errors(self) -> dict[str, float]:
        """The earlier name of :attr:`derived_errors`."""
        return self.derived_errors

    @property
    def seconds_per_revolution(self) -> float | None:
        """Wall time per simulated driver revolution (None for a sliding driver)."""
        return self.settings["seconds_per_revolution"]

    def error_table(self) -> pd.DataFrame:
        """Per quantity: ``quantity, source`` (``pymunk`` or ``momentum balance``),
        ``unit, scale`` (largest |computed|), ``max_abs_error``, ``error`` (relative)
        and ``position`` of the worst row."""
        out = []
        for q, g in self.rows[self.rows.used].groupby("quantity", sort=False):
            d = np.abs(g.simulated.to_numpy() - g.computed.to_numpy())
            i = int(np.argmax(d))
            out.append({"quantity": q, "source": g.source.iloc[0],
                        "unit": quantity_unit(q, self.scene),
                        "scale": float(np.abs(g.computed).max()),
                        "max_abs_error": float(d[i]),
                        "error": self.errors.get(q, self.derived_errors.get(q)),
                        "position": float(g.position.to_numpy()[i])})
        return pd.DataFrame(out)

    def wide(self) -> pd.DataFrame:
        """One row per sample: ``position``, ``time`` and ``<quantity> sim`` /
        ``<quantity> ks`` columns, ``used``."""
        r = self.rows
        first = r[r.quantity == r.quantity.iloc[0]]
        out = pd.DataFrame({"position": first.position.to_numpy(),
                            "time": first.time.to_numpy()})
        for q, g in r.groupby("quantity", sort=False):
            out[f"{q} sim"] = g.simulated.to_numpy()
            out[f"{q} ks"] = g.computed.to_numpy()
        out["used"] = first.used.to_numpy()
        return out

    def summary(self) -> dict[str, Any]:
        """A JSON-ready dict: the settings, ``seconds_per_revolution``, ``max_error``,
        ``errors`` per quantity (pymunk's readings), ``derived_errors`` (the momentum
        balance's values), ``vector_check``, notes."""
        worst = max(self.errors, key=self.errors.get) if self.errors else None
        s = dict(self.settings)
        s.update({
            "title": self.scene.title,
            "max_error": self.max_error,
            "worst": worst,
            "errors": dict(self.errors),
            "derived_errors": dict(self.derived_errors),
            "vector_check": self.record.vector_check,
            "rows": int(self.rows.position.nunique()),
            "rows_compared": int(self.rows[self.rows.used].position.nunique()),
            "notes": list(self.notes),
        })
        return s


def quantity_unit(q: str, scene: Scene) -> str:
    if q.startswith("M[") or q in ("Me", "|Me|"):
        return "N m"
    return "N"



def compare(sc: Scene, model, rec: SimRecord, ref, *, compare_from: float) -> CrossCheck:
    """Build the comparison tables of a run (see :func:`crosscheck`)."""
    n = rec.time.size
    used = rec.time > compare_from * (1.0 + 1e-12)
    flagged = _flagged(sc, model, rec, ref)
    used &= ~flagged
    if not used.any():
        raise SimulationError(
            f"none of the {n} simulated rows can be compared ({int(flagged.sum())} flagged "
            "singular / undefined_load / resist point nearly still, the rest in the first "
            "revolution); simulate more revolutions or another sweep")
    react = ref.reactions
    parts = []
    errors: dict[str, float] = {}
    verr: dict[str, float] = {}
    notes: list[str] = []

    def err(sim, ks_) -> float:
        if not used.any():
            return float("nan")
        scale = float(np.max(np.abs(ks_[used])))
        d = float(np.max(np.abs(sim[used] - ks_[used])))
        return d / scale if scale > 0.0 else (0.0 if d == 0.0 else float("inf"))

    def add(q, sim, ks_, into=verr, table=False):
        into[q] = err(sim, ks_)
        if table:
            parts.append(pd.DataFrame({"position": rec.position, "time": rec.time,
                                       "quantity": q,
                                       "source": "pymunk" if into is errors
                                       else "momentum balance",
                                       "simulated": sim, "computed": ks_, "used": used}))

    zero: dict[str, float] = {}
    for name, j in sc.joints.items():
        r = react[react.joint == name]
        F = r.F.to_numpy()[1:]
        add(f"F[{name}]", rec.impulse[name], F, errors, True)
        fx, fy = rec.signed[name]
        add(f"Fx[{name}]", fx, r.Fx.to_numpy()[1:])
        add(f"Fy[{name}]", fy, r.Fy.to_numpy()[1:])
        if j.kind == "T":
            N, M = r.N.to_numpy()[1:], r.M.to_numpy()[1:]
            add(f"N[{name}]", rec.signed[f"{name}:N"], N)
            Ms = rec.signed[f"{name}:M"]
            # a couple that kinetostatics finds zero (to rounding) has no scale of its
            # own: measure it against the joint's force times the mechanism's size
            top = float(np.max(np.abs(M[used]))) if used.any() else 0.0
            big = float(np.max(F[used])) * sc.size if used.any() else 0.0
            if top <= ZERO_COUPLE * big:
                zero[f"M[{name}]"] = (float(np.max(np.abs(Ms[used] - M[used]))) / big
                                      if big > 0.0 else 0.0)
                notes.append(f"prismatic joint {name!r}: kinetostatics gives M = 0; the "
                             f"simulated couple is at most {zero[f'M[{name}]']:.1e} of "
                             "max|F| x the mechanism's size (in derived_errors)")
            else:
                add(f"M[{name}]", Ms, M, table=True)
    verr.update(zero)
    q = "Me" if sc.driver.kind == "R" else "Fe"
    drive = np.asarray(ref.Me, dtype=float)[1:]
    add(f"|{q}|", rec.impulse["driver"], np.abs(drive), errors, True)
    add(q, rec.signed["driver"], drive, table=True)
    notes.extend(_run_notes(sc, model, flagged))
    rows = pd.concat(parts, ignore_index=True)
    return CrossCheck(sc, rec, ref, rows, errors, verr, {}, notes)


def _flagged(sc: Scene, model, rec: SimRecord, ref) -> np.ndarray:
    """The simulated rows left out of the errors: singular, an undefined load, a resist
    point nearly still, self-locking, or near a reversal of a joint's relative motion
    (with joint friction)."""
    flagged = np.asarray(ref.singular[1:], dtype=bool) | \
        np.asarray(ref.undefined_load[1:], dtype=bool) | rec.resist_unsure
    if ref.self_locking is not None:
        flagged |= np.asarray(ref.self_locking[1:], dtype=bool)
    if model.joint_friction:
        flagged |= near_reversals(sc, ref.kin, rec.time, rec.dt)
    return flagged


def _run_notes(sc: Scene, model, flagged: np.ndarray) -> list[str]:
    """What the run's notes say besides the joints': the model's notes, the bodies built
    differently, the friction simulated, the rows left out."""
    n = flagged.size
    notes = list(model.notes)
    if model.translating:
        notes.append("bodies that only translate, built with an infinite moment of inertia: "
                     + ", ".join(sorted(model.translating)))
    for name, b in sc.bodies.items():
        if b.mass_model is not None:
            notes.append(f"body {name!r} has a {b.mass_model.kind} mass model: kinetostatics "
                         "uses it, the simulation uses the body's exact mass and inertia")
    if model.joint_friction:
        notes.append("joint friction simulated (" + ", ".join(j[1] for j in model.joint_friction)
                     + "): couples rho |F| and forces mu |N| from the reactions of the steps "
                     "before, extrapolated; rows near a reversal of a joint's relative motion "
                     "are flagged")
    skipped = int(np.count_nonzero(flagged))
    if skipped:
        what = "singular / undefined_load / resist point nearly still" + (
            " / self-locking / friction reversing" if model.joint_friction else "")
        notes.append(f"{skipped} of {n} rows flagged {what}: left out of the errors")
    return notes
