"""The crank's cos and sin of the tables' pass (``table_pass.block_turn``): the solve
keeps none (its fused kernel works them out into each tile's scratch), so the pass works
them out per block, the compiled path's (``trig_kernels.turn_rows``, the doubles the
solve's kernels work out), and the tables are the composed kernels' full solve's."""

from __future__ import annotations

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.solver.fast import solve as fast_solve
from kinetostatics.solver.fast.table_pass import block_turn

from ..solver.test_fast_short import full_solve
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


def test_tables_of_the_cos_and_sin_worked_out_per_block(fast):
    """The four-bar's ``reactions`` and ``kinematics`` of a long sweep (the solve lean,
    keeping no cos and sin: the tables' pass works them out) and of the composed
    kernels' full solve: the same tables, bit for bit."""
    text = scene_text("four_bar")
    sol = ks.solve(text)
    assert not hasattr(sol.__dict__["_deferred"], "crank")
    tables = bits(sol.reactions), bits(sol.kinematics)
    ref = full_solve(text)
    assert (bits(ref.reactions), bits(ref.kinematics)) == tables
