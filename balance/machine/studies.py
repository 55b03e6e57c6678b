"""How well the machine's methods recover an unbalance, against the speed history and
the size of the trial mass (:func:`coast_down_study`)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterable
from concurrent.futures import Executor
from dataclasses import replace

import numpy as np

from ..errors import BalanceError, BalanceWarning
from ..resonance.methods import parallelogram, trial_runs
from .coastdown import CoastDown
from .mount import BalancingMachine, machine_record
from .records import MachineRecord, method_result
from .unbalances import random_unbalance


def _study_record(item: tuple) -> MachineRecord | None:
    """A study's run: as :func:`machine_record`, None when the run gives no peak."""
    try:
        return machine_record(item)
    except BalanceError:
        return None


def coast_down_study(durations: Iterable[float | None] = (None, 10.0, 3.0, 1.0, 0.5),
                     trial_factors: Iterable[float] = (0.1, 1.0, 10.0),
                     seeds: Iterable[int] = (1, 2, 3), *,
                     machine: BalancingMachine | None = None, trial_radius: float = 0.08,
                     correction_radius: float = 0.08,
                     executor: Executor | str | None = None):
    """How well the machine's methods recover an unbalance, against the speed history
    and the size of the trial mass.

    For each duration of the coast-down (None: the constant-speed machine at
    resonance), each seeded random unbalance (:func:`random_unbalance`) and each trial
    mass (``trial_factor`` x |U| / ``trial_radius``: the trial unbalance that many
    times the one put in), the machine runs the rotor as it is and with the trial mass
    at 0, 120, 180 and 240 deg; the three-run method (eqs 3.29-3.31) takes the 0 and
    180 deg runs, the four-run method the 0, 120 and 240 deg ones, each without and
    with the mass correction (:meth:`BalancingMachine.mass_factor`). All the runs are
    one batch through ``executor`` (see :meth:`BalancingMachine.runs`).

    Parameters
    ----------
    durations : iterable of float or None
        Coast-down times (s) from 1.5 to 0.5 omega_n; None for constant speed.
    trial_factors : iterable of float
        Trial unbalance / unbalance.
    seeds : iterable of int
        Random unbalances.
    machine : BalancingMachine, optional
        The machine (default ``BalancingMachine()``); its ``coast_down`` is replaced.
    trial_radius, correction_radius : float
        m.
    executor : Executor, ``"serial"`` or None
        Default: processes, one per core.

    Returns
    -------
    pandas.DataFrame
        One row per duration, trial factor and correction: ``duration`` (s),
        ``passage`` (time constants to cross the half-power band),
        ``trial_factor``, ``mass_correction``, ``three_error`` and ``three_angle``
        (largest |m r| relative error and angle error, deg, over the seeds; the
        nearer mirror candidate), ``four_error``, ``four_angle``, ``peak_speed``
        (mean speed at the A1 peak / omega_n), ``peak_ratio`` (mean A1 / the largest
        steady amplitude |U| / (c sqrt(M / k - c^2 / 4 k^2))), ``three_failed``,
        ``four_failed`` (seeds for which the method gave no result: no peak inside a
        run, or amplitudes no parallelogram joins), ``seeds``.
    """

    import pandas as pd
    base = machine if machine is not None else BalancingMachine()
    durs = list(durations)
    facs = [float(f) for f in trial_factors]
    sds = list(seeds)
    marks = (0.0, 120.0, 180.0, 240.0)
    machines = [replace(base, coast_down=None if d is None else CoastDown(duration=float(d)),
                        speed=None) for d in durs]
    items, index = [], {}
    for i, bm in enumerate(machines):
        st = bm.settings()
        for sd in sds:
            us = random_unbalance(sd)
            plain = [(u.mass, u.radius, u.angle) for u in us]
            index[i, sd, None, None] = len(items)
            items.append((st, plain))
            for f in facs:
                tm = f * abs(sum((u.U for u in us), 0j)) / trial_radius
                for a in marks:
                    index[i, sd, f, a] = len(items)
                    items.append((st, [*plain, (tm, trial_radius, a)]))
    from kinetostatics.simulation import run_batch
    recs = run_batch(_study_record, items, executor=executor)
    rows = []
    for i, (d, bm) in enumerate(zip(durs, machines, strict=True)):
        k, c = bm.stiffness, bm.damping
        for f in facs:
            for corr in (False, True):
                out = {"three": [], "three_angle": [], "four": [], "four_angle": [],
                       "speed": [], "ratio": []}
                failed = {"three": 0, "four": 0}
                for sd in sds:
                    us = random_unbalance(sd)
                    U = sum((u.U for u in us), 0j)
                    tm = f * abs(U) / trial_radius
                    r1 = recs[index[i, sd, None, None]]
                    rk = {a: recs[index[i, sd, f, a]] for a in marks}
                    if r1 is None or any(r is None for r in rk.values()):
                        failed["three"] += 1
                        failed["four"] += 1
                        continue
                    m_all = bm.frame_mass + bm.rotor_mass + sum(u.mass for u in us)
                    top = abs(U) / (c * math.sqrt(m_all / k - c * c / (4.0 * k * k)))
                    out["speed"].append(r1.speed / bm.omega_n)
                    out["ratio"].append(r1.amplitude / top)
                    fac = bm.mass_factor(sum(u.mass for u in us), tm) if corr else 1.0
                    A = {a: r.amplitude * fac for a, r in rk.items()}
                    _recover(out, failed, r1.amplitude, A, tm, us, trial_radius,
                             correction_radius)

                def worst(v: list) -> float:
                    return float(max(v)) if v else float("nan")

                rows.append({
                    "duration": float("inf") if d is None else float(d),
                    "passage": float("inf") if d is None
                    else bm.coast_down.passage(bm.omega_n, bm.damping_ratio),
                    "trial_factor": f, "mass_correction": corr,
                    "three_error": worst(out["three"]), "three_angle": worst(out["three_angle"]),
                    "four_error": worst(out["four"]), "four_angle": worst(out["four_angle"]),
                    "peak_speed": float(np.mean(out["speed"])) if out["speed"] else float("nan"),
                    "peak_ratio": float(np.mean(out["ratio"])) if out["ratio"] else float("nan"),
                    "three_failed": failed["three"], "four_failed": failed["four"],
                    "seeds": len(sds)})
    return pd.DataFrame(rows)


