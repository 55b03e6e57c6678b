"""ISO 21940-11 balance quality."""

from __future__ import annotations

import math

import numpy as np
import pytest

from balance import (
    BalanceError,
    iso_allocate,
    iso_check,
    iso_permissible_unbalance,
    iso_tolerances,
    kgm_to_gmm,
    to_bearing_planes,
)


def test_permissible_unbalance_g63_10kg_3000rpm() -> None:
    assert round(iso_permissible_unbalance(6.3, 10.0, 3000.0), 1) == 200.5
    assert iso_permissible_unbalance(6.3, 10.0, 3000.0) == pytest.approx(
        9549.0 * 6.3 * 10.0 / 3000.0, rel=1e-4)
    assert iso_permissible_unbalance(1.0, 1.0, 60.0) == pytest.approx(
        1000.0 / (2.0 * math.pi), rel=1e-15)


@pytest.mark.parametrize("z_cog, share_a, limited", [
    (0.5, 0.5, False), (0.4, 0.6, False), (0.3, 0.7, False), (0.1, 0.7, True),
    (0.0, 0.7, True), (0.95, 0.3, True), (1.0, 0.3, True),
])
def test_allocation_lever_rule_with_limits(z_cog, share_a, limited) -> None:
    a = iso_allocate(200.0, 0.0, 1.0, z_cog)
    assert a.plane_a == pytest.approx(200.0 * share_a, rel=1e-12)
    assert a.plane_a + a.plane_b == pytest.approx(200.0, rel=1e-12)
    assert a.limited is limited


def test_allocation_planes_in_either_order() -> None:
    a = iso_allocate(100.0, 0.8, 0.2, 0.4)       # L_A = 0.4, L_B = 0.2, L = 0.6
    assert a.plane_a == pytest.approx(100.0 * 0.2 / 0.6, rel=1e-12)
    assert a.plane_b == pytest.approx(100.0 * 0.4 / 0.6, rel=1e-12)


def test_allocation_errors() -> None:
    with pytest.raises(BalanceError):
        iso_allocate(100.0, 0.2, 0.2, 0.2)
    with pytest.raises(BalanceError) as exc:
        iso_allocate(100.0, 0.0, 1.0, 1.5)
    assert "outside" in str(exc.value)


def test_check() -> None:
    U = iso_permissible_unbalance(6.3, 10.0, 3000.0)
    assert iso_check(kgm_to_gmm(150e-6), U).ok
    assert not iso_check(kgm_to_gmm(250e-6), U).ok
    c = iso_check([80.0, 120.0], iso_allocate(U, 0.0, 1.0, 0.5))
    assert not c.ok and c.ratio[1] > 1.0 > c.ratio[0]
    with pytest.raises(BalanceError):
        iso_check([1.0, 2.0], 3.0)
    with pytest.raises(BalanceError):
        iso_check(-1.0, 3.0)


@pytest.mark.parametrize("args", [(0.0, 10.0, 3000.0), (6.3, -1.0, 3000.0), (6.3, 10.0, 0.0)])
def test_bad_inputs(args) -> None:
    with pytest.raises(BalanceError):
        iso_permissible_unbalance(*args)


# ------------------------------------------- bearing planes and correction planes


def bearing_loads_by_statics(U1: complex, U2: complex, z1: float, z2: float, za: float,
                             zb: float) -> tuple[complex, complex]:
    """Independent: the bearing-plane pair with the same force and moment, from the
    2x2 system U_A + U_B = U1 + U2, U_A z_A + U_B z_B = U1 z1 + U2 z2."""
    A = np.array([[1.0, 1.0], [za, zb]], dtype=complex)
    ua, ub = np.linalg.solve(A, [U1 + U2, U1 * z1 + U2 * z2])
    return ua, ub


def worst_over_angles(t1: float, t2: float, z1, z2, za, zb, n: int = 721) -> np.ndarray:
    """max over both residual angles of |U_A|, |U_B| for residuals t1, t2 (grid)."""
    th = np.radians(np.linspace(0.0, 360.0, n))
    U1 = t1 * np.exp(1j * th)[:, None]
    U2 = t2 * np.exp(1j * th)[None, :]
    A = np.array([[1.0, 1.0], [za, zb]])
    inv = np.linalg.inv(A)
    ua = inv[0, 0] * (U1 + U2) + inv[0, 1] * (U1 * z1 + U2 * z2)
    ub = inv[1, 0] * (U1 + U2) + inv[1, 1] * (U1 * z1 + U2 * z2)
    return np.array([np.abs(ua).max(), np.abs(ub).max()])


@pytest.mark.parametrize("planes", [(0.1, 0.5), (-0.2, 0.7), (0.0, 0.6), (0.25, 0.35),
                                    (0.65, 0.9)])
def test_plane_tolerances_keep_the_bearings_within_tolerance(planes) -> None:
    """Residuals at the plane tolerances, at their worst angles (a 0.5 deg grid), load
    each bearing plane at most up to its tolerance, and one of them exactly."""
    za, zb, zc = 0.0, 0.6, 0.24
    t = iso_tolerances(200.0, (za, zb), zc, planes)
    worst = worst_over_angles(*t.plane_tolerances, *planes, za, zb)
    tol = np.array(t.bearing_tolerances)
    assert np.all(worst <= tol * (1 + 1e-12))
    assert np.max(worst / tol) == pytest.approx(1.0, rel=1e-9)


