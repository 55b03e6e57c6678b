"""Splitting a correction onto fixed positions, combining weights, units (balance.field,
balance.model.units), each against an independent computation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from balance import BalanceError, Units, combine_weights, split_correction
from balance.model.units import parse_units


def vec(m: float, deg: float) -> complex:
    return m * complex(math.cos(math.radians(deg)), math.sin(math.radians(deg)))


def neighbours_by_linear_solve(m: float, theta: float, n: int, first: float):
    """Independent: try every adjacent pair of positions, solve the real 2x2 system
    for the two masses, keep the pair whose masses are both non-negative."""
    w = vec(m, theta)
    found = []
    for k in range(n):
        a, b = first + k * 360.0 / n, first + (k + 1) * 360.0 / n
        A = np.array([[math.cos(math.radians(a)), math.cos(math.radians(b))],
                      [math.sin(math.radians(a)), math.sin(math.radians(b))]])
        x = np.linalg.solve(A, [w.real, w.imag])
        if x.min() >= -1e-12:
            found.append((k + 1, (k + 1) % n + 1, x))
    return found


def test_hand_worked_split() -> None:
    # 10 g at 100 deg on 8 holes (45 deg apart): holes at 90 and 135 deg.
    # Law of sines: m90 = 10 sin 35 / sin 45 = 8.1116, m135 = 10 sin 10 / sin 45 = 2.4558.
    s = split_correction(10.0, 100.0, 8)
    assert [(p.position, p.angle) for p in s.placements] == [(3, 90.0), (4, 135.0)]
    assert s.placements[0].mass == pytest.approx(10 * math.sin(math.radians(35))
                                                 / math.sin(math.radians(45)), rel=1e-14)
    assert s.placements[1].mass == pytest.approx(2.4558, abs=5e-5)
    assert s.total_mass > s.mass


@settings(max_examples=300, deadline=None)
@given(st.floats(0.01, 100.0), st.floats(-720.0, 720.0), st.integers(3, 36),
       st.floats(-360.0, 360.0))
def test_split_matches_linear_solve_and_sums_to_the_correction(m, theta, n, first) -> None:
    s = split_correction(m, theta, n, first)
    total = sum(vec(p.mass, p.angle) for p in s.placements)
    assert abs(total - vec(m, theta)) <= 1e-9 * m
    assert all(p.mass >= 0.0 for p in s.placements)
    pitch = 360.0 / n
    for p in s.placements:                       # every position lies on the hole pattern
        k = ((p.angle - first) / pitch) % n
        assert min(k % 1.0, 1.0 - k % 1.0) < 1e-9 * n
    if len(s.placements) == 2:
        ref = neighbours_by_linear_solve(m, theta, n, first)
        got = {(s.placements[0].position, s.placements[1].position)}
        assert got & {(a, b) for a, b, _ in ref}
        x = next(x for a, b, x in ref if (a, b) in got)
        assert [p.mass for p in s.placements] == pytest.approx(list(x), rel=1e-9, abs=1e-12)


def test_split_on_a_position_and_radius_scaling() -> None:
    s = split_correction(5.0, 90.0, 4)
    assert [(p.position, p.angle, p.mass) for p in s.placements] == [(2, 90.0, 5.0)]
    s = split_correction(5.0, 90.0, 4, radius=0.2, correction_radius=0.1)
    assert s.placements[0].mass == pytest.approx(2.5, rel=1e-15)   # twice the radius
    assert split_correction(0.0, 10.0, 6).placements == ()


@pytest.mark.parametrize("args, kwargs, text", [
    ((1.0, 0.0, 2), {}, "at least 3"),
    ((1.0, 0.0, 4.5), {}, "whole number"),
    ((-1.0, 0.0, 4), {}, "negative"),
    ((1.0, 0.0, 4), {"radius": 0.1}, "both"),
])
def test_split_errors(args, kwargs, text) -> None:
    with pytest.raises(BalanceError) as exc:
        split_correction(*args, **kwargs)
    assert text in str(exc.value) and "\n" not in str(exc.value)


def test_combine_against_component_sums() -> None:
    w = [(3.0, 0.0, 0.12), (2.0, 90.0, 0.12), (4.0, 200.0, 0.10)]
    c = combine_weights(w, radius=0.12)
    x = sum(m * r * math.cos(math.radians(a)) for m, a, r in w) / 0.12
    y = sum(m * r * math.sin(math.radians(a)) for m, a, r in w) / 0.12
    assert c.mass == pytest.approx(math.hypot(x, y), rel=1e-14)
    assert c.angle == pytest.approx(math.degrees(math.atan2(y, x)) % 360.0, abs=1e-12)
    assert c.count == 3
    same = combine_weights([(3.0, 0.0), (4.0, 90.0)])            # 3-4-5 triangle
    assert same.mass == pytest.approx(5.0, rel=1e-15)
    assert same.angle == pytest.approx(math.degrees(math.atan2(4, 3)), abs=1e-12)
    gone = combine_weights([(2.0, 10.0), (2.0, 190.0)])
    assert gone.mass == 0.0 and gone.angle is None


def test_combine_then_split_gives_back_the_weights() -> None:
    c = combine_weights([(2.0, 45.0), (1.0, 90.0)])
    s = split_correction(c.mass, c.angle, 8)                     # holes at 45 and 90
    assert [p.mass for p in s.placements] == pytest.approx([2.0, 1.0], rel=1e-12)


@pytest.mark.parametrize("weights, radius, text", [
    ([], None, "no weights"),
    ([(1.0, 0.0, 0.1), (1.0, 0.0)], 0.1, "every weight"),
    ([(1.0, 0.0, 0.1)], None, "give the radius"),
    ([(1.0, 0.0)], 0.1, "needs the radius"),
    ([(1.0,)], None, "must be"),
])
def test_combine_errors(weights, radius, text) -> None:
    with pytest.raises(BalanceError) as exc:
        combine_weights(weights, radius)
    assert text in str(exc.value)


def test_units_round_trip_and_factors() -> None:
    u = parse_units({"mass": "g", "length": "mm", "unbalance": "g mm", "vibration": "mils"})
    assert u.to_si(250.0, "mass") == pytest.approx(0.25, rel=1e-15)
    assert u.to_si(200.5, "unbalance") == pytest.approx(200.5e-6, rel=1e-15)
    assert u.to_si(1.0, "vibration") == pytest.approx(25.4e-6, rel=1e-15)   # 1 mil
    assert u.from_si(u.to_si(3.7, "length"), "length") == pytest.approx(3.7, rel=1e-15)
    # g mm from g and mm: 1 g at 1 mm is 1e-3 kg x 1e-3 m
    assert u.to_si(1.0, "unbalance") == pytest.approx(u.to_si(1.0, "mass")
                                                      * u.to_si(1.0, "length"), rel=1e-15)
    assert not u.is_si and Units().is_si
    assert parse_units({"vibration": "µm"}).vibration == "um"
    assert parse_units({"vibration": "mm/s"}).to_si(2.0, "vibration") == pytest.approx(2e-3)


@pytest.mark.parametrize("table, text", [
    ({"mas": "g"}, "unknown quantity"), ({"mass": "lb"}, "unknown unit"),
    ({"mass": 3}, "unit name"), ("g", "must be a table"),
])
def test_units_errors(table, text) -> None:
    with pytest.raises(BalanceError) as exc:
        parse_units(table)
    assert text in str(exc.value)
