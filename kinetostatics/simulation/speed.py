"""The cross-check's speed against its previous defaults, for ``python -m kinetostatics
bench`` (:func:`crosscheck_speed`).

For each scene the automatic settings of :func:`~kinetostatics.simulation.crosscheck`
are found twice: as they are now (the ballast where the driver-last run diverges, the
lag rule keeping a settled lower count) and as they were before
(``ballast=False, keep_lower=False``). Then the stepping loop of each chosen setting is
timed side by side, alternating, ``repeat`` times: seconds per simulated revolution
(``seconds_per_revolution`` of the cross-check; a sliding driver: per sweep), best and
median, with the largest error of each (the cross-check's ``max_error``).
"""

from __future__ import annotations

import gc
import statistics
from typing import Any

from ..model.scene import Scene
from .comparison import CrossCheck
from .model import build_space
from .runner import crosscheck, plan, rebuildable_scene
from .stepper import run

__all__ = ["SPEED_SCENES", "crosscheck_speed"]

SPEED_SCENES = ("shaper", "slotted_lever")
"""The bundled scenes timed by default: the shaper (RTR + RRT, the slowest chain) and
the slotted lever (RTR)."""


def _scene(item: Any) -> Scene:
    """A scene from a bundled example's name, a path, TOML text or a dict."""
    if isinstance(item, str) and "\n" not in item and not item.endswith(".toml"):
        from ..model.examples import example
        item = example(item)
    return rebuildable_scene(item)


def _label(cc: CrossCheck) -> str:
    """The chosen setting in a few words."""
    s = cc.settings
    extra = ", ballast" if s.get("ballast") else ""
    return (f"{s['steps_per_revolution']} steps x {s['iterations']} it., "
            f"{s['solver_order']}{extra}")


def _timer(sc: Scene, cc: CrossCheck):
    """A function that runs the stepping loop of ``cc``'s setting once, as the
    cross-check ran it, and returns its wall time per simulated revolution (sweep)."""
    s = cc.settings
    revs = s["revolutions"] if s["revolutions"] is not None else s["sweeps"]
    p = plan(sc, dt=s["dt"], steps_per_revolution=None, revolutions=revs if
             s["full_turn"] else 2.0, samples_per_revolution=360)

    def once() -> float:
        model = build_space(sc, dt=p["dt"], iterations=s["iterations"], start=p["start"],
                            error_bias=s["error_bias"],
                            driver_first=s["solver_order"] == "driver first",
                            ballast=bool(s["ballast"]))
        rec = run(model, p["steps"], p["every"])
        return rec.wall / (p["duration"] / p["unit"])

    return once


def crosscheck_speed(scenes=None, *, repeat: int = 3) -> list[dict[str, Any]]:
    """Seconds per simulated revolution of the cross-check's automatic settings against
    the previous defaults, timed side by side (see the module docstring).

    Parameters
    ----------
    scenes : iterable, optional
        Bundled example names, paths, TOML texts or dicts (default ``SPEED_SCENES``).
    repeat : int
        Alternating timed runs of each setting (the best and the median are reported).

    Returns
    -------
    list of dict
        One row per scene: ``measure, size`` (steps per revolution of the automatic
        setting), ``seconds_best, baseline_best, ratio_best, ratio_median, error``
        (the automatic setting's ``max_error``), and ``baseline_error``, ``settings``,
        ``baseline_settings``, ``work`` and ``baseline_work`` (steps x iterations per
        revolution).
    """
    rows = []
    for item in scenes or SPEED_SCENES:
        sc = _scene(item)
        new = crosscheck(sc)
        old = crosscheck(sc, ballast=False, keep_lower=False)
        jobs = {"new": _timer(sc, new), "old": _timer(sc, old)}
        times: dict[str, list[float]] = {k: [] for k in jobs}
        for _ in range(max(1, int(repeat))):
            for k, f in jobs.items():
                gc.collect()
                times[k].append(f())
        t, b = times["new"], times["old"]
        unit = "revolution" if sc.driver.kind == "R" else "sweep"
        rows.append({
            "measure": f"pymunk cross-check, s per simulated {unit}: {sc.title} "
                       "(automatic settings / previous defaults)",
            "size": new.settings["steps_per_revolution"],
            "seconds_best": min(t), "baseline_best": min(b), "ratio_best": min(t) / min(b),
            "ratio_median": statistics.median(t) / statistics.median(b),
            "error": new.max_error, "baseline_error": old.max_error,
            "settings": _label(new), "baseline_settings": _label(old),
            "work": new.settings["steps_per_revolution"] * new.settings["iterations"],
            "baseline_work": old.settings["steps_per_revolution"] * old.settings["iterations"],
        })
    return rows
