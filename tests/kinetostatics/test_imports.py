"""A quick start: ``import kinetostatics`` and ``import balance`` load numpy and the
scene model, not pandas, matplotlib, scipy or pymunk (those come with the first table,
picture or simulation that needs them). Not a timing test: it reads sys.modules."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("pandas", "matplotlib", "scipy", "pymunk")


def loaded_after(code: str) -> set[str]:
    probe = (f"{code}\nimport json, sys\n"
             "print(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                         check=True)
    return set(json.loads(out.stdout.splitlines()[-1]))


@pytest.mark.parametrize("package", ["kinetostatics", "balance"])
def test_import_loads_no_heavy_library(package: str) -> None:
    assert loaded_after(f"import {package}") & set(HEAVY) == set()


def test_public_names_still_there() -> None:
    code = ("import kinetostatics as ks, balance\n"
            "assert callable(ks.solve) and callable(ks.solve_many) and ks.Solution\n"
            "assert callable(balance.solve_mechanism_balancing)\n"
            "assert set(ks.__all__) <= set(dir(ks))")
    assert "pandas" in loaded_after(code)      # the names load what they need


def test_solve_out_writes_csv_without_pandas(tmp_path) -> None:
    """``python -m kinetostatics solve SCENE --out DIR`` (every table as CSV): no pandas."""
    code = ("from kinetostatics.cli import main\n"
            f"assert main(['solve', 'four_bar', '--out', {str(tmp_path)!r}]) == 0")
    assert loaded_after(code) & set(HEAVY) == set()
    assert (tmp_path / "dyads.csv").stat().st_size > 0


# (a new interpreter each, 0.3-0.6 s: one in the quick tier)
@pytest.mark.parametrize(("old", "new"), [
    ("output", "results.output"), *(pytest.param(*pair, marks=pytest.mark.slow) for pair in (
        ("csvtext", "results.csvtext"), ("longtable", "results.longtable"),
        ("bench_speed", "bench.speed"), ("bench_tables", "bench.tables")))])
def test_moved_modules_answer_to_their_old_names_with_a_warning(old: str, new: str) -> None:
    """The modules moved into ``results/`` and ``bench/`` keep their old names for a
    release: the same module object, with a DeprecationWarning naming the new one."""
    code = ("import importlib, warnings\n"
            "with warnings.catch_warnings(record=True) as w:\n"
            "    warnings.simplefilter('always')\n"
            f"    old = importlib.import_module('kinetostatics.{old}')\n"
            f"new = importlib.import_module('kinetostatics.{new}')\n"
            "assert old is new and new.__spec__.name == new.__name__, new.__spec__\n"
            "assert [x.category for x in w] == [DeprecationWarning], w\n"
            f"assert 'kinetostatics.{new}' in str(w[0].message)\n")
    subprocess.run([sys.executable, "-c", code], check=True)


@pytest.mark.parametrize(("module", "name"), [("kinetostatics.solver.pipeline", "solve"),
                                              ("kinetostatics.solver.many", "solve_many")])
def test_the_solvers_old_public_names_warn_and_give_the_new(module: str, name: str) -> None:
    """The solver gives arrays now; its old public solve and solve_many are the
    package's (which wrap them in Solutions), with a DeprecationWarning."""
    import importlib
    import warnings

    import kinetostatics as ks
    mod = importlib.import_module(module)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        got = getattr(mod, name)
    assert got is getattr(ks, name)
    assert [x.category for x in w] == [DeprecationWarning] and f"kinetostatics.{name}" in \
        str(w[0].message)
    with pytest.raises(AttributeError):
        mod.no_such_name  # noqa: B018
