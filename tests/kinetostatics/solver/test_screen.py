"""The dead-point screen's compiled scan (``solver/fast/screen_kernels.py``) against the
numpy scan of :func:`~kinetostatics.solver.deadpoints._candidates`: the same intervals,
in the same order, of the same dtype."""

from __future__ import annotations

import numpy as np
import pytest

from kinetostatics.solver import deadpoints, many
from kinetostatics.solver.fast import loader, use

from .test_deadpoints import _candidates_reference

pytestmark = pytest.mark.skipif(not loader.installed(), reason="numba not installed")


@pytest.fixture
def on_path():
    """Sets the solve path (``"fast"``: the kernels loaded), put back after."""
    def set_path(path: str) -> None:
        use(path)
        if path == "fast" and loader.kernels() is None:
            pytest.skip("no writable cache folder")
    yield set_path
    use(None)


def test_the_compiled_scan_is_taken_on_the_compiled_path_only(on_path) -> None:
    """The solver's many gives every screen the compiled path's scan (deadpoints cannot
    import it); it is taken on the compiled path only."""
    assert many.compiled_scan in deadpoints.SCANS
    on_path("fast")
    assert deadpoints.compiled_scan() is not None
    on_path("numpy")
    assert deadpoints.compiled_scan() is None


def test_compiled_scan_gives_the_numpy_scans_intervals(on_path) -> None:
    """Segments of any length (empty ones too), ties, values within rounding of each
    other (the dip's 1 - 1e-9), NaN and infinities, one segment or many."""
    rng = np.random.default_rng(11)
    pool = np.array([0.0, 0.1, 0.1 * (1 - 1e-10), 0.1 * (1 - 2e-9), 0.2, 0.25,
                     0.25 * (1 - 1e-16), 0.3, 0.6, np.nan, np.inf])
    for _ in range(3000):
        counts = rng.integers(0, 9, rng.integers(1, 7))
        counts[-1] = max(counts[-1], 1)
        starts = np.cumsum(counts) - counts
        n = int(counts.sum())
        m2 = rng.choice(pool, n) if rng.random() < 0.6 else rng.random(n) * 0.6
        whole = (np.zeros(1, dtype=int), np.array([n]))
        got = {}
        for path in ("numpy", "fast"):
            on_path(path)
            scan = deadpoints.compiled_scan()
            # (a stack's segments are scanned on numpy: the kernel asked directly)
            got[path] = (deadpoints._candidates(m2, starts, counts) if scan is None
                         else deadpoints.scanned(scan, m2, starts, counts),
                         deadpoints._candidates(m2))
        for numpy_scan, compiled in zip(got["numpy"], got["fast"], strict=True):
            assert compiled.dtype == numpy_scan.dtype == np.int64
            np.testing.assert_array_equal(compiled, numpy_scan)
        np.testing.assert_array_equal(got["fast"][0],
                                      _candidates_reference(m2, starts, counts))
        np.testing.assert_array_equal(got["fast"][1], _candidates_reference(m2, *whole))


def test_compiled_scan_on_a_long_sweep(on_path) -> None:
    """A long sweep with many rows below the screen (a shaper's 45 % at 1e6 rows): the
    same intervals both ways, every dip found: sin^2 vanishes at 0 (the first row: its
    interval after it alone) and 12 times inside (0, 40) (the intervals on either side)."""
    m2 = 0.6 * np.sin(np.linspace(0.0, 40.0, 200_001)) ** 2
    on_path("numpy")
    expected = deadpoints._candidates(m2)
    on_path("fast")
    np.testing.assert_array_equal(deadpoints._candidates(m2), expected)
    assert expected.size == 1 + 2 * 12


