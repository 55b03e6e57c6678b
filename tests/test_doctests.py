"""Every docstring example of both packages runs and holds: one runner over every module
whose source holds an example (``>>>``), found by reading the files (no hand list to
forget a module in), each module asserted to run at least one example."""

from __future__ import annotations

import doctest
import importlib

import pytest

from tests.helpers import ROOT

PACKAGES = ("kinetostatics", "balance")


def modules_with_examples() -> list[str]:
    """Dotted names of the packages' modules whose source holds ``>>>``."""
    names = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            if ">>>" in path.read_text(encoding="utf-8"):
                parts = path.relative_to(ROOT).with_suffix("").parts
                if parts[-1] == "__init__":
                    parts = parts[:-1]
                names.append(".".join(parts))
    return names


MODULES = modules_with_examples()


def test_the_examples_are_found():
    """The finder sees the modules known to hold examples, in both packages (so that a
    broken finder cannot make the runner below pass on nothing)."""
    assert {"kinetostatics.model.units", "kinetostatics.simulation.runner",
            "balance.machine.pivot", "balance.rotor.design", "balance.field.weights",
            "balance.resonance.chi2"} <= set(MODULES)
    assert len(MODULES) >= 15


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    module = importlib.import_module(name)
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    for test in finder.find(module, name):
        runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.attempted > 0, f"{name} has '>>>' but no example was collected"
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples failed"
