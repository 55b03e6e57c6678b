"""Speed against error of the simulation: :func:`study` sweeps the time step and the
solver iterations and reports the wall time per simulated revolution against the
error, with the observed order of convergence. Its runs are a batch
(:func:`~kinetostatics.simulation.run_batch`)."""

from __future__ import annotations

import math
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from ..common.jsontext import plain
from .batch import run_batch
from .errors import SimulationDiverged, SimulationError
from .model import check_scene
from .runner import crosscheck, rebuildable_scene

__all__ = ["ORDER_FLOOR", "STUDY_ITERATIONS", "STUDY_STEPS", "Study", "study"]

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
        ``case, dt, steps_per_revolution`` (an integer), ``iterations,
        ms_per_revolution`` (the best of ``repeats`` runs), ``max_error, diverged``,
        ``drift`` (m), ``order`` (the local order log(e1 / e2) / log(dt1 / dt2) against
        the previous converged, larger step with the same iterations) and
        ``timing_noise`` (the cost fell although the steps grew: the wall time was
        disturbed, not a result), ``solver``: the constraints' order and whether the
        run fell back on the ballast ("driver last", "driver last, ballast", "driver
        first"; "-" where it diverged). A diverged setting has no error, order or time
        (NaN): its numbers are not a result.
    order : dict
        Iterations -> the order fitted (least squares in log-log) on the converged
        errors above 1e-6, or None with fewer than two such points.
    order_points : dict
        Iterations -> ``(used, settings, diverged)``: how many settings the fit used,
        of how many, and how many of them diverged.
    repeats : int
        Runs per setting (the fastest wall time is kept).
    """

    table: pd.DataFrame
    order: dict[int, float | None]
    order_points: dict[int, tuple[int, int, int]] = field(default_factory=dict)
    repeats: int = 1

    def order_line(self, iterations: int) -> str:
        """How the observed order reads for one iteration count, with what it rests on."""
        o = self.order[iterations]
        used, total, blown = self.order_points.get(iterations, (0, 0, 0))
        tail = f"{blown} diverged" if blown else "none diverged"
        if o is not None:
            return f"{o:.2f} (fitted on {used} of {total} settings; {tail})"
        if blown == total:
            return f"n/a (all {total} settings diverged)"
        return (f"n/a (fewer than two converged errors above {ORDER_FLOOR:g}: {used} of "
                f"{total} settings; {tail})")

    def formatted(self) -> pd.DataFrame:
        """The table as text for reading: integer step counts, a diverged setting as
        "diverged" with no error, time or order, a noisy wall time marked "(noise)", a
        dash where no value applies."""
        rows = []
        for r in self.table.itertuples(index=False):
            rows.append({
                "case": r.case, "dt (s)": f"{r.dt:.3g}",
                "steps/rev": f"{r.steps_per_revolution:d}", "iterations": f"{r.iterations:d}",
                "ms/rev": "-" if r.diverged else
                f"{r.ms_per_revolution:.3g}" + (" (noise)" if r.timing_noise else ""),
                "max error": "diverged" if r.diverged else f"{r.max_error:.3g}",
                "order": "-" if r.diverged or r.order != r.order else f"{r.order:.2f}",
                "drift (m)": f"{r.drift:.2g}", "solver": r.solver})
        return pd.DataFrame(rows)

    def best(self, threshold: float) -> dict[str, Any] | None:
        """The cheapest converged run (ms per revolution) whose error is at most
        ``threshold``; runs flagged as timing noise are passed over."""
        t = self.table
        ok = t[~t.diverged & ~t.timing_noise & (t.max_error <= threshold)]
        if ok.empty:
            return None
        return _plain(ok.sort_values("ms_per_revolution").iloc[0].to_dict())

    def summary(self) -> dict[str, Any]:
        """JSON-ready: the rows (a diverged one: ``"diverged": true`` and its drift, no
        error), the fitted orders with the settings they used, the cheapest runs at
        1e-5 and 1e-6."""
        rows = []
        for r in self.table.to_dict(orient="records"):
            r = _plain(r)
            if r["diverged"]:
                for k in ("max_error", "order", "ms_per_revolution", "timing_noise"):
                    r.pop(k, None)
            rows.append(r)
        return {"rows": rows, "repeats": self.repeats,
                "order": {str(k): v for k, v in self.order.items()},
                "order_settings": {str(k): {"used": u, "settings": n, "diverged": d}
                                   for k, (u, n, d) in self.order_points.items()},
                "best_1e-5": self.best(1e-5), "best_1e-6": self.best(1e-6)}


def _plain(row: dict) -> dict:
    """numpy scalars to Python; integer columns as int."""
    out = plain(row)
    for k in ("steps_per_revolution", "iterations"):
        if k in out:
            out[k] = int(out[k])
    return out


def study(scene: Any, *, steps: tuple[int, ...] | None = None,
          dts: tuple[float, ...] | None = None,
          iterations: tuple[int, ...] = STUDY_ITERATIONS, revolutions: float = 2.0,
          samples_per_revolution: int = 360, repeats: int = 1, case: str | None = None,
          fast: bool | None = None, executor: Executor | str | None = None,
          ballast: bool = True) -> Study:
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
    revolutions, samples_per_revolution, fast, ballast
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
        A setting that diverged (:class:`~kinetostatics.simulation.SimulationDiverged`)
        is a row with ``diverged`` True and its drift, left out of the order's fit.
    """
    sc = rebuildable_scene(scene)
    check_scene(sc)
    if steps is not None and dts is not None:
        raise SimulationError("give steps per revolution or dts, not both")
    grid = [("dt", float(x)) for x in dts] if dts is not None else \
        [("steps", int(x)) for x in (steps or STUDY_STEPS)]
    n_rep = max(1, int(repeats))
    keys = [(int(it), kind, val) for it in iterations for kind, val in grid]
    settings = {"revolutions": revolutions, "samples_per_revolution": samples_per_revolution,
                "fast": fast, "ballast": bool(ballast)}
    items = [(sc.raw, kind, val, it, settings) for it, kind, val in keys
             for _ in range(n_rep)]
    done = run_batch(_study_run, items, executor=executor)
    rows = []
    for i, (it, _kind, _val) in enumerate(keys):
        runs = done[i * n_rep:(i + 1) * n_rep]
        best = min(runs, key=lambda r: r["wall"])
        blown = best["diverged"]
        rows.append({"case": case or sc.title, "dt": best["dt"],
                     "steps_per_revolution": int(round(best["steps_per_revolution"])),
                     "iterations": it,
                     "ms_per_revolution": math.nan if blown else 1e3 * best["wall"],
                     "max_error": math.nan if blown else best["max_error"],
                     "diverged": blown, "drift": best["drift"],
                     "solver": best["solver"]})
    table = pd.DataFrame(rows)
    table["order"] = np.nan
    table["timing_noise"] = False
    order: dict[int, float | None] = {}
    points: dict[int, tuple[int, int, int]] = {}
    for it, g in table.groupby("iterations"):
        ok = g[~g.diverged].sort_values("dt", ascending=False)
        e, h = ok.max_error.to_numpy(), ok.dt.to_numpy()
        with np.errstate(divide="ignore", invalid="ignore"):
            local = np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])
        table.loc[ok.index[1:], "order"] = local
        table.loc[ok.index, "timing_noise"] = timing_noise(ok.ms_per_revolution.to_numpy())
        fit = (e > ORDER_FLOOR) & (e < 1.0)
        order[int(it)] = float(np.polyfit(np.log(h[fit]), np.log(e[fit]), 1)[0]) \
            if fit.sum() >= 2 else None
        points[int(it)] = (int(fit.sum()), len(g), int(g.diverged.sum()))
    return Study(table, order, points, n_rep)


