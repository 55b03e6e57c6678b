"""The kinetostatic solve: scene -> structure -> kinematics -> loads -> reactions."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..model.errors import AssemblyError
from ..model.scene import load_scene
from ..results import Solution
from .friction import has_friction, solve_with_friction
from .kinematics import solve_kinematics
from .loads import applied_loads, inertia_loads, resultants
from .reactions import solve_reactions
from .structure import analyse


def solve(scene: Any) -> Solution:
    """Kinematics, reactions in every joint and the equilibrating moment over the sweep.

    Parameters
    ----------
    scene : Scene, pathlib.Path, str or dict
        A loaded scene, a path to a ``.toml`` file, TOML text or a dict
        (``scene-format.md`` section 1).

    Returns
    -------
    Solution
        Arrays and lazily built tables: ``kinematics``, ``bodies``, ``reactions``,
        ``driver``, ``dyads``, ``sliders``, ``frame``, ``reduced`` and ``summary()``.

    Raises
    ------
    SceneError, StructureError, AssemblyError
        One-line messages for a bad scene, a chain that is not driver + dyads, a
        mechanism that cannot be assembled or is exactly singular somewhere.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> sol = ks.solve(ks.example("four_bar"))
    >>> round(float(sol.driver["Me"].abs().max()), 1) > 0
    True
    """
    sc = load_scene(scene)
    structure = analyse(sc)
    try:
        kin = solve_kinematics(sc, structure)
        sol = _solve_loads(sc, structure, kin)
    except (OverflowError, ZeroDivisionError) as exc:
        raise AssemblyError(f"the scene's numbers overflow ({exc}); check its dimensions "
                            "and masses") from None
    _check_finite(sol)
    return sol


def _solve_loads(sc, structure, kin) -> Solution:
    inertia = inertia_loads(sc, kin)
    applied, undefined = applied_loads(sc, kin)
    loads = applied + inertia
    if has_friction(sc):
        reactions, drive, fl, locking = solve_with_friction(sc, kin, loads)
        return Solution(sc, structure, kin, loads + fl, reactions, drive, undefined,
                        self_locking=locking)
    acc = resultants(loads, sc.bodies, kin.n)
    reactions, drive = solve_reactions(kin, acc)
    return Solution(sc, structure, kin, loads, reactions, drive, undefined)


def _check_finite(sol: Solution) -> None:
    """Never a silent NaN: a scene whose numbers overflow is refused."""
    arrays = [np.asarray(sol.Me)] + [np.asarray(v) for r in sol.joint_reactions.values()
                                     for v in (r.fx, r.fy)]
    for b in sol.kin.bodies.values():
        arrays += [np.asarray(b.cos), np.asarray(b.ox), np.asarray(b.oy), np.asarray(b.ax)]
    locked = sol.self_locking     # rows where friction locks: Me and reactions are NaN
    for i, a in enumerate(arrays):
        if locked is not None and locked.any() and i <= 2 * len(sol.joint_reactions):
            a = np.where(locked, 0.0, np.broadcast_to(a, sol.positions.shape))
        if not np.isfinite(np.sum(a)):
            bad = np.flatnonzero(~np.isfinite(np.broadcast_to(a, sol.positions.shape)))
            raise AssemblyError(
                "the solution overflows (numbers too large or a degenerate geometry) at "
                f"driver position {sol.positions[bad[0]]:g}; check the scene's dimensions")
