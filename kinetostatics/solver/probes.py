"""The closeness to a dead centre from the positions alone: the probes between rows of
:mod:`~kinetostatics.solver.deadpoints` and of a stack's screen
(:mod:`~kinetostatics.solver.many`, :mod:`~kinetostatics.solver.stack`). The same
operations as :func:`~kinetostatics.solver.kinematics.solve_kinematics` gives its
``closeness2`` with, without the velocities and accelerations.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..model.scene import GROUND, Scene
from . import arith as A
from .closure import DyadSolver, body_origin, dyad_param
from .driver import BodyMotion, driver_motion, ground_motion
from .kinematics import choose_assembly, with_positions
from .velocity_system import (
    closing_point,
    dead_centre_closeness2,
    guide_line,
    velocity_column,
    velocity_matrix,
)

if TYPE_CHECKING:
    from .structure import Dyad, Structure


class Closing:
    """What the closeness to a dead centre reads of a dyad's velocity system
    (:func:`dead_centre_closeness2`), from its positions alone: for a revolute inner joint the
    columns c1, c2 at X and their determinant, for a prismatic one the line's
    direction u (the numbers of the kinematics' velocity system: the same operations)."""

    def __init__(self, dyad: Dyad, solver: DyadSolver, pr, cs, org):
        self.revolute = dyad.inner.kind == "R"
        self.c1 = self.c2 = self.det = self.ux = self.uy = None
        if self.revolute:
            xx, xy = closing_point(dyad, solver, cs, org)
            self.c1, self.c2 = velocity_column(pr[0], xx, xy), velocity_column(pr[1], xx, xy)
            self.det = velocity_matrix(True, self.c1, self.c2, 1.0, 1.0, None, None)[1]
        else:
            self.ux, self.uy = guide_line(solver, cs)


def probe_closeness(scene: Scene, structure: Structure, positions=None,
                    measured: bool = False) -> tuple[list[np.ndarray], np.ndarray]:
    """The closeness to a dead centre of each dyad at driver ``positions`` (a probe
    between rows, :mod:`~kinetostatics.solver.deadpoints`; default the scene's sweep),
    from the positions alone:
    exactly the ``closeness2`` of :func:`solve_kinematics` with ``strict = False`` (the
    same operations, no velocities or accelerations), and the rows where some dyad
    cannot close (its links do not reach by more than 1e-9 of the mechanism's size,
    from the closure's own gap).

    ``measured``: the links' lengths were checked at the solve before (a stack's
    scenes, :func:`~kinetostatics.solver.stack.assemblies`), not again row by row.

    Returns
    -------
    closeness2 : list of numpy.ndarray
        Per dyad, min(sin^2 tau, (pivot distance / size)^2) per row (:func:`dead_centre_closeness2`
        as a probe measures it).
    open : numpy.ndarray
        Rows where some dyad cannot close.
    """
    if len(structure.assembly) == len(structure.dyads):
        assembly: tuple = structure.assembly
    else:
        assembly = choose_assembly(scene, structure)
    if positions is not None:
        scene = with_positions(scene, positions)
    n = scene.driver.positions.size
    motions: dict[str, BodyMotion] = {GROUND: ground_motion(),
                                      scene.driver.body: driver_positions(scene)}
    out, opened = [], np.zeros(n, dtype=bool)
    with np.errstate(all="ignore"):
        for dyad, k in zip(structure.dyads, assembly, strict=True):
            sin2, gap = probe_dyad(scene, dyad, motions, k, DyadSolver(scene, dyad, measured))
            out.append(sin2)
            if gap is not None:
                opened |= ~(np.broadcast_to(gap, (n,)) <= 1e-9 * scene.size)
    return out, opened


def driver_positions(scene: Scene) -> BodyMotion:
    """A crank's angle, cos, sin and origin over the rows, as
    :func:`~kinetostatics.solver.driver.driver_motion` works them out (the same
    operations, seed 000 ch. 4: o = P - R a), its origin's velocity and acceleration
    left at 0.0: a probe reads the positions alone (measured 2026-11-29, 1000 four-bars:
    six passes over some 5900 probe rows a round, 0.1 ms of solve_many's 2.3 ms of
    probes). A sliding driver's, or a run's crank with its cos and sin given, is
    driver_motion's."""
    drv = scene.driver
    if drv.kind != "R" or "driver_trig" in scene.__dict__:
        return driver_motion(scene)
    joint = scene.joints[drv.joint]
    c, s = drv.trig()
    px, py = scene.ground[joint.point_on(GROUND)]
    rax, ray = A.rotate(c, s, *scene.bodies[drv.body].local(joint.point_on(drv.body)))
    return BodyMotion(drv.angles, c, s, float(drv.speed), float(drv.acceleration),
                      A.sub(A.scalar(px), rax), A.sub(A.scalar(py), ray), 0.0, 0.0, 0.0, 0.0)


def probe_dyad(scene: Scene, dyad: Dyad, motions: dict[str, BodyMotion], k,
               solver: DyadSolver) -> tuple[np.ndarray, object]:
    """One dyad of :func:`probe_closeness` in assembly ``k``: its closeness2 (as
    :func:`solve_dyad` with ``strict = False`` gives it) and the closure's gap (None where
    it closes everywhere); its bodies' positions added to ``motions`` (no speeds: a
    probe reads none; :func:`~kinetostatics.solver.closure.dyad_param` with ``speeds``
    False)."""
    n = scene.driver.positions.size
    pr = (dyad_param(scene, dyad, 0, motions, speeds=False),
          dyad_param(scene, dyad, 1, motions, speeds=False))
    k = 1 if solver.branches == 1 else k
    cs, ss, gap = solver.positions(pr, k)
    reach = solver.reach
    if reach is not None:
        reach = A.full(reach / scene.size, n)
    org = [body_origin(pr[i], cs[i], ss[i]) for i in range(2)]
    for i, name in enumerate(dyad.bodies):
        motions[name] = BodyMotion(None, cs[i][0], cs[i][1], 0.0, 0.0, org[i][0], org[i][1],
                                   0.0, 0.0, 0.0, 0.0)
    return dead_centre_closeness2(Closing(dyad, solver, pr, cs, org), pr, reach, n), gap


__all__ = ["Closing", "driver_positions", "probe_closeness", "probe_dyad"]
