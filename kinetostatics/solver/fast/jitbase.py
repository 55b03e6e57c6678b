"""What every compiled kernel module shares: numba's decorators with the rules measured on
a prototype (``error_model="numpy"``: a division by zero gives an infinity, as numpy's,
counted; no ``fastmath``, the numbers stay IEEE; no ``prange``) and the count of values
that are not finite. Imported only after the cache folder is settled
(:func:`~kinetostatics.solver.fast.loader.kernels`)."""

from __future__ import annotations

import numpy as np
from numba import njit
from numba.core import types
from numba.core.registry import CPUDispatcher

jit = njit(cache=True, error_model="numpy", nogil=True, no_cfunc_wrapper=True)
# the helpers and a dyad's kernel body, inlined where they are called (a call that
# passes arrays costs atomic reference counts per row; inlined, they are pruned), a
# dyad's body into each kind's entry point with its kind a constant. Inlined by LLVM
# (``forceinline``: each helper typed and compiled once, marked alwaysinline), not by
# numba (``inline="always"``: numba copies the callee's IR into every call site, nested,
# a deep copy of its whole scope per block). Measured 2026-11-29, a cold cache: the
# four-bar's kernels 43.5 s of processor time with numba's inlining, 15.7 s with
# LLVM's; the kernels as fast (RRR motion 22-23 ns a row either way, reactions 17).
# Called from compiled code only: no wrapper for Python (each helper's wrapper was
# compiled to machine code for nothing: measured 2026-11-29, the composed kernels of the
# four-bar, slider-crank and shaper 20.5-21.0 s of processor time on an empty cache
# against 24.0-25.0 s with the wrappers; the same numbers, bit for bit)
_inlined = njit(error_model="numpy", nogil=True, forceinline=True, no_cpython_wrapper=True,
                no_cfunc_wrapper=True)


class PlainArgs(CPUDispatcher):
    """A helper's dispatcher typed on its arguments' plain types: numba types a constant
    passed from compiled code as a literal (``Literal[int](0)``) and compiles the callee
    once per value, and each of those again every helper it calls (``outer_param``: six
    signatures in the compiled-path tests). Typed on ``int64``, each helper compiles once
    for every constant; LLVM, inlining it (``forceinline``), folds the constant in its
    caller as before (measured 2026-11-30: the driver tables of the four-bar, the
    slider-crank and the shaper at 2e5 and 1e6 rows bit for bit, as fast). Entry points
    (:data:`jit`) have no C wrapper (``no_cfunc_wrapper``): they are called from Python
    or from compiled code, never through a C pointer."""

    def get_call_template(self, args, kws):
        return super().get_call_template(
            tuple(types.unliteral(a) for a in args),
            {k: types.unliteral(v) for k, v in kws.items()})


def body(func):
    """A helper of the kernels, compiled as :class:`PlainArgs` (see the comment above)."""
    dispatcher = _inlined(func)
    dispatcher.__class__ = PlainArgs
    return dispatcher


def jit_as(name: str):
    """:data:`jit` for a kernel a factory makes once per kind, named ``name`` first: numba
    names a cached function's index file by the function's qualified name and line, so
    a factory's kernels would share one index, and two processes compiling two kinds at
    once (xdist workers on a cold cache) may each save into the same data file, one
    kind's machine code then loading for the other's, without a warning (numba's
    ``IndexDataCacheFile.save`` picks the first free name from the index it read). Named
    apart, each kind has an index of its own."""
    def decorate(func):
        func.__name__ = func.__qualname__ = name
        return jit(func)
    return decorate


@body
def not_literal(code: int) -> int:
    """A kind's ``code`` (a constant of a factory's entry) as a plain integer to the
    helpers it is passed to: numba types a constant passed to a compiled helper as a
    literal and compiles the helper, and every helper it calls, once per value (each
    kind's entry compiled again every shared helper: dyad_row, the closures, the fused
    kernels' bodies). Passed as an integer, each helper is typed and lowered once a
    process for every kind; the constant is still the entry's, and LLVM, inlining the
    helpers into it, folds the other kinds' branches away as before."""
    return code | 0


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