def test_bearing_planes_as_correction_planes_give_the_lever_rule() -> None:
    t = iso_tolerances(200.0, (0.0, 0.6), 0.24, planes=(0.0, 0.6))
    assert t.kind == "inboard"
    assert t.bearing_tolerances == pytest.approx((200.0 * 0.36 / 0.6, 200.0 * 0.24 / 0.6))
    assert t.plane_tolerances == pytest.approx(t.bearing_tolerances, rel=1e-12)


def test_scene_example_numbers_by_hand() -> None:
    """10 kg, 3000 rpm, G 6.3; bearings 0 and 600 mm, cog 240 mm, planes 100, 500 mm:
    U_per = 200.535 g mm, U_A = U_per 360/600 = 120.32, U_B = 80.21; the plane
    tolerances t = s (0.65, 0.35) with s = U_A / (500/600 0.65 + 100/600 0.35) = U_per."""
    U = iso_permissible_unbalance(6.3, 10.0, 3000.0)
    t = iso_tolerances(U, (0.0, 600.0), 240.0, planes=(100.0, 500.0))
    assert t.bearing_tolerances == pytest.approx((U * 0.6, U * 0.4), rel=1e-12)
    assert t.plane_tolerances == pytest.approx((U * 0.65, U * 0.35), rel=1e-12)


def test_overhung_rotor_bearing_tolerances_are_the_statics_of_u_per_at_the_cog() -> None:
    za, zb, zc = 0.0, 0.5, 0.8
    t = iso_tolerances(100.0, (za, zb), zc)
    ua, ub = bearing_loads_by_statics(100.0, 0.0, zc, zc, za, zb)
    assert t.kind == "overhung"
    assert t.bearing_tolerances == pytest.approx((abs(ua), abs(ub)), rel=1e-12)   # 60, 160
    t2 = iso_tolerances(100.0, (za, zb), zc, planes=(0.7, 0.9))
    worst = worst_over_angles(*t2.plane_tolerances, 0.7, 0.9, za, zb)
    assert np.max(worst / np.array(t2.bearing_tolerances)) == pytest.approx(1.0, rel=1e-9)


def test_narrow_rotor_static_and_couple() -> None:
    """Static S (S/2 in each plane) and couple +-C at b = 0.1 m: at the tolerances,
    at the worst relative angle, each bearing is loaded at most to its tolerance."""
    za, zb, zc, z1, z2 = 0.0, 1.0, 0.5, 0.45, 0.55
    t = iso_tolerances(200.0, (za, zb), zc, (z1, z2), narrow=True)
    assert t.kind == "narrow" and t.plane_tolerances is None
    assert t.static == pytest.approx(100.0, rel=1e-12)            # half of U_per
    assert t.couple == pytest.approx(50.0 * 1.0 / 0.1, rel=1e-12)  # (100 - 50) L / b
    th = np.radians(np.linspace(0.0, 360.0, 1441))
    S, C = t.static, t.couple * np.exp(1j * th)
    ua, ub = bearing_loads_by_statics(S / 2 + C, S / 2 - C, z1, z2, za, zb)
    tol = np.array(t.bearing_tolerances)
    assert max(np.abs(ua).max() / tol[0], np.abs(ub).max() / tol[1]) == pytest.approx(
        1.0, rel=1e-6)
    # the worst-case plane tolerances of the same rotor would be about U_per / 2 each
    wc = iso_tolerances(200.0, (za, zb), zc, (z1, z2))
    assert t.couple > 4 * max(wc.plane_tolerances)


def test_to_bearing_planes_exact_and_worst_case() -> None:
    U1, U2 = 60.0 * np.exp(0.5j), 45.0 * np.exp(4.4j)
    got = to_bearing_planes([U1, U2], (100.0, 500.0), (0.0, 600.0))
    ua, ub = bearing_loads_by_statics(U1, U2, 100.0, 500.0, 0.0, 600.0)
    assert got == pytest.approx([abs(ua), abs(ub)], rel=1e-12)
    worst = to_bearing_planes([60.0, 45.0], (100.0, 500.0), (0.0, 600.0))
    assert worst == pytest.approx(worst_over_angles(60.0, 45.0, 100.0, 500.0, 0.0, 600.0),
                                  rel=1e-9)


@pytest.mark.parametrize("call, text", [
    (lambda: iso_tolerances(1.0, (0.2, 0.2), 0.2), "coincide"),
    (lambda: iso_tolerances(1.0, (0.0, 1.0), 0.5, (0.3, 0.3)), "coincide"),
    (lambda: iso_tolerances(1.0, (0.0, 1.0), 0.5, narrow=True), "narrow"),
    (lambda: iso_tolerances(1.0, (0.0, 1.0), 0.5, (0.4, 0.6), narrow=True,
                            static_share=1.0), "static_share"),
    (lambda: to_bearing_planes([1.0], (0.0, 1.0), (0.0, 1.0)), "one residual"),
])
def test_tolerance_errors(call, text) -> None:
    with pytest.raises(BalanceError) as exc:
        call()
    assert text in str(exc.value) and "\n" not in str(exc.value)
