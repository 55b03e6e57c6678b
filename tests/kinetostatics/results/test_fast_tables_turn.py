"""The crank's cos and sin of the tables' pass (``table_pass.block_turn``) where the solve
kept none: numpy's, bit for bit, whichever road works them out (one compiled pass of
the C library's ``sincos`` where ``solve.kernel_trig`` finds it numpy's, else numpy's
two passes), and the tables then those of the pass given the solve's kept cos and sin."""

from __future__ import annotations

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.solver.fast import solve as fast_solve
from kinetostatics.solver.fast.table_pass import block_turn

from .test_onepass import bits, scene_text

pytest.importorskip("numba")
pytestmark = pytest.mark.slow       # (the kernels compiled first on a fresh machine)


@pytest.mark.parametrize("trig", [True, False], ids=["compiled", "numpy"])
def test_the_block_turn_gives_numpys_cos_and_sin(fast, monkeypatch, trig):
    """On a read-only sweep of angles (as a driver holds them) and on the angles
    ``kernel_trig`` probes: numpy's cos and sin, bit for bit, by the road the solve
    takes here (``trig``: the compiled one, where ``kernel_trig`` holds) and by numpy's."""
    if trig and not fast_solve.kernel_trig():
        pytest.skip("the C library's cos and sin are not numpy's on this machine")
    monkeypatch.setattr(fast_solve, "kernel_trig", lambda: trig)
    turn = block_turn()
    sweep = np.radians(np.linspace(0.0, 360.0, 10_001))
    sweep.flags.writeable = False
    for angles in (sweep, fast_solve.trig_probes(2_000)):
        cs, sn = np.full((2, angles.size), np.nan)
        with np.errstate(invalid="ignore"):     # (infinities among the probes)
            turn(angles, cs, sn)
            assert cs.tobytes() == np.cos(angles).tobytes()
            assert sn.tobytes() == np.sin(angles).tobytes()


def test_tables_without_the_solves_cos_and_sin_either_road(fast, monkeypatch):
    """The four-bar's ``reactions`` and ``kinematics`` with the solve's kept cos and sin,
    and without them (worked out per block) by either road: the same tables, bit for
    bit."""
    text = scene_text("four_bar")
    sol = ks.solve(text)
    assert sol.__dict__["_deferred"].crank is not None
    tables = bits(sol.reactions), bits(sol.kinematics)
    for trig in (fast_solve.kernel_trig(), False):
        monkeypatch.setattr(fast_solve, "kernel_trig", lambda trig=trig: trig)
        again = ks.solve(text)
        again.__dict__["_deferred"].crank = None
        assert (bits(again.reactions), bits(again.kinematics)) == tables
