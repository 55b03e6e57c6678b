"""Kinematics against the course's closed forms, and properties over random geometries."""

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import kinetostatics as ks
from tests.helpers import OWN_CASES
from tests.kinetostatics import checks, scenes


def test_slider_crank_closed_form_seed_004():
    """Seed 004 eqs (1)-(3): r = 0.150 m, l = 0.350 m, 1500 rpm; x = r cos(th) +
    sqrt(l^2 - r^2 sin^2 th) and its exact time derivatives, to 1e-12 of the largest."""
    sol = ks.solve(OWN_CASES / "slider_crank.toml")
    k = sol.kinematics.query("body == 'piston' and point == 'C'")
    th = np.deg2rad(k.position.to_numpy())
    w = 1500 * np.pi / 30
    r, l = 0.150, 0.350
    s, c = np.sin(th), np.cos(th)
    S = np.sqrt(l * l - r * r * s * s)
    x = r * c + S
    v = w * (-r * s - r * r * s * c / S)
    a = w * w * (-r * c - r * r * (c * c - s * s) / S - r**4 * s * s * c * c / S**3)
    for got, want in ((k.x, x), (k.vx, v), (k.ax, a)):
        assert np.abs(got.to_numpy() - want).max() <= 1e-12 * np.abs(want).max()
    assert np.abs(k.y.to_numpy()).max() == 0.0


def test_slotted_lever_transmission_functions_seed_001():
    """Seed 001, the oscillating slotted lever: tan(phi3) = (l0 + l1 sin phi1)/(l1 cos phi1),
    omega3 = omega1 l1 (l1 + l0 sin phi1) / D, eps3 = eps1 l1 (l1 + l0 sin phi1) / D
    - omega1^2 l0 l1 (l1^2 - l0^2) cos phi1 / D^2, D = l1^2 + 2 l0 l1 sin phi1 + l0^2."""
    d = checks_dict("slotted_lever")
    d["driver"]["acceleration"] = 4.0
    sol = ks.solve(d)
    l0, l1, w1, e1 = 0.30, 0.12, 20.0, 4.0
    b = sol.bodies.query("body == 'lever'")
    phi1 = np.deg2rad(b.position.to_numpy())
    s, c = np.sin(phi1), np.cos(phi1)
    D = l1 * l1 + 2 * l0 * l1 * s + l0 * l0
    phi3 = np.arctan2(l0 + l1 * s, l1 * c)
    w3 = w1 * l1 * (l1 + l0 * s) / D
    e3 = e1 * l1 * (l1 + l0 * s) / D - w1**2 * l0 * l1 * (l1 * l1 - l0 * l0) * c / D**2
    dphi = np.angle(np.exp(1j * (np.deg2rad(b.angle.to_numpy()) - phi3)))
    assert np.abs(dphi).max() < 1e-12
    assert np.abs(b.omega.to_numpy() - w3).max() <= 1e-12 * np.abs(w3).max()
    assert np.abs(b.alpha.to_numpy() - e3).max() <= 1e-12 * np.abs(e3).max()


def checks_dict(name):
    import tomllib
    with open(OWN_CASES / f"{name}.toml", "rb") as fh:
        return tomllib.load(fh)


def test_angles_continuous_and_first_in_range():
    sol = ks.solve(OWN_CASES / "slotted_lever.toml")
    for name, g in sol.bodies.groupby("body"):
        a = g.angle.to_numpy()
        if name != "crank":
            assert -180 < a[0] <= 180
            assert np.abs(np.diff(a)).max() < 10
    crank = sol.bodies.query("body == 'crank'")
    assert np.array_equal(crank.angle.to_numpy(), crank.position.to_numpy())


def four_bar(a, b, c, d, cog3, cog4, m, load, branch):
    return scenes.four_bar(
        a, b, c, d, masses=m, inertias=(0.002, 0.01, 0.008), cogs=([a / 3, 0.01], cog3, cog4),
        speed=17.0, count=2001, gravity=[0.0, -9.81], coupler_point=[b / 2, 0.05],
        loads=[{"body": "coupler", "point": "P", "force": load, "moment": 2.0}],
        near=[d, branch * 0.3])

