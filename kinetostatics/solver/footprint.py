"""The peak memory of a solve, estimated from its rows and columns before it allocates.

A solve keeps, per row (driver position), a few arrays per named point and centre of
mass (kinematics), per joint (reactions) and per body (inertia loads), and passes of
the same size while it works. Measured with ``/usr/bin/time -v`` on the bundled scenes
at 5e5-1e6 positions: 375 B per row for the four-bar and the slider-crank (18 and 15
columns), 650 B for the shaper (26 columns), 573 B for the four-bar when ``--out`` also
writes the tables; ``PER_COLUMN`` and ``PER_ROW`` are a little above these.
"""

from __future__ import annotations

from ..model.memory import FLOAT, check_memory
from ..model.scene import Scene

PER_COLUMN = 3.5 * FLOAT      # bytes per row and column (point, cog, joint, body)
PER_ROW = 16 * FLOAT          # bytes per row of the driver's own arrays
BASE = 60e6                   # the interpreter, numpy and the scene


def columns(scene: Scene) -> int:
    """Named points, centres of mass (twice: kinematics and inertia loads) and joints."""
    return (sum(len(b.points) for b in scene.bodies.values()) + 2 * len(scene.bodies)
            + len(scene.joints))


def solve_bytes(scene: Scene, rows: int) -> float:
    """Estimated peak bytes of a solve of ``scene`` at ``rows`` positions."""
    return BASE + rows * (PER_ROW + PER_COLUMN * columns(scene))


def check_solve(scene: Scene, rows: int, what: str | None = None) -> None:
    """Refuse, in one line, a solve whose estimated peak is over the memory budget
    (:func:`kinetostatics.model.memory.check_memory`)."""
    if rows < 100_000:          # (under 0.1 GB for any scene of a few dozen columns)
        return
    check_memory(solve_bytes(scene, rows),
                 what or f"the solve of {scene.title!r} at {rows:,} positions",
                 "use fewer positions (driver.count, or a shorter positions list), or write "
                 "the tables block by block with solve --out DIR on the command line")
