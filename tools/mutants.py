"""Mutation check: every named mutation of a core formula fails a quick-tier test.

Each mutant is a small edit of the source (a sign flipped, a term left out, a unit
confused) that a wrong derivation or a slip of the pen would make. The script copies the
source tree to a temporary folder, applies one mutant at a time to the copy (the checkout
is never touched), runs the quick tier there (``python -m pytest -m "not slow" -x``, by
default only the test folders of the mutant's package) and reports each mutant as
``killed`` (a test failed: which one) or ``survived``. Before the mutants, the same tests
run on the unmutated copy and must pass (else a "kill" would mean nothing).

Usage (from the repository's root)::

    python tools/mutants.py                 # every mutant, its package's quick tests
    python tools/mutants.py --list          # the mutants and where they edit
    python tools/mutants.py --only coriolis-slider --only inertia-sign
    python tools/mutants.py --killers       # cheap: only the tests named to kill each
    python tools/mutants.py --everywhere    # the whole quick tier for each mutant

Exit code 0 when every mutant is killed, 1 when one survives, 2 when a mutant's edit no
longer matches the source (the formula moved: update its entry here).
"""

from __future__ import annotations

import argparse
import gc
import importlib
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
QUICK = ["-m", "not slow", "-x", "-q", "-p", "no:cacheprovider", "-p", "no:xdist",
         "-rf", "--no-header"]
SOLVER_TESTS = ("tests/kinetostatics/solver", "tests/kinetostatics/test_invariance.py")
BALANCE_TESTS = ("tests/balance",)
_S = "tests/kinetostatics/solver/"


@dataclass(frozen=True)
class Mutant:
    """One mutation: ``edits`` (old, new) in ``path``, each old text found exactly once;
    ``tests``: where the quick tier looks for it; ``killers``: quick tests known to
    kill it (the cheap run)."""

    name: str
    what: str
    path: str
    edits: tuple[tuple[str, str], ...]
    tests: tuple[str, ...]
    killers: tuple[str, ...]


MUTANTS = (
    Mutant("inertia-sign",
           "the inertia force +m a_G instead of -m a_G (seed 002 eq. 2.1)",
           "kinetostatics/solver/loads.py",
           (("neg = -body.mass", "neg = body.mass"),),
           SOLVER_TESTS,
           (_S + "test_cases.py::test_case_matches_expected[own-four_bar]",)),
    Mutant("coriolis-slider",
           "the Coriolis term 2 omega_g rdot of a slider on a turning guide left out "
           "(seed 001 eq. 8)",
           "kinetostatics/solver/kinematics.py",
           (("r2 = A.sub(A.mul(2.0 * sgn, A.mul(om_g, rdot)),",
             "r2 = A.sub(A.mul(0.0 * sgn, A.mul(om_g, rdot)),"),),
           SOLVER_TESTS,
           (_S + "test_cases.py::test_case_matches_expected[own-slotted_lever]",)),
    Mutant("coriolis-guide",
           "the Coriolis term 2 omega_K x v_rel of a body sliding on a moving guide left "
           "out (seed 001 eq. 8)",
           "kinetostatics/solver/kinematics.py",
           (("f = A.mul(2.0 * p.known.omega, qd[i])", "f = A.mul(0.0 * p.known.omega, qd[i])"),),
           SOLVER_TESTS,
           (_S + "test_checks.py::test_finite_differences[trt_slotted_crank]",)),
    Mutant("assembly-branch",
           "the assembly k = +-1 whose hinted points lie farthest (seed 000 eq. 5.1)",
           "kinetostatics/solver/assembly.py",
           (("return 1 if dist[1] < dist[-1] else -1", "return -1 if dist[1] < dist[-1] else 1"),),
           SOLVER_TESTS,
           (_S + "test_assembly.py::test_structure_carries_the_assembly",)),
    Mutant("reduced-degrees",
           "the reduced moment read at a unit speed of 1 deg/s instead of 1 rad/s "
           "(seed 002 eqs 2.71-2.75)",
           "kinetostatics/solver/reduction.py",
           (("replace(drv, speed=1.0, acceleration=0.0)",
             "replace(drv, speed=np.pi / 180.0, acceleration=0.0)"),),
           SOLVER_TESTS,
           (_S + "test_reduction.py::test_reduced_moments_add_up_to_minus_me"
            "[0.0-5.0-four_bar]",)),
    Mutant("influence-trial",
           "the influence coefficients (V_k - V_0) without dividing by the trial mass "
           "T_k (alpha = (V_k - V_0) / T_k)",
           "balance/field/influence.py",
           (("np.linalg.pinv(d.T) @ dV", "np.linalg.pinv((d.T != 0).astype(complex)) @ dV"),),
           BALANCE_TESTS,
           ("tests/balance/test_influence.py::test_published_two_plane_case",)),
    Mutant("parallelogram-diagonal",
           "the amplitude parallelogram's diagonals with A1^2 once instead of twice "
           "(seed 002 eq. 3.29)",
           "balance/resonance/methods.py",
           (("A_sq = (A2**2 + A3**2 - 2.0 * A1**2) / 2.0",
             "A_sq = (A2**2 + A3**2 - A1**2) / 2.0"),),
           BALANCE_TESTS,
           # the published case (not the property test of the method, whose failure
           # Hypothesis shrinks: 4.5 s of CPU against 1.3 s)
           ("tests/balance/test_balance_cases.py::test_embedded_case[resonance_example]",)),
)