def _recover(out: dict, failed: dict, a1: float, A: dict, tm: float, us: list,
             trial_radius: float, correction_radius: float) -> None:
    """The three-run (0 and 180 deg) and four-run (0, 120, 240 deg) methods on one
    seed's amplitudes ``a1`` (the rotor as it is) and ``A`` (with the trial mass ``tm``
    at each mark): their errors added to ``out``, a method that gives no result counted
    in ``failed``."""
    with warnings.catch_warnings():
        # the methods warn of ill-conditioned readings (the warnings are in their
        # results too); the study counts their errors
        warnings.simplefilter("ignore", BalanceWarning)
        try:
            res = parallelogram(a1, A[0.0], A[180.0], tm, trial_radius, correction_radius)
            mr = method_result(res, {}, us, [])
            out["three"].append(mr.unbalance_error)
            # the method cannot tell its two candidates apart
            out["three_angle"].append(min(mr.angle_error, mr.mirror_angle_error))
        except BalanceError:
            failed["three"] += 1
        try:
            res = trial_runs(a1, [(a, A[a]) for a in (0.0, 120.0, 240.0)], tm,
                             trial_radius, correction_radius)
            mr = method_result(res, {}, us, [])
            out["four"].append(mr.unbalance_error)
            out["four_angle"].append(mr.angle_error)
        except BalanceError:
            failed["four"] += 1