def timing_noise(ms: np.ndarray) -> np.ndarray:
    """Which of the wall times of settings with ever more steps fell below that of a
    setting with fewer steps (a finer step cannot cost less: the time was disturbed)."""
    ms = np.asarray(ms, dtype=float)
    return ms < np.maximum.accumulate(ms) if ms.size else np.zeros(0, dtype=bool)


def _study_run(item: tuple) -> dict[str, Any]:
    """One run of a study (a batch work item: plain data in, plain data out)."""
    raw, kind, val, it, settings = item
    try:
        cc = crosscheck(raw, dt=val if kind == "dt" else None,
                        steps_per_revolution=val if kind == "steps" else None,
                        iterations=it, **settings)
    except SimulationDiverged as exc:
        return {"dt": exc.dt, "steps_per_revolution": exc.steps_per_revolution,
                "wall": math.inf, "max_error": math.nan, "diverged": True,
                "drift": exc.drift, "solver": "-"}
    s = cc.settings
    wall = s["seconds_per_revolution"] or s["seconds_per_sweep"]
    return {"dt": s["dt"], "steps_per_revolution": s["steps_per_revolution"],
            "wall": float(wall), "max_error": float(cc.max_error), "diverged": False,
            "drift": float(cc.record.drift),
            "solver": s["solver_order"].replace("scene, ", "")
            + (", ballast" if s["ballast"] else "")}
