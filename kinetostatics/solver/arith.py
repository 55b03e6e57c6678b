"""Arithmetic that skips exact scalar zeros and ones.

Coordinates are kept as separate x and y arrays over positions, but many of them are
scalars: the ground's, a fixed pivot's, a constant speed's, a local coordinate that is
0. Multiplying or adding a full array by such a scalar is a wasted pass over memory;
these helpers return the other operand instead. Results are bit-identical to the plain
expressions (x + 0.0 == x, x * 1.0 == x, x * 0.0 == 0.0 for finite x); a NaN or an
infinity multiplied by an exact zero stays NaN, so the solver's final check sees it.
(One exception, :func:`rotate` of the zero vector: its cos and sin are a body's, which
the final check sees themselves.)
"""

from __future__ import annotations

import math
import weakref

import numpy as np

from .trap import TRAPPED


def zero(x) -> bool:
    """True for a Python or numpy scalar equal to 0 (never for an array)."""
    t = type(x)
    if t is float:
        return x == 0.0
    if t is np.ndarray:
        return False
    if t is int:
        return x == 0
    return isinstance(x, float | int) and x == 0


_FINITE: weakref.WeakValueDictionary = weakref.WeakValueDictionary()


_REMEMBER = 4096        # arrays at least this long are remembered once found finite
_sum = np.add.reduce


def _finite(x) -> bool:
    """True when x (a scalar or an array) holds no NaN or infinity; each long array is
    summed once (remembered by identity while it lives: below ``_REMEMBER`` values a
    second sum costs less than remembering)."""
    if type(x) is float:
        return math.isfinite(x)
    if not isinstance(x, np.ndarray):
        return bool(np.isfinite(x))
    if x.size < _REMEMBER:
        return math.isfinite(_sum(x, axis=None))
    if _FINITE.get(id(x)) is x:
        return True
    ok = math.isfinite(_sum(x, axis=None))
    if ok:
        _FINITE[id(x)] = x
    return ok


_ARRAY = np.ndarray
_trapped = TRAPPED.get


def _times_zero(other, a, b):
    """a * b where the operand other than ``other`` is an exact zero (0.0 without a look
    at ``other`` inside a trapped solve: a NaN there would have touched the trap,
    :mod:`~kinetostatics.solver.trap`)."""
    if TRAPPED.get() or _finite(other):
        return 0.0
    with np.errstate(invalid="ignore"):
        return a * b


# The three operations below are the solver's hottest Python: each dispatches on the
# exact types first (an array with an array, an array with a Python number), the cases
# that make up nearly every call, and leaves the rest to the general rules of zero().

def mul(a, b):
    """a * b; an exact scalar zero gives 0.0 without a pass over the other operand, unless
    that operand holds a NaN or an infinity (0 * NaN is NaN: never hidden)."""
    ta, tb = type(a), type(b)
    if ta is _ARRAY:
        if tb is _ARRAY:
            return a * b
        if tb is float or tb is int:
            if b == 0:
                # (inside a trapped solve: 0.0 at once, _times_zero's first test)
                return 0.0 if _trapped() else _times_zero(a, a, b)
            return a if b == 1 else a * b
    elif tb is _ARRAY and (ta is float or ta is int):
        if a == 0:
            return 0.0 if _trapped() else _times_zero(b, a, b)
        return b if a == 1 else a * b
    elif ta is float and tb is float:       # (the general rules below, for two floats)
        if a == 0.0 or b == 0.0:
            o = b if a == 0.0 else a
            # (a finite other: 0.0, _times_zero's answer, without its call)
            return 0.0 if math.isfinite(o) else _times_zero(o, a, b)
        return b if a == 1.0 else a if b == 1.0 else a * b
    if zero(a) or zero(b):
        return _times_zero(b if zero(a) else a, a, b)
    if isinstance(a, float | int) and a == 1:
        return b
    if isinstance(b, float | int) and b == 1:
        return a
    return a * b


def add(a, b):
    """a + b."""
    ta, tb = type(a), type(b)
    if ta is _ARRAY:
        if tb is _ARRAY:
            return a + b
        if tb is float or tb is int:
            return a if b == 0 else a + b
    elif tb is _ARRAY and (ta is float or ta is int):
        return b if a == 0 else a + b
    elif ta is float and tb is float:       # (the general rules below, for two floats)
        return a if b == 0.0 else b if a == 0.0 else a + b
    if zero(b):
        return a
    if zero(a):
        return b
    return a + b


