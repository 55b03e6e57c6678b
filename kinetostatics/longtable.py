"""Long result tables, defined block by block: one block of rows per joint (point, body),
one row per position in each block.

A :class:`LongTable` knows its blocks' names and how to compute any chunk of positions
of a block from the solver's arrays. The same definition gives the pandas table
(:meth:`LongTable.frame`: every column allocated once and filled in place, the name
columns categorical) and the CSV file written chunk by chunk without the table ever
being held (:func:`kinetostatics.output.write_long_csv`), so both give the same values.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd

import numpy as np

CHUNK = 32_768          # positions computed at a time: the temporaries stay in the CPU caches


def categorical(names: list[str], n: int) -> pd.Categorical:
    """A categorical column with ``names[i]`` on the ``n`` rows of block ``i``."""
    import pandas as pd
    cats = list(dict.fromkeys(names))
    kind = np.int8 if len(cats) < 127 else np.int16 if len(cats) < 32767 else np.int32
    codes = np.array([cats.index(x) for x in names], dtype=kind)
    return pd.Categorical.from_codes(np.repeat(codes, n), categories=cats)


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
    """

    positions: np.ndarray
    labels: dict[str, list[str]]
    floats: tuple[str, ...]
    chunk: Callable[[int, slice], dict]

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
        """The table as a DataFrame: each float column allocated once, filled in place."""
        import pandas as pd
        n, k = self.n, self.blocks
        out = {c: np.empty(n * k) for c in self.floats}
        for i, part in self.parts():
            rows = slice(i * n + part.start, i * n + part.stop)
            for c, v in self.chunk(i, part).items():
                out[c][rows] = v
        cols = {"position": np.tile(np.asarray(self.positions, dtype=float), k)}
        cols.update({c: categorical(names, n) for c, names in self.labels.items()})
        cols.update(out)
        return pd.DataFrame(cols, copy=False)
