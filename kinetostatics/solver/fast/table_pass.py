"""A long sweep of a crank and one dyad solved again by the fused table kernels
(:mod:`~kinetostatics.solver.fast.fused_tables`), its ``kinematics`` and ``reactions``
rows written straight into the tables' columns (no numba here: the kernels come
loaded).

Which scratch row of the kernel holds each joint's reaction, and with which sign, is read
off the composed path's own reading (:func:`~kinetostatics.solver.fast.compose.block_reactions`
on a probe array whose every row holds its own number): one account of where a
reaction lies, the composed path's.
"""

from __future__ import annotations

import numpy as np

from ...model.scene import GROUND, Scene
from .compose import Plan, Refused, block_reactions, driver_input
from .layout import DYAD_OUT
from .layout import MOTION as BODY_ROWS
from .layout import REACTIONS as REACTION_ROWS
from .short import OWNERS, START, fused_arguments, fused_kernel

# Rows per call of a fused table kernel (the crank's cos and sin worked out per block
# into one scratch pair, in a pass of their own, where the solve kept none). The calls'
# own cost is small: 245 calls of no rows 1.5-2 ms (2026-11-30, load 9-12).
# Tried and left 2026-11-30 (Intel Xeon, 2 MB L2, load 9-12, the four-bar at 1e6, the
# pass alone, processor time, best of 7-9; docs/solve-paths.md, "Where the warm round's
# time goes"): the kernel keeping the block (each tile's motion of the three bodies and
# each joint's Fx, Fy, F, N, M copied into 4096 rows, every column then written in runs
# of 4096) 190-213 ms in pages already had against 138-166, 310-321 against 219-277 in
# fresh pages (50 rows copied a row of the sweep; the copies then a vectorised loop a
# row, alternated with this build twice: 163-173 against 114-129 ms, 246-259 against
# 187-224, the same bytes); ordinary stores in place of the non-temporal ones
# (streams.stream) 120-124 against 118-140 ms, 192-194 against 184-209 in fresh pages:
# within the load's noise. (On that Xeon streams.stream made ordinary stores of every
# column but the negated ones until 2026-12-01: that comparison was of ordinary stores
# with ordinary stores, mostly; streams.py.)
BLOCK = 4096


class FusedTables:
    """The fused table kernel of ``scene`` (its own sweep) and ``structure`` (with the
    assemblies it was solved with), or :attr:`kernel` None: not a crank and one dyad the
    fused kernels cover, or ``resist`` loads (their statistics are the sweep's; the
    composed kernels solve those again).

    Attributes
    ----------
    reactions : dict
        Joint -> its :class:`~kinetostatics.solver.reactions.JointReaction` as the
        composed path records it (``on``, ``by``, ``sign``), over one probe row.
    """

    def __init__(self, kernels, scene: Scene, structure):
        self.scene = scene
        self.kernel = None
        plan = Plan(kernels, scene, structure, structure.assembly)
        found = None if plan.swept else fused_kernel(plan)
        if found is None:
            return
        from .fused_tables import TABLES, W_DYAD, W_LOADS, W_REACTIONS
        kernel, order, known = found
        dyad = plan.dyads[0][2]
        self.fixed = fused_arguments(plan, order, known)[:11]   # (no swept loads)
        self.slot = {b: i + 1 for i, b in enumerate(order)}
        probe = np.arange(1.0, W_REACTIONS + REACTION_ROWS + 1)[:, None]
        R = BODY_ROWS
        rows = {"m": {b: probe[R * i:R * (i + 1)] for i, b in enumerate((GROUND, *order))},
                "a": {b: probe[W_LOADS + 3 * i:W_LOADS + 3 * (i + 1)]
                      for i, b in enumerate(order)},
                "d": [probe[W_DYAD:W_DYAD + DYAD_OUT]], "r": [probe[W_REACTIONS:]],
                "drv": None, "u": None}
        self.reactions = block_reactions(plan, scene, rows)
        self.kernel = TABLES.get(dyad.kind)

    def sources(self, joints: list[str]) -> tuple[np.ndarray, np.ndarray]:
        """Per joint (in ``joints``' order) the scratch rows of its ``Fx, Fy, N, M`` (-1:
        a pin, no N, M) and the signs of its force and of its ``N, M``, as the
        ``reactions`` table reads them."""
        src = np.full((len(joints), 4), -1, dtype=np.int64)
        sign = np.ones((len(joints), 2))
        for q, j in enumerate(joints):
            r = self.reactions[j]
            fx, fy = _row(r.fx), _row(r.fy)
            if fx < 0 or fy < 0:
                raise Refused("a reaction's force recorded negated")
            src[q, 0], src[q, 1] = fx - 1, fy - 1
            sign[q, 0] = 1.0 if r.sign > 0 else -1.0
            if r.N is not None:
                nn, mm = _row(r.N), _row(r.M)
                if (nn < 0) != (mm < 0):
                    raise Refused("N and M of a prismatic joint of unlike signs")
                src[q, 2], src[q, 3] = abs(nn) - 1, abs(mm) - 1
                sign[q, 1] = -1.0 if nn < 0 else 1.0
        return src, sign

    def write(self, points: list[tuple[str, tuple[float, float]]], kout: np.ndarray,
              joints: list[str] | None = None, rout: np.ndarray | None = None) -> None:
        """Solve the sweep again block by block and write every row of the ``kinematics``
        table's float columns into ``kout`` (``points``: each point's body and local
        coordinates, in the table's order) and, with ``joints`` (in the table's order),
        of the ``reactions`` table's ``Fx, Fy, F, N, M`` into ``rout``, the crank angle's
        cos and sin worked out per block (:func:`block_turn`: the solve's numbers; the
        solve keeps none over the sweep, ``fused_kernels._tile_turn``). Raises
        :class:`~kinetostatics.solver.fast.compose.Refused` where a kernel met a row
        that is not finite (never expected: the sweep was solved by the same kernels)."""
        if joints is None:
            src, sign, rout = np.zeros((0, 4), dtype=np.int64), np.ones((0, 2)), kout
        else:
            src, sign = self.sources(joints)
        slots = np.array([self.slot[b] for b, _ in points], dtype=np.int64)
        local = np.array([loc for _, loc in points], dtype=float).reshape(-1, 2)
        own = own_hypot()
        angles = block_angles(self.scene)
        n = self.scene.driver.positions.size
        width = min(BLOCK, n)
        cs, sn, at = np.empty(width), np.empty(width), np.empty(width)
        turn = block_turn()
        bad = 0
        for lo in range(0, n, width):
            m = min(lo + width, n) - lo
            turn(angles(slice(lo, lo + m), at), cs[:m], sn[:m])
            bad += self.kernel(0, m, OWNERS, cs, sn, START, *self.fixed, slots, local, n, lo,
                               kout, src, sign, rout, own)
        if bad:
            raise Refused(bad)