def sub(a, b):
    """a - b."""
    ta, tb = type(a), type(b)
    if ta is _ARRAY:
        if tb is _ARRAY:
            return a - b
        if tb is float or tb is int:
            return a if b == 0 else a - b
    elif tb is _ARRAY and (ta is float or ta is int):
        return -b if a == 0 else a - b
    elif ta is float and tb is float:       # (the general rules below, for two floats)
        return a if b == 0.0 else -b if a == 0.0 else a - b
    if zero(b):
        return a
    if zero(a):
        return -b
    return a - b


def less(a, b):
    """a - b with the bits of the plain expression, signed zeros and NaN included (unlike
    :func:`sub`, whose a - 0 is a for b = -0.0 too): an array less the number +0.0 is
    the array itself (x - (+0.0) is x for every double), without a pass."""
    if type(a) is _ARRAY and type(b) is float and b == 0.0 and math.copysign(1.0, b) > 0:
        return a
    return a - b


def squares(x, y):
    """x * x + y * y with the bits of the plain expression: the square of a number 0.0
    (either sign) is +0.0, which leaves the other square (never -0.0) as it is, so an
    array with such a number costs one pass, not three."""
    if type(x) is _ARRAY and type(y) is float and y == 0.0:
        return x * x
    if type(y) is _ARRAY and type(x) is float and x == 0.0:
        return y * y
    return x * x + y * y


_F64 = np.dtype(np.float64)


def fresh(r, *inputs) -> bool:
    """True when ``r`` is a float array just made from ``inputs`` (not one of them): a
    temporary its maker alone holds, which the next operation may write its result into.

    (Called some 90 times a solve of a slider-crank: the identities looked at first,
    by a plain loop, and the dtype compared by identity before equality; measured
    2026-12-01, 2.3 us a call before, 0.4-0.6 us after, with all() over a generator
    and ``dtype == np.float64``, which makes a dtype of the type each time.)"""
    if type(r) is not _ARRAY:
        return False
    for x in inputs:
        if r is x:
            return False
    dt = r.dtype
    return (dt is _F64 or dt == _F64) and r.flags.writeable


def into(op, plain, a, b, fa: bool, fb: bool):
    """``plain(a, b)`` (:func:`add` or :func:`sub`, whose ufunc is ``op``) written into
    ``a`` (``fa``: a fresh temporary, :func:`fresh`) or else ``b`` (``fb``) where
    ``plain`` would make a new array: the same operation on the same operands in the
    same order, so the same bits, one fresh array and one pass of page faults fewer."""
    ta, tb = type(a), type(b)
    if ta is _ARRAY and tb is _ARRAY:
        if a.shape == b.shape and (fa or fb):
            return op(a, b, out=a if fa else b)
    elif ta is _ARRAY and fa and (tb is float or tb is int) and b != 0:
        return op(a, b, out=a)
    elif tb is _ARRAY and fb and (ta is float or ta is int) and a != 0:
        return op(a, b, out=b)
    return plain(a, b)


def mul_add(a, b, c, d, den=None):
    """a b + c d, that is add(mul(a, b), mul(c, d)), the sum written into a product's
    array (:func:`into`); with ``den``, that sum / den (:func:`over`)."""
    p, q = mul(a, b), mul(c, d)
    return _joined(np.add, add, p, q, a, b, c, d, den)


def mul_sub(a, b, c, d, den=None):
    """a b - c d, that is sub(mul(a, b), mul(c, d)), the difference written into a
    product's array (:func:`into`); with ``den``, that difference / den (:func:`over`)."""
    p, q = mul(a, b), mul(c, d)
    return _joined(np.subtract, sub, p, q, a, b, c, d, den)


def _joined(op, plain, p, q, a, b, c, d, den):
    """``over(into(op, plain, p, q, fresh(p, a, b), fresh(q, c, d)), den, a, b, c, d)``
    of :func:`mul_add` and :func:`mul_sub` (p = a b, q = c d), the same operations on
    the same operands: q's freshness looked at only where into reads it (p not
    fresh), and no call of :func:`over` without ``den``. (Measured 2026-12-01: some 25
    of these a slider-crank's solve, 40 a shaper's; each call's Python work, not its
    passes, is what a 2001-row solve spends.)"""
    if type(p) is _ARRAY and type(q) is _ARRAY:
        if p.shape == q.shape:
            if fresh(p, a, b):
                r = op(p, q, out=p)
            elif fresh(q, c, d):
                r = op(p, q, out=q)
            else:
                r = op(p, q)
        else:
            r = op(p, q)
    elif type(q) is float and q == 0.0:
        r = p       # (plain(p, 0.0) is p, whatever p: a product the arithmetic skipped)
    else:
        r = into(op, plain, p, q, fresh(p, a, b), fresh(q, c, d))
    return r if den is None else over(r, den, a, b, c, d)


