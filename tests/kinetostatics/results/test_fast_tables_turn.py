"""The crank's cos and sin of the tables' pass (``table_pass.block_turn``) where the solve
kept none: the compiled path's (``trig_kernels.turn_rows``, the doubles the solve's
kernels work out), and the tables then those of the pass given the solve's kept cos and
sin."""

from __future__ import annotations

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.solver.fast import solve as fast_solve
from kinetostatics.solver.fast.table_pass import block_turn

from .test_onepass import bits, scene_text

pytest.importorskip("numba")
pytestmark = pytest.mark.slow       # (the kernels compiled first on a fresh machine)


def test_the_block_turn_gives_the_compiled_paths_cos_and_sin(fast):
    """On a read-only sweep of angles (as a driver holds them) and on the angles
    ``kernel_trig`` probes: ``trig_kernels.turned``'s cos and sin, bit for bit."""
    from kinetostatics.solver.fast.trig_kernels import turned
    turn = block_turn()
    sweep = np.radians(np.linspace(0.0, 360.0, 10_001))
    sweep.flags.writeable = False
    for angles in (sweep, fast_solve.trig_probes(2_000)):
        cs, sn = np.full((2, angles.size), np.nan)
        with np.errstate(invalid="ignore"):     # (infinities among the probes)
            turn(angles, cs, sn)
            want = turned(angles)
        assert cs.tobytes() == want[0].tobytes()
        assert sn.tobytes() == want[1].tobytes()


def test_tables_without_the_solves_cos_and_sin(fast):
    """The four-bar's ``reactions`` and ``kinematics`` with the solve's kept cos and sin,
    and without them (worked out per block): the same tables, bit for bit."""
    text = scene_text("four_bar")
    sol = ks.solve(text)
    assert sol.__dict__["_deferred"].crank is not None
    tables = bits(sol.reactions), bits(sol.kinematics)
    again = ks.solve(text)
    again.__dict__["_deferred"].crank = None
    assert (bits(again.reactions), bits(again.kinematics)) == tables
