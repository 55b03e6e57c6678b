"""Unit slips named by rule (kinetostatics.teaching.slips), without a kernel."""

from __future__ import annotations

import math

import numpy as np

from kinetostatics.teaching.slips import slip_note


def test_radians_for_degrees_is_named_modulo_a_turn() -> None:
    assert slip_note("angle_x", "deg", "angle", math.radians(75.94), 75.94, 0.5) == \
        "pi/180 x the key: rad instead of deg?"
    assert "rad instead of deg" in slip_note("angle_x", "deg", "angle",
                                             math.radians(75.94 - 360.0), 75.94, 0.5)


def test_a_degree_answer_merely_off_is_no_slip() -> None:
    """An answer 5 % off an angle key is wrong, not a slip: times 180/pi it wraps onto the
    key every 360/59.16 deg, which named 39 of these keys a slip before the answer had
    to look like radians."""
    keys = 360.0 / 59.16 * np.arange(1, 40)
    assert [k for k in keys if slip_note("angle_x", "deg", "angle", 1.05 * k, k, 0.5)] == []


def test_newton_millimetres_for_newton_metres() -> None:
    assert slip_note("Me@60", "N m", "number", 300800.0, 300.8, 0.01 * 300.8).startswith(
        "1000x the key")
