"""ISO 21940-11 balance quality."""

from __future__ import annotations

import math

import pytest

from balance import (
    BalanceError,
    iso_allocate,
    iso_check,
    iso_permissible_unbalance,
    kgm_to_gmm,
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
