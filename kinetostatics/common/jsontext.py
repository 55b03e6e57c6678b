"""numpy values as plain JSON: the one home of that conversion (result dicts, summaries,
studies, ``--json`` output)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def json_default(x: Any) -> Any:
    """numpy scalars and arrays as plain JSON values: the ``default`` of
    :func:`json.dumps` for a result dict holding them."""
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(f"{type(x).__name__} is not JSON serialisable")


def plain(obj: Any, finite: bool = False) -> Any:
    """``obj`` with every numpy scalar as the Python number it holds, every array as a
    list, every dict's keys as text and every tuple as a list, all the way down;
    ``finite``: a float that is not finite becomes None (JSON has no NaN)."""
    if isinstance(obj, dict):
        return {str(k): plain(v, finite) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [plain(v, finite) for v in obj]
    if isinstance(obj, np.ndarray):
        return plain(obj.tolist(), finite)
    if isinstance(obj, np.generic):
        obj = obj.item()
    if finite and isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj
