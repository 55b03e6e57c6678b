"""Balancing input at the extremes: integer fields bounded by what they index, magnitudes
that would underflow the methods, a mechanism's balancing over the memory budget. Each
is one WorkbenchError line (never a bare ValueError, a MemoryError or inf)."""

from __future__ import annotations

import copy
import math
import tomllib
import warnings
from pathlib import Path

import pytest

import balance
from balance.resonance.methods import parallelogram, trial_runs
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.model.memory import ENV, MemoryBudgetError

SCENES = Path(balance.__file__).parent / "scenes"


def _scene(name: str) -> dict:
    return tomllib.loads((SCENES / f"{name}.toml").read_text())


def _finite(obj) -> bool:
    if isinstance(obj, dict):
        return all(_finite(v) for v in obj.values())
    if isinstance(obj, list | tuple):
        return all(_finite(v) for v in obj)
    return not isinstance(obj, float) or math.isfinite(obj)


@pytest.mark.parametrize("plane", [3, 10**30])
def test_an_influence_plane_beyond_the_planes_is_one_line(plane: int) -> None:
    """plane = 10**30 allocated a list over 1e30 planes (MemoryError) before."""
    d = _scene("influence_two_plane")
    d["influence"][0]["runs"][1]["plane"] = plane
    with pytest.raises(WorkbenchError, match=f"plane {plane:_} does not exist .*2 trial run"):
        balance.solve(d)


def test_a_trim_plane_beyond_the_coefficients_is_one_line() -> None:
    """It was solved as if a second plane existed, silently."""
    d = _scene("trim_run")
    d["influence"][0]["trim"][0]["plane"] = 2
    with pytest.raises(WorkbenchError, match="plane 2 does not exist .*coefficients have 1"):
        balance.solve(d)


def test_split_positions_are_bounded() -> None:
    d = _scene("split_combine")
    d["split"][0]["positions"] = 10**30
    with pytest.raises(WorkbenchError, match="split\\[0\\].positions must be at most 100_000"):
        balance.solve(d)


@pytest.mark.parametrize("value", [1e-308, 5e-324, 1e-61])
@pytest.mark.parametrize("where", ["A1", "runs.0.A", "runs.2.A"])
def test_an_amplitude_that_underflows_is_one_line(where: str, value: float) -> None:
    """A1 = 1e-308 gave 'cannot reshape array of size 0' (a bare ValueError) before."""
    d = _scene("four_run")
    t = d["resonance_test"][0]
    if where == "A1":
        t["A1"] = value
    else:
        t["runs"][int(where.split(".")[1])]["A"] = value
    with pytest.raises(WorkbenchError, match="too small to compute with"):
        balance.solve(d)


def test_the_methods_refuse_underflowing_amplitudes_too() -> None:
    with pytest.raises(WorkbenchError, match="A1 .* too small"):
        trial_runs(1e-308, [(0.0, 184.7), (120.0, 692.4), (240.0, 846.4)], 0.002, 0.06, 0.05)
    with pytest.raises(WorkbenchError, match="too small"):
        parallelogram(1.0, 1e-300, 1.0, 0.002, 0.06, 0.05)


@pytest.mark.parametrize(("name", "path"), [
    ("rotor_two_plane", ("rotor", "planes", 0, "radius")),
    ("static_device", ("static_test", "disk_mass")),
    ("static_device", ("static_test", "alpha")),
    ("four_run", ("resonance_test", 0, "correction_radius")),
    ("iso_tolerance", ("iso", "speed_rpm")),
])
def test_tiny_positive_quantities_are_refused_not_inf(name: str, path: tuple) -> None:
    """A radius of 5e-324 gave an infinite correction mass; an alpha of 5e-324 a
    ZeroDivisionError."""
    d = _scene(name)
    obj = d
    for k in path[:-1]:
        obj = obj[k]
    obj[path[-1]] = 5e-324
    with pytest.raises(WorkbenchError, match="too small to compute with"):
        balance.solve(d)
    obj[path[-1]] = 1e-3           # small but computable: a finite result (a slip warned
    with warnings.catch_warnings():  # of, maybe)
        warnings.simplefilter("ignore")
        out = balance.solve(copy.deepcopy(d))
    assert _finite(out)


def test_bearings_that_coincide_within_rounding_are_one_line() -> None:
    d = _scene("iso_tolerance")
    z = d["iso"]["bearings"][0]
    d["iso"]["bearings"][1] = z + 1e-308
    with pytest.raises(WorkbenchError, match="coincide"):
        balance.solve(d)


def test_a_mechanism_balancing_over_the_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    """count = 1e7 gave 'internal error, please report: MemoryError' under 4 GB before."""
    monkeypatch.setenv(ENV, "1G")
    d = _scene("four_bar_balancing")
    d["driver"]["count"] = 10_000_000
    with pytest.raises(MemoryBudgetError, match="balancing .* 10,000,000 positions"):
        balance.solve(d)
