"""The long tables' DataFrame builder (results/longtable.py own_frame)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from kinetostatics.results import longtable
from kinetostatics.results.longtable import own_frame


def _columns(n: int) -> dict[str, np.ndarray]:
    return {"position": np.arange(n, dtype=float), "Me": np.linspace(-1.0, 1.0, n)}


def test_own_frame_takes_the_arrays_as_they_are() -> None:
    cols = _columns(5)
    frame = own_frame(cols, 5)
    assert list(frame.columns) == ["position", "Me"]
    assert frame.index.equals(pd.RangeIndex(5))
    assert np.shares_memory(frame["Me"].to_numpy(), cols["Me"])
    frame.columns.name = "table"                # (each table's own labels)
    assert own_frame(_columns(5), 5).columns.name is None


def test_own_frame_without_pandas_private_names(monkeypatch: pytest.MonkeyPatch) -> None:
    """A pandas without RangeIndex._simple_new / Index._view: the public forms, the same
    frame."""
    want = own_frame(_columns(7), 7)

    def gone(*args, **kwargs):
        raise AttributeError("no such name in this pandas")
    monkeypatch.setattr(longtable, "_private_forms", gone)
    got = own_frame(_columns(7), 7)
    pd.testing.assert_frame_equal(got, want)
    assert got.index.equals(pd.RangeIndex(7))


@pytest.mark.parametrize("shape", [7, (6, 300_001), (3, 0)])
def test_a_table_block_starts_a_cache_line(shape, monkeypatch: pytest.MonkeyPatch) -> None:
    """A table's float block (``table_block``, either page setting) begins a cache line,
    with its shape, C order and writable (glibc gives an array this large the 16th byte
    of its page: the non-temporal stores of the table kernels then wrote part lines)."""
    for huge in (True, False):
        monkeypatch.setattr(longtable, "HUGE_PAGES", huge)
        a = longtable.table_block(shape)
        assert a.size == 0 or a.ctypes.data % longtable.LINE == 0
        assert a.shape == ((shape,) if isinstance(shape, int) else shape)
        assert a.dtype == np.float64 and a.flags.c_contiguous and a.flags.writeable
        a[...] = 2.5
        assert (a == 2.5).all()
