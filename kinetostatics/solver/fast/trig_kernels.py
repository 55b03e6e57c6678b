"""The compiled path's cos and sin of an angle (numba): a branch-free polynomial kernel
that LLVM vectorises in a loop (four rows at a time with AVX2), the C library's outside
its range.

Range reduction by Cody and Waite: the angle less the nearest multiple q of pi/4 (q even:
|r| <= pi/4), pi/4 in three parts (Cephes' ``sin.c``, S. L. Moshier: DP1, DP2, DP3; the
first two's products with q are exact for |q| < 2^29), with the rounding error of the
reduced angle kept as a tail (two-sums); then fdlibm's kernels on [-pi/4, pi/4]
(``k_sin.c``, ``k_cos.c``, Sun Microsystems 1993: their minimax coefficients, the tail as
their ``y``, cos as w + (((1 - w) - z/2) + ...) with w = 1 - z/2) and the quadrant's
signs.

Measured 2026-11-30 against numpy's cos and sin (glibc's, correctly rounded in
practice): at most 1 ULP over a dense sweep of +-20 rad (2e6 angles) and 2e6 random
angles each within +-400 rad and +-:data:`LIMIT`, 7.2-7.3 % of the angles with a cos or
a sin 1 ULP off; tiny angles (down to the subnormals: sin x = x within 1 ULP, cos x = 1,
sin(-0) = -0); at the doubles nearest the multiples of pi/2 up to :data:`LIMIT`, where
the value is near 0, an absolute error within 2.7e-25 (the three parts of pi/4). Some 3.6
ns a row (8 until 2026-11-30, its floors then integers: :func:`sincos_poly`) against 27
for the C library's cos and sin and 37-46 for numpy's (1e6 angles, processor time);
tests/kinetostatics/solver/test_fast_trig.py.
"""

from __future__ import annotations

import math

import numpy as np

from .jitbase import body, jit

# pi/4 in three parts (Cephes sin.c): DP1 + DP2 + DP3 = pi/4 to about 2^-170
DP1 = 7.85398125648498535156e-1
DP2 = 3.77489470793079817668e-8
DP3 = 2.69515142907905952645e-15
FOPI = 1.27323954473516268615       # 4/pi
# the angles the polynomial kernel takes (|x| <= LIMIT rad, 2^20: some 1.7e5 turns);
# beyond, and NaN and the infinities, the C library's
LIMIT = 1048576.0


@body
def sincos_poly(x):
    """``(cos x, sin x)`` by the polynomial kernel (no branch: a loop over rows that calls
    it vectorises), for |x| <= :data:`LIMIT`; beyond it not meant to be read
    (:func:`sincos_rows` takes the C library's there)."""
    # (np.floor: a double, one vroundpd for four rows; math.floor is an int64 in numba,
    # each lane converted to an integer and back one at a time, AVX2 having no vector
    # conversion of 64-bit integers: measured 2026-11-30, turn_rows on 1e6 angles 7.9-8.2
    # -> 3.6 ns a row; the same doubles, bit for bit, over 8.4e6 angles within LIMIT and
    # its edges; beyond LIMIT the values are libm's, written over these)
    q = np.floor(x * FOPI)
    q = q + (q - 2.0 * np.floor(q * 0.5))          # the even neighbour above an odd q
    k = q * 0.5 - 4.0 * np.floor(q * 0.125)       # the quadrant, 0 to 3
    # x - q pi/4 = r + e (Cody-Waite; q DP1 and q DP2 exact, x - q DP1 too): r rounded,
    # e what r's roundings lost (two-sums), the kernels' tail as fdlibm's y[1]
    a = x - q * DP1
    b = q * DP2
    t = a - b
    e1 = (a - t) - b
    d = q * DP3
    r = t - d
    e = ((t - r) - d) + e1
    z = r * r
    # fdlibm k_sin.c: r + (e + r^3 (S1 + z (S2 + ... + z S6))) (sin(r + e) ~ sin r + e)
    ps = r + (e + z * r * (-1.66666666666666324348e-01 + z * (8.33333333332248946124e-03 + z * (
        -1.98412698298579493134e-04 + z * (2.75573137070700676789e-06 + z * (
            -2.50507602534068634195e-08 + z * 1.58969099521155010221e-10))))))
    ps = r if r == 0.0 else ps                     # (sin(-0) = -0)
    # fdlibm k_cos.c: 1 - z/2 + (z^2 (C1 + z (C2 + ... + z C6)) - r e), its last bits kept
    hz = 0.5 * z
    w = 1.0 - hz
    pc = w + (((1.0 - w) - hz) + (z * (z * (4.16666666666666019037e-02 + z * (
        -1.38888888888741095749e-03 + z * (2.48015872894767294178e-05 + z * (
            -2.75573143513906633035e-07 + z * (2.08757232129817482790e-09
                                               + z * -1.13596475577881948265e-11))))))
                                     - r * e))
    # x = q pi/4 + r, k = q/2 mod 4: sin x = sin r, cos r, -sin r, -cos r; cos x likewise
    odd = k == 1.0 or k == 3.0
    s = pc if odd else ps
    c = ps if odd else pc
    s = -s if k >= 2.0 else s
    c = -c if (k == 1.0 or k == 2.0) else c
    return c, s


@body
def sincos_rows(x, cs, sn):
    """The cos and sin of the angles ``x`` (a 1-d array) into ``cs``, ``sn`` (1-d arrays
    of as many values): :func:`sincos_poly` in one loop (vectorised), then the C
    library's for the angles beyond :data:`LIMIT` (NaN and the infinities too), if any,
    in a second."""
    far = 0
    for t in range(x.shape[0]):
        a = x[t]
        cs[t], sn[t] = sincos_poly(a)
        far += 0 if abs(a) <= LIMIT else 1
    if far:
        for t in range(x.shape[0]):
            a = x[t]
            if not abs(a) <= LIMIT:
                cs[t], sn[t] = math.cos(a), math.sin(a)


@jit
def turn_rows(angles, cs, sn):
    """The compiled path's cos and sin of ``angles`` into ``cs``, ``sn``
    (:func:`sincos_rows`): every kernel that turns a crank's angle into its cos and sin
    works them out so, and the composing code calls this where it hands the kernels
    a crank's cos and sin (the same doubles a row either way)."""
    sincos_rows(angles, cs, sn)


@jit
def libm_rows(angles, cs, sn):
    """The C library's cos and sin of ``angles`` into ``cs``, ``sn`` (LLVM fuses the two
    calls of a row into one ``sincos``): what
    :func:`~kinetostatics.solver.fast.solve.kernel_trig` holds against numpy's (the
    dead-point screen's probes take them where they are numpy's)."""
    for i in range(angles.shape[0]):
        a = angles[i]
        cs[i], sn[i] = math.cos(a), math.sin(a)


def turned(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The compiled path's cos and sin of ``angles`` (:func:`turn_rows`, given them
    read-only, as a driver's: one compiled signature), new arrays."""
    cs, sn = np.empty(angles.size), np.empty(angles.size)
    a = angles.view()
    a.flags.writeable = False
    turn_rows(a, cs, sn)
    return cs, sn


__all__ = ["LIMIT", "libm_rows", "sincos_poly", "sincos_rows", "turn_rows", "turned"]