def over(r, den, *inputs):
    """r / den (r itself for ``den`` None), written into r when it is a fresh array made
    from ``inputs`` (:func:`fresh`) and den an array of its shape or a Python number: the
    same quotients."""
    if den is None:
        return r
    td = type(den)
    if fresh(r, *inputs) and (td is float or td is int or td is _ARRAY and den.shape == r.shape):
        return np.true_divide(r, den, out=r)
    return r / den


def sub_mul(a, s, x):
    """a - s x; with a an exact zero, s a Python number and x an array, (-s) x: one pass
    instead of two, the same numbers (-(s x) is (-s) x exactly, signed zeros too); else
    the difference written into the product's array (:func:`into`)."""
    if type(x) is _ARRAY and (type(s) is float or type(s) is int) and s != 0 and zero(a):
        return mul(-s, x)
    t = mul(s, x)
    return _onto(np.subtract, sub, a, t, s, x)


def add_mul(a, s, x):
    """a + s x, that is add(a, mul(s, x)), the sum written into the product's array."""
    t = mul(s, x)
    return _onto(np.add, add, a, t, s, x)


def _onto(op, plain, a, t, s, x):
    """``into(op, plain, a, t, False, fresh(t, s, x))`` of :func:`add_mul` and
    :func:`sub_mul` (t = s x), the same operations: two arrays of one shape at once,
    and an exact scalar zero t (a product the arithmetic skipped) gives ``a`` as
    ``plain`` does, without the calls. (Measured 2026-12-01: some 40 a slider-crank's
    solve, 60 a shaper's.)"""
    tt = type(t)
    if tt is _ARRAY:
        if type(a) is _ARRAY:
            if a.shape == t.shape and fresh(t, s, x):
                return op(a, t, out=t)
            return op(a, t)
    elif tt is float and t == 0.0:
        return a
    return into(op, plain, a, t, False, fresh(t, s, x))


def cross(ax, ay, bx, by):
    """z component of (ax, ay) x (bx, by)."""
    return mul_sub(ax, by, ay, bx)


def rotate(c, s, lx: float, ly: float):
    """R(theta) (lx, ly) with c = cos theta, s = sin theta; lx, ly are scalars.

    The zero vector gives (0.0, 0.0) without a look at c and s: in the solver they are
    always a body's cos and sin, which its final check reads (a NaN there is refused
    all the same)."""
    if type(lx) is float and type(ly) is float and lx == 0.0 and ly == 0.0:
        return 0.0, 0.0
    if ly == 0.0 if type(ly) is float else zero(ly):
        return mul(c, lx), mul(s, lx)
    if lx == 0.0 if type(lx) is float else zero(lx):
        return mul(-ly, s), mul(c, ly)
    return c * lx - s * ly, s * lx + c * ly


def iadd(acc, x, sign: float = 1.0) -> None:
    """acc += sign * x, in place (acc: an owned float array; x: array or scalar)."""
    if type(x) is not _ARRAY and (x == 0.0 if type(x) is float else zero(x)):
        return
    if sign > 0:
        np.add(acc, x, out=acc)
    else:
        np.subtract(acc, x, out=acc)


def icross(acc, rx, ry, fx, fy, tmp, sign: float = 1.0) -> None:
    """acc += sign * (rx fy - ry fx), in place, with ``tmp`` as scratch (no allocation)."""
    if type(rx) is _ARRAY and type(fy) is _ARRAY or not (zero(rx) or zero(fy)):
        np.multiply(rx, fy, out=tmp)
        iadd(acc, tmp, sign)
    if type(ry) is _ARRAY and type(fx) is _ARRAY or not (zero(ry) or zero(fx)):
        np.multiply(ry, fx, out=tmp)
        iadd(acc, tmp, -sign)


def scalar(x):
    """A Python float of a scalar; a per-row array (a stacked batch of scenes,
    :func:`kinetostatics.solve_many`) as it is."""
    t = type(x)
    if t is float:
        return x
    return x if t is _ARRAY or isinstance(x, np.ndarray) else float(x)


def full(x, n: int) -> np.ndarray:
    """x as a float array of n values over the positions (a scalar is broadcast, read-only;
    a float array of n values is x itself)."""
    if type(x) is _ARRAY and x.shape == (n,) and x.dtype == np.float64:
        return x
    return np.broadcast_to(np.asarray(x, dtype=float), (n,))
