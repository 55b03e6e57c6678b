"""The static balancing device (seed 002 fig. 3.9, eqs 3.18-3.21)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from balance import BalanceError, static_device


def test_seed_formulas() -> None:
    r = static_device(5.0, 0.05, 0.10, 25.0, 0.08)
    cot = 1.0 / math.tan(math.radians(25.0))
    assert r.unbalance == pytest.approx(0.05 * 0.10 * cot, rel=1e-14)          # eq. 3.19
    assert r.eccentricity == pytest.approx(0.05 / 5.0 * 0.10 * cot, rel=1e-14)  # eq. 3.20
    assert r.correction_mass == pytest.approx(5.0 * r.eccentricity / 0.08, rel=1e-14)  # 3.21
    assert set(r.to_dict()) == {"eccentricity", "correction_mass"}


@settings(max_examples=200, deadline=None)
@given(st.floats(0.1, 100.0), st.floats(1e-3, 1.0), st.floats(0.01, 0.5),
       st.floats(0.5, 89.5), st.floats(0.01, 0.5))
def test_equilibrium_of_moments(m, mc, rc, alpha, re) -> None:
    """eq. 3.18: the disk's moment m r sin(alpha) balances m_c r_c cos(alpha)."""
    r = static_device(m, mc, rc, alpha, re)
    a = math.radians(alpha)
    assert m * r.eccentricity * math.sin(a) == pytest.approx(mc * rc * math.cos(a), rel=1e-12)
    assert r.correction_mass * re == pytest.approx(m * r.eccentricity, rel=1e-12)


def test_ninety_degrees_means_balanced() -> None:
    r = static_device(5.0, 0.05, 0.10, 90.0, 0.08)
    assert r.eccentricity == 0.0 and r.correction_mass == 0.0


@pytest.mark.parametrize("alpha", [0.0, -10.0, 90.0001, 135.0, float("inf")])
def test_alpha_outside_range_refused(alpha: float) -> None:
    with pytest.raises(BalanceError) as exc:
        static_device(5.0, 0.05, 0.10, alpha, 0.08)
    assert "alpha" in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.parametrize("args", [(0.0, 0.05, 0.1, 25.0, 0.08), (5.0, -0.05, 0.1, 25.0, 0.08),
                                  (5.0, 0.05, 0.0, 25.0, 0.08), (5.0, 0.05, 0.1, 25.0, 0.0)])
def test_non_positive_data_refused(args) -> None:
    with pytest.raises(BalanceError):
        static_device(*args)
