"""Rotor balancing by design (seed 002 s. 3.2, eqs 3.3-3.14)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from balance import BalanceError, BalanceWarning, CorrectionPlane, Unbalance, balance_rotor

masses = st.floats(0.0, 0.5)
radii = st.floats(0.0, 0.3)
angles = st.floats(-720.0, 720.0)
zs = st.floats(-1.0, 1.0)
unbalance = st.tuples(masses, radii, angles, zs)


def applied(result) -> tuple[complex, complex]:
    """Sum of unbalances and of their moments about z = 0, with the corrections placed
    from the reported masses and angles (not from the internal vectors)."""
    F = complex(result.unbalances.sum())
    M = complex((result.z * result.unbalances).sum())
    for c in result.corrections:
        u = c.mass * c.radius * complex(math.cos(math.radians(c.angle)),
                                        math.sin(math.radians(c.angle)))
        F += u
        M += c.z * u
    return F, M


@settings(max_examples=300, deadline=None)
@given(st.lists(unbalance, min_size=1, max_size=8), zs, st.floats(0.05, 1.0),
       st.floats(0.01, 0.5), st.floats(0.01, 0.5), st.booleans())
def test_two_planes_cancel_force_and_moment(ub, z1, gap, r1, r2, flip) -> None:
    z2 = z1 - gap if flip else z1 + gap
    with warnings.catch_warnings(record=True) as seen:   # close planes, large corrections
        warnings.simplefilter("always", BalanceWarning)
        res = balance_rotor(ub, [(z1, r1), (z2, r2)])
    assert [str(w.message) for w in seen] == list(res.warnings)   # each said in the result
    F, M = applied(res)
    size = sum(m * r for m, r, _, _ in ub)
    zsize = sum(m * r * (abs(z) + 1.0) for m, r, _, z in ub) / gap
    assert abs(F) <= 1e-11 * (size + zsize) + 1e-300
    assert abs(M) <= 1e-11 * (size + zsize) * 2.0 + 1e-300
    assert res.residual_force <= 1e-11 * (size + zsize) + 1e-300
    assert res.residual_moment <= 2e-11 * (size + zsize) + 1e-300
    for c in res.corrections:
        assert 0.0 <= c.angle < 360.0
        assert c.mass >= 0.0
        assert math.isclose(c.U, c.mass * c.radius, rel_tol=1e-12, abs_tol=1e-300)


@settings(max_examples=200, deadline=None)
@given(st.lists(unbalance, min_size=1, max_size=8), zs, st.floats(0.01, 0.5))
def test_one_plane_cancels_force(ub, z1, r1) -> None:
    res = balance_rotor(ub, [(z1, r1)])
    F, _ = applied(res)
    size = sum(m * r for m, r, _, _ in ub)
    assert abs(F) <= 1e-12 * size + 1e-300
    c = res.corrections[0]
    assert 0.0 <= c.angle < 360.0
    # eq. 3.6: U_e = -U_d, |U_e| is the initial resultant
    assert math.isclose(c.U, res.initial_force, rel_tol=1e-12, abs_tol=1e-15 * size)


def test_static_balancing_example_by_hand() -> None:
    """Two equal masses 90 deg apart: U_e = m r sqrt(2) at 225 deg (eq. 3.8)."""
    res = balance_rotor([Unbalance(0.01, 0.1, 0.0), Unbalance(0.01, 0.1, 90.0)],
                        [CorrectionPlane(0.0, 0.05)])
    c = res.corrections[0]
    assert c.U == pytest.approx(0.001 * math.sqrt(2.0), rel=1e-14)
    assert c.mass == pytest.approx(0.02 * math.sqrt(2.0), rel=1e-14)
    assert c.angle == pytest.approx(225.0, abs=1e-12)
    assert res.residual_force == pytest.approx(0.0, abs=1e-18)


def test_static_correction_leaves_the_couple() -> None:
    """Two equal opposite masses in different planes: no force, a pure couple."""
    res = balance_rotor([(0.01, 0.1, 0.0, 0.0), (0.01, 0.1, 180.0, 0.2)], [(0.1, 0.1)])
    assert res.corrections[0].mass == 0.0 and res.corrections[0].angle == 0.0
    assert res.residual_moment == pytest.approx(0.01 * 0.1 * 0.2, rel=1e-12)
    res2 = balance_rotor([(0.01, 0.1, 0.0, 0.0), (0.01, 0.1, 180.0, 0.2)],
                         [(0.0, 0.1), (0.2, 0.1)])
    assert [c.mass for c in res2.corrections] == pytest.approx([0.01, 0.01], rel=1e-12)
    assert [c.angle for c in res2.corrections] == pytest.approx([180.0, 0.0], abs=1e-9)


def test_zero_correction_has_mass_and_angle_zero() -> None:
    res = balance_rotor([(0.01, 0.1, 10.0, 0.1), (0.01, 0.1, 190.0, 0.1)],
                        [(0.0, 0.1), (0.3, 0.1)])
    for c in res.corrections:
        assert c.mass == 0.0 and c.angle == 0.0 and c.U == 0.0
    res = balance_rotor([(0.0, 0.1, 10.0)], [(0.0, 0.1)])
    assert res.to_dict()["corrections"][0] == {"plane": 1, "z": 0.0, "radius": 0.1,
                                              "mass": 0.0, "angle": 0.0, "U": 0.0}


def test_correction_in_a_plane_of_the_masses_is_exact() -> None:
    """All masses in plane II: plane I needs nothing."""
    res = balance_rotor([(0.02, 0.1, 30.0, 0.3), (0.01, 0.1, 100.0, 0.3)],
                        [(0.0, 0.1), (0.3, 0.1)])
    assert res.corrections[0].mass == 0.0
    assert res.corrections[1].mass > 0.0


def test_units_follow_the_speed() -> None:
    ub = [(0.02, 0.1, 30.0, 0.05)]
    a = balance_rotor(ub, [(0.0, 0.1)])
    b = balance_rotor(ub, [(0.0, 0.1)], speed_rpm=3000.0)
    w2 = (3000.0 * 2.0 * math.pi / 60.0) ** 2
    assert a.units == ("kg m", "kg m^2") and b.units == ("N", "N m")
    assert b.initial_force == pytest.approx(a.initial_force * w2, rel=1e-14)
    assert b.initial_moment == pytest.approx(a.initial_moment * w2, rel=1e-14)
    assert a.corrections == b.corrections      # the masses do not depend on the speed


def test_to_dict_has_exactly_the_contract_keys() -> None:
    d = balance_rotor([(0.02, 0.1, 30.0, 0.05)], [(0.0, 0.1), (0.3, 0.1)]).to_dict()
    assert set(d) == {"corrections", "initial_force", "initial_moment", "residual_force",
                      "residual_moment", "warnings"}
    assert d["warnings"] == []
    assert all(set(c) == {"plane", "z", "radius", "mass", "angle", "U"}
               for c in d["corrections"])
    assert [c["plane"] for c in d["corrections"]] == [1, 2]


def test_dict_inputs_and_plane_order() -> None:
    """Planes are reported in input order, even when plane 1 lies at larger z."""
    ub = [{"mass": 0.02, "radius": 0.1, "angle": 30.0, "z": 0.05}]
    a = balance_rotor(ub, [{"z": 0.0, "radius": 0.1}, {"z": 0.3, "radius": 0.1}])
    b = balance_rotor(ub, [{"z": 0.3, "radius": 0.1}, {"z": 0.0, "radius": 0.1}])
    assert a.corrections[0].mass == pytest.approx(b.corrections[1].mass, rel=1e-12)
    assert a.corrections[1].angle == pytest.approx(b.corrections[0].angle, abs=1e-9)


def one_line(exc: pytest.ExceptionInfo) -> str:
    msg = str(exc.value)
    assert "\n" not in msg and msg
    return msg


def test_coincident_planes_refused() -> None:
    with pytest.raises(BalanceError) as exc:
        balance_rotor([(0.02, 0.1, 30.0, 0.05)], [(0.1, 0.1), (0.1, 0.12)])
    assert "coincide" in one_line(exc)
    with pytest.raises(BalanceError):
        balance_rotor([(0.02, 0.1, 30.0, 0.05)], [(0.1, 0.1), (0.1 + 1e-14, 0.12)])
    # planes that differ below the printed precision of %g are told apart in the message
    with pytest.raises(BalanceError) as exc:
        balance_rotor([(0.02, 0.1, 30.0, 0.05)], [(0.2, 0.1), (0.2 + 1e-11, 0.12)])
    assert "z = 0.2 and 0.20000000001 m" in one_line(exc)


def test_planes_too_close_for_the_rotor_warn() -> None:
    """Planes 10 um apart on a 0.3 m rotor give corrections of kilograms: flagged, with
    the numbers, in the result and as a BalanceWarning."""
    ub = [(0.02, 0.1, 30.0, 0.05), (0.015, 0.12, 150.0, 0.15), (0.01, 0.08, 260.0, 0.3)]
    with pytest.warns(BalanceWarning) as seen:
        r = balance_rotor(ub, [(0.1, 0.1), (0.10001, 0.1)])
    assert [str(w.message) for w in seen] == list(r.warnings)
    assert "planes are 1e-05 m apart" in r.warnings[0]
    assert max(c.mass for c in r.corrections) > 100.0        # the absurd correction
    assert len(r.warnings) == 2 and "times the unbalance" in r.warnings[1]
    assert r.to_dict()["warnings"] == list(r.warnings)
    # planes 5 % of the extent apart warn; a 0.3 m span on a 0.3 m rotor does not
    with pytest.warns(BalanceWarning) as seen:
        near = balance_rotor(ub, [(0.1, 0.1), (0.11, 0.1)])   # 0.04 of 0.25 m
    assert [str(w.message) for w in seen] == list(near.warnings)
    assert "apart" in near.warnings[0] and "times the unbalance" in near.warnings[1]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert balance_rotor(ub, [(0.0, 0.1), (0.3, 0.1)]).warnings == ()


@pytest.mark.parametrize("n", [0, 3])
def test_zero_or_three_planes_refused(n: int) -> None:
    with pytest.raises(BalanceError) as exc:
        balance_rotor([(0.02, 0.1, 30.0, 0.05)], [(0.1 * k, 0.1) for k in range(n)])
    assert "one" in one_line(exc) and "two" in one_line(exc)


@pytest.mark.parametrize("ub, planes, words", [
    ([(-0.02, 0.1, 30.0, 0.05)], [(0.0, 0.1)], "mass"),
    ([(0.02, -0.1, 30.0, 0.05)], [(0.0, 0.1)], "radius"),
    ([(0.02, 0.1, 30.0, 0.05)], [(0.0, 0.0)], "radius"),
    ([(0.02, 0.1, float("nan"), 0.05)], [(0.0, 0.1)], "angle"),
    ([], [(0.0, 0.1)], "no unbalance"),
    ([{"mas": 0.02, "radius": 0.1, "angle": 0.0}], [(0.0, 0.1)], "did you mean 'mass'"),
])
def test_bad_rotor_inputs(ub, planes, words) -> None:
    with pytest.raises(BalanceError) as exc:
        balance_rotor(ub, planes)
    assert words in one_line(exc)


def test_bad_speed() -> None:
    with pytest.raises(BalanceError):
        balance_rotor([(0.02, 0.1, 30.0)], [(0.0, 0.1)], speed_rpm=0.0)


def test_vectors_for_plots() -> None:
    res = balance_rotor([(0.02, 0.1, 90.0, 0.05)], [(0.0, 0.1)])
    assert np.allclose(res.unbalances, [0.002j], atol=1e-18)
    assert res.corrections[0].vector == pytest.approx(-0.002j, abs=1e-18)