def copy_tree(dest: Path) -> Path:
    """The checkout's files (sources, tests, notebooks, data) copied to ``dest``."""
    tree = dest / "tree"
    shutil.copytree(ROOT, tree, ignore=shutil.ignore_patterns(
        ".git", "__pycache__", "*.egg-info", ".venv", ".pytest_cache", ".hypothesis",
        ".ruff_cache", "build", "dist"))
    return tree


def mutate(text: str, m: Mutant) -> str:
    """``text`` with the mutant's edits; SystemExit(2) where an edit no longer matches."""
    for old, new in m.edits:
        if text.count(old) != 1:
            print(f"error: mutant {m.name}: {old!r} found {text.count(old)} times in {m.path} "
                  "(expected once): update tools/mutants.py", file=sys.stderr)
            raise SystemExit(2)
        text = text.replace(old, new)
    return text


#: Libraries the tests import, loaded once in this process before it forks a run (each
#: run then imports only the project, from the tree it tests): a run costs its tests,
#: not a new interpreter's start (about 9 s of CPU each).
WARM = ("numpy", "scipy.optimize", "scipy.integrate", "scipy.linalg", "scipy.stats",
        "pandas", "matplotlib.pyplot", "hypothesis", "pytest", "xdist", "nbformat",
        "nbclient", "jupyter_client", "pyarrow", "numba", "pint")
#: Those the killers' runs import (tests/conftest.py's and the project's): scipy's
#: solvers and pint are left out (1.6 s of CPU, measured 2026-11-30).
WARM_KILLERS = tuple(n for n in WARM if not n.startswith("scipy.") and n != "pint")


def _environment(tree: Path) -> dict[str, str]:
    return {"PYTHONPATH": os.pathsep.join(
        [str(tree), *filter(None, [os.environ.get("PYTHONPATH")])]),
        "MPLBACKEND": "Agg"}


def warm(names: tuple[str, ...] = WARM) -> None:
    """Import ``names`` here (those installed), never the project; then freeze the
    collector's view of them (gc.freeze): each run's collections (pytest's several at
    its end) walk only what the run made, not the libraries (0.5 s of CPU a run)."""
    os.environ["MPLBACKEND"] = "Agg"
    for name in names:
        try:
            importlib.import_module(name)
        except ImportError:
            continue
    gc.collect()
    gc.freeze()


def forget_bytecode(path: Path) -> None:
    """Remove the cached bytecode of ``path`` in the copied tree. The runs cache the
    tree's bytecode (the first run compiles it, the others read it: 0.7 s of CPU a run),
    which Python checks by the source's modification time (whole seconds) and size: a
    mutant of the same size written within the same second would run the cached
    original. So the mutated module's bytecode goes before and after each mutant."""
    cached = Path(importlib.util.cache_from_source(str(path)))
    cached.unlink(missing_ok=True)


def _run_forked(tree: Path, targets: list[str]) -> int:
    """pytest on ``targets`` in a child forked from this process, its output on fd 1;
    the child's exit code."""
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:                        # the child: the tree first on the path
        code = 3
        try:
            os.dup2(1, 2)
            os.chdir(tree)
            os.environ.update(_environment(tree))
            sys.path.insert(0, str(tree))
            import pytest
            code = int(pytest.main([*QUICK, *targets]))
        except BaseException:           # noqa: BLE001 (reported, then the child ends)
            traceback.print_exc()
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(code)
    return os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])


