"""The finite check proved by the floating-point exception flags instead of a pass per array.

Every number a solve starts from is finite (the scene's and the driver positions are
checked where they are read). A NaN or an infinity can then only be born in an
operation that raises one of IEEE 754's exception flags: an overflow, a division by
zero or an invalid operation (0/0, inf - inf, 0 * inf, the root of a negative). numpy
tests those flags after every operation anyway; under :func:`trapped` it reports them
to a :class:`FloatTrap` instead of warning. A solve that ends with the trap untouched
holds finite numbers only, and neither the final check
(:func:`~kinetostatics.solver.pipeline._check_finite`, a summing pass per kept array)
nor the look at an operand multiplied by an exact zero (:func:`arith.mul`) is needed.

A trapped solve is tried only where the scene's own Python-number arithmetic cannot
overflow either (:func:`tame`: every number of the scene within ``TAME`` of 1, a
product of a few of them stays finite: Python floats overflow to infinity without a
flag). Where the trap was touched, or the scene is not tame, the solve is done again
with every check, as before: its numbers, its refusals and its warnings are exactly the
checked solve's (the trapped pass computes the same numbers, only fewer checks).
"""

from __future__ import annotations

import contextvars
from collections.abc import Iterator
from contextlib import contextmanager, nullcontext

import numpy as np

# True inside trapped() (this thread and context): the finite checks left to the trap
TRAPPED: contextvars.ContextVar[bool] = contextvars.ContextVar("trapped", default=False)

TAME = 1e50     # |x| of every nonzero scene number within [1/TAME, TAME]: six factors
                # of them multiply to at most 1e300 (finite) and at least 1e-300


class FloatTrap:
    """Remembers whether numpy met a floating-point exception (the ``call`` of
    :func:`numpy.errstate`)."""

    __slots__ = ("hit",)

    def __init__(self) -> None:
        self.hit = False

    def __call__(self, kind: str, flag: int) -> None:
        self.hit = True


@contextmanager
def trapped(trap: FloatTrap | None = None) -> Iterator[FloatTrap]:
    """A block whose numpy floating-point exceptions are recorded by the yielded trap
    (``trap``, or a new one; not warned), and in which :func:`active` is True (this
    thread and context only)."""
    trap = FloatTrap() if trap is None else trap
    token = TRAPPED.set(True)
    try:
        with np.errstate(over="call", divide="call", invalid="call", call=trap):
            yield trap
    finally:
        TRAPPED.reset(token)


def first_trapped(solve, *args):
    """``solve(*args)`` in a trap of its own; done again with every check (outside any
    trap) if the trap was touched or the trapped pass raised (the checked pass decides
    what to raise)."""
    trap = FloatTrap()
    try:
        with trapped(trap):
            out = solve(*args)
        if not trap.hit:
            return out
    except Exception:
        pass
    return solve(*args)


def active() -> bool:
    """True inside :func:`trapped`: the finite checks may be left to the trap."""
    return TRAPPED.get()


def quiet():
    """The errstate of an operation that may divide by zero or be invalid at a singular
    row (the solver finds such rows by their values): ignored in a checked solve; left to
    the trap in a trapped one (a touched trap sends the solve back to the checked road)."""
    if TRAPPED.get():
        return nullcontext()
    return np.errstate(divide="ignore", invalid="ignore")


def tame(scene, positions: np.ndarray | None = None) -> bool:
    """Whether every number of the scene (and the driver positions: the scene's own, or
    ``positions``) is zero or within [1/TAME, TAME] in magnitude (told once per scene,
    remembered on it as its ``size``)."""
    ok = scene.__dict__.get("tame")
    if ok is None:
        ok = scene.__dict__["tame"] = (_scene_tame(scene)
                                       and positions_tame(scene.driver.positions))
    return ok and (positions is None or positions is scene.driver.positions
                   or positions_tame(positions))


def positions_tame(pos: np.ndarray) -> bool:
    """Driver positions (finite: checked where read) no larger than TAME (a tiny one is
    harmless: an angle or a distance added, never divided by)."""
    return pos.size == 0 or max(pos.max(), -pos.min()) <= TAME


def tame_values(values) -> bool:
    """Whether every number of ``values`` (numbers and arrays) is zero or within
    [1/TAME, TAME] in magnitude."""
    for v in values:
        a = np.abs(np.asarray(v, dtype=float))
        if a.size and not (a.max() <= TAME and bool(np.all((a == 0.0) | (a >= 1.0 / TAME)))):
            return False
    return True


def _scene_tame(scene) -> bool:
    """Every number of the scene (its driver positions apart) zero or within
    [1/TAME, TAME] in magnitude (a mass model: not looked into, not tame)."""
    nums: list[float] = [*scene.gravity]
    for p in scene.ground.values():
        nums += p
    for b in scene.bodies.values():
        if b.mass_model is not None:
            return False
        if not isinstance(b.mass, float | int) or not isinstance(b.inertia, float | int):
            return False            # (a stack's per-row masses: judged per scene)
        nums += (b.mass, b.inertia)
        if b.cog is not None:
            nums += b.cog
        for p in b.points.values():
            nums += p
    for j in scene.joints.values():
        nums.append(j.beta)
    for p in scene.near.values():
        nums += p
    for ld in scene.loads:
        if ld.force is not None:
            nums += ld.force
        if ld.resist is not None:
            nums.append(ld.resist)
        nums.append(ld.moment)
    drv = scene.driver
    nums += (drv.speed, drv.acceleration)
    try:
        nonzero = [a for a in map(abs, map(float, nums)) if a]
    except (TypeError, ValueError):
        return False
    return not nonzero or (max(nonzero) <= TAME and min(nonzero) >= 1.0 / TAME)

