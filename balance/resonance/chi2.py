"""The chi-square distribution, numpy-free and scipy-free: its CDF and its quantiles.

The CDF of chi-square with k degrees of freedom is the regularised lower incomplete
gamma function P(k/2, x/2), evaluated by its power series for x < a + 1 and by the
continued fraction of Q = 1 - P otherwise (Abramowitz & Stegun 6.5.29 and 6.5.31,
with the modified Lentz algorithm). Quantiles invert the CDF by bisection to full
double precision; they are cached, so the estimates pay for each one once.
"""

from __future__ import annotations

import math
from functools import lru_cache

from ..errors import BalanceError

__all__ = ["chi2_cdf", "chi2_quantile"]

_EPS = 1e-16
_TINY = 1e-300


def _gamma_p(a: float, x: float) -> float:
    """Regularised lower incomplete gamma P(a, x) for a > 0, x >= 0."""
    if x <= 0.0:
        return 0.0
    log_front = a * math.log(x) - x - math.lgamma(a)
    if x < a + 1.0:                     # series: P = e^-x x^a / Gamma(a+1) sum x^n / (a+1)_n
        term = total = 1.0 / a
        ap = a
        for _ in range(10_000):
            ap += 1.0
            term *= x / ap
            total += term
            if abs(term) < abs(total) * _EPS:
                break
        return min(1.0, total * math.exp(log_front))
    # continued fraction for Q(a, x) (modified Lentz)
    b = x + 1.0 - a
    c = 1.0 / _TINY
    d = 1.0 / b
    h = d
    for i in range(1, 10_000):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = _TINY if abs(d) < _TINY else d
        c = b + an / c
        c = _TINY if abs(c) < _TINY else c
        d = 1.0 / d
        step = d * c
        h *= step
        if abs(step - 1.0) < _EPS:
            break
    return max(0.0, 1.0 - math.exp(log_front) * h)


def chi2_cdf(x: float, k: int) -> float:
    """P(X <= x) for X chi-square with ``k`` >= 1 degrees of freedom.

    Examples
    --------
    >>> round(chi2_cdf(3.841458820694124, 1), 12)
    0.95
    """
    if k < 1:
        raise BalanceError(f"chi-square needs at least 1 degree of freedom, got {k}")
    return _gamma_p(0.5 * k, 0.5 * max(float(x), 0.0))


@lru_cache(maxsize=256)
def chi2_quantile(p: float, k: int) -> float:
    """The x with ``chi2_cdf(x, k) = p`` (0 < p < 1), to double precision (bisection).

    Examples
    --------
    >>> round(chi2_quantile(0.95, 1), 9), round(chi2_quantile(0.95, 2), 9)
    (3.841458821, 5.991464547)
    """
    if not 0.0 < p < 1.0:
        raise BalanceError(f"a confidence must lie in (0, 1), got {p:g}")
    lo, hi = 0.0, max(1.0, 2.0 * k)
    while chi2_cdf(hi, k) < p:
        lo, hi = hi, 2.0 * hi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if chi2_cdf(mid, k) < p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)
