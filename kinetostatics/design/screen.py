"""A population's designs that cannot be feasible, told by one stacked kinematic pass
before the solve: :func:`screen` (for the designs judged one Solution each,
:func:`~kinetostatics.design.judging.evaluate_scenes`; the stacked road,
:mod:`~kinetostatics.design.stacked`, reads the same numbers from its one pass).

Early in a search many designs cannot be assembled over their sweep; the stacked solve
refuses a run of scenes that holds one and solves its scenes one by one (each design
then costs a whole solve of its own). The screen closes every dyad of every design at
every row at once (:mod:`~kinetostatics.solver.stack`, the solver's own closure with
``strict = False``) and reads, per row, the dyad's closeness to a dead centre, the
number the solver flags rows ``singular`` by (min(sin^2 tau, (pivot distance /
size)^2) at most ``SINGULAR_WARN``^2; NaN where the links do not reach). The numbers
are the solve's own, elementwise, so a design the screen sets aside is one the solve
refuses or flags singular somewhere: infeasible either way. A design it passes is
still solved and judged in full.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..model.scene import Scene, load_scene
from ..solver.kinematics import SINGULAR_WARN, solve_kinematics
from ..solver.many import RUN_ROWS
from ..solver.stack import Stacker, assemblies, signature
from ..solver.structure import analyse

NOT_AT_FIRST_ROW = "cannot be assembled at its first row (or no hint settles its assembly)"
NOT_OVER_SWEEP = "cannot be assembled over the sweep"
DEAD_CENTRE = ("cannot be assembled at some row, or passes a dead centre (a row with sin tau "
               "below 1e-3)")


def screen(scenes: list[Scene]) -> list[str | None]:
    """Per scene, why it cannot be feasible (it cannot close at some row, or passes a
    dead centre), or None: to be solved. Scenes the solver does not stack (joint
    friction, a mass model, mixed structures) are all passed."""
    out: list[str | None] = [None] * len(scenes)
    keys = {signature(s) for s in scenes}
    if len(scenes) < 2 or len(keys) != 1 or None in keys:
        return out
    structure = analyse(scenes[0], assemble=False)
    stacker = Stacker(scenes)
    try:
        ks, ok = assemblies(stacker, structure)
    except Exception:       # (the solve tells each scene's reason)
        return out
    counts = np.array([s.driver.positions.size for s in scenes])
    starts = np.cumsum(counts) - counts
    positions = np.concatenate([s.driver.positions for s in scenes])
    reach = np.ones(positions.size, dtype=bool)
    close = np.ones(positions.size, dtype=bool)
    # in runs of whole scenes of about RUN_ROWS rows, as the solve goes (its arrays stay
    # in the cache: about 3x quicker than one pass over all the rows)
    bounds = np.concatenate([np.flatnonzero(np.diff(starts // RUN_ROWS)) + 1, [len(scenes)]])
    lo = 0
    for hi in bounds.tolist():
        a, b = int(starts[lo]), int(starts[hi - 1] + counts[hi - 1])
        rows = replace(structure, assembly=tuple(np.repeat(k[lo:hi], counts[lo:hi])
                                                 for k in ks))
        with np.errstate(all="ignore"):
            kin = solve_kinematics(stacker.runs(lo, hi, counts[lo:hi], positions[a:b]), rows,
                                   strict=False)
            for dm in kin.dyads:
                c2 = np.broadcast_to(dm.closeness2, (b - a,))
                reach[a:b] &= ~np.isnan(c2)
                close[a:b] &= c2 > SINGULAR_WARN**2
        lo = hi
    all_reach = np.logical_and.reduceat(reach, starts)
    all_clear = np.logical_and.reduceat(close, starts)
    for i in np.flatnonzero(~(ok & all_clear)).tolist():
        out[i] = (NOT_AT_FIRST_ROW if not ok[i] else
                  NOT_OVER_SWEEP if not all_reach[i] else DEAD_CENTRE)
    return out


def loaded(dicts: list) -> tuple[list, list[str | None]]:
    """Each scene (a dict, or a Scene already made) loaded (or the error the loader
    raises for it), and the screen's reasons for those loaded."""
    scenes: list = []
    for d in dicts:
        try:
            scenes.append(load_scene(d))
        except Exception as exc:
            scenes.append(exc)
    good = [i for i, s in enumerate(scenes) if not isinstance(s, Exception)]
    why: list[str | None] = [None] * len(dicts)
    for i, r in zip(good, screen([scenes[i] for i in good]), strict=True):
        why[i] = r
    return scenes, why
