"""Rotors balanced by design (seed 002 s. 3.2: one or two correction planes) and the
static balancing device (fig. 3.9, eqs 3.18-3.21)."""

from __future__ import annotations

from .design import (
    Correction,
    CorrectionPlane,
    RotorResult,
    Unbalance,
    balance_rotor,
)
from .static_device import (
    StaticDeviceResult,
    static_device,
)

__all__ = [
    "Correction",
    "CorrectionPlane",
    "RotorResult",
    "StaticDeviceResult",
    "Unbalance",
    "balance_rotor",
    "static_device",
]
