"""A mutation fuzzer over every bundled scene kind (slow tier).

Each bundled scene (mechanisms, the motion scene, cams, balancing scenes) is mutated by
hypothesis: a key deleted, a value of the wrong type, NaN, inf, huge, negative, zero or
tiny numbers, a name that points nowhere, a list entry repeated, a unit swapped or made
up. Through the API each must end in a finite result or one ``WorkbenchError`` line;
through the command line (a sample) in exit 0, or one ``error:`` line with exit 2, and
an output folder whole or absent. Never a traceback, an internal error, a memory error
or a half-written folder. The memory budget is set low, so that a mutated count or
number of cycles is refused in one line instead of run.
"""

from __future__ import annotations

import copy
import math
import os
import subprocess
import sys
import tomllib
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import balance  # noqa: E402
import kinetostatics as ks  # noqa: E402
from kinetostatics.cams import solve_cam  # noqa: E402
from kinetostatics.model.memory import ENV  # noqa: E402
from kinetostatics.model.outputs import PARTIAL, STAGING  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
BUDGET = "400M"         # a mutated count of 1e7 is refused, the bundled sizes run
MECHANISMS = sorted((ROOT / "kinetostatics" / "scenes").glob("*.toml"))
CAMS = sorted((ROOT / "kinetostatics" / "scenes" / "cams").glob("*.toml"))
BALANCING = sorted((ROOT / "balance" / "scenes").glob("*.toml"))
SCENES = [("mechanism", p) for p in MECHANISMS] + [("cam", p) for p in CAMS] + [
    ("balance", p) for p in BALANCING]

ODD = ["x", "", [], {}, True, None, [1.0, 2.0, 3.0], {"a": 1}]
NUMBERS = [math.nan, math.inf, -math.inf, 1e300, -1e300, 1e12, 0.0, -1.0, 1e-308, 5e-324,
           10**30, 10_000_000, -7]
UNITS = ["furlong", "mm", "km", "g", "t", "rpm", "rad", "um", "in", 3]

pytestmark = pytest.mark.slow


def _paths(obj: Any, path: tuple = ()) -> list[tuple]:
    """Every place in a scene: keys of tables and entries of lists, depth first."""
    out = [path] if path else []
    if isinstance(obj, dict):
        for k, v in obj.items():
            out += _paths(v, (*path, k))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            out += _paths(v, (*path, i))
    return out


def _get(obj: Any, path: tuple) -> Any:
    for k in path:
        obj = obj[k]
    return obj


@st.composite
def mutated(draw, raw: dict) -> dict:
    """``raw`` with one to three mutations."""
    d = copy.deepcopy(raw)
    for _ in range(draw(st.integers(1, 3))):
        paths = _paths(d)
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        parent, key = _get(d, path[:-1]), path[-1]
        value = parent[key]
        kind = draw(st.sampled_from(["delete", "type", "number", "name", "repeat", "unit"]))
        if kind == "delete":
            del parent[key]
        elif kind == "type":
            parent[key] = copy.deepcopy(draw(st.sampled_from(ODD)))
        elif kind == "number":
            base = value if isinstance(value, int | float) and not isinstance(value, bool) \
                else 1.0
            parent[key] = draw(st.sampled_from(NUMBERS + [-base, base * 1e6, base * 1e-6]))
        elif kind == "name":
            parent[key] = draw(st.sampled_from(["nowhere", "A", "crank", "bearing A"]))
        elif kind == "repeat" and isinstance(value, list) and value:
            value.append(copy.deepcopy(value[draw(st.integers(0, len(value) - 1))]))
        elif kind == "unit":
            parent[key] = draw(st.sampled_from(UNITS))
    return d


