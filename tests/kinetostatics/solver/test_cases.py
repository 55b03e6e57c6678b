"""The example scenes against their expected values (cases/README rule: 1e-9 of the scale).

Our own copies in tests/data/cases always run; ../shared/cases runs too when present.
"""

import numpy as np
import pytest

import kinetostatics as ks
from tests.helpers import case_sources, compare_case

CASES = case_sources()


@pytest.mark.parametrize("name,scene,expected", CASES, ids=[c[0] for c in CASES])
def test_case_matches_expected(name, scene, expected):
    sol = ks.solve(scene)
    errors = compare_case(sol, expected)
    worst = max(errors, key=errors.get)
    assert errors[worst] <= 1e-9, f"{name}: {worst} off by {errors[worst]:.2e} of its scale"
    kinds = {q.split("[")[0] for q in errors}
    assert {"x", "vx", "ax", "angle", "omega", "alpha"} <= kinds


@pytest.mark.parametrize("name,scene,expected", CASES[:5], ids=[c[0] for c in CASES[:5]])
def test_tables_are_finite(name, scene, expected):
    sol = ks.solve(scene)
    for table in (sol.driver, sol.kinematics, sol.bodies, sol.dyads, sol.frame):
        num = table.select_dtypes("number")
        assert np.isfinite(num.to_numpy()).all()
    r = sol.reactions.drop(columns="offset")
    assert np.isfinite(r.select_dtypes("number").to_numpy()).all()


def test_bundled_examples_are_the_cases():
    """The package ships the case scenes used by the README's demo."""
    assert {"four_bar", "slider_crank", "slotted_lever", "scotch_yoke", "sliding_driver",
            "shaper"} <= set(ks.examples())
