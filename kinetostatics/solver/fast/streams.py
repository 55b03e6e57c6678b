"""Stores that go past the caches (non-temporal), for kernels that write result tables
far larger than the caches, each byte once.

An ordinary store to memory not in the caches first reads its line of 64 bytes from
memory (to own it), then writes it back: twice the traffic of the bytes written. A
non-temporal store sends the line to memory without reading it (the stores of a line
gathered in a write-combining buffer), as ``memset`` writes large blocks. Measured
2026-11-29 on the 2-core machine (AMD EPYC, numba's LLVM: ``movntsd``), the four-bar's
``kinematics`` columns at 1e6 positions (432 MB, one output column per loop), processor
time: 0.026 s against 0.047 s with ordinary stores in pages already had (numpy's
``fill`` 0.017 s), 0.066 s against 0.085 s in fresh pages (``fill`` 0.056-0.067 s).
With six output columns a loop the non-temporal stores gained nothing (0.047 s): the
write-combining buffers are few, so a loop of these stores writes one column.

Non-temporal stores are not ordered with the processor's other stores: a kernel that
made them calls :func:`drain` before it returns (another thread may read the table
next). Where the processor has no such store, LLVM makes an ordinary one: the same
numbers either way. A double is stored as its 64 bits (``movnti`` from a general
register, SSE2, every x86-64): LLVM gives a ``double`` store marked non-temporal
``movntsd`` where the processor has it (AMD's SSE4a) and an ordinary ``vmovsd`` where
not, so on an Intel Xeon (2026-12-01, 2 MB L2, AVX-512) the table kernels' writes
were ordinary stores but for the negated columns (their sign flipped in an integer
register: ``movnti``), 36 non-temporal stores in the four-bar kernel's code, the
point columns' none. Imported only after the cache folder is settled
(:func:`~kinetostatics.solver.fast.loader.kernels`).
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from .jitbase import body

_I64 = ir.IntType(64)


@intrinsic
def stream(typingctx, array, index, value):
    """``array[index] = value`` (a 1-d array, ``0 <= index < len(array)``, unchecked) by a
    non-temporal store."""
    sig = types.void(array, index, value)

    def codegen(context, builder, signature, args):
        kind = signature.args[0]
        where = context.make_array(kind)(context, builder, args[0])
        ptr = cgutils.get_item_pointer(context, builder, kind, where, [args[1]],
                                       wraparound=False)
        value = context.cast(builder, args[2], signature.args[2], kind.dtype)
        if kind.dtype == types.float64:     # (stored as its bits: movnti, see above)
            value, ptr = builder.bitcast(value, _I64), builder.bitcast(ptr, _I64.as_pointer())
        store = builder.store(value, ptr)
        store.set_metadata("nontemporal", builder.module.add_metadata([ir.IntType(32)(1)]))
        return context.get_dummy_value()

    return sig, codegen


@intrinsic
def drain(typingctx):
    """A full memory fence (``mfence`` on x86): the non-temporal stores made before it
    are in memory, in order with every other store, before any later load or store."""
    sig = types.void()

    def codegen(context, builder, signature, args):
        builder.fence("seq_cst")
        return context.get_dummy_value()

    return sig, codegen


@body
def stream_column(values, m, negate, out):
    """``out[t] = values[t]`` (``-values[t]`` where ``negate``) for the first ``m`` rows,
    by non-temporal stores (1-d arrays)."""
    if negate:
        for t in range(m):
            stream(out, t, -values[t])
    else:
        for t in range(m):
            stream(out, t, values[t])


__all__ = ["drain", "stream", "stream_column"]