def block_angles(scene: Scene):
    """``angles(rows, out)``: the crank's angles (rad) of the sweep's ``rows``, read-only
    (as a driver's angles: :func:`block_turn`'s kernel is compiled for one type of array;
    a writable sweep here was a second compile of it, found by test_fast's one-signature
    check, 2026-11-30), the doubles the solve's kernels turn: a view of the driver's
    ``angles`` where they are made, else worked out into ``out`` block by block
    (:meth:`~kinetostatics.model.scene.Driver.angles_into`: the lean solve makes none, and
    the whole sweep's 8 MB at 1e6 rows, fresh pages and a pass of their own, were made
    here for one read; measured 2026-12-01, 2-5 ms of processor time a table pass)."""
    drv = scene.driver
    if drv.kind == "R":
        return drv.angles_into
    x = driver_input(scene).view()
    x.flags.writeable = False
    return lambda rows, out: x[rows]


def block_turn():
    """``turn(angles, cs, sn)``: the cos and sin of a block's crank angles into ``cs``,
    ``sn``, the compiled path's
    (:func:`~kinetostatics.solver.fast.trig_kernels.turn_rows`: the doubles the solve's
    kernels work out). (Measured 2026-11-30, the four-bar's ``kinematics`` and
    ``reactions`` at 1e6 rows, processor time, best of 5 at a load of 17: 246 ms
    without the solve's kept cos and sin, the C library's then, 233 reading the kept
    pair. Since 2026-11-30 the solve keeps none, issue #31: its kernel works them out
    into each tile's scratch, two arrays of the sweep fewer written and faulted in
    when the driver table alone is asked for; they are the compiled path's here, some
    7 ns a row.)"""
    from .trig_kernels import turn_rows  # (numba loaded: the kernels given)
    return turn_rows


_HYPOT: dict[str, bool] = {}


def own_hypot() -> bool:
    """Whether the kernels' inlined hypot (glibc's algorithm,
    :func:`~kinetostatics.solver.fast.table_kernels.hypot`) gives numpy's ``hypot`` bit
    for bit here: checked once a process on 100 000 pairs (every class of double, each
    order of size, pairs near equal and far apart, zeros, subnormals, the largest
    doubles, infinities and NaN). Where numpy's C library computes it otherwise (another
    C library, a build with fused multiply-adds) the kernels call that library's, as
    numpy does."""
    if "own" not in _HYPOT:
        from .table_kernels import hypot_rows
        with np.errstate(all="ignore"):     # (probes of every size: some overflow)
            x, y = hypot_probes()
            want = np.hypot(x, y)
        out = np.empty_like(x)
        hypot_rows(x, y, out, True)
        _HYPOT["own"] = out.tobytes() == want.tobytes()
    return _HYPOT["own"]


def hypot_probes(n: int = 25_000) -> tuple[np.ndarray, np.ndarray]:
    """Pairs of doubles whose hypot :func:`own_hypot` checks (``4 n`` plus the special
    values' every pair)."""
    rng = np.random.default_rng(31)
    special = np.array([0.0, -0.0, 5e-324, 2.2e-308, 2.0**-511, 2.0**-512, 2.0**-600,
                        1.0, 3.0, 4.0, 2.0**511, 2.0**512, 1.7976931348623157e308,
                        np.inf, -np.inf, np.nan])
    wide = [rng.standard_normal(n) * 2.0 ** rng.integers(-1074, 1024, n).astype(float)
            for _ in range(2)]
    usual = rng.standard_normal((2, n)) * 500.0
    near = rng.standard_normal(n)
    apart = usual[0] * 2.0 ** rng.integers(-64, 64, n).astype(float)
    x = np.concatenate([np.repeat(special, special.size), wide[0], usual[0], near,
                        usual[0]])
    y = np.concatenate([np.tile(special, special.size), wide[1], usual[1],
                        near * (1.0 + 1e-3 * rng.standard_normal(n)), apart])
    return x, y


def _row(value) -> int:
    """The probe row a reaction's value is read from, counted from 1, negative where
    the composed path records its negation."""
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.size != 1 or v[0] != int(v[0]) or v[0] == 0.0:
        raise Refused("a reaction not read from one row")
    return int(v[0])