# The fused kernels of solve_many (fused_kernels): tiles of 24 rows. Their scratch array
# (some 160 rows of a tile: every body's motion, the dyad's data, the loads, the
# reactions and the geometry) is then about 30 KB, within the processor's 32 KB
# first-level cache, against 40 KB at 32 rows and 80 KB at 64 (measured 2026-11-29, a
# tile per scene's rows, 1000 four-bars x 361 in one call, processor time: 10.0-10.2 ms
# at 32 rows against 11.1-11.7 at 64, 11.9-12.1 at 16, 10.3-10.9 at 24; measured again
# 2026-11-30 once a tile may hold several scenes' rows (no partly worked-out last tile
# of each scene), the kernel alone, alternating runs at a load of 8-9: 13.4-13.9 ms at
# 24 rows against 14.3-14.8 at 32, 14.3-15.4 at 28, 15.5-15.6 at 48; the same numbers,
# bit for bit). Measured again 2026-11-30 on the machine the bench now runs on (an Intel
# Xeon, 48 KB first-level cache a core, AVX-512), the kernel alone on solve_many's call
# (1000 four-bars x 361), one process, alternating, best / median of 21 at a load of 8-10:
# 14.5 / 15.5 ms at 16 rows against 15.9 / 16.5 at 24, 15.5 / 15.9 at 32, 21.3 / 22.5 at 8
# (and 15.3 / 16.0 against 16.7 / 17.5 at 24 in another run; 12 rows, not a multiple of
# the vectors' 4, 21.3); the same numbers, bit for bit
FUSED_TILE = 16


def scratch_for(width: int):
    """``scratch(rows)``: a tile's scratch array (``rows`` x ``width``, zeros: rows a
    kernel never writes go out as 0). ``width`` is a constant of the compiled helper (a
    tile's loops of a constant count vectorise; of a count known at run time they ran
    about 1.5x slower, measured 2026-11-29)."""
    @body
    def scratch(rows):
        return np.zeros((rows, width))
    return scratch


scratch = scratch_for(TILE)


@body
def tile_in(w, k, j0, nt):
    """Columns ``j0`` to ``j0 + nt`` of ``k``'s rows into ``w[:, :nt]`` (each row a
    loop of its own over 1-d views: it vectorises)."""
    for f in range(w.shape[0]):
        src, dst = k[f, j0:j0 + nt], w[f]
        for t in range(nt):
            dst[t] = src[t]


def tile_out_for(add: bool):
    """``tile_out(k, w, j0, nt)``: ``w[:, :nt]`` into columns ``j0`` to ``j0 + nt`` of
    ``k``'s rows, or added to them (``add``, a constant of the compiled helper)."""
    @body
    def tile_out(k, w, j0, nt):
        for f in range(w.shape[0]):
            src, dst = w[f], k[f, j0:j0 + nt]
            for t in range(nt):
                if add:
                    dst[t] += src[t]
                else:
                    dst[t] = src[t]
    return tile_out


tile_out, tile_add = tile_out_for(False), tile_out_for(True)


def tile_rows_for(width: int):
    """``tile_rows(gs, own, t0, hi)``: the rows of the tile that starts at row ``t0`` (of
    rows up to ``hi``): at most ``width``, all of one scene (``own[i * gs]``: row ``i``'s
    scene in a stack, ``gs`` 0 for one scene)."""
    @body
    def tile_rows(gs, own, t0, hi):
        nt = min(width, hi - t0)
        if gs != 0:
            s = own[t0]
            while own[t0 + nt - 1] != s:
                nt -= 1
        return nt
    return tile_rows


tile_rows = tile_rows_for(TILE)


@body
def tile_geometry(wg, g, gs, own, t0, last):
    """A kernel's geometry into its tile (:func:`tile_rows`: one scene's rows): column
    ``own[t0 * gs]`` of ``g`` (a column per scene of a stack; one for one scene) in each
    of the tile's columns, unless the tile holds it already (``last``: the column filled
    last, -1 for none; returned for the next tile). A stack's numbers stay in a table of
    a column per scene (copied per row they cost some 100 numbers a row read from
    arrays over the run: measured 2026-11-29, the RRR motion 107-226 ns a row there,
    23 with one scene's)."""
    a = own[t0 * gs]
    if a != last:
        # (a slice filled: vectorised; a loop over the tile storing one value is not,
        # LLVM's remark "value that could not be identified as reduction is used outside
        # the loop": measured 2026-11-29, 28 rows for 1000 scenes 0.13 ms against 0.6-1.3)
        for f in range(wg.shape[0]):
            wg[f, :] = g[f, a]
    return a


@body
def tile_next(wg, g, gs, own, t0, hi, last):
    """``(nt, last)`` of the tile that starts at row ``t0`` (of rows up to ``hi``): its
    count of rows (:func:`tile_rows`: one scene's) and the scene whose geometry ``wg``
    then holds, put there unless ``last`` is it (:func:`tile_geometry`)."""
    nt = tile_rows(gs, own, t0, hi)
    return nt, tile_geometry(wg, g, gs, own, t0, last)
