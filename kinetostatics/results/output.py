"""Writing result tables: CSV with 17 significant digits, or Parquet; size estimates.

CSV text comes from :mod:`kinetostatics.results.csvtext` (numpy, whole columns at a time):
the same text as pandas' ``to_csv(index=False, float_format="%.17g")``, written in
chunks of rows by two threads when a core is free (numpy releases the interpreter lock
while it works).
Two shortcuts keep long tables fast: a long table repeats its ``position`` column once
per block (joint, point, body), so each chunk of positions is formatted once and
reused; and a chunk of a column holding one value (a fixed pivot, the zero couple of a
pin) is formatted once. Parquet (``pyarrow``, the optional ``[parquet]`` extra) keeps
the dtypes, categoricals included, and every bit of every float.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..model.errors import WorkbenchError
from ..model.units import Units, labelled
from . import csvtext
from .longtable import LongTable

if TYPE_CHECKING:
    import pandas as pd

CHUNK = 16_384          # rows formatted at a time (the arrays stay in the CPU caches)
THREADS = 2             # writer threads when a core is free (see _threads)
THREADED = 200_000      # fields in a table written by the threads (fewer: no threads)
BATCH = 16_384          # float fields formatted in one call (several columns of a chunk)
# CSV written per second (bytes) for the time estimate of the warning, measured with
# `python -m kinetostatics bench --tables` and `solve --out` (1e6 positions: 2.2 GB in
# about 15 s) on the 2-core development machine, busy; a little under it
CSV_RATE = 120e6
WARN_ROWS = 1_000_000           # a longer table is announced with its size and time


class Repeats:
    """Formatted chunks of a column that repeats from block to block and from table to
    table (``position``): each chunk's values and fields by its offset and separator,
    used again only where the values have the same bits. One ``Repeats`` may serve every
    table written from one solution (:meth:`kinetostatics.Solution.write`)."""

    def __init__(self):
        self.seen: dict[tuple[int, str], tuple[np.ndarray, tuple]] = {}

    def get(self, offset: int, values: np.ndarray, sep: str = ","):
        hit = self.seen.get((offset, sep))
        if hit is not None and _same_bits(hit[0], values):
            return hit[1]
        return None

    def put(self, offset: int, values: np.ndarray, fields: tuple, sep: str = ",") -> None:
        self.seen[(offset, sep)] = (values.copy(), fields)


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Every value of ``a`` has the bits of ``b`` (broadcast): -0.0 differs from 0.0."""
    a = np.ascontiguousarray(a, dtype=float).view(np.int64)
    b = np.ascontiguousarray(b, dtype=float).view(np.int64)
    if b.shape[0] not in (1, a.shape[0]):
        return False
    return bool((a == b).all())


