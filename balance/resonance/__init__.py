"""Balancing from vibration amplitudes at resonance (seed 002 s. 3.3.2): the
amplitude parallelogram and any trial runs (:mod:`~balance.resonance.methods`), the
maximum-likelihood estimate beside them (:mod:`~balance.resonance.estimate`, fitted by
:mod:`~balance.resonance.amplitude_fit`) and the chi-square quantiles it needs
(:mod:`~balance.resonance.chi2`)."""

from __future__ import annotations

from .chi2 import (
    chi2_cdf,
    chi2_quantile,
)
from .estimate import (
    Estimate,
    estimate,
)
from .methods import (
    COS_TOLERANCE,
    ResonanceResult,
    four_run,
    parallelogram,
    trial_runs,
)

__all__ = [
    "COS_TOLERANCE",
    "Estimate",
    "ResonanceResult",
    "chi2_cdf",
    "chi2_quantile",
    "estimate",
    "four_run",
    "parallelogram",
    "trial_runs",
]
