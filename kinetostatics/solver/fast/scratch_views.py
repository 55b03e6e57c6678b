"""Where a fused kernel's tile values lie in its one scratch array (a row of the tile per
value): views at fixed offsets of that array, shared by the fused kernels
(:mod:`~kinetostatics.solver.fast.fused_kernels`,
:mod:`~kinetostatics.solver.fast.guide_kernels`). Fixed offsets of one array let LLVM
prove the rows apart and vectorise the rows' loops (``jitbase.TILE``). Inlined by LLVM
(``body``); the kernels module's rules hold here.
"""

from __future__ import annotations

from .jitbase import body
from .layout import DYAD_GEOMETRY, DYAD_OUT
from .layout import REACTIONS as REACTION_ROWS

LOAD_ROWS = 15          # a crank and one dyad's load resultants: five blocks of three rows
DYAD_ROWS = DYAD_OUT + REACTION_ROWS + DYAD_GEOMETRY    # a dyad's data, reactions, geometry


@body
def resultant_views(w_, b):
    """The load resultants (``Fx, Fy, M`` over the tile) from row ``b`` of ``w_``
    (:data:`LOAD_ROWS` rows): the crank's, the dyad's first body's and its second's, then
    what the dyad's outer joints load their known bodies with (seed 002 s. 2.1-2.3)."""
    return (w_[b:b + 3], w_[b + 3:b + 6], w_[b + 6:b + 9], w_[b + 9:b + 12],
            w_[b + 12:b + 15])


@body
def dyad_views(w_, b):
    """A dyad's rows from row ``b`` of ``w_`` (:data:`DYAD_ROWS` rows): its solved data,
    its reactions and its geometry (``layout.DYAD_OUT``, ``REACTIONS``,
    ``DYAD_GEOMETRY``), and the row after them."""
    e = b + DYAD_OUT
    f = e + REACTION_ROWS
    return w_[b:e], w_[e:f], w_[f:f + DYAD_GEOMETRY], f + DYAD_GEOMETRY


@body
def load_views(wl, gl):
    """The first three bodies' load geometry (``gl``: a table per body, its rows) in
    consecutive rows of ``wl``, a view each (the crank's, the dyad's first body's, its
    second's)."""
    n0, n1 = gl[0].shape[0], gl[1].shape[0]
    return wl[:n0], wl[n0:n0 + n1], wl[n0 + n1:n0 + n1 + gl[2].shape[0]]


__all__ = ["DYAD_ROWS", "LOAD_ROWS", "dyad_views", "load_views", "resultant_views"]