def _finite(obj: Any) -> bool:
    if isinstance(obj, dict):
        return all(_finite(v) for v in obj.values())
    if isinstance(obj, list | tuple):
        return all(_finite(v) for v in obj)
    if isinstance(obj, np.ndarray) and obj.dtype.kind in "fc":
        return bool(np.isfinite(obj).all())
    if isinstance(obj, float | np.floating):
        return math.isfinite(obj)
    return True


def run_api(kind: str, d: dict) -> Any:
    """The scene through its API: a result to check for finiteness."""
    if kind == "cam":
        return solve_cam(d).summary
    if kind == "balance":
        return balance.solve(d)
    out = ks.solve(d).summary()
    if "motion" in d:
        out["motion"] = ks.simulate_motion(d).summary
    if "balancing" in d:
        out["balancing"] = balance.solve(d)
    return out


def check_api(kind: str, d: dict) -> str:
    """'ok' or 'refused'; anything else fails the test with what happened."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = run_api(kind, d)
    except ks.WorkbenchError as exc:
        text = str(exc)
        assert "\n" not in text.strip() and "internal error" not in text, text
        return "refused"
    assert _finite(out), out
    return "ok"


@pytest.fixture(autouse=True)
def _low_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(ENV, BUDGET)


@pytest.mark.parametrize(("kind", "path"), SCENES, ids=[p.stem for _, p in SCENES])
def test_mutated_scenes_through_the_api(kind: str, path: Path) -> None:
    raw = tomllib.loads(path.read_text())

    @settings(max_examples=60, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(mutated(raw))
    def check(d: dict) -> None:
        check_api(kind, d)

    check()


def _toml(obj: Any) -> str:
    """A mutated scene written back as TOML (inline tables; None as a missing key)."""
    def value(v: Any) -> str:
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, float):
            return {math.inf: "inf", -math.inf: "-inf"}.get(v, "nan" if v != v else repr(v))
        if isinstance(v, int | str):
            return str(v) if isinstance(v, int) else '"' + v.replace('"', "") + '"'
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v if x is not None) + "]"
        return "{" + ", ".join(f'"{k}" = {value(x)}' for k, x in v.items()
                               if x is not None) + "}"
    return "\n".join(f'"{k}" = {value(v)}' for k, v in obj.items() if v is not None) + "\n"


COMMANDS = {"mechanism": ["-m", "kinetostatics", "solve"], "cam": ["-m", "kinetostatics", "cam"],
            "balance": ["-m", "balance", "solve"]}


@pytest.mark.parametrize(("kind", "path"), [SCENES[0], SCENES[len(MECHANISMS)],
                                            SCENES[-3]], ids=["mechanism", "cam", "balance"])
def test_a_sample_through_the_command_line(kind: str, path: Path, tmp_path: Path) -> None:
    raw = tomllib.loads(path.read_text())
    env = dict(os.environ, MPLBACKEND="Agg", **{ENV: BUDGET})
    seen = []

    @settings(max_examples=8, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(mutated(raw))
    def check(d: dict) -> None:
        scene = tmp_path / "scene.toml"
        scene.write_text(_toml(d))
        out = tmp_path / f"out{len(seen)}"
        args = ["--report", str(out / "report.html")] if kind == "balance" \
            else ["--out", str(out)]
        r = subprocess.run([sys.executable, *COMMANDS[kind], str(scene), *args],
                           capture_output=True, text=True, cwd=ROOT, env=env, timeout=300)
        seen.append(r.returncode)
        assert "Traceback" not in r.stderr and "internal error" not in r.stderr, r.stderr
        errors = [ln for ln in r.stderr.splitlines() if ln.startswith("error:")]
        if r.returncode == 0:
            assert not errors and out.is_dir()
            names = {p.name for p in out.iterdir()}
            assert "summary.json" in names or "report.html" in names, names
        else:
            assert r.returncode == 2 and len(errors) == 1, r.stderr
            assert not out.exists()
        if out.exists():
            assert not [p for p in out.iterdir() if p.name.startswith((STAGING, PARTIAL))]

    check()
    assert seen
