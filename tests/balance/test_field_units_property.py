"""Issue 30, property: a random field-balancing scene ([[influence]] with trims, [iso],
[[split]], [[combine]]; some draws slipped: a trial mass in g typed as kg, phases in
radians) typed in other units gives the same warnings, by field and rule, and the same
numbers in SI (the field sections answer in the scene's masses, converted back here)."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from tests.kinetostatics.model.test_twins_every_kind import (
    SYSTEMS,
    balancing_in,
    balancing_slips,
    si_numbers,
)


@st.composite
def field_scenes(draw) -> dict:
    """A one-plane influence section with a trim run, an [iso] rotor, a split and a
    combine, all SI (kg, m, degrees)."""
    trial = draw(st.floats(1e-4, 0.5))
    if draw(st.booleans()):
        trial *= 1000.0                               # grams typed as kilograms
    a0, p0 = draw(st.floats(1.0, 50.0)), draw(st.floats(0.0, 359.0))
    a1, p1 = draw(st.floats(0.5, 50.0)), draw(st.floats(0.0, 359.0))
    if draw(st.booleans()):
        p0, p1 = math.radians(p0), math.radians(p1)   # radians typed for degrees
    rotor = draw(st.sampled_from([0.5, 12.0, 500.0, 4000.0]))
    return {
        "influence": [{"initial": [[a0, p0]], "trial_radius": 0.1, "correction_radius": 0.08,
                       "runs": [{"plane": 1, "mass": trial, "angle": 0.0,
                                 "readings": [[a1, p1]]}],
                       "trim": [{"plane": 1, "mass": trial / 10.0, "angle": 30.0,
                                 "readings": [[a0 / 20.0, p0]]}]}],
        "iso": {"rotor_mass": rotor, "grade": 6.3, "speed_rpm": 3000.0,
                "bearings": [0.0, 0.4], "cog": draw(st.floats(0.15, 0.25))},
        "split": [{"mass": draw(st.floats(1e-4, 0.5)), "angle": draw(st.floats(0.0, 359.0)),
                   "positions": draw(st.integers(3, 24))}],
        "combine": [{"weights": [{"mass": draw(st.floats(1e-4, 0.5)), "angle": 10.0},
                                 {"mass": draw(st.floats(1e-4, 0.5)), "angle": 70.0}]}],
    }


@settings(max_examples=40, deadline=None)
@given(si=field_scenes(), system=st.sampled_from(sorted(SYSTEMS)))
def test_a_field_scene_in_other_units_gives_the_same_warnings_and_numbers(si, system) -> None:
    import warnings

    from balance import solve
    from balance.errors import BalanceWarning
    from tests.kinetostatics.model.test_slips_property import close

    typed = balancing_in(si, SYSTEMS[system])
    assert balancing_slips(typed) == balancing_slips(si)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BalanceWarning)
        a, b = solve(si), solve(typed)
    x, y = si_numbers(a, {}), si_numbers(b, SYSTEMS[system])
    assert close(x, y, 1e-12), (x, y)               # measured: within a few ulp
