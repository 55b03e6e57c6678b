"""The quick tier still catches the named mutations of the core formulas
(``tools/mutants.py``): each mutant, applied to a copy of the tree, fails the quick tests
named to kill it, and the unmutated copy passes them."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.helpers import ROOT


def test_every_mutant_has_an_edit_that_matches_the_source() -> None:
    """Each mutant's old text is found exactly once where it points (a formula that moved
    must move its mutant too), and the mutated text differs."""
    sys.path.insert(0, str(ROOT / "tools"))
    try:
        import mutants
    finally:
        sys.path.remove(str(ROOT / "tools"))
    assert len(mutants.MUTANTS) >= 6
    for m in mutants.MUTANTS:
        text = (ROOT / m.path).read_text(encoding="utf-8")
        assert mutants.mutate(text, m) != text, m.name


@pytest.mark.slow
def test_every_mutant_is_killed_by_a_quick_test() -> None:
    out = subprocess.run([sys.executable, str(ROOT / "tools" / "mutants.py"), "--killers"],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stdout + out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith("baseline") and "passes" in lines[0], out.stdout
    killed = [ln for ln in lines if " killed " in ln]
    assert len(killed) >= 6 and not [ln for ln in lines if "survived" in ln], out.stdout
