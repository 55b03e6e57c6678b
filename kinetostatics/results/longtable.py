"""Long result tables, defined block by block: one block of rows per joint (point, body),
one row per position in each block.

A :class:`LongTable` knows its blocks' names and how to compute any chunk of positions
of a block from the solver's arrays. The same definition gives the pandas table
(:meth:`LongTable.frame`: every column allocated once and filled in place, the name
columns categorical) and the CSV file written chunk by chunk without the table ever
being held (:func:`kinetostatics.results.output.write_long_csv`), so both give the same values.

Memory (at 1e6 positions a long table holds hundreds of MB): columns several tables
have in common are held once (:func:`shared`: the ``position`` column of every long
table is a view of one tiled array, see :class:`TiledPositions`), and a float column
holding one value on every row (the ``N``, ``M`` and ``offset`` of a mechanism of
revolute joints only) is a read-only view of that one number (:func:`constant`).
pandas' copy-on-write keeps them apart: a table written to copies its column first, so
the other tables never see the change.

The short tables (``driver``, ``dyads``, ``sliders``, ``frame``: one row per position or
per position and dyad) are built from columns of their own (:func:`table_column`,
:func:`own_column`, :func:`text_column`, :func:`concat_blocks`) laid into a DataFrame
(:func:`columns_frame`; :func:`own_frame` for plain numpy columns, which it takes as
they are).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd

import numpy as np

CHUNK = 32_768          # positions computed at a time: the temporaries stay in the CPU caches
CONSTANTS_KEPT = 256    # distinct (value, length) pairs of constant columns held at most
# From this many rows on, Solution.driver shares its columns (position with the long
# tables, Me with the solve) instead of copying them. Copies cost less time at every size
# (2001 rows: 61 against 250 us; 262145: 486 against 861 us) but hold 16 bytes a row
# twice (1e6 rows with every table: the peak must stay under 1.2 GB); and the shared
# path's one large buffer, freed with the solution, raises glibc's trim threshold, so a
# loop of solves at 2e5 rows reuses its pages (34 against 42 ms a solve measured): the
# copies are kept to sizes where neither weighs.
SHARE_ROWS = 65_536
# Whether a long table's columns (:func:`table_block`) are laid on transparent huge pages,
# as numpy lays every large array where the kernel's setting is ``madvise``: kept on.
# Measured 2026-11-29 on the 2-core machine (THP madvise, defrag madvise), four-bar
# at 1e6, solve + driver, reactions and kinematics tables (630 MB), processor time, three
# rounds in each of two fresh processes per setting, alternating: on 0.50-0.71 s, off
# 0.78-0.83 s (the reactions and kinematics tables alone 0.36-0.57 s against 0.65-0.71 s:
# 4 kB faults on every page). In one earlier series off won the first round of a process
# (0.95-1.04 s against 1.75-2.17 s: the same 532 faults cost 0.07-1.4 s in turn) and lost the
# later ones; which wins depends on the machine's memory, the default stays numpy's.
HUGE_PAGES = True


# the float columns of the long tables, in order
REACTIONS_FLOATS = ("Fx", "Fy", "F", "N", "M", "offset")
KINEMATICS_FLOATS = ("x", "y", "vx", "vy", "ax", "ay")

def reaction_labels(joints: list[str], reactions: dict) -> dict[str, list[str]]:
    """The ``reactions`` table's name columns: each joint, the body its force acts ``on``
    and the body it comes ``by`` (``reactions``: joint -> its reaction)."""
    return {"joint": joints, "on": [reactions[j].on for j in joints],
            "by": [reactions[j].by for j in joints]}


def point_labels(points: list[tuple]) -> dict[str, list[str]]:
    """The ``kinematics`` table's name columns of ``points`` (body, point, local point)."""
    return {"body": [b for b, _, _ in points], "point": [p for _, p, _ in points]}


OFFSET_EMPTY = 1e-12     # offset = M / N is left empty where |N| <= 1e-12 max|N|


