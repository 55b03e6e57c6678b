"""Writing result tables: CSV with 17 significant digits, or Parquet; size estimates.

CSV text comes from :mod:`kinetostatics.csvtext` (numpy, whole columns at a time):
the same text as pandas' ``to_csv(index=False, float_format="%.17g")``, written in
chunks of rows by two threads (numpy releases the interpreter lock while it works).
Two shortcuts keep long tables fast: a long table repeats its ``position`` column once
per block (joint, point, body), so each chunk of positions is formatted once and
reused; and a chunk of a column holding one value (a fixed pivot, the zero couple of a
pin) is formatted once. Parquet (``pyarrow``, the optional ``[parquet]`` extra) keeps
the dtypes, categoricals included, and every bit of every float.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from . import csvtext
from .longtable import LongTable
from .model.errors import WorkbenchError
from .model.units import BASE, Units

if TYPE_CHECKING:
    import pandas as pd

CHUNK = 16_384          # rows formatted at a time (the arrays stay in the CPU caches)
THREADS = 2
# CSV written per second (bytes) for the time estimate of the warning, measured with
# `python -m kinetostatics bench --tables` on the 2-core development machine
CSV_RATE = 60e6
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
    if not isinstance(col, np.ndarray) or col.dtype.kind != "f":
        return csvtext.format_column(col, sep)
    if repeats is not None:
        hit = repeats.get(offset, col, sep)
        if hit is not None:
            return hit
    if col.size and _same_bits(col, col[:1]):
        out = _repeat(csvtext.format_floats(col[:1], sep), col.size)
    else:
        out = csvtext.format_floats(col, sep)
    if repeats is not None:
        repeats.put(offset, col, out, sep)
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
        start, stop, offset = span
        return csvtext.rows_text([_fields(d[start:stop], seps[i], repeats.get(i), offset)
                                  for i, d in enumerate(data)])

    def per_row() -> float:
        sample = np.linspace(0, rows - 1, 4096).astype(np.intp)
        return len(csvtext.rows_text([_fields(d[sample], seps[i])
                                      for i, d in enumerate(data)])) / sample.size

    return _write_lines(Path(path), names, list(_chunks(rows, block)), text, rows,
                        per_row, announce)


def write_long_csv(table: LongTable, path: str | Path,
                   announce: Callable[[str], None] | None = None,
                   repeats: Repeats | None = None) -> Path:
    """Write a long table as CSV straight from its definition, chunk by chunk: the same
    text as ``write_csv(table.frame(), path)`` without the table ever being held
    (``repeats``: the formatted ``position`` chunks shared with other tables)."""
    names = table.columns
    seps = _separators(len(names))
    nl = len(table.labels)
    labels = [[csvtext.format_label(x, seps[1 + j]) for x in block_names]
              for j, block_names in enumerate(table.labels.values())]
    repeats = repeats if repeats is not None else Repeats()

    def text(span: tuple[int, slice]) -> bytes:
        i, part = span
        m = part.stop - part.start
        values = table.chunk(i, part)
        fields = [_fields(np.asarray(table.positions[part], dtype=float), seps[0], repeats,
                          part.start)]
        fields += [_repeat(labels[j][i], m) for j in range(nl)]
        for k, c in enumerate(table.floats):
            v = values[c]
            sep = seps[1 + nl + k]
            fields.append(_repeat(csvtext.format_floats(np.array([v], dtype=float), sep), m)
                          if np.ndim(v) == 0 else _fields(np.asarray(v, dtype=float), sep))
        return csvtext.rows_text(fields)

    def per_row() -> float:
        parts = [(i, slice(0, min(512, table.n))) for i in range(table.blocks)]
        return sum(len(text(p)) for p in parts) / sum(p.stop for _, p in parts)

    return _write_lines(Path(path), names, list(table.parts(CHUNK)), text,
                        table.n * table.blocks, per_row, announce)


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
            size = per_row() * rows
            announce(f"{path.name}: {rows:,} rows, about {size / 1e6:,.0f} MB of CSV and "
                     f"{size / CSV_RATE:.0f} s to write (--format parquet is smaller and "
                     "faster)")
        if THREADS > 1 and len(spans) > 1:
            with ThreadPoolExecutor(THREADS) as pool:
                window = 4 * THREADS
                for i in range(0, len(spans), window):
                    for chunk in pool.map(text, spans[i:i + window]):
                        fh.write(chunk)
        else:
            for span in spans:
                fh.write(text(span))
    return path


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


def summary_with_units(summary: dict, units: Units) -> dict:
    """A summary that repeats the scene's ``[units]`` (scene-format.md, opening: the result
    tables and numbers stay SI; ``units`` says how the scene was written). ``units`` is a
    :class:`~kinetostatics.model.units.Units`."""
    return {**summary, "units": units.to_dict(BASE)}


def write_summary(path: str | Path, summary: dict) -> Path:
    """Write ``summary.json`` (indented JSON, one trailing newline)."""
    path = Path(path)
    path.write_text(json.dumps(summary, indent=2) + "\n")
    return path
