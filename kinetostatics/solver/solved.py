"""What the solver gives: the arrays of a solved sweep, before any table.

:class:`Solved` holds them all; a long sweep solved lean
(:class:`~kinetostatics.solver.blocks.LeanSolved`) and one scene of a stacked solve
(:class:`~kinetostatics.solver.cut.CutSolved`) hold some at first and give the others
when asked (:class:`Deferred`, the protocol both follow). The results package wraps any
of them in a :class:`~kinetostatics.results.Solution`; the solver never builds one.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np

if TYPE_CHECKING:
    from ..model.scene import Scene
    from .kinematics import Kinematics
    from .loads import PointLoad
    from .reactions import DriverReaction, JointReaction
    from .structure import Structure

# the arrays a deferred solve may give later, by the name a Solution holds them under
DEFERRED = ("kin", "joint_reactions", "drive", "undefined_load")


def drive_values(drive: DriverReaction, shape: tuple) -> np.ndarray:
    """``Me``/``Fe`` over the sweep, read-only: a view of the solver's array, or a
    scalar broadcast to ``shape``."""
    value = drive.value
    if type(value) is np.ndarray and value.shape == shape:
        # what np.broadcast_to gives for an array of the shape already, for a tenth
        # of its cost (the solve and the driver table both ask for it)
        view = value.view()
        view.flags.writeable = False
        return view
    return np.broadcast_to(value, shape)


@dataclass
class Solved:
    """Every array of a solved sweep.

    Attributes
    ----------
    scene, structure, kin
        The checked scene, its structure (driver + dyads, assemblies chosen) and the
        motion arrays.
    loads : list of PointLoad or None
        With joint friction the applied, gravity, inertia and friction loads; None
        without (let go: they are computed again from ``kin`` when asked for).
    joint_reactions : dict
        Per joint, the reaction arrays.
    drive : DriverReaction
        ``Me`` (N m) on a crank or ``Fe`` (N) on a sliding driver.
    undefined_load : ndarray of bool
        Rows where a ``resist`` point stands still.
    self_locking : ndarray of bool or None
        With joint friction, the rows where friction locks the mechanism.
    """

    scene: Scene
    structure: Structure
    kin: Kinematics
    loads: list[PointLoad] | None
    joint_reactions: dict[str, JointReaction]
    drive: DriverReaction
    undefined_load: np.ndarray
    self_locking: np.ndarray | None = None

    @property
    def positions(self) -> np.ndarray:
        return self.kin.positions

    @property
    def Me(self) -> np.ndarray:
        return drive_values(self.drive, self.positions.shape)


class Deferred(Protocol):
    """A solve that holds some of its arrays and gives the others when asked.

    ``known``: the fields of a Solution it holds from the start (``scene``,
    ``structure``, ``self_locking``, ...); ``positions`` and ``singular()`` (an array of
    its own each call, which the caller may keep) answer without solving again;
    ``give(name, have)`` returns the fields to add once ``name`` (one of
    :data:`DEFERRED`) is asked for, ``have`` being the names the Solution holds already;
    ``solved()`` gives everything, as a :class:`Solved` (to pickle).
    """

    known: dict

    @property
    def positions(self) -> np.ndarray: ...

    def singular(self) -> np.ndarray: ...

    def give(self, name: str, have) -> dict: ...

    def solved(self) -> Solved: ...