def test_a_stack_with_many_rows_below_the_screen_is_scanned_compiled(on_path, monkeypatch
                                                                    ) -> None:
    """A stack's segments (solve_many's scenes) with more than one row in
    ``deadpoints.MANY_BELOW`` under the screen (the six-bars', some 45 %) are scanned
    compiled on the compiled path, fewer on numpy (a four-bar's): the same intervals
    as the numpy scan either way."""
    counts = np.array([361] * 30 + [7, 0, 361])
    starts = np.cumsum(counts) - counts
    n = int(counts.sum())
    dense = 0.6 * np.sin(np.linspace(0.0, 40.0, n)) ** 2
    sparse = np.where(dense < 0.004, dense, 0.6)        # (about 5 % below the screen)
    calls = []
    on_path("fast")
    scan = deadpoints.compiled_scan()

    def counted(*args):
        calls.append(args[0].size)
        return scan(*args)
    for m2, compiled in ((dense, True), (sparse, False)):
        rows = np.flatnonzero(m2 < deadpoints.SCREEN**2)
        assert (rows.size > n // deadpoints.MANY_BELOW) is compiled
        on_path("numpy")
        expected = deadpoints._candidates(m2, starts, counts, rows=rows)
        on_path("fast")
        monkeypatch.setattr(deadpoints, "SCANS", [lambda: counted])
        calls.clear()
        got = deadpoints._candidates(m2, starts, counts, rows=rows)
        assert calls == ([n] if compiled else [])       # (written in one pass)
        assert got.dtype == expected.dtype == np.int64
        np.testing.assert_array_equal(got, expected)
        np.testing.assert_array_equal(got, _candidates_reference(m2, starts, counts))


def test_a_scan_with_more_intervals_than_its_first_array_writes_them_all(on_path, monkeypatch
                                                                        ) -> None:
    """More intervals than ``deadpoints.SCAN_FIRST``: counted in the first pass, all
    written in a second (the same intervals as the numpy scan); as many or fewer: one
    pass."""
    m2 = 0.6 * np.sin(np.linspace(0.0, 40.0, 20_001)) ** 2     # (25 intervals)
    starts, counts = np.zeros(1, dtype=int), np.array([m2.size])
    on_path("numpy")
    expected = deadpoints._candidates(m2)
    on_path("fast")
    scan = deadpoints.compiled_scan()
    calls = []

    def counted(*args):
        calls.append(args[-1].size)
        return scan(*args)
    for first, passes in ((4, [4, 25]), (24, [24, 25]), (25, [25]), (4096, [4096])):
        monkeypatch.setattr(deadpoints, "SCAN_FIRST", first)
        calls.clear()
        got = deadpoints.scanned(counted, m2, starts, counts)
        assert calls == passes
        assert got.dtype == np.int64
        np.testing.assert_array_equal(got, expected)


def test_two_dyads_flags_measure_and_screen_in_one_pass(on_path) -> None:
    """A six-bar's lean sweep (``compose.kept_sweep`` with ``measure``): each dyad's
    singular rows, m^2 and the screen's intervals from one compiled pass, the numbers of
    numpy's ``~(c > SINGULAR_WARN**2)``, ``np.minimum`` and the scan: ties, values within
    rounding of each other, NaN (in either dyad), infinities, -0.0; an ``out`` too short
    for the intervals (their count still told)."""
    from kinetostatics.solver.fast.screen_kernels import flags_and_measure
    from kinetostatics.solver.kinematics import SINGULAR_WARN
    on_path("fast")
    rng = np.random.default_rng(12)
    pool = np.array([0.0, -0.0, 1e-7, 1e-6, 1e-6 * (1 - 1e-10), 0.1, 0.1 * (1 - 2e-9),
                     0.25, 0.3, 0.6, np.nan, np.inf])
    warn2, screen2 = SINGULAR_WARN**2, deadpoints.SCREEN**2
    for _ in range(2000):
        n = int(rng.integers(0, 12))
        c0, c1 = (rng.choice(pool, n) if rng.random() < 0.7 else rng.random(n) * 0.6
                  for _ in range(2))
        s0, s1, m2 = np.empty(n, dtype=bool), np.empty(n, dtype=bool), np.empty(n)
        out = np.empty(int(rng.integers(0, 5)), dtype=np.int64)
        k, below = flags_and_measure(c0, c1, warn2, screen2, s0, s1, m2, out)
        np.testing.assert_array_equal(s0, ~(c0 > warn2))
        np.testing.assert_array_equal(s1, ~(c1 > warn2))
        expected = np.minimum(c0, c1)
        np.testing.assert_array_equal(m2, expected)        # (NaN where numpy's is)
        intervals = _candidates_reference(expected, np.zeros(1, dtype=int), np.array([n]))
        assert k == intervals.size
        np.testing.assert_array_equal(out[:k], intervals[:out.size])
        assert below == bool((expected < screen2).any())


def test_a_shapers_lean_sweep_tells_the_screen_its_intervals(on_path, monkeypatch) -> None:
    """The bundled shaper solved lean (the guide's kernel, two dyads): the screen is given
    the intervals of the pass that made m^2 (``Kept.screened``), the numpy scan's of that
    m^2 (the sweep's many dips: not an empty answer), and m^2 the minimum of the two
    dyads' closeness to a dead centre the sweep solved in full gives (the compiled
    path's own: its cos and sin differ from numpy's by an ulp at some rows)."""
    import kinetostatics as ks
    from kinetostatics.model.scene import load_scene
    d = load_scene(ks.example("shaper")).raw
    d = {**d, "driver": {**d["driver"], "count": 4001}}
    seen = []
    stacked = deadpoints.dead_points_stacked

    def spy(m2u, positions, starts, counts, at, **kw):
        seen.append((m2u, kw))
        return stacked(m2u, positions, starts, counts, at, **kw)
    monkeypatch.setattr(deadpoints, "dead_points_stacked", spy)
    on_path("fast")
    sol = ks.solve(d)
    assert sol.path == "fast"
    (m2, kw), = seen
    assert kw["increasing"]
    intervals = _candidates_reference(m2, np.zeros(1, dtype=int), np.array([m2.size]))
    assert intervals.size > 0
    np.testing.assert_array_equal(kw["candidates"], intervals)
    dyads = sol.kin.dyads           # (solved again in full, the same kernels)
    np.testing.assert_array_equal(m2, np.minimum(*(dm.closeness2 for dm in dyads)))