def run_all_checks(sol, fd=True):
    assert checks.loop_closure(sol) < 1e-12
    assert checks.virtual_power(sol) < 1e-9
    assert checks.matrix_difference(sol) < 1e-8
    assert checks.body_equilibrium(sol) < 1e-9
    if fd:
        assert checks.finite_differences(sol) < 1e-6


length = st.floats(0.15, 0.45)


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(a=st.floats(0.04, 0.12), b=length, c=length, d=length,
       cog3=st.tuples(st.floats(-0.05, 0.3), st.floats(-0.05, 0.05)),
       cog4=st.tuples(st.floats(-0.05, 0.3), st.floats(-0.05, 0.05)),
       m=st.tuples(st.floats(0.1, 3), st.floats(0.1, 3), st.floats(0.1, 3)),
       load=st.tuples(st.floats(-200, 200), st.floats(-200, 200)),
       branch=st.sampled_from([1, -1]))
def test_random_crank_rockers(a, b, c, d, cog3, cog4, m, load, branch):
    links = sorted([a, b, c, d])
    assume(links[0] == a and a + links[-1] < links[1] + links[2] - 0.02)
    sol = ks.solve(four_bar(a, b, c, d, list(cog3), list(cog4), list(m), list(load), branch))
    assert sol.kin.dyads[0].k in (1, -1)
    assert not sol.singular.any()
    run_all_checks(sol)


def random_with_angles(test):
    """Ten random mechanisms whose angles (deg) may look like radians to the slip check:
    its warning is meant and kept quiet."""
    test = settings(max_examples=10, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])(test)
    return pytest.mark.filterwarnings(
        "ignore::kinetostatics.model.errors.UnitWarning")(test)


# a random line angle within 2 pi with decimals looks like radians: the slip warning is meant
@random_with_angles
@given(r=st.floats(0.03, 0.15), lam=st.floats(0.15, 0.45), e=st.floats(-0.05, 0.05),
       ang=st.floats(-40, 40))
def test_random_offset_slider_cranks(r, lam, e, ang):
    """RRT with an offset and an inclined guide line."""
    l = r / lam
    assume(abs(e) + r < 0.8 * l)
    run_all_checks(ks.solve(scenes.offset_slider_crank(r, l, e, ang)))


# a slot angle within +-20 deg with a fraction looks like radians to the slip check
@random_with_angles
@given(r=st.floats(0.05, 0.14), h=st.floats(0.2, 0.4), e=st.floats(-0.03, 0.03),
       beta=st.floats(-20, 20))
def test_random_slotted_levers(r, h, e, beta):
    """RTR with the slot offset from the pivot and at an angle in the lever's frame."""
    assume(r + abs(e) < 0.8 * h)
    sol = ks.solve(scenes.varied_slotted_lever(checks_dict("slotted_lever"), r, h, e, beta, 2001))
    run_all_checks(sol)


@pytest.mark.parametrize("name", ["four_bar", "slider_crank", "shaper", "slotted_lever",
                                  "sliding_driver", "scotch_yoke"])
def test_what_the_solve_lets_go_comes_back_the_same(name, numpy_path):
    """After the solve each dyad lets go of its velocity system's columns and determinant
    (and its outer pivots' velocity and acceleration); asked for again (the transmission
    angle, the dyads table), they are worked out with exactly the numbers the solve had."""
    from kinetostatics.model.scene import load_scene
    from kinetostatics.solver.kinematics import solve_kinematics
    from kinetostatics.solver.structure import analyse
    sc = load_scene(ks.example(name))
    held = solve_kinematics(sc, analyse(sc))             # nothing let go
    sol = ks.solve(sc)
    for kept, dm in zip(held.dyads, sol.kin.dyads, strict=True):
        assert dm._c1 is None and dm._det is None        # let go by the solve
        assert all(p.vpx is None and p.apy is None for p in dm.params)
        for a, b in ((kept.c1, dm.c1), (kept.c2, dm.c2), ((kept.det,), (dm.det,)),
                     ((kept.sin_tau, kept.cos_tau), (dm.sin_tau, dm.cos_tau))):
            for x, y in zip(a, b, strict=True):
                np.testing.assert_array_equal(np.broadcast_to(x, (sol.positions.size,)),
                                              np.broadcast_to(y, (sol.positions.size,)))