def offsets(nn: np.ndarray, mm: np.ndarray, largest: float) -> np.ndarray:
    """The ``reactions`` table's ``offset`` = M / N of a prismatic joint's rows, empty
    (NaN) where ``|N| <= OFFSET_EMPTY * largest`` (``largest``: max |N| over the sweep)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(np.abs(nn) > OFFSET_EMPTY * largest, mm / nn, np.nan)


def categorical(names: list[str], n: int, block: int | None = None) -> pd.Categorical:
    """A categorical column with ``names[i]`` on the ``n`` rows of block ``i`` (``block``:
    the rows of that block alone, with every block's names as categories)."""
    import pandas as pd
    cats = list(dict.fromkeys(names))
    kind = np.int8 if len(cats) < 127 else np.int16 if len(cats) < 32767 else np.int32
    codes = np.array([cats.index(x) for x in names], dtype=kind)
    # (codes made here, in range by construction: pandas' check, a min and a max over
    # every row, 0.3 ms per 9e6 rows, is skipped; ``validate`` is pandas 2.1's)
    if block is not None:
        return pd.Categorical.from_codes(np.full(n, codes[block]), categories=cats,
                                         validate=False)
    return pd.Categorical.from_codes(np.repeat(codes, n), categories=cats, validate=False)


class Labels:
    """A text column as its distinct texts and a code per row: what
    :func:`kinetostatics.results.csvtext.format_column` formats fastest (each text once, as a
    categorical), without pandas; ``objects()`` gives the column as an array of its
    texts (as a DataFrame takes it)."""

    def __init__(self, texts: list[str], codes: np.ndarray):
        self.categories = list(texts)
        self.codes = np.asarray(codes)

    def __len__(self) -> int:
        return self.codes.shape[0]

    def __getitem__(self, rows) -> Labels:
        return Labels(self.categories, self.codes[rows])

    def objects(self) -> np.ndarray:
        """The column as an array of objects (one text per row)."""
        table = np.empty(len(self.categories), dtype=object)
        table[:] = self.categories
        return table[self.codes]

    @staticmethod
    def concat(parts: list[Labels]) -> Labels:
        """Columns one after another."""
        texts: dict[str, int] = {}
        codes = []
        for p in parts:
            remap = np.array([texts.setdefault(t, len(texts)) for t in p.categories] or [0])
            codes.append(remap[p.codes])
        return Labels(list(texts), np.concatenate(codes) if codes else np.zeros(0, np.intp))


def shared(values: np.ndarray) -> pd.Series:
    """``values`` as a column that several tables may hold without a copy.

    Each table takes a view of the returned Series (``s.iloc[a:b]`` or ``s`` itself);
    while the Series lives (the caller keeps it), pandas knows the views share their
    data and copies a column before writing to it, so writing to one table never
    changes another (nor ``values``)."""
    import pandas as pd
    return pd.Series(values, copy=False)


_CONSTANTS: dict[tuple[int, int], pd.Series] = {}


def constant(value: float, rows: int) -> pd.Series | np.ndarray:
    """A float column of ``rows`` copies of ``value``: a read-only view of one number
    (8 bytes for any length; -0.0 and NaN keep their bits).

    The Series are kept for the life of the process (at most ``CONSTANTS_KEPT`` of them,
    a few hundred bytes each: past that a column of its own is returned), so that pandas
    always sees the view as shared and copies the column before a write to it."""
    bits = int(np.float64(value).view(np.int64))
    key = (bits, rows)
    hit = _CONSTANTS.get(key)
    if hit is not None:
        return hit
    if len(_CONSTANTS) >= CONSTANTS_KEPT:
        return np.full(rows, np.float64(value))
    hit = _CONSTANTS[key] = shared(np.broadcast_to(np.float64(value), (rows,)))
    return hit


class TiledPositions:
    """The ``position`` column of the long tables: the sweep repeated block after block,
    held once for every table of one solution.

    One array of room for the longest table is reserved at first use, and blocks are
    filled only as a table asks for them (the reserved memory of blocks never filled
    is not touched, so it takes no room); a table of ``k`` blocks takes a view of the
    first ``k`` (:func:`shared`)."""

    def __init__(self, positions: np.ndarray, most: int):
        self.positions = np.asarray(positions, dtype=float)
        self.n = self.positions.size
        self.most = max(int(most), 1)
        self._buffer: np.ndarray | None = None
        self._series: pd.Series | None = None
        self._filled = 0

    def column(self, blocks: int) -> pd.Series | np.ndarray:
        """``np.tile(positions, blocks)``, a view of the shared array where it fits."""
        if blocks > self.most:
            return np.tile(self.positions, blocks)
        if self._buffer is None:
            self._buffer = table_block(self.n * self.most)
            self._series = shared(self._buffer)
        n = self.n
        for i in range(self._filled, blocks):
            self._buffer[i * n:(i + 1) * n] = self.positions
        self._filled = max(self._filled, blocks)
        return self._series.iloc[:n * blocks]


def _same(a: float, b: float) -> bool:
    """The same bits (NaN equals NaN, -0.0 differs from 0.0)."""
    return bool(np.float64(a).view(np.int64) == np.float64(b).view(np.int64))


@dataclass
class LongTable:
    """A long table: ``position``, the name columns, the float columns.

    Attributes
    ----------
    positions : ndarray
        The sweep (one row per position in every block).
    labels : dict
        Name column -> the name of each block (e.g. ``{"body": [...], "point": [...]}``).
    floats : tuple of str
        The float columns, in order.
    chunk : callable
        ``chunk(i, part)`` -> ``{column: values}`` for the positions ``part`` (a slice)
        of block ``i``; a value may be a scalar (the same on every row).
    tiled : TiledPositions, optional
        The ``position`` column shared with the other tables of the same solution
        (default: a column of this table's own).
    whole : dict, optional
        Float column -> a callable giving that column whole (all blocks, in row order),
        for a column the solution already holds in that layout (:meth:`frame` then takes
        it as it is instead of filling it from the chunks; the chunks still give it for
        the CSV writer).
    """

    positions: np.ndarray
    labels: dict[str, list[str]]
    floats: tuple[str, ...]
    chunk: Callable[[int, slice], dict]
    tiled: TiledPositions | None = None
    whole: dict[str, Callable[[], object]] = field(default_factory=dict)

    @property
    def n(self) -> int:
        return self.positions.size

    @property
    def blocks(self) -> int:
        return len(next(iter(self.labels.values())))

    @property
    def columns(self) -> list[str]:
        return ["position", *self.labels, *self.floats]

    def parts(self, size: int = CHUNK) -> Iterator[tuple[int, slice]]:
        """(block, positions) of every chunk, in row order."""
        for i in range(self.blocks):
            for s in range(0, self.n, size):
                yield i, slice(s, min(s + size, self.n))

    def frame(self) -> pd.DataFrame:
        """The table as a DataFrame, in one pass over its bytes: the float columns filled
        in place, chunk by chunk, into one block allocated once (:class:`FloatBlock`); a
        column of one value on every row held as that one value (:func:`constant`), the
        ``position`` column shared (``tiled``)."""
        fill = FloatBlock(self)
        n = self.n
        for i, part in self.parts():
            fill.put(i, slice(i * n + part.start, i * n + part.stop), self.chunk(i, part))
        return self.frame_of(fill)

    def frame_of(self, fill: FloatBlock) -> pd.DataFrame:
        """The DataFrame of the float columns ``fill`` holds (every row written), with
        the ``position`` and name columns and the ``whole`` columns."""
        import pandas as pd
        k = self.blocks
        cols: dict[str, object] = {
            "position": self.tiled.column(k) if self.tiled is not None
            else np.tile(np.asarray(self.positions, dtype=float), k)}
        cols.update({c: categorical(names, self.n) for c, names in self.labels.items()})
        filled = fill.columns()
        for c in self.floats:
            cols[c] = self.whole[c]() if c in self.whole else filled[c]
        return pd.DataFrame(cols, copy=False)

    def block_frame(self, i: int) -> pd.DataFrame:
        """Block ``i`` of the table over all its positions, as a DataFrame with the
        columns and dtypes of :meth:`frame` (the name columns' categories: every block's
        names), for a table written block by block."""
        import pandas as pd
        n = self.n
        values = self.chunk(i, slice(0, n))
        cols: dict[str, object] = {"position": np.array(self.positions, dtype=float)}
        cols.update({c: categorical(names, n, i) for c, names in self.labels.items()})
        cols.update({c: np.array(np.broadcast_to(np.asarray(values[c], dtype=float), (n,)))
                     for c in self.floats})
        return pd.DataFrame(cols, copy=False)


def table_block(shape: int | tuple[int, ...]) -> np.ndarray:
    """An uninitialised float array for a table's columns, its first byte on a cache line
    (:func:`line_aligned`), asked of the kernel in pages of 4 kB unless
    :data:`HUGE_PAGES` (numpy asks for transparent huge pages on large arrays; that
    choice is numpy's process-wide switch, turned off here for this one allocation and
    put back)."""
    switch = _huge_page_switch()
    if HUGE_PAGES or switch is None:
        return line_aligned(shape)
    was = switch(False)
    try:
        return line_aligned(shape)
    finally:
        switch(was)


LINE = 64       # bytes of a cache line


def line_aligned(shape: int | tuple[int, ...]) -> np.ndarray:
    """``np.empty(shape)`` whose first byte starts a cache line of :data:`LINE` bytes (a
    view of a byte array ``LINE`` bytes longer). glibc gives a large array the 16th byte
    of its first page, so the compiled table kernels' non-temporal stores
    (:mod:`~kinetostatics.solver.fast.streams`), a tile of 64 rows a column, wrote a
    part of a line at each end of every tile's 512 bytes; from a line's start, whole
    lines (measured 2026-11-30, the four-bar's ``reactions`` and ``kinematics`` pass at
    1e6 rows in pages already had, processor time, best of 7-9 in one process at a
    load of 3-5: 88.6 and 92.0 ms against 93.8 and 110.6)."""
    shape = (shape,) if isinstance(shape, int) else tuple(shape)
    size = int(np.prod(shape, dtype=np.int64)) * 8
    raw = np.empty(size + LINE, dtype=np.uint8)
    at = -raw.ctypes.data % LINE
    return raw[at:at + size].view(np.float64).reshape(shape)


def _huge_page_switch():
    """numpy's ``_set_madvise_hugepage`` (private: None where it is missing)."""
    try:
        from numpy._core import multiarray
    except ImportError:                                     # numpy < 2
        from numpy.core import multiarray
    return getattr(multiarray, "_set_madvise_hugepage", None)


class FloatBlock:
    """The float columns of a :class:`LongTable` (those not given ``whole``), written in
    place chunk by chunk, in any order of chunks, each row once.

    The columns are the rows of one 2-D array, allocated at the first chunk that is not
    one value (a single allocation; rows of a column that stays one value are never
    touched, so they take no memory). A column that is the same number on every row
    written so far is kept as that number and becomes :func:`constant` (8 bytes); when
    another value comes, the rows written as the number are filled with it first.
    """

    def __init__(self, table: LongTable):
        self.size = table.n * table.blocks
        self.names = [c for c in table.floats if c not in table.whole]
        self.block: np.ndarray | None = None
        self.rows: dict[str, np.ndarray] = {}       # columns written as arrays
        self.same: dict[str, float] = {}            # columns of one value so far
        self.wrote: dict[str, list[slice]] = {}     # ... and the rows written with it

    def put(self, i: int, rows: slice, values: dict, names=None) -> None:
        """``values`` (column -> array or number, as :attr:`LongTable.chunk` gives them)
        into the rows ``rows`` of the whole table (``i``: the block, for the caller;
        ``names``: those columns only, default every one)."""
        for c in self.names if names is None else names:
            v = values[c]
            out = self.rows.get(c)
            if out is None:
                if np.ndim(v) == 0:
                    if c not in self.same:
                        self.same[c], self.wrote[c] = float(v), [rows]
                        continue
                    if _same(self.same[c], v):
                        self.wrote[c].append(rows)
                        continue
                out = self._column(c)
            out[rows] = v

    def reserve(self) -> np.ndarray:
        """The array of every column (one row each), allocated now if it is not yet: its
        memory is taken page by page as it is written (a caller may keep numbers of its
        own in rows not written yet, and must have read them before it writes them)."""
        if self.block is None:
            self.block = table_block((len(self.names), self.size))
        return self.block

    def array(self, c: str) -> np.ndarray:
        """Column ``c`` as an array (its row of :meth:`reserve`), from now on, for a
        caller that writes its rows in place (the rows written so far as one value
        filled with it)."""
        out = self.rows.get(c)
        return self._column(c) if out is None else out

    def _column(self, c: str) -> np.ndarray:
        """Column ``c`` as an array, the rows written as one value filled with it."""
        self.reserve()
        out = self.rows[c] = self.block[self.names.index(c)]
        value = self.same.pop(c, None)
        for rows in self.wrote.pop(c, ()):
            out[rows] = value
        return out

    def columns(self) -> dict[str, object]:
        """Every column: an array, a :func:`constant`, or empty (a table of no rows)."""
        out: dict[str, object] = {}
        for c in self.names:
            if c in self.rows:
                out[c] = self.rows[c]
            elif c in self.same:
                out[c] = constant(self.same[c], self.size)
            else:
                out[c] = np.empty(0)
        return out


def fill_offsets(fill: FloatBlock, prismatic: list[int], n: int) -> None:
    """The ``offset`` of each prismatic joint's rows, from its whole ``N`` and ``M``."""
    for i in prismatic:
        rows = slice(i * n, (i + 1) * n)
        nn, mm = fill.rows["N"][rows], fill.rows["M"][rows]
        fill.rows["offset"][rows] = offsets(nn, mm, np.abs(nn).max() if n else 0.0)


# -- short tables: columns of their own, laid into a DataFrame -----------------------
def table_column(value: object, n: int, dtype: type = float) -> np.ndarray:
    """A table column of its own (a copy: the table never shares the solver's arrays)."""
    return np.array(np.broadcast_to(value, (n,)), dtype=dtype)


def whole_column(value: object, n: int, dtype: type = np.float64) -> bool:
    """Whether ``value`` is an array of ``n`` values of ``dtype``: a column as it is."""
    return type(value) is np.ndarray and value.shape == (n,) and value.dtype == dtype


def own_column(value: object, n: int, dtype: type = np.float64) -> np.ndarray:
    """:func:`table_column` by the shortest road: an array of ``n`` values of ``dtype``
    already is copied as it is (the same values, bit for bit)."""
    return value.copy() if whole_column(value, n, dtype) else table_column(value, n, dtype)


def made_column(value: object, n: int, dtype: type = np.bool_) -> np.ndarray:
    """:func:`own_column` of an array made for this table alone (nothing else holds it, a
    deferred solve's ``singular()``): taken as it is, no copy (measured 2026-11-30, the
    slider-crank at 1e6 rows: 1 MB a driver table)."""
    return value if whole_column(value, n, dtype) else table_column(value, n, dtype)


def text_column(value: str, n: int) -> Labels:
    """A column of ``n`` copies of one text (the CSV writer formats it once; the
    DataFrame holds it as objects, as pandas holds text)."""
    return Labels([value], np.zeros(n, dtype=np.int8))


def concat_blocks(parts: list[dict], names: list[str]) -> dict:
    """The blocks of a table one after another (no block: empty columns)."""
    if not parts:
        return {c: np.empty(0, dtype=object) for c in names}
    return {c: Labels.concat([p[c] for p in parts]) if isinstance(parts[0][c], Labels)
            else np.concatenate([p[c] for p in parts]) for c in names}


def columns_frame(columns: dict, copy: bool | None = None) -> pd.DataFrame:
    """A table's columns as a DataFrame (pandas imported here, when a table is asked for;
    text columns as objects)."""
    import pandas as pd
    return pd.DataFrame({c: v.objects() if isinstance(v, Labels) else v
                         for c, v in columns.items()}, copy=copy)


_LABELS: dict[tuple[str, ...], pd.Index] = {}


def _private_forms(n: int, labels: pd.Index) -> tuple[pd.RangeIndex, pd.Index]:
    """``pd.RangeIndex(n)`` and ``labels.copy()`` by pandas' private names (no checks)."""
    import pandas as pd
    return pd.RangeIndex._simple_new(range(n)), labels._view()


def own_frame(columns: dict[str, np.ndarray], n: int) -> pd.DataFrame:
    """A DataFrame of 1-D numpy columns of ``n`` rows that nothing else holds (copies
    made for this table), taken as they are: one block per column, as
    ``pd.DataFrame(columns, copy=False)`` lays them out, built without the constructor's
    checks and inference (13 against 58 us for the driver's four columns at 2001 rows).

    pandas' block API (:func:`pandas.api.internals.create_dataframe_from_blocks`, pandas
    3) takes the arrays as they are; where it is missing, the constructor does. The
    column labels are made once per set of names and each table gets its own copy of
    them (an Index's ``name`` can be set in place)."""
    import pandas as pd
    try:
        from pandas.api.internals import create_dataframe_from_blocks
    except ImportError:                                     # pandas < 3
        return pd.DataFrame(columns, copy=False)
    names = tuple(columns)
    labels = _LABELS.get(names)
    if labels is None:
        labels = _LABELS[names] = pd.Index(list(names))
    blocks = [(v.reshape(1, n), np.array([i])) for i, v in enumerate(columns.values())]
    # the row index and the labels' copy by what pd.RangeIndex(n) and Index.copy() end
    # in, without their checks of arguments given here (measured 2026-11-29, the driver
    # table at 2001 rows after a garbage collection, as the bench times a call: 30-60 us
    # of 270-330); both are pandas' private names: a pandas without them takes the public
    # forms
    try:
        index, labels = _private_forms(n, labels)
    except AttributeError:
        index, labels = pd.RangeIndex(n), labels.copy()
    return create_dataframe_from_blocks(blocks, index=index, columns=labels)
