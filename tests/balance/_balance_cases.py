"""The three shared balancing cases (../shared/cases), embedded so a fresh clone tests them.

Inputs are copies of the ``.toml`` files and the expected numbers copies of the
``.expected.json`` files (reference values from an independent solver), with the
comparison rules of ../shared/cases/README.md: numbers to 1e-9 relative, residuals
(zero) to 1e-12 of the scene's initial unbalance, angles to 1e-7 deg.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

# ../shared/cases beside the checkout (/work/shared/cases), or $WORKBENCH_SHARED/cases
SHARED_CASES = (Path(os.environ["WORKBENCH_SHARED"]) / "cases" if os.environ.get(
    "WORKBENCH_SHARED") else Path(__file__).resolve().parents[3] / "shared" / "cases")
CASE_NAMES = ("rotor_two_plane", "static_device", "resonance_example")

SCENES = {
    "rotor_two_plane": (
        'title = "Rotor with three eccentric masses, dynamic balancing in two planes '
        '(seed 002, eqs 3.9-3.14)"\n'
    ) + """
[rotor]
speed_rpm = 1500                # forces and moments are reported in N and N m

unbalance = [
    { mass = 0.020, radius = 0.10, angle = 30.0, z = 0.05 },
    { mass = 0.015, radius = 0.12, angle = 150.0, z = 0.15 },
    { mass = 0.010, radius = 0.08, angle = 260.0, z = 0.25 },
]

[[rotor.planes]]
z = 0.0
radius = 0.12

[[rotor.planes]]
z = 0.30
radius = 0.12
""",
    "static_device": """
title = "Static balancing device (seed 002, eqs 3.18-3.21)"

[static_test]
disk_mass = 5.0
comparison_mass = 0.05
comparison_radius = 0.10
alpha = 25.0                    # deg, equilibrium angle read on the dial
correction_radius = 0.08
""",
    "resonance_example": """
title = "Resonance-speed amplitude-parallelogram method, plane 1 (seed 002, eqs 3.22-3.31)"
# amplitudes in micrometres, read at resonance during coast-down on a pendulum machine

[[resonance_test]]
plane = 1
trial_mass = 0.002
trial_radius = 0.06
correction_radius = 0.05
A1 = 546.5
A2 = 1071.9
A3 = 495.0
""",
}

# a two-plane influence section (two sensors, one trial run a plane): the base the scene
# tests edit
INFLUENCE_TWO_PLANE = """
[[influence]]
initial = [[170.0, 112.0], [53.0, 78.0]]
runs = [
  { plane = 1, mass = 1.15, angle = 0.0, readings = [[235.0, 94.0], [58.0, 68.0]] },
  { plane = 2, mass = 1.15, angle = 0.0, readings = [[185.0, 115.0], [77.0, 104.0]] },
]
"""

EXPECTED: dict[str, dict[str, Any]] = {
    "rotor_two_plane": {
        "rotor": {
            "corrections": [
                {"plane": 1, "z": 0.0, "radius": 0.12, "mass": 0.010985430183867051,
                 "angle": 240.91555249924863, "U": 0.001318251622064046},
                {"plane": 2, "z": 0.3, "radius": 0.12, "mass": 0.00506518619736897,
                 "angle": 3.7611803496503207, "U": 0.0006078223436842764},
            ],
            "initial_force": 27.454332379967987,
            "initial_moment": 4.499224558730087,
            "residual_force": 6.687904083270987e-16,
            "residual_moment": 0.0,
        }
    },
    "static_device": {
        "static_test": {"eccentricity": 0.002144506920509559,
                        "correction_mass": 0.1340316825318474}
    },
    "resonance_example": {
        "resonance_test": [
            {"plane": 1, "A": 631.137904898763, "phi": 49.06592590293181,
             "unbalance": 0.00010390756044119911, "correction_mass": 0.0020781512088239823,
             "angle": 229.0659259029318, "mirror_angle": 130.9340740970682}
        ]
    },
}

ANGLE_KEYS = {"angle", "mirror_angle", "phi"}
# keys the contract adds beside the expected numbers (the best estimate and the warnings,
# compared by their own tests); a public case must give no warning
OPTIONAL_KEYS = {"estimate", "warnings", "uncertainty", "result_units", "scene_units"}
RESIDUAL_KEYS = {"residual_force", "residual_moment"}


def angle_diff(a: float, b: float) -> float:
    """|a - b| in degrees, across the 0/360 seam."""
    return abs((a - b + 180.0) % 360.0 - 180.0)


def assert_matches(got: Any, want: Any, path: str = "", residual_scale: float = 0.0) -> None:
    """Compare a result dict with an expected one under the cases' tolerances."""
    if isinstance(want, dict):
        assert isinstance(got, dict), path
        extra = set(got) - set(want)
        assert set(want) <= set(got) and extra <= OPTIONAL_KEYS, \
            f"{path}: keys {sorted(got)} != {sorted(want)}"
        assert got.get("warnings", []) == [], f"{path}: warnings {got['warnings']}"
        if "initial_force" in want:   # residuals are compared with the initial unbalance
            residual_scale = max(want["initial_force"], want["initial_moment"])
        for k in want:
            _compare_item(got[k], want[k], f"{path}.{k}", k, residual_scale)
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), path
        for i, (g, w) in enumerate(zip(got, want, strict=True)):
            assert_matches(g, w, f"{path}[{i}]", residual_scale)
    else:
        _compare_item(got, want, path, "", residual_scale)


def _compare_item(got: Any, want: Any, path: str, key: str, residual_scale: float) -> None:
    if isinstance(want, dict | list):
        assert_matches(got, want, path, residual_scale)
    elif want is None:
        assert got is None, path
    elif isinstance(want, bool) or isinstance(want, int) and key == "plane":
        assert got == want, path
    elif key in ANGLE_KEYS:
        assert 0.0 <= got < 360.0, f"{path} = {got} not in [0, 360)"
        assert angle_diff(got, want) <= 1e-7, f"{path}: {got} != {want}"
    elif key in RESIDUAL_KEYS:
        assert abs(got) <= 1e-12 * residual_scale, f"{path}: {got} not ~0"
    else:
        assert math.isclose(got, want, rel_tol=1e-9, abs_tol=0.0), f"{path}: {got} != {want}"
