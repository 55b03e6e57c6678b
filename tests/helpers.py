"""Shared test helpers: where the cases are, and the contract's comparison rule."""

from __future__ import annotations

import contextlib
import importlib
import io
import json
import os
import subprocess
import warnings
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
OWN_CASES = DATA / "cases"
SCENES = DATA / "scenes"


def shared_cases() -> Path | None:
    """``../shared/cases`` beside the checkout (or $WORKBENCH_SHARED/cases), if present."""
    env = os.environ.get("WORKBENCH_SHARED")
    for base in ([Path(env)] if env else []) + [ROOT.parent / "shared"]:
        if (base / "cases").is_dir():
            return base / "cases"
    return None


MECHANISM_CASES = ["four_bar", "slider_crank", "slotted_lever", "scotch_yoke", "sliding_driver"]


def case_sources():
    """(id, scene path, expected csv path) for our own copies and the shared ones."""
    out = []
    for name in MECHANISM_CASES:
        out.append((f"own-{name}", OWN_CASES / f"{name}.toml", OWN_CASES / f"{name}.expected.csv"))
    shared = shared_cases()
    if shared is not None:
        for name in MECHANISM_CASES:
            if (shared / f"{name}.toml").is_file():
                out.append((f"shared-{name}", shared / f"{name}.toml",
                            shared / f"{name}.expected.csv"))
    return out


KIND = {"Me": "moment", "M": "moment", "Fe": "force", "F": "force", "N": "force",
        "x": "length", "y": "length", "offset": "length", "vx": "velocity", "vy": "velocity",
        "ax": "acceleration", "ay": "acceleration", "angle": "angle", "omega": "omega",
        "alpha": "alpha"}


def split_quantity(q: str) -> tuple[str, str, str]:
    """'F[A]x' -> ('F', 'A', 'x'); 'x[crank.B]' -> ('x', 'crank.B', ''); 'Me' -> ('Me','','')."""
    if "[" not in q:
        return q, "", ""
    head, rest = q.split("[", 1)
    arg, tail = rest.split("]", 1)
    return head, arg, tail


def lookup(sol, quantity: str, positions: np.ndarray) -> np.ndarray:
    """The solution's value of an expected-file quantity at the given positions."""
    head, arg, tail = split_quantity(quantity)
    pos = sol.positions
    idx = np.array([int(np.argmin(np.abs(pos - p))) for p in positions])
    assert np.allclose(pos[idx], positions, atol=1e-9), "expected positions not in the sweep"
    if head in ("Me", "Fe"):
        return sol.driver[head].to_numpy()[idx]
    if head in ("F", "N", "M", "offset"):
        r = sol.reactions
        sub = r[r.joint == arg]
        col = "F" + tail if head == "F" else head
        return sub[col].to_numpy()[idx]
    if head in ("angle", "omega", "alpha"):
        b = sol.bodies
        return b[b.body == arg][head].to_numpy()[idx]
    body, point = arg.split(".", 1)
    k = sol.kinematics
    return k[(k.body == body) & (k.point == point)][head].to_numpy()[idx]


def compare_case(sol, expected_csv: Path, rel: float = 1e-9) -> dict[str, float]:
    """Errors per quantity by the cases/README rule; returns {quantity: error/scale}."""
    exp = pd.read_csv(expected_csv)
    kind_max: dict[str, float] = {}
    for q, g in exp.groupby("quantity"):
        k = KIND[split_quantity(q)[0]]
        kind_max[k] = max(kind_max.get(k, 0.0), float(np.abs(g.value).max()))
    errors = {}
    for q, g in exp.groupby("quantity"):
        head = split_quantity(q)[0]
        got = lookup(sol, q, g.position.to_numpy())
        want = g.value.to_numpy()
        scale = max(float(np.abs(want).max()), 1e-3 * kind_max[KIND[head]], 1e-12)
        if head == "angle":
            diff = (got - want + 180.0) % 360.0 - 180.0
        else:
            diff = got - want
        errors[q] = float(np.abs(diff).max() / scale)
    return errors


def to_toml(d: dict) -> str:
    """A minimal TOML writer for the test scenes (tables, arrays of tables, inline)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{json.dumps(k)} = {val(x)}" for k, x in v.items()) + " }"
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return repr(float(v)) if isinstance(v, float) else str(v)
    lines = []
    for k, v in d.items():
        if not isinstance(v, dict | list) or (isinstance(v, list) and not
                                              (v and isinstance(v[0], dict))):
            lines.append(f"{k} = {val(v)}")
    for k, v in d.items():
        if isinstance(v, dict):
            lines.append(f"[{k}]")
            lines += [f"{json.dumps(a)} = {val(b)}" for a, b in v.items()]
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                lines.append(f"[[{k}]]")
                lines += [f"{a} = {val(b)}" for a, b in item.items()]
    return "\n".join(lines) + "\n"


def run_main(package: str, *args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    """``python -m <package> <args>`` run in this process, through the package's
    ``main``: (exit code, stdout, stderr) as :func:`subprocess.run` gives them.

    A command line in a subprocess costs 1.5 s of CPU to import numpy, pandas and
    matplotlib again; in the process it costs only its own work. One test per command line
    keeps the subprocess (the ``python -m`` entry itself). The working folder, the
    environment (``--memory`` sets a variable), matplotlib's settings and the warning
    filters are restored afterwards."""
    module = {"kinetostatics": "kinetostatics.cli", "balance": "balance.__main__"}[package]
    main = importlib.import_module(module).main
    out, err = io.StringIO(), io.StringIO()
    env = dict(os.environ)
    with contextlib.ExitStack() as stack:
        stack.enter_context(matplotlib.rc_context())
        stack.enter_context(contextlib.chdir(cwd or ROOT))
        stack.enter_context(contextlib.redirect_stdout(out))
        stack.enter_context(contextlib.redirect_stderr(err))
        stack.enter_context(warnings.catch_warnings())
        try:
            code = main(list(map(str, args)))
        except SystemExit as exc:          # argparse's mistakes and --help
            code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        finally:
            os.environ.clear()
            os.environ.update(env)
    return subprocess.CompletedProcess([package, *args], code, out.getvalue(), err.getvalue())
