"""What every compiled kernel module shares: numba's decorators with the rules measured on
a prototype (``error_model="numpy"``: a division by zero gives an infinity, as numpy's,
counted; no ``fastmath``, the numbers stay IEEE; no ``prange``) and the count of values
that are not finite. Imported only after the cache folder is settled
(:func:`~kinetostatics.solver.fast.loader.kernels`)."""

from __future__ import annotations

import numpy as np
from numba import njit

jit = njit(cache=True, error_model="numpy", nogil=True)
# the helpers and a dyad's kernel body, inlined where they are called (a call that
# passes arrays costs atomic reference counts per row; inlined, they are pruned), a
# dyad's body into each kind's entry point with its kind a constant
body = njit(error_model="numpy", nogil=True, inline="always")


@body
def nonfinite(values) -> int:
    """1 when a value of the tuple ``values`` is not finite (v * 0 is 0 for a finite v,
    NaN otherwise). Inlined, and without branches: a loop that calls it still vectorises."""
    z = 0.0
    for v in values:
        z += v * 0.0
    return 0 if z == 0.0 else 1


@body
def fmax(a, b):
    """``max(a, b)`` as numba's (``a`` unless ``b > a``: a NaN ``a`` kept) without a
    branch (numba's builtin ``max`` of floats stops LLVM vectorising the loop)."""
    return b if b > a else a


@body
def fmin(a, b):
    """``min(a, b)`` as numba's (``a`` unless ``b < a``), without a branch."""
    return b if b < a else a


# Rows per tile: each kernel copies a tile of its input rows into one scratch array, works
# it out in a loop over the tile's rows that reads and writes that array only (LLVM then
# proves its rows apart and vectorises the loop: measured 2026-11-29, the RRR motion
# 10 ns a row against 48 ns for the one loop over ~40 arrays), and copies the results out
TILE = 64


@body
def scratch(rows):
    """A tile's scratch array (``rows`` x :data:`TILE`, zeros: rows a kernel never
    writes go out as 0)."""
    return np.zeros((rows, TILE))


@body
def tile_in(w, k, j0, nt):
    """Columns ``j0`` to ``j0 + nt`` of ``k``'s rows into ``w[:, :nt]`` (each row a
    loop of its own over 1-d views: it vectorises)."""
    for f in range(w.shape[0]):
        src, dst = k[f, j0:j0 + nt], w[f]
        for t in range(nt):
            dst[t] = src[t]


@body
def tile_out(k, w, j0, nt):
    """``w[:, :nt]`` into columns ``j0`` to ``j0 + nt`` of ``k``'s rows."""
    for f in range(w.shape[0]):
        src, dst = w[f], k[f, j0:j0 + nt]
        for t in range(nt):
            dst[t] = src[t]


@body
def tile_add(k, w, j0, nt):
    """``w[:, :nt]`` added to columns ``j0`` to ``j0 + nt`` of ``k``'s rows."""
    for f in range(w.shape[0]):
        src, dst = w[f], k[f, j0:j0 + nt]
        for t in range(nt):
            dst[t] += src[t]


@body
def tile_geometry(wg, g, gs, t0, nt, first):
    """A kernel's geometry into its tile: once (``first``) when it is the same for every
    row (``gs`` 0), else each tile's rows."""
    if gs == 0:
        if first:
            for f in range(wg.shape[0]):
                v = g[f, 0]
                for t in range(wg.shape[1]):
                    wg[f, t] = v
    else:
        tile_in(wg, g, t0, nt)
