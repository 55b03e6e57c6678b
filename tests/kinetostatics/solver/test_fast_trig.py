"""The compiled path's cos and sin (``fast/trig_kernels.py``: Cody-Waite's reduction and
fdlibm's kernels, vectorised) against numpy's (glibc's, correctly rounded in practice):
within 1 ULP over sweeps and random angles, at tiny and hard angles (near the multiples
of pi/2), the C library's beyond the polynomial's range; and every road of the compiled
path that turns a crank's angles into cos and sin gives its doubles."""

from __future__ import annotations

import numpy as np
import pytest

from kinetostatics.solver.fast import loader

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


@pytest.fixture
def trig(kernels):
    """The trigonometry kernels' module, the kernels loaded (conftest's ``kernels``)."""
    from kinetostatics.solver.fast import trig_kernels
    return trig_kernels


def ulps(got: np.ndarray, want: np.ndarray) -> np.ndarray:
    """Each value's error in units of the last place of the wanted value."""
    return np.abs(got - want) / np.spacing(np.abs(want))


def angles(limit: float) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(7)
    return {"sweep": np.linspace(-20.0, 20.0, 400_001),
            "turns": rng.uniform(-400.0, 400.0, 400_000),
            "range": rng.uniform(-limit, limit, 400_000),
            "tiny": np.concatenate([s * 10.0 ** rng.uniform(-320.0, -1.0, 20_000)
                                    for s in (1.0, -1.0)])}


def test_within_one_ulp_of_numpys(trig) -> None:
    # (measured 2026-11-30: 1 ULP at most on each set, 7.2-7.3 % of the angles with a cos
    # or a sin 1 ULP off on the first three; the tiny angles' cos 1 exactly)
    for name, x in angles(trig.LIMIT).items():
        c, s = trig.turned(x)
        assert ulps(c, np.cos(x)).max() <= 1.0, name
        assert ulps(s, np.sin(x)).max() <= 1.0, name
        off = np.mean((c != np.cos(x)) | (s != np.sin(x)))
        assert off <= 0.15, name        # (measured 0.073 at most; 0 for the tiny angles)


def test_hard_angles(trig) -> None:
    """The doubles nearest the multiples of pi/2 within the range (the value near 0 there,
    its relative error no measure: the absolute one), zeros keep their sign."""
    k = np.arange(-int(trig.LIMIT / (np.pi / 2)), int(trig.LIMIT / (np.pi / 2)) + 1)
    near = k * (np.pi / 2)
    x = np.concatenate([near, np.nextafter(near, np.inf), np.nextafter(near, -np.inf)])
    c, s = trig.turned(x)
    # (measured 2026-11-30: 2.65e-25 at most, the three parts of pi/4's reach)
    assert np.abs(c - np.cos(x)).max() <= 1e-24
    assert np.abs(s - np.sin(x)).max() <= 1e-24
    c, s = trig.turned(np.array([0.0, -0.0]))
    assert c.tolist() == [1.0, 1.0]
    assert np.signbit(s).tolist() == [False, True] and s.tolist() == [0.0, 0.0]


def test_beyond_its_range_the_c_librarys(trig) -> None:
    """Past ``LIMIT`` (and NaN, the infinities) the C library's cos and sin, numpy's where
    ``kernel_trig`` holds; within it the polynomial's, rows alike either side."""
    from kinetostatics.solver.fast.solve import kernel_trig, trig_probes
    lim = trig.LIMIT
    x = np.array([np.nextafter(lim, np.inf), -1.5 * lim, 1e9, 1e300, np.inf, -np.inf,
                  np.nan, 3.0, -lim, lim])
    # (read-only, as kernel_trig's angles: libm_rows compiled for one signature, not again
    # for a writable array no solve passes it; 0.3 s of an empty cache's compiling)
    x.flags.writeable = False
    c, s = trig.turned(x)
    ref = np.empty((2, x.size))
    trig.libm_rows(x, *ref)
    far = slice(0, 7)
    assert c[far].tobytes() == ref[0][far].tobytes()
    assert s[far].tobytes() == ref[1][far].tobytes()
    one = [trig.turned(x[i:i + 1]) for i in range(7, x.size)]   # (alone: no fallback pass)
    assert [v[0][0] for v in one] == c[7:].tolist()
    assert [v[1][0] for v in one] == s[7:].tolist()
    with np.errstate(invalid="ignore"):
        p = trig_probes(2_000)
        trig.libm_rows(p, c := np.empty(p.size), s := np.empty(p.size))
        same = c.tobytes() == np.cos(p).tobytes() and s.tobytes() == np.sin(p).tobytes()
    assert kernel_trig() == same


def test_every_road_gives_the_kernels_doubles(trig) -> None:
    """The composed kernels' crank pass (``compose.turn``), the tables' pass
    (``table_pass.block_turn``) and the stacked runs' (``stack.SWEEP_TURN``):
    ``turn_rows``'s doubles (the fused kernels' tile pass: test_fast_rowcost.py)."""
    from kinetostatics.solver.fast.compose import turn
    from kinetostatics.solver.fast.table_pass import block_turn
    from kinetostatics.solver.stack import SWEEP_TURN
    x = np.radians(np.linspace(-30.0, 390.0, 5_001))
    want = trig.turned(x)
    got = np.empty((2, x.size))
    turn(loader.kernels(), x, *got)                 # (a writable array: read-only view)
    assert got.tobytes() == np.array(want).tobytes()
    x.flags.writeable = False
    block_turn()(x, *got)
    assert got.tobytes() == np.array(want).tobytes()
    assert np.array(SWEEP_TURN[0](x)).tobytes() == np.array(want).tobytes()
