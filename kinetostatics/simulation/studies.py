"""Speed against error of the simulation: :func:`study` sweeps the time step and the
solver iterations and reports the wall time per simulated revolution against the
error, with the observed order of convergence. Its runs are a batch
(:func:`~kinetostatics.simulation.run_batch`)."""

from __future__ import annotations

import math
from concurrent.futures import Executor
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from .batch import run_batch
from .errors import SimulationError
from .runner import _dict_scene, crosscheck

STUDY_STEPS = (500, 1000, 2000, 4000, 8000, 16000, 32000)
"""Default steps per revolution of the study."""

STUDY_ITERATIONS = (10, 30)
"""Default solver iterations of the study."""

ORDER_FLOOR = 1e-6
"""The convergence order is fitted on errors above this (rounding takes over near 1e-7)."""

@dataclass
class Study:
    """Speed against error over time steps and iteration counts.

    Attributes
    ----------
    table : pandas.DataFrame
        ``case, dt, steps_per_revolution, iterations, ms_per_revolution, max_error,
        order`` (``order``: the local order log(e1 / e2) / log(dt1 / dt2) against the
        previous, larger step with the same iterations).
    order : dict
        Iterations -> the order fitted (least squares in log-log) on the errors above
        1e-6, or None with fewer than two such points.
    """

    table: pd.DataFrame
    order: dict[int, float | None]

    def best(self, threshold: float) -> dict[str, Any] | None:
        """The cheapest run (ms per revolution) whose error is at most ``threshold``."""
        ok = self.table[self.table.max_error <= threshold]
        if ok.empty:
            return None
        return ok.sort_values("ms_per_revolution").iloc[0].to_dict()

    def summary(self) -> dict[str, Any]:
        """JSON-ready: the rows, the fitted orders and the cheapest runs at 1e-5 and 1e-6."""
        return {"rows": self.table.to_dict(orient="records"),
                "order": {str(k): v for k, v in self.order.items()},
                "best_1e-5": self.best(1e-5), "best_1e-6": self.best(1e-6)}


def study(scene: Any, *, steps: tuple[int, ...] | None = None,
          dts: tuple[float, ...] | None = None,
          iterations: tuple[int, ...] = STUDY_ITERATIONS, revolutions: float = 2.0,
          samples_per_revolution: int = 360, repeats: int = 1, case: str | None = None,
          fast: bool | None = None, executor: Executor | str | None = None) -> Study:
    """Sweep the time step and the iterations; wall time per revolution against error.

    Parameters
    ----------
    scene : path, TOML text, dict or Scene
    steps : tuple of int, optional
        Steps per revolution to try (default ``STUDY_STEPS``); or give ``dts``.
    dts : tuple of float, optional
        Time steps (s) to try instead.
    iterations : tuple of int
        Solver iterations to try (default 10 and 30).
    revolutions, samples_per_revolution, fast
        As in :func:`crosscheck`.
    repeats : int
        Runs per setting; the wall time is the smallest (the least disturbed).
    case : str, optional
        Label of the ``case`` column (default the scene's title).
    executor : Executor, ``"serial"`` or None
        Runs the settings (times the repeats) as a batch
        (:func:`kinetostatics.simulation.run_batch`): None, processes (one per core);
        ``"serial"``, one after another in this process; or any
        ``concurrent.futures.Executor`` (a dask ``Client.get_executor()``). Each run
        times its own stepping loop in its worker, so the wall times stay per run; but
        runs side by side share the machine (memory, caches, clock boost: on a 2-core
        machine two at once were measured up to about 10 % slower each), so tables of
        wall time are best made ``"serial"``. The errors do not depend on it.

    Returns
    -------
    Study
    """
    sc = _dict_scene(scene)
    if steps is not None and dts is not None:
        raise SimulationError("give steps per revolution or dts, not both")
    grid = [("dt", float(x)) for x in dts] if dts is not None else \
        [("steps", int(x)) for x in (steps or STUDY_STEPS)]
    n_rep = max(1, int(repeats))
    keys = [(int(it), kind, val) for it in iterations for kind, val in grid]
    settings = {"revolutions": revolutions, "samples_per_revolution": samples_per_revolution,
                "fast": fast}
    items = [(sc.raw, kind, val, it, settings) for it, kind, val in keys
             for _ in range(n_rep)]
    done = run_batch(_study_run, items, executor=executor)
    rows = []
    for i, (it, _kind, _val) in enumerate(keys):
        best = min(done[i * n_rep:(i + 1) * n_rep], key=lambda r: r["wall"])
        err = best["max_error"]
        rows.append({"case": case or sc.title, "dt": best["dt"],
                     "steps_per_revolution": best["steps_per_revolution"],
                     "iterations": it, "ms_per_revolution": 1e3 * best["wall"],
                     "max_error": err if math.isfinite(err) else float("inf")})
    table = pd.DataFrame(rows)
    table["order"] = np.nan
    order: dict[int, float | None] = {}
    for it, g in table.groupby("iterations"):
        g = g.sort_values("dt", ascending=False)
        e, h = g.max_error.to_numpy(), g.dt.to_numpy()
        with np.errstate(divide="ignore", invalid="ignore"):
            local = np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])
        table.loc[g.index[1:], "order"] = local
        fit = (e > ORDER_FLOOR) & np.isfinite(e) & (e < 1.0)
        order[int(it)] = float(np.polyfit(np.log(h[fit]), np.log(e[fit]), 1)[0]) \
            if fit.sum() >= 2 else None
    return Study(table, order)


def _study_run(item: tuple) -> dict[str, Any]:
    """One run of a study (a batch work item: plain data in, plain data out)."""
    raw, kind, val, it, settings = item
    try:
        cc = crosscheck(raw, dt=val if kind == "dt" else None,
                        steps_per_revolution=val if kind == "steps" else None,
                        iterations=it, **settings)
    except (FloatingPointError, np.linalg.LinAlgError) as exc:   # diverged
        raise SimulationError(f"iterations {it}, {kind} {val}: {exc}") from exc
    s = cc.settings
    wall = s["seconds_per_revolution"] or s["seconds_per_sweep"]
    return {"dt": s["dt"], "steps_per_revolution": s["steps_per_revolution"],
            "wall": float(wall), "max_error": float(cc.max_error)}
