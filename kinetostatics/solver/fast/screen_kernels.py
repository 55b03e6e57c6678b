"""The dead-point screen's scan in one compiled pass: the intervals next to a local
minimum of the closeness to a dead centre (``deadpoints._candidates`` on the numpy
arithmetic, a dozen passes and gathers over the rows below the screen).

Only comparisons and one product by a constant are made, each the numpy scan's own
(IEEE doubles, no fastmath): the same intervals, in the same order. Imported only once
the kernels are loaded (:func:`~kinetostatics.solver.fast.loader.kernels`: numba's cache
folder settled first).
"""

from __future__ import annotations

import numpy as np

from .jitbase import jit

# a real dip is below a neighbour by more than rounding jitter (deadpoints._candidates)
SHRINK = 1.0 - 1e-9


@jit
def scan_candidates(m2, starts, counts, screen2, out):
    """The intervals i (rows i, i + 1) next to a local minimum of m over each segment of
    rows alone (segment s: ``counts[s]`` rows from ``starts[s]``), in increasing order,
    written to ``out`` (at least ``m2.size`` long); returns how many.

    A row r below the screen (m^2 < ``screen2``: NaN never is) is a dip when
    (m_r < m_left (1 - 1e-9) and m_r <= m_right) or (m_r <= m_left and
    m_r < m_right (1 - 1e-9)), a segment's end having no neighbour beyond it (+inf); the
    intervals (r - 1, r) unless r starts its segment and (r, r + 1) unless it ends it,
    each once."""
    inf = np.inf
    k = 0
    prev = -1           # (the last interval written: the intervals never decrease)
    for s in range(starts.size):
        a = starts[s]
        b = a + counts[s]
        for r in range(a, b):
            v = m2[r]
            if not v < screen2:
                continue
            left = m2[r - 1] if r > a else inf
            right = m2[r + 1] if r + 1 < b else inf
            if not (((v < left * SHRINK) and (v <= right))
                    or ((v <= left) and (v < right * SHRINK))):
                continue
            if r > a and r - 1 != prev:
                out[k] = r - 1
                k += 1
                prev = r - 1
            if r + 1 < b and r != prev:
                out[k] = r
                k += 1
                prev = r
    return k
