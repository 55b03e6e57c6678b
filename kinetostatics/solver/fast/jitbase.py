"""What every compiled kernel module shares: numba's decorators with the rules measured on
a prototype (``error_model="numpy"``: a division by zero gives an infinity, as numpy's,
counted; no ``fastmath``, the numbers stay IEEE; no ``prange``) and the count of values
that are not finite. Imported only after the cache folder is settled
(:func:`~kinetostatics.solver.fast.loader.kernels`)."""

from __future__ import annotations

from numba import njit

jit = njit(cache=True, error_model="numpy", nogil=True)
# the helpers and a dyad's kernel body, inlined where they are called (a call that
# passes arrays costs atomic reference counts per row; inlined, they are pruned), a
# dyad's body into each kind's entry point with its kind a constant
body = njit(error_model="numpy", nogil=True, inline="always")


@jit
def nonfinite(*values) -> int:
    """1 when a value is not finite (v * 0 is 0 for a finite v, NaN otherwise)."""
    z = 0.0
    for v in values:
        z += v * 0.0
    return 0 if z == 0.0 else 1
