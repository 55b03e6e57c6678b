"""The compound helpers of :mod:`kinetostatics.solver.arith` with fewer Python calls
(2026-12-01: ``fresh`` by identity, ``mul_add``/``mul_sub`` through ``_joined``,
``add_mul``/``sub_mul`` through ``_onto``) give the bits of their former compositions of
``mul``, ``into``, ``fresh`` and ``over``, signed zeros, NaN and infinities included, and
write into no operand; an RTR dyad's closeness to a dead centre, now from its closing's
own pivot distance, is the one ``inner_t_tau`` gives."""

from __future__ import annotations

import itertools
from contextlib import nullcontext

import numpy as np
import pytest

from kinetostatics.model.examples import example
from kinetostatics.model.scene import load_scene
from kinetostatics.solver import arith as A
from kinetostatics.solver import closure as C
from kinetostatics.solver import kinematics as K
from kinetostatics.solver import velocity_system as V
from kinetostatics.solver.pipeline import structure_of
from kinetostatics.solver.trap import FloatTrap, trapped

SPECIAL = [0.0, -0.0, 1.0, -1.0, 2.5e-310, 1e300, -1e300, np.inf, -np.inf, np.nan]


def bits(x) -> np.ndarray:
    return np.asarray(x, dtype=float).view(np.int64)


