"""The shortcuts that spare a stack's runs passes over its rows give the bits of the plain
expressions they replace: signed zeros, NaN and infinities included (solve_many's tables
are compared with solve's bit for bit, the sign of each zero too)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetostatics.solver import arith as A
from kinetostatics.solver.driver import BodyMotion
from kinetostatics.solver.loads import PointLoad, resultants
from kinetostatics.solver.stack import Rows

SPECIAL = [0.0, -0.0, 1.0, -1.0, 2.5e-310, -2.5e-310, 1e300, -1e300, np.inf, -np.inf,
           np.nan]


def bits(x) -> np.ndarray:
    return np.asarray(x, dtype=float).view(np.int64)


def rows(n: int = 64, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    x = rng.normal(size=n) * 10.0 ** rng.integers(-3, 3, n)
    x[: len(SPECIAL)] = SPECIAL
    return x


@pytest.mark.parametrize("b", [0.0, -0.0, 0.5, -3.0])
def test_less_is_the_plain_difference(b) -> None:
    a = rows()
    np.testing.assert_array_equal(bits(A.less(a, b)), bits(a - b))
    assert (A.less(a, b) is a) == (b == 0.0 and np.copysign(1.0, b) > 0)


@pytest.mark.parametrize("y", [0.0, -0.0, 0.25])
def test_squares_is_the_plain_sum(y) -> None:
    x = rows()
    with np.errstate(over="ignore"):
        pairs = ((A.squares(x, y), x * x + y * y), (A.squares(y, x), y * y + x * x))
    for got, want in pairs:
        np.testing.assert_array_equal(bits(got), bits(want))


def _plain_resultants(loads, names, n):
    """The sums as main made them: from arrays of zeros, term by term."""
    acc = {b: [np.zeros(n), np.zeros(n), np.zeros(n)] for b in names}
    for ld in loads:
        r = acc[ld.body]
        r[0] += np.broadcast_to(ld.fx, (n,))
        r[1] += np.broadcast_to(ld.fy, (n,))
        r[2] += np.broadcast_to(ld.rx, (n,)) * ld.fy
        r[2] -= np.broadcast_to(ld.ry, (n,)) * ld.fx
        r[2] += np.broadcast_to(ld.m, (n,))
    return acc


VALUES = st.sampled_from([0.0, -0.0, 1.5, -2.0, "row", "row", "zeros", "negzeros"])


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(["a", "b"]), *[VALUES] * 5), max_size=6),
       st.integers(0, 10_000))
def test_resultants_equal_the_sums_from_zeros(specs, seed) -> None:
    """Sums that start as numbers, skip exact zeros and make their array from their
    first array term: the bits of sums from arrays of zeros (measured: equal on every
    drawn case; a sum started from the term itself, without 0.0 +, fails on -0.0)."""
    n = 16
    rng = np.random.default_rng(seed)

    def value(v):
        if v == "row":
            x = rng.normal(size=n)
            x[rng.random(n) < 0.2] = -0.0
            return x
        if v == "zeros":
            return np.zeros(n)
        if v == "negzeros":
            return np.full(n, -0.0)
        return v
    loads = [PointLoad(b, "applied", *(value(v) for v in vs)) for b, *vs in specs]
    got = resultants(loads, ["a", "b"], n)
    want = _plain_resultants(loads, ["a", "b"], n)
    for b in ("a", "b"):
        for g, w in zip(got[b], want[b], strict=True):
            assert type(g) is np.ndarray and g.shape == (n,)
            np.testing.assert_array_equal(bits(g), bits(w))


def test_rows_tests_on_the_first_row_and_plain_arithmetic() -> None:
    """A stack's masses answer the signature's tests (== 0, > 0) from the first row and
    give plain arrays in arithmetic; other comparisons stay row by row."""
    m = np.array([2.0, 3.0, 4.0]).view(Rows)
    assert (m == 0.0) is False and (m > 0.0) is True
    z = np.zeros(3).view(Rows)
    assert (z == 0.0) is True and (z > 0.0) is False and not z
    assert type(-m) is np.ndarray and type(m * 9.81) is np.ndarray
    np.testing.assert_array_equal(-m, [-2.0, -3.0, -4.0])
    assert not (m == 3.0) and (m > 1.0)         # row by row: not all equal 3, all > 1


def test_arms_and_omega2_kept_are_the_computed_ones() -> None:
    rng = np.random.default_rng(3)
    th = rng.uniform(0, 6.3, 32)
    om = rng.normal(size=32)
    b = BodyMotion(th, np.cos(th), np.sin(th), om, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    local = (0.3, -0.2)
    a1 = b.arm(local)
    assert b.arm(local) is a1                       # kept
    for x, y in zip(a1, A.rotate(b.cos, b.sin, *local), strict=True):
        np.testing.assert_array_equal(bits(x), bits(y))
    assert b.arm(tuple([0.3, -0.2])) is not a1      # another tuple: worked out anew
    np.testing.assert_array_equal(bits(b.omega2()), bits(om * om))
    b.forget_arms()
    assert b.arm(local) is not a1


def same(x, y) -> None:
    """The same doubles, the sign of each zero too (NaN for NaN: its sign may differ)."""
    x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    nan = np.isnan(y)
    np.testing.assert_array_equal(np.isnan(x), nan)
    np.testing.assert_array_equal(bits(x)[~nan], bits(y)[~nan])


OPERANDS = [rows(seed=1), rows(seed=2)[::-1].copy(), 0.0, 1.0, -2.0]


@pytest.mark.parametrize("den", [None, 3.0, "array"])
def test_fused_forms_give_the_composed_bits_and_leave_the_operands(den) -> None:
    """mul_add, mul_sub, add_mul and sub_mul (sums written into a product's own array)
    give the bits of the composed add/sub/mul and never write into an operand."""
    d = rows(seed=3) if den == "array" else den
    with np.errstate(all="ignore"):     # (infinities and NaN among the operands)
        for a, b, c, e in itertools.product(OPERANDS, repeat=4):
            kept = [np.copy(x) for x in (a, b, c, e)]
            for fused, plain in ((A.mul_add, A.add), (A.mul_sub, A.sub)):
                want = plain(A.mul(a, b), A.mul(c, e))
                same(fused(a, b, c, e, den=d), want if d is None else want / d)
            same(A.add_mul(a, b, c), A.add(a, A.mul(b, c)))
            same(A.sub_mul(a, b, c), A.sub(a, A.mul(b, c)))
            for x, k in zip((a, b, c, e), kept, strict=True):
                same(x, k)      # (no operand written into)