def run_tests(tree: Path, targets: list[str]) -> tuple[int, str, float]:
    """Run the quick tier on ``targets`` in ``tree``: (exit code, output, seconds). Where
    the system forks, in a child of this process (:func:`warm` first); else in a new
    interpreter."""
    t0 = time.perf_counter()
    if not hasattr(os, "fork"):
        out = subprocess.run([sys.executable, "-m", "pytest", *QUICK, *targets], cwd=tree,
                             env=dict(os.environ, **_environment(tree)), capture_output=True,
                             text=True)
        return out.returncode, out.stdout + out.stderr, time.perf_counter() - t0
    with tempfile.TemporaryFile() as log:
        saved = os.dup(1)
        os.dup2(log.fileno(), 1)
        try:
            code = _run_forked(tree, targets)
        finally:
            os.dup2(saved, 1)
            os.close(saved)
        log.seek(0)
        return code, log.read().decode(errors="replace"), time.perf_counter() - t0


def first_failure(output: str) -> str:
    """The first failed test's id (pytest's short summary line)."""
    m = re.search(r"^(?:FAILED|ERROR) (\S+)", output, re.MULTILINE)
    return m.group(1) if m else "?"


def targets_of(m: Mutant, how: str) -> list[str]:
    if how == "killers":
        return list(m.killers)
    return ["tests"] if how == "everywhere" else list(m.tests)


def check(mutants: list[Mutant], how: str, baseline: bool = True) -> int:
    """Run the baseline and every mutant; print one line each; the exit code."""
    if hasattr(os, "fork"):
        warm(WARM_KILLERS if how == "killers" else WARM)
    with tempfile.TemporaryDirectory(prefix="mutants-") as tmp:
        tree = copy_tree(Path(tmp))
        if baseline:
            targets = sorted({t for m in mutants for t in targets_of(m, how)})
            code, output, sec = run_tests(tree, targets)
            if code != 0:
                print(f"error: the unmutated tree fails its quick tests ({sec:.0f} s):\n"
                      f"{output[-3000:]}", file=sys.stderr)
                return 2
            print(f"{'baseline':24s} passes    {sec:6.1f} s  {' '.join(targets)}")
        survivors = 0
        for m in mutants:
            path = tree / m.path
            original = path.read_text(encoding="utf-8")
            path.write_text(mutate(original, m), encoding="utf-8")
            forget_bytecode(path)
            try:
                code, output, sec = run_tests(tree, targets_of(m, how))
            finally:
                path.write_text(original, encoding="utf-8")
                forget_bytecode(path)
            if code == 1:
                verdict = f"killed    {sec:6.1f} s  by {first_failure(output)}"
            else:
                survivors += 1
                verdict = (f"survived  {sec:6.1f} s" if code == 0 else
                           f"error     {sec:6.1f} s  pytest exit code {code}:\n{output[-2000:]}")
            print(f"{m.name:24s} {verdict}", flush=True)
    print(f"{len(mutants) - survivors} of {len(mutants)} mutants killed by the quick tier")
    return 1 if survivors else 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--only", action="append", metavar="NAME", help="run this mutant (repeat)")
    ap.add_argument("--killers", action="store_true",
                    help="run only the tests named to kill each mutant (cheap)")
    ap.add_argument("--everywhere", action="store_true",
                    help="run the whole quick tier for each mutant")
    ap.add_argument("--no-baseline", action="store_true",
                    help="skip the run of the unmutated tree")
    args = ap.parse_args(argv)
    names = {m.name: m for m in MUTANTS}
    if args.list:
        for m in MUTANTS:
            print(f"{m.name:24s} {m.path}: {m.what}")
        return 0
    unknown = [n for n in args.only or [] if n not in names]
    if unknown:
        print(f"error: no mutant {unknown[0]!r} (see --list)", file=sys.stderr)
        return 2
    chosen = [names[n] for n in args.only] if args.only else list(MUTANTS)
    how = "killers" if args.killers else "everywhere" if args.everywhere else "package"
    return check(chosen, how, baseline=not args.no_baseline)


if __name__ == "__main__":
    sys.exit(main())