def rows(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    x = rng.normal(size=24) * 10.0 ** rng.integers(-3, 3, 24)
    x[: len(SPECIAL)] = np.roll(SPECIAL, seed)
    return x


# the former definitions (before 2026-12-01), the reference
def fresh_then(r, *inputs) -> bool:
    return (type(r) is np.ndarray and r.dtype == np.float64 and r.flags.writeable
            and all(r is not x for x in inputs))


def mul_add_then(a, b, c, d, den=None):
    p, q = A.mul(a, b), A.mul(c, d)
    return A.over(A.into(np.add, A.add, p, q, fresh_then(p, a, b), fresh_then(q, c, d)),
                  den, a, b, c, d)


def mul_sub_then(a, b, c, d, den=None):
    p, q = A.mul(a, b), A.mul(c, d)
    return A.over(A.into(np.subtract, A.sub, p, q, fresh_then(p, a, b),
                         fresh_then(q, c, d)), den, a, b, c, d)


def sub_mul_then(a, s, x):
    if type(x) is np.ndarray and type(s) in (float, int) and s != 0 and A.zero(a):
        return A.mul(-s, x)
    t = A.mul(s, x)
    return A.into(np.subtract, A.sub, a, t, False, fresh_then(t, s, x))


def add_mul_then(a, s, x):
    t = A.mul(s, x)
    return A.into(np.add, A.add, a, t, False, fresh_then(t, s, x))


def operands():
    """Arrays (a fresh one each time: the helpers may write into temporaries), Python
    numbers including exact zeros of either sign and ones, an int, a numpy scalar."""
    return [lambda i=i: rows(i) for i in range(3)] + [
        lambda v=v: v for v in (0.0, -0.0, 1.0, 2.5, -3.0, 0, 2, np.float64(0.5))]


def same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(bits(np.broadcast_to(a, (24,))), bits(np.broadcast_to(b, (24,))))
    return bits(a) == bits(b)


@pytest.mark.parametrize("road", ["trapped", "checked"])
def test_four_operand_helpers_keep_their_bits(road) -> None:
    ops = operands()
    combos = list(itertools.product(ops, repeat=4))[::7]    # (a spread of the 11^4)
    with np.errstate(all="ignore"):
        for make in combos:
            for new, old in ((A.mul_add, mul_add_then), (A.mul_sub, mul_sub_then)):
                for den in (None, 0.75, "array"):
                    args = [m() for m in make]
                    kept = [np.copy(x) if isinstance(x, np.ndarray) else x for x in args]
                    d = rows(7) if den == "array" else den
                    # (a trapped solve's exact zero times a NaN is 0.0: the trap
                    # stands for the look at the other operand, in both)
                    with trapped(FloatTrap()) if road == "trapped" else nullcontext():
                        got = new(*args, den=d)
                        want = old(*[m() for m in make], den=d)
                    assert same(got, want), (new.__name__, args, den)
                    for x, k in zip(args, kept, strict=True):      # no operand written
                        assert same(x, k)


def test_three_operand_helpers_keep_their_bits() -> None:
    ops = operands()
    with np.errstate(all="ignore"):
        for make in itertools.product(ops, repeat=3):
            for new, old in ((A.add_mul, add_mul_then), (A.sub_mul, sub_mul_then)):
                args = [m() for m in make]
                kept = [np.copy(x) if isinstance(x, np.ndarray) else x for x in args]
                got = new(*args)
                assert same(got, old(*[m() for m in make])), (new.__name__, args)
                for x, k in zip(args, kept, strict=True):
                    assert same(x, k)


def test_fresh_answers_as_before() -> None:
    a = rows(0)
    ro = rows(1)
    ro.flags.writeable = False
    cases = [a, a * 2.0, ro, np.broadcast_to(1.0, (24,)), np.arange(24),
             np.arange(24.0).astype(np.float32), a[::2], 1.0, None]
    for r in cases:
        for inputs in ((), (a,), (r,), (a, r, 2.0)):
            assert A.fresh(r, *inputs) == fresh_then(r, *inputs)


@pytest.mark.parametrize("name", ["shaper", "slotted_lever"])
def test_rtr_closeness_is_inner_t_tau_s(name) -> None:
    """The RTR closing's own D and |D| (DyadSolver.pivots) give the closeness of
    inner_t_tau's, bit for bit (in both bundled scenes the slider is the dyad's second
    body: D there is minus inner_t_tau's, squared alike)."""
    sc = load_scene(example(name))
    st = structure_of(sc)
    kin = K.solve_kinematics(sc, st)
    real = V.dead_centre_closeness2

    def former(vs, pr, reach, n, solver=None):
        if vs.revolute:
            return real(vs, pr, reach, n, solver)
        sin2 = A.full(V.inner_t_tau(pr, vs.ux, vs.uy, cos=False)[0], n) ** 2
        return sin2 if reach is None else np.minimum(sin2, reach * reach)

    K.dead_centre_closeness2 = former
    try:
        then = K.solve_kinematics(sc, st)
    finally:
        K.dead_centre_closeness2 = real
    rtr = 0
    for now, was in zip(kin.dyads, then.dyads, strict=True):
        assert np.array_equal(bits(now.closeness2), bits(was.closeness2))
        rtr += now.nx is not None and all(p.kind == "rot" for p in now.params)
    assert rtr == 1


def test_circle_line_discriminant_and_root_keep_their_bits() -> None:
    """closure's circle-line closing in fewer arrays (2026-12-01): its discriminant, its
    root written into its own array, and k = 1 not multiplied, the plain bits."""
    with np.errstate(all="ignore"):
        for i in range(4):
            b, wx, wy = rows(i), rows(i + 1)[::-1].copy(), rows(i + 2)
            for rs in (0.0, 0.25, 1e300, rows(i + 3)):
                got, own = C._discriminant(b, wx, wy, rs)
                want = b * b - (wx * wx + wy * wy) + rs
                assert own and np.array_equal(bits(got), bits(want))
                least = got.min()
                mine = C._clipped_root(got, least, own=True)
                assert mine is got
                assert np.array_equal(bits(mine), bits(C._clipped_root(want, least)))
            assert np.array_equal(bits(1 * b - wx), bits(b - wx))
        # (a number or arrays of two shapes: the plain expression, not its own array)
        assert C._discriminant(0.5, 0.25, 2.0, 1.0) == (0.5 * 0.5 - (0.25 * 0.25 + 4.0) + 1.0,
                                                       False)
        assert not C._discriminant(rows(0), rows(1), rows(2)[:1], 1.0)[1]