def _fields(col, sep: str, repeats: Repeats | None = None,
            offset: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """One chunk of one column as CSV fields (``csvtext.format_column``), with the
    shortcuts for a repeated chunk and a chunk of one value."""
    return _fields_of([col], [sep], [repeats], offset)[0]


def _fields_of(cols: list, seps: list[str], repeats: list[Repeats | None],
               offset: int = 0) -> list[tuple[np.ndarray, np.ndarray]]:
    """Chunks of columns (one length) as CSV fields: a repeated chunk taken again, a
    chunk of one value formatted once, the other float chunks formatted together (one
    call of ``csvtext.format_floats`` for up to ``BATCH`` values: a small table costs a
    few calls, not one per column and block)."""
    out: list = [None] * len(cols)
    pending = []
    for i, (col, sep, rep) in enumerate(zip(cols, seps, repeats, strict=True)):
        if not isinstance(col, np.ndarray) or col.dtype.kind != "f":
            out[i] = csvtext.format_column(col, sep)
            continue
        hit = rep.get(offset, col, sep) if rep is not None else None
        if hit is not None:
            out[i] = hit
        elif col.size and _same_bits(col, col[:1]):
            out[i] = _repeat(csvtext.format_floats(col[:1], sep), col.size)
        else:
            pending.append(i)
    m = cols[pending[0]].size if pending else 0
    if len(pending) > 1 and m * len(pending) <= BATCH:
        chars, length = csvtext.format_floats(np.concatenate([cols[i] for i in pending]))
        rows = np.arange(m)
        for k, i in enumerate(pending):
            ch, ln = chars[k * m:(k + 1) * m], length[k * m:(k + 1) * m]
            if seps[i] != ",":          # the separator is each field's last character
                ch[rows, ln.astype(np.intp) - 1] = ord(seps[i])
            out[i] = (ch, ln)
    else:
        for i in pending:
            out[i] = csvtext.format_floats(cols[i], seps[i])
    for i in pending:
        if repeats[i] is not None:
            repeats[i].put(offset, cols[i], out[i], seps[i])
    return out


def _chunks(rows: int, block: int | None) -> Iterator[tuple[int, int, int]]:
    """(start, stop, offset within the block) of the chunks, never across a block."""
    block = block or max(rows, 1)
    for b in range(0, rows, block):
        for s in range(b, min(b + block, rows), CHUNK):
            yield s, min(s + CHUNK, b + block, rows), s - b


def write_csv(df: pd.DataFrame | dict, path: str | Path, block: int | None = None,
              announce: Callable[[str], None] | None = None,
              repeats: Repeats | None = None) -> Path:
    """Write a table as CSV: header, then one line per row, floats as ``'%.17g'``.

    Parameters
    ----------
    df : DataFrame or dict
        The table (its index is not written), or its columns by name (arrays of one
        length: written as the DataFrame of them would be, without pandas).
    path : str or Path
    block : int, optional
        Rows per block of a long table (the number of positions): ``position`` is
        formatted once per chunk of positions and reused in every block.
    announce : callable, optional
        Called with one line (size and time estimate) before a table of more than
        ``WARN_ROWS`` rows is written.
    repeats : Repeats, optional
        The formatted ``position`` chunks shared with the other tables of the same
        solution (with ``block``).
    """
    if isinstance(df, dict):
        names = list(df)
        data = [np.asarray(v) if not hasattr(v, "categories") else v for v in df.values()]
    else:
        names = list(df.columns)
        data = []
        for name in names:
            s = df[name]
            data.append(s.array if hasattr(s.dtype, "categories") else s.to_numpy())
    rows = len(data[0]) if data else 0
    shared = repeats if repeats is not None else Repeats()
    repeats = {i: shared for i, n in enumerate(names) if n == "position" and block}
    seps = _separators(len(names))

    def text(span: tuple[int, int, int]) -> bytes:
        return _columns_text(data, seps, repeats, span)

    def per_row() -> float:
        sample = np.linspace(0, rows - 1, 4096).astype(np.intp)
        return len(csvtext.rows_text([_fields(d[sample], seps[i])
                                      for i, d in enumerate(data)])) / sample.size

    return _write_lines(Path(path), names, list(_chunks(rows, block)), text, rows,
                        per_row, announce)


def _columns_text(data: list, seps: list[str], repeats: dict, span: tuple[int, int, int]
                  ) -> bytes:
    """The CSV lines of the rows ``span`` = (start, stop, offset within the block) of the
    columns ``data`` (``repeats``: column index -> the formatted chunks it repeats)."""
    start, stop, offset = span
    return csvtext.rows_text(_fields_of([d[start:stop] for d in data], seps,
                                        [repeats.get(i) for i in range(len(data))], offset))


def write_long_csv(table: LongTable, path: str | Path,
                   announce: Callable[[str], None] | None = None,
                   repeats: Repeats | None = None) -> Path:
    """Write a long table as CSV straight from its definition, chunk by chunk: the same
    text as ``write_csv(table.frame(), path)`` without the table ever being held
    (``repeats``: the formatted ``position`` chunks shared with other tables)."""
    names = table.columns
    text = _long_text(table, repeats if repeats is not None else Repeats())

    def per_row() -> float:
        parts = [(i, slice(0, min(512, table.n))) for i in range(table.blocks)]
        return sum(len(text(p)) for p in parts) / sum(p.stop for _, p in parts)

    return _write_lines(Path(path), names, list(table.parts(CHUNK)), text,
                        table.n * table.blocks, per_row, announce)


def _long_text(table: LongTable, repeats: Repeats) -> Callable[[tuple[int, slice]], bytes]:
    """The function giving the CSV lines of the chunk (block, positions) of a long table
    (``repeats``: the formatted ``position`` chunks)."""
    names = table.columns
    seps = _separators(len(names))
    nl = len(table.labels)
    labels = [[csvtext.format_label(x, seps[1 + j]) for x in block_names]
              for j, block_names in enumerate(table.labels.values())]

    def text(span: tuple[int, slice]) -> bytes:
        i, part = span
        m = part.stop - part.start
        values = table.chunk(i, part)
        cols = [np.asarray(table.positions[part], dtype=float)]
        cols += [np.broadcast_to(np.asarray(values[c], dtype=float), (m,))
                 for c in table.floats]
        fields = _fields_of(cols, [seps[0], *seps[1 + nl:]],
                            [repeats] + [None] * len(table.floats), part.start)
        return csvtext.rows_text(fields[:1] + [_repeat(labels[j][i], m) for j in range(nl)]
                                 + fields[1:])
    return text


def _threads() -> int:
    """``THREADS`` when the load average leaves a core free, else 1: with no core free
    the threads only take turns, and their many hand-overs of the interpreter lock cost
    about 30 % more CPU (measured at 1e5 positions on the 2-core development machine)."""
    try:
        free = (os.cpu_count() or 1) - os.getloadavg()[0]
    except (AttributeError, OSError):       # no load average on this system
        return THREADS
    return THREADS if free > 0.5 else 1


def _separators(columns: int) -> list[str]:
    return [","] * (columns - 1) + ["\n"]


def _repeat(fields: tuple[np.ndarray, np.ndarray], m: int) -> tuple[np.ndarray, np.ndarray]:
    """One field (a row of chars, its length) on ``m`` rows, without copies."""
    chars, length = fields
    return (np.broadcast_to(chars[:1], (m, chars.shape[1])),
            np.broadcast_to(length[:1], (m,)))


def _write_lines(path: Path, names: list[str], spans: list, text: Callable[..., bytes],
                 rows: int, per_row: Callable[[], float],
                 announce: Callable[[str], None] | None) -> Path:
    """The header, then ``text(span)`` of every span in order (two threads, bounded
    read-ahead), after announcing a table of more than ``WARN_ROWS`` rows."""
    with path.open("wb") as fh:
        fh.write(csvtext.header_text(names))
        if not names or not spans:
            return path
        if announce is not None and rows > WARN_ROWS:
            _announce(announce, path, rows, per_row())
        _write_spans(fh, spans, text, rows * len(names))
    return path


def _announce(announce: Callable[[str], None], path: Path, rows: int, per_row: float) -> None:
    size = per_row * rows
    announce(f"{path.name}: {rows:,} rows, about {size / 1e6:,.0f} MB of CSV and "
             f"{size / CSV_RATE:.0f} s to write (--format parquet is smaller and faster)")


def _write_spans(fh, spans: list, text: Callable[..., bytes], fields: int) -> None:
    """``text(span)`` of every span written in order (two threads, bounded read-ahead,
    for a table of ``THREADED`` fields or more when a core is free)."""
    threads = _threads()
    if threads > 1 and len(spans) > 1 and fields >= THREADED:
        from concurrent.futures import ThreadPoolExecutor
        with ThreadPoolExecutor(threads) as pool:
            window = 4 * threads
            for i in range(0, len(spans), window):
                for chunk in pool.map(text, spans[i:i + window]):
                    fh.write(chunk)
    else:
        for span in spans:
            fh.write(text(span))


class CsvStream:
    """One CSV table written block of rows after block of rows (a streamed write,
    :mod:`kinetostatics.results.streamed`): the header, then each part's lines, the
    text :func:`write_csv` or :func:`write_long_csv` gives for the whole table.

    Parameters
    ----------
    path : Path
    names : list of str
        The columns.
    rows : int
        The table's rows in all (for the announcement of a table over ``WARN_ROWS``).
    announce : callable, optional
    """

    def __init__(self, path: Path, names: list[str], rows: int,
                 announce: Callable[[str], None] | None = None):
        self.path, self.names, self.rows, self.announce = path, names, rows, announce
        self.fh = path.open("wb")
        self.fh.write(csvtext.header_text(names))
        self.told = not (announce is not None and rows > WARN_ROWS)

    def _tell(self, text: bytes, rows: int) -> None:
        if not self.told and rows:
            self.told = True
            _announce(self.announce, self.path, self.rows, len(text) / rows)

    def columns(self, cols: dict, repeats: Repeats) -> None:
        """The next rows, as columns by name (one block: ``position`` formatted once per
        chunk and shared through ``repeats``)."""
        data = [np.asarray(v) if not hasattr(v, "categories") else v for v in cols.values()]
        rows = len(data[0]) if data else 0
        seps = _separators(len(data))
        reps = {i: repeats for i, n in enumerate(cols) if n == "position"}
        spans = list(_chunks(rows, rows))
        if spans:
            self._tell(_columns_text(data, seps, reps, spans[0]), spans[0][1])
        _write_spans(self.fh, spans, lambda s: _columns_text(data, seps, reps, s),
                     rows * len(data))

    def block(self, table: LongTable, i: int, repeats: Repeats) -> None:
        """The next rows: block ``i`` of a long table over all its positions."""
        text = _long_text(table, repeats)
        spans = [(i, slice(s, min(s + CHUNK, table.n))) for s in range(0, table.n, CHUNK)]
        if spans:
            self._tell(text(spans[0]), spans[0][1].stop)
        _write_spans(self.fh, spans, text, table.n * len(self.names))

    def close(self) -> None:
        self.fh.close()


class ParquetStream:
    """One Parquet table written block of rows after block of rows: a row group per
    part, the schema (dtypes, categories, pandas' metadata) of the first part, so that
    reading it back gives what :func:`write_parquet` of the whole table gives."""

    def __init__(self, path: Path):
        parquet_available()
        self.path = path
        self.writer = None
        self.schema = None

    def frame(self, df: pd.DataFrame) -> None:
        """The next rows, as a DataFrame."""
        import pyarrow as pa
        import pyarrow.parquet as pq
        if self.writer is None:
            self.schema = pa.Schema.from_pandas(df, preserve_index=False)
            self.writer = pq.ParquetWriter(self.path, self.schema)
        self.writer.write_table(pa.Table.from_pandas(df, schema=self.schema,
                                                     preserve_index=False))

    def close(self) -> None:
        if self.writer is not None:
            self.writer.close()


def parquet_available() -> None:
    """Refuse Parquet, with the fix, when ``pyarrow`` is not installed."""
    try:
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise WorkbenchError("--format parquet needs pyarrow: pip install "
                             "'mechanisms-workbench[parquet]' (or write CSV)") from None


def write_parquet(df: pd.DataFrame, path: str | Path) -> Path:
    """Write a table as Parquet (needs ``pyarrow``: the ``[parquet]`` extra)."""
    parquet_available()
    path = Path(path)
    df.to_parquet(path, index=False, engine="pyarrow")
    return path


def summary_with_units(summary: dict, units: Units, warnings: tuple[str, ...] = (),
                       position: str = "deg") -> dict:
    """A mechanism solve's summary that says its units key by key (SI; ``position`` the
    unit of the driver's positions, deg or m) and carries the scene's warnings, with the
    scene's ``[units]`` under ``scene_units`` (:func:`kinetostatics.model.units.labelled`).
    ``units`` is a :class:`~kinetostatics.model.units.Units`."""
    q = "Fe" if any(k.startswith("Fe_") for k in summary) else "Me"
    effort = "N" if q == "Fe" else "N m"
    unit_of = {f"{q}_mean": effort, f"{q}_max": effort, f"{q}_min": effort,
               "reaction_max": {"F": "N", "position": position},
               "transmission_angle_min": "deg", "transmission_angle_min_position": position,
               "dead_points_between_rows": position, "unassembled_between_rows": position}
    return labelled(summary, units, unit_of, warnings)


def write_summary(path: str | Path, summary: dict) -> Path:
    """Write ``summary.json`` (indented JSON, one trailing newline)."""
    path = Path(path)
    path.write_text(json.dumps(summary, indent=2) + "\n")
    return path
