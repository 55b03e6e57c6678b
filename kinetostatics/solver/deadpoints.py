"""Dead points that fall between two rows of the sweep.

A row is flagged ``singular`` where some dyad is near a dead centre: the sine of its
transmission angle (the velocity system's |det| / (|c1| |c2|), seed 002 eqs 2.60-2.61)
or the distance it divides by (its outer pivots' distance, against the mechanism's size)
is at most 1e-3. A dead point can also lie between two rows: a four-bar passing its
change point (a + b = c + d) or a slotted lever whose block passes through the lever's
pivot. Both rows then look regular, while the computed motion is not smooth across the
interval (the rocker's angular velocity changes sign, the lever turns by 180 deg).

Search: the measure m = min(|sin tau|, pivot distance / size) of every dyad dips to zero
at a dead point, so every interval next to a local minimum of m over the rows is probed
at 31 interior positions, three times zooming on the smallest value (resolution 1/29791
of the interval, one vectorised solve of the same mechanism per round). An interval whose
interior minimum is at most 1e-3 and below both its rows' values holds a dead point: both
rows are flagged ``singular`` and the interval is reported. The same probe one row's
spacing beyond each end of the sweep flags an end row near a dead point just outside it
(for a whole turn that is the same state as the other end row).

Rows are taken in increasing driver position (:func:`~.continuity.sweep_order`), so a
``positions`` list in any order finds the same intervals.

A probe where some dyad cannot close (no closed form: the links do not reach) is not a
dead point: there is no motion from one row to the other at all, the two rows lie in
separate ranges of assembly. Such intervals are reported apart (``unassembled``;
``summary.json``: ``unassembled_between_rows``), their rows are not flagged
``singular`` for it, and no dead point is looked for in them. Beyond the ends of the
sweep such probes are left out.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..model.scene import Scene
from .continuity import open_rows, sweep_order
from .kinematics import SINGULAR_WARN, Kinematics
from .probes import probe_closeness
from .structure import Structure

# what a probe gives (:func:`_probe`): each dyad's closeness2 and the rows where some dyad
# cannot close, or (as before) the kinematics solved with strict = False
Probed = tuple[list, np.ndarray] | Kinematics

PROBES = 31        # interior positions per interval and round
ROUNDS = 3         # zooms on the smallest value
SCREEN = 0.5       # local minima of m below this are probed
# a stack's rows are scanned on numpy below one in MANY_BELOW of them under the screen
# (a four-bar's few and sparse rows: its gathers over them cost less than the compiled
# scan's pass over every row), compiled above (:func:`_candidates`)
MANY_BELOW = 16
# an interval's probes at lo + (hi - lo) t for t in STEPS[1:-1] (made once: its
# linspace cost 4-8 us of each probe's call; read only, as every caller reads it)
STEPS = np.linspace(0.0, 1.0, PROBES + 2)
_min = np.fmin.reduce   # the smallest value, NaN left out (a NaN row is never probed)


def kin_measure2(kin: Kinematics) -> np.ndarray:
    """m^2 per row: the smallest closeness to a dead centre over the dyads."""
    return measure2([d.closeness2 for d in kin.dyads], kin.n)


def measure2(closeness2: list, n: int, spent: bool = False) -> np.ndarray:
    """m^2 per row of ``n`` rows: the smallest of the dyads' ``closeness2`` (one dyad's
    own array of ``n`` values as it is: min(inf, x) is x, NaN and -0.0 too; no caller
    writes to it); of two dyads' own arrays (the six-bars'), their ``np.minimum`` in one
    pass, the same bits as ``min(min(inf, a), b)`` (measured 2026-11-30, the shaper at 1e6
    rows: 1.0 ms against 2.1), written over the second where ``spent`` (the caller's
    arrays, read by nothing else after: measured 2026-11-30, 1000 shapers x 361, 706 page
    faults, about 2 ms a call, faulting in a fresh one)."""
    whole = [type(c) is np.ndarray and c.shape == (n,) and c.dtype == np.float64
             for c in closeness2]
    if len(closeness2) == 1 and whole[0]:
        return closeness2[0]
    if len(closeness2) == 2 and all(whole):
        return np.minimum(closeness2[0], closeness2[1],
                          out=closeness2[1] if spent else None)
    m2 = np.full(n, np.inf)
    for c in closeness2:
        np.minimum(m2, np.broadcast_to(c, (n,)), out=m2)
    return m2


def _candidates(m2: np.ndarray, starts: np.ndarray | None = None,
                counts: np.ndarray | None = None, rows: np.ndarray | None = None
                ) -> np.ndarray:
    """Intervals i (rows i, i + 1) next to a local minimum of m over the rows, in
    increasing order; with ``starts`` and ``counts``, over each segment of rows alone
    (many scenes' sweeps one after another, :func:`dead_points_stacked`): no interval
    joins two segments.

    Only the rows below the screen (``m < SCREEN``, a few in a hundred) can start a probe,
    so only they are compared with their neighbours: one pass over all the rows instead
    of a dozen (the comparisons, row by row, are the same). ``rows``: those rows, when
    known."""
    n = m2.size
    none = np.zeros(0, dtype=int)
    if n < 2:
        return none
    if starts is None:
        starts, counts = np.zeros(1, dtype=int), np.array([n])
    # (a stack's segments scanned compiled too where many of their rows are below the
    # screen, the six-bars': measured 2026-11-30, 1000 shapers x 361, some 45 % of the
    # rows below, 5.7 ms a call on numpy)
    many = rows is not None and rows.size > n // MANY_BELOW
    scan = compiled_scan() if starts.size == 1 or many else None
    if scan is not None and m2.dtype == np.float64:     # (the same intervals)
        return scanned(scan, m2, starts, counts)
    if rows is None:
        rows = np.flatnonzero(m2 < SCREEN**2)       # (NaN is not below: never probed)
    if rows.size == 0:
        return none
    # the rows that begin or end a segment, marked over all rows (a pass over them
    # instead of a binary search per row below the screen)
    full = counts > 0
    edge = np.zeros(n, dtype=np.int8)
    edge[starts[full]] = 1
    edge[(starts + counts - 1)[full]] |= 2
    at = edge[rows]
    first = (at & 1) != 0
    last = (at & 2) != 0
    v = m2[rows]
    left = m2[np.maximum(rows - 1, 0)]
    right = m2[np.minimum(rows + 1, n - 1)]
    left[first] = np.inf            # a segment's end has no neighbour beyond it
    right[last] = np.inf
    # a real dip (not rounding jitter on a constant measure), small enough to matter
    shrink = 1.0 - 1e-9
    dip = (((v < left * shrink) & (v <= right))
           | ((v <= left) & (v < right * shrink)))
    # the intervals on either side of each dip: (r - 1, r) unless r starts a segment,
    # (r, r + 1) unless r ends one; as rows increase, r0 - 1, r0, r1 - 1, r1, ... never
    # decrease, so a repeat is always next to its twin
    both = np.stack([rows[dip] - 1, rows[dip]], axis=1).ravel()
    ok = np.stack([~first[dip], ~last[dip]], axis=1).ravel()
    both = both[ok]
    if both.size < 2:
        return both
    return both[np.concatenate([[True], both[1:] != both[:-1]])]


# Where the compiled path's scan comes from: each a function giving it, or None (the
# numpy scan). This module cannot import the compiled path's package, which imports it:
# the solver's many (imported with the results) adds fast.screen.compiled_scan here, so
# that every screen, a single sweep's too, scans compiled once the kernels are loaded.
SCANS: list[Callable[[], Callable | None]] = []


def scanned(scan: Callable, m2: np.ndarray, starts: np.ndarray, counts: np.ndarray
            ) -> np.ndarray:
    """The intervals of :func:`_candidates` by the compiled ``scan``
    (:func:`~kinetostatics.solver.fast.screen_kernels.scan_candidates`): written to an
    array of :data:`SCAN_FIRST` in one pass over the rows; more of them, counted there,
    written in a second pass to an array of their count (no array as long as the rows).
    (Measured 2026-11-30, the shaper's single sweep at 2e5 and 1e6 rows, 45 % of them
    below the screen, no interval: its screen 0.67-0.69 -> 0.42-0.46 ms and 3.8-4.1 ->
    2.5-2.7 ms of processor time, best of 30, three alternating pairs of processes at a
    load of 8-12, against a pass to count them and one to write them.)"""
    starts = np.asarray(starts, dtype=np.int64)
    counts = np.asarray(counts, dtype=np.int64)
    out = np.empty(SCAN_FIRST, dtype=np.int64)
    k = scan(m2, starts, counts, SCREEN**2, out)
    if k > out.size:
        out = np.empty(k, dtype=np.int64)
        scan(m2, starts, counts, SCREEN**2, out)
    return out[:k]


# the intervals a compiled scan writes in its first pass (scanned): a sweep's few, a
# stack's too (1000 shapers x 361: 2263, measured 2026-11-30; 32 KB)
SCAN_FIRST = 4096


def compiled_scan() -> Callable | None:
    """The compiled scan of :func:`_candidates` from :data:`SCANS`
    (:func:`~kinetostatics.solver.fast.screen_kernels.scan_candidates`: the same intervals
    in a pass over the rows, :func:`scanned`; measured 2026-11-29, the shaper's solve at
    1e6 rows, 45 % of them below the screen: one pass 1.5 ms against 13.8 ms, processor
    time, load 8-9;
    taken for a single sweep, :func:`_candidates`) when the
    compiled kernels are loaded in this process and the numpy path is not asked for;
    else None."""
    for source in SCANS:
        scan = source()
        if scan is not None:
            return scan
    return None


# Where a sweep's compiled probe comes from: each a function of the scene and its
# structure giving the probe ``at(positions, owner)`` (as for :func:`_probe`), or None.
# As for SCANS, the compiled path's package adds its own here
# (fast.screen.sweep_probe: a sweep that the compiled path solved, probed in one
# compiled call; measured 2026-11-30, see there); none gives one: numpy's probe.
SWEEP_PROBES: list[Callable[[Scene, Structure], Callable | None]] = []


def sweep_probe(scene: Scene, structure: Structure) -> Callable | None:
    """The compiled probe of a sweep of ``scene`` solved with ``structure``, from
    :data:`SWEEP_PROBES`, or None (numpy's :func:`~.probes.probe_closeness`)."""
    for source in SWEEP_PROBES:
        at = source(scene, structure)
        if at is not None:
            return at
    return None


# Where a sweep's numpy probe gets its ``clear`` (the proven bound,
# fast.screen_bound.sweep_clear, told here as SWEEP_PROBES are): each a function of the
# scene and its structure giving ``clear(lo, hi, owner, m_lo, m_hi)`` (as for
# :func:`_probe_unclear`), or None (every interval probed).
SWEEP_BOUNDS: list[Callable[[Scene, Structure], Callable | None]] = []


def sweep_bound(scene: Scene, structure: Structure) -> Callable | None:
    """The ``clear`` of a sweep of ``scene`` solved with ``structure`` from
    :data:`SWEEP_BOUNDS`, or None."""
    for source in SWEEP_BOUNDS:
        clear = source(scene, structure)
        if clear is not None:
            return clear
    return None


def _probe(at: Callable[[np.ndarray, np.ndarray], Probed], lo: np.ndarray,
           hi: np.ndarray, owner: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The smallest m^2 found inside each interval (lo, hi), zooming ROUNDS times, and
    the intervals where some probe found a dyad that cannot close (no closed form).
    ``at(positions, owner)`` probes the mechanism at driver positions, row i of the
    mechanism (segment) ``owner[i]``: the closeness of each dyad and the rows where one
    cannot close (:func:`~.probes.probe_closeness`), or the kinematics solved with
    ``strict = False``; interval j belongs to ``owner[j]``."""
    t = STEPS
    rounds = getattr(at, "rounds", None)
    if rounds is not None:      # (every round in one call: the same numbers)
        return rounds(lo, hi, owner, t, ROUNDS)
    rows = np.arange(lo.size)
    best = np.full(lo.size, np.inf)
    open_ = np.zeros(lo.size, dtype=bool)
    probe_owner = np.repeat(owner, PROBES)
    for _ in range(ROUNDS):
        grid = lo[:, None] + (hi - lo)[:, None] * t[None, :]
        got = at(grid[:, 1:-1].ravel(), probe_owner)
        if isinstance(got, Kinematics):
            pm2, gone = kin_measure2(got), open_rows(got)
        else:
            pm2, gone = measure2(got[0], got[1].size), got[1]
        pm2 = pm2.reshape(lo.size, PROBES)
        nan = np.isnan(pm2) | gone.reshape(lo.size, PROBES)
        open_ |= nan.any(axis=1)
        pm2 = np.where(nan, np.inf, pm2)        # no closed form there: not a dead point
        j = np.argmin(pm2, axis=1)
        best = np.minimum(best, pm2[rows, j])
        lo, hi = grid[rows, j], grid[rows, j + 2]
    return best, open_


def _probe_unclear(at: Callable[[np.ndarray, np.ndarray], Probed], lo: np.ndarray,
                   hi: np.ndarray, owner: np.ndarray, m_lo: np.ndarray, m_hi: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_probe` of the intervals that the probe's ``at.clear`` (when it has one,
    :func:`~kinetostatics.solver.fast.screen_bound.cleared`) does not prove clear from
    their rows' m^2 ``m_lo``, ``m_hi`` (-inf: no row, beyond a sweep's end); a clear one
    gets +inf and not opened, the verdicts its probes would give (no dead point, none
    that cannot close: proven there)."""
    clear = getattr(at, "clear", None)
    if clear is None:
        return _probe(at, lo, hi, owner)
    keep = ~clear(lo, hi, owner, m_lo, m_hi)
    if keep.all():
        return _probe(at, lo, hi, owner)
    best, open_ = np.full(lo.size, np.inf), np.zeros(lo.size, dtype=bool)
    if keep.any():
        best[keep], open_[keep] = _probe(at, lo[keep], hi[keep], owner[keep])
    return best, open_


def dead_points_between_rows(scene: Scene, structure: Structure, kin: Kinematics
                             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Dead points between rows, and just beyond the sweep's ends; intervals the
    mechanism cannot cross.

    Parameters
    ----------
    scene, structure, kin
        The mechanism and its kinematics over the sweep (rows in any order).

    Returns
    -------
    between : numpy.ndarray
        (k, 2) rows (i, j), neighbours in increasing driver position (i before j), with a
        dead point between them; in increasing position.
    ends : numpy.ndarray
        The end rows (smallest and/or largest position) with a dead point within one
        row's spacing beyond them (outside the sweep: for a whole turn, the same state as
        the other end).
    unassembled : numpy.ndarray
        (k, 2) rows (i, j) as in ``between`` where some dyad cannot close at a position
        probed between them: the two rows are not joined by any motion of the mechanism.
    """
    return dead_points_of_sweep(scene, structure, kin.positions, kin_measure2(kin))


def dead_points_of_sweep(scene: Scene, structure: Structure, positions: np.ndarray,
                         m2: np.ndarray, screened: tuple | None = None
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`dead_points_between_rows` of a sweep at ``positions`` whose closeness to a
    dead centre is ``m2`` (:func:`measure2`) per row. ``screened``: what a compiled pass
    that made ``m2`` found of it, or None: the intervals :func:`_candidates` finds over
    the rows in their order (None: not told) and whether some row is below the screen
    (:func:`~kinetostatics.solver.fast.screen_kernels.flags_and_measure`; the intervals
    read only where the rows are the scene's own, known to increase)."""
    low = m2.size and (bool(_min(m2) < SCREEN**2) if screened is None else screened[1])
    if not low:                     # nothing to probe (the usual case; no rows: none)
        pairs = np.zeros((0, 2), dtype=int)
        return pairs, np.zeros(0, dtype=int), pairs

    at = sweep_probe(scene, structure)
    if at is None:
        def at(positions: np.ndarray, owner: np.ndarray) -> Probed:
            return probe_closeness(scene, structure, positions)
        # the intervals the rows prove clear, not probed (screen_bound's L)
        clear = sweep_bound(scene, structure)
        if clear is not None:
            at.clear = clear
    # (the scene's own positions known to increase, Driver.increasing: not told again,
    # measured 2026-11-30, the shaper at 1e6 rows: _segment_order's pass 1.3 ms)
    drv = scene.driver
    pos = np.asarray(positions, dtype=float)
    increasing = drv.increasing and pos is drv.positions
    cand = screened[0] if increasing and screened is not None else None
    return dead_points_stacked(m2, pos, np.zeros(1, dtype=int), np.array([m2.size]), at,
                               increasing=increasing, candidates=cand)[0]


def dead_points_stacked(m2u: np.ndarray, positions: np.ndarray, starts: np.ndarray,
                        counts: np.ndarray,
                        at: Callable[[np.ndarray, np.ndarray], Probed],
                        increasing: bool = False, candidates: np.ndarray | None = None,
                        below: np.ndarray | None = None) -> list[tuple]:
    """:func:`dead_points_between_rows` of many sweeps at once: segment s holds rows
    ``starts[s]`` to ``starts[s] + counts[s]`` (one scene of a stack,
    :func:`kinetostatics.solve_many`), searched alone, with the probes of all segments in
    one solve (``at``, as for :func:`_probe`). Every number is the one a segment's scene
    gives alone: the same elementwise operations on each row.

    Parameters
    ----------
    m2u : numpy.ndarray
        m^2 per row (:func:`kin_measure2`), rows in the sweeps' own order.
    positions : numpy.ndarray
        The driver position of each row.
    starts, counts : numpy.ndarray
        Each segment's first row and number of rows (one after another, in order).
    at : callable
        ``at(positions, owner)``: the probe at ``positions`` (row i of segment
        ``owner[i]``), as for :func:`_probe`.
    increasing : bool
        Every segment's positions are known to increase (their order is then not told
        again).
    candidates : numpy.ndarray, optional
        With ``increasing``, the intervals :func:`_candidates` finds (told by the pass
        that made ``m2u``): not scanned again.
    below : numpy.ndarray, optional
        The rows whose m^2 is below the screen, ``flatnonzero(m2u < SCREEN**2)``, when
        known (told by the pass that made ``m2u``: solve_many's fused kernel); not
        looked for again.

    Returns
    -------
    list of tuple
        Per segment, ``(between, ends, unassembled)`` as :func:`dead_points_between_rows`
        returns them, in the segment's own row numbers.
    """
    starts = np.asarray(starts, dtype=int)
    counts = np.asarray(counts, dtype=int)
    m = starts.size
    none, pairs = np.zeros(0, dtype=int), np.zeros((0, 2), dtype=int)
    # the rows below the screen, which alone can start a probe (NaN is not below; none:
    # nothing to probe, the usual case for one scene; one pass over the rows, told once)
    # (a single sweep's compiled scan, compiled_scan, reads the rows itself: no such
    # pass; nothing below the screen then leaves nothing to probe, below; a stack's
    # scenes are scanned on numpy: its rows below the screen are few and sparse, the
    # numpy scan's gathers over them cost less than a compiled pass over every row)
    # (the intervals told, in a sweep known to increase: no pass over the rows here,
    # nor a look for the compiled scan)
    told = candidates is not None and increasing
    one = m == 1
    if told or one and compiled_scan() is not None:
        below = None
    elif below is None:
        below = np.flatnonzero(m2u < SCREEN**2)
    if below is not None and below.size == 0:
        return [(pairs, none, pairs)] * m
    # the rows in increasing position (None: as they are, the usual case: then no
    # array over all the rows is taken in another order)
    order = None if increasing else _segment_order(positions, starts)
    m2 = m2u if order is None else m2u[order]
    pos = positions if order is None else positions[order]
    if order is not None:
        below = None            # (the same rows, told in their order)
    if told:
        cand = candidates
    else:
        cand = (_candidates(m2, rows=below) if one
                else _candidates(m2, starts, counts, rows=below))
    # beyond the ends: an end row that is a dip of m, probed over one spacing outside
    lo_e, hi_e, seg_e, row_e = _end_probes(m2, pos, starts, counts)
    k = cand.size
    lo = np.concatenate([pos[cand], lo_e])
    hi = np.concatenate([pos[cand + 1], hi_e])
    owner = np.concatenate([_segment_of(cand, starts), seg_e])
    if lo.size == 0:
        return [(pairs, none, pairs)] * m
    best, open_ = _probe_unclear(at, lo, hi, owner, np.concatenate([m2[cand], m2[row_e]]),
                                 np.concatenate([m2[cand + 1], np.full(row_e.size, -np.inf)]))
    ends_m2 = np.minimum(m2[cand], m2[cand + 1])
    dead = (best[:k] <= SINGULAR_WARN**2) & (best[:k] < ends_m2) & ~open_[:k]
    be = best[k:]
    hit = (be <= SINGULAR_WARN**2) & (be < m2[row_e])
    # per segment, its end rows near a dead point outside, in its own row numbers (its
    # first row before its last)
    edges: dict[int, list[int]] = {}
    for s, r in zip(seg_e[hit].tolist(), row_e[hit].tolist(), strict=True):
        edges.setdefault(s, []).append(r)
    between = _per_segment(cand[dead], order, starts)
    gaps = _per_segment(cand[open_[:k]], order, starts)
    # (a segment with nothing found shares one tuple of empty arrays: most of a stack's,
    # a thousand tuples fewer for the garbage collector to walk)
    out = [(pairs, none, pairs)] * m
    for s in between.keys() | gaps.keys():
        out[s] = (between.get(s, pairs), none, gaps.get(s, pairs))
    for s, rs in edges.items():
        rows = rs if order is None else order[rs].tolist()
        out[s] = (out[s][0], np.array(rows, dtype=int) - int(starts[s]), out[s][2])
    return out


def _end_probes(m2: np.ndarray, pos: np.ndarray, starts: np.ndarray, counts: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The end rows of the segments (of two rows or more) probed beyond them: those whose
    m is below the screen and not above their neighbour's, each over one row's spacing
    outside its segment; the probes' intervals (lo, hi), segments and rows, every
    segment's first row, then every segment's last. One segment's (a sweep's) two ends
    are told in numbers (the same comparisons and doubles: a dozen passes over
    one-value arrays spared, some 40 us a call, measured 2026-11-30)."""
    if starts.size == 1:
        a, n = int(starts[0]), int(counts[0])
        lo, hi, rows = [], [], []
        if n >= 2:
            b = a + n - 1
            if m2[a] < SCREEN**2 and m2[a] <= m2[a + 1]:
                lo.append(2.0 * pos[a] - pos[a + 1])
                hi.append(pos[a])
                rows.append(a)
            if m2[b] < SCREEN**2 and m2[b] <= m2[b - 1]:
                lo.append(pos[b])
                hi.append(2.0 * pos[b] - pos[b - 1])
                rows.append(b)
        return (np.array(lo, dtype=float), np.array(hi, dtype=float),
                np.zeros(len(rows), dtype=int), np.array(rows, dtype=int))
    two = counts >= 2
    first, last = starts[two], (starts + counts - 1)[two]
    use_f = (m2[first] < SCREEN**2) & (m2[first] <= m2[first + 1])
    use_l = (m2[last] < SCREEN**2) & (m2[last] <= m2[last - 1])
    first, last = first[use_f], last[use_l]
    segs = np.flatnonzero(two)
    return (np.concatenate([2.0 * pos[first] - pos[first + 1], pos[last]]),
            np.concatenate([pos[first], 2.0 * pos[last] - pos[last - 1]]),
            np.concatenate([segs[use_f], segs[use_l]]), np.concatenate([first, last]))


def _segment_of(rows: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """The segment holding each row (segments one after another from ``starts``; an
    empty segment holds none): of one segment, 0."""
    if starts.size == 1:
        return np.zeros(rows.size, dtype=np.intp)
    return np.searchsorted(starts, rows, side="right") - 1


def _segment_order(positions: np.ndarray, starts: np.ndarray) -> np.ndarray | None:
    """The rows in increasing driver position within each segment (each segment's
    :func:`~.continuity.sweep_order`), or None where every sweep increases (the rows
    as they are)."""
    n = positions.size
    up = positions[1:] > positions[:-1]
    up[starts[1:][starts[1:] > 0] - 1] = True         # no order across segments
    if n < 2 or bool(up.all()):
        return None
    if starts.size == 1:
        return sweep_order(positions)
    seg = np.repeat(np.arange(starts.size), np.diff(np.append(starts, n)))
    return np.lexsort((positions, seg))


def _per_segment(intervals: np.ndarray, order: np.ndarray | None, starts: np.ndarray
                 ) -> dict[int, np.ndarray]:
    """Intervals (global rows in increasing position) as (k, 2) row pairs per segment
    that holds some, in each segment's own row numbers (``order`` None: the rows as they
    are)."""
    if intervals.size == 0:
        return {}
    owner = _segment_of(intervals, starts)
    if order is None:
        pairs = np.stack([intervals, intervals + 1], axis=1) - starts[owner, None]
    else:
        pairs = np.stack([order[intervals], order[intervals + 1]], axis=1) - starts[owner, None]
    cuts = np.searchsorted(owner, np.arange(starts.size + 1))
    return {s: pairs[cuts[s]:cuts[s + 1]]
            for s in np.flatnonzero(cuts[1:] > cuts[:-1]).tolist()}
