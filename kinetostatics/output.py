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

from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from . import csvtext
from .model.errors import WorkbenchError

CHUNK = 16_384          # rows formatted at a time (the arrays stay in the CPU caches)
THREADS = 2
# CSV written per second (bytes) for the time estimate of the warning, measured with
# `python -m kinetostatics bench --tables` on the 2-core development machine
CSV_RATE = 60e6
WARN_ROWS = 1_000_000           # a longer table is announced with its size and time


class _Repeats:
    """Formatted chunks of a column that repeats from block to block (``position``)."""

    def __init__(self):
        self.seen: dict[int, tuple[np.ndarray, tuple]] = {}

    def get(self, offset: int, values: np.ndarray):
        hit = self.seen.get(offset)
        if hit is not None and _same_bits(hit[0], values):
            return hit[1]
        return None

    def put(self, offset: int, values: np.ndarray, fields: tuple) -> None:
        self.seen[offset] = (values.copy(), fields)


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Every value of ``a`` has the bits of ``b`` (broadcast): -0.0 differs from 0.0."""
    a = np.ascontiguousarray(a, dtype=float).view(np.int64)
    b = np.ascontiguousarray(b, dtype=float).view(np.int64)
    if b.shape[0] not in (1, a.shape[0]):
        return False
    return bool((a == b).all())


def _fields(col, sep: str, repeats: _Repeats | None = None,
            offset: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """One chunk of one column as CSV fields (``csvtext.format_column``), with the
    shortcuts for a repeated chunk and a chunk of one value."""
    if not isinstance(col, np.ndarray) or col.dtype.kind != "f":
        return csvtext.format_column(col, sep)
    if repeats is not None:
        hit = repeats.get(offset, col)
        if hit is not None:
            return hit
    if col.size and _same_bits(col, col[:1]):
        chars, length = csvtext.format_floats(col[:1], sep)
        out = (np.broadcast_to(chars, (col.size, chars.shape[1])),
               np.broadcast_to(length, (col.size,)))
    else:
        out = csvtext.format_floats(col, sep)
    if repeats is not None:
        repeats.put(offset, col, out)
    return out


def _chunks(rows: int, block: int | None) -> Iterator[tuple[int, int, int]]:
    """(start, stop, offset within the block) of the chunks, never across a block."""
    block = block or max(rows, 1)
    for b in range(0, rows, block):
        for s in range(b, min(b + block, rows), CHUNK):
            yield s, min(s + CHUNK, b + block, rows), s - b


def write_csv(df: pd.DataFrame, path: str | Path, block: int | None = None,
              announce: Callable[[str], None] | None = None) -> Path:
    """Write a table as CSV: header, then one line per row, floats as ``'%.17g'``.

    Parameters
    ----------
    df : DataFrame
        The table (its index is not written).
    path : str or Path
    block : int, optional
        Rows per block of a long table (the number of positions): ``position`` is
        formatted once per chunk of positions and reused in every block.
    announce : callable, optional
        Called with one line (size and time estimate) before a table of more than
        ``WARN_ROWS`` rows is written.
    """
    path = Path(path)
    names = list(df.columns)
    data = []
    for name in names:
        s = df[name]
        data.append(s.array if isinstance(s.dtype, pd.CategoricalDtype) else s.to_numpy())
    repeats = {i: _Repeats() for i, n in enumerate(names) if n == "position" and block}
    seps = [","] * (len(names) - 1) + ["\n"]

    def text(span: tuple[int, int, int]) -> bytes:
        start, stop, offset = span
        return csvtext.rows_text([_fields(d[start:stop], seps[i], repeats.get(i), offset)
                                  for i, d in enumerate(data)])

    with path.open("wb") as fh:
        fh.write(csvtext.header_text(names))
        spans = list(_chunks(len(df), block))
        if not names or not spans:
            return path
        if announce is not None and len(df) > WARN_ROWS:
            sample = np.linspace(0, len(df) - 1, 4096).astype(np.intp)
            size = len(csvtext.rows_text([_fields(d[sample], seps[i])
                                          for i, d in enumerate(data)])) \
                * len(df) / sample.size
            announce(f"{path.name}: {len(df):,} rows, about {size / 1e6:,.0f} MB of CSV and "
                     f"{size / CSV_RATE:.0f} s to write (--format parquet is smaller and "
                     "faster)")
        if THREADS > 1 and len(spans) > 1:
            with ThreadPoolExecutor(THREADS) as pool:
                window = 4 * THREADS        # bounded read-ahead: memory stays flat
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
