"""Reduction to the driving element (seed 002 s. 2.5) for the scene as given: any speed
and acceleration, zero included.

References: the kinetostatic Me (eq. 2.73: the three reduced moments add up to -Me), an
I_red computed here from the tables of a unit-speed solve (eq. 2.75: sum m v_G^2 +
I_G omega^2 over omega_1^2), its fourth-order finite differences for dI_red, and the
closed form of a lone crank."""

import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from tests.helpers import OWN_CASES
from tests.kinetostatics.scenes import with_friction

SCENES = ["four_bar", "slider_crank", "slotted_lever", "scotch_yoke", "sliding_driver"]
STATES = [(0.0, 5.0), (0.0, 0.0), (20.0, -3.0), (-7.0, 0.0), (1e-7, 4.0)]


def load(name, speed=None, acceleration=None, count=None):
    with open(OWN_CASES / f"{name}.toml", "rb") as fh:
        d = tomllib.load(fh)
    drv = d["driver"]
    if speed is not None:
        drv.pop("speed_rpm", None)
        drv["speed"] = speed
    if acceleration is not None:
        drv["acceleration"] = acceleration
    if count is not None:
        drv["count"] = count
    return d


def columns(sol):
    q = "M" if sol.drive.kind == "R" else "F"
    i = "I" if sol.drive.kind == "R" else "m"
    r = sol.reduced
    return (r[f"{q}_red"].to_numpy(), r[f"{q}_red_friction"].to_numpy(),
            r[f"{q}_red_inertia"].to_numpy(), r[f"{i}_red"].to_numpy(),
            r[f"d{i}_red"].to_numpy())


def independent_i_red(name, count):
    """I_red (m_red) from the kinematics and bodies tables of a solve at unit speed."""
    sol = ks.solve(load(name, speed=1.0, acceleration=0.0, count=count))
    k, b = sol.kinematics, sol.bodies
    total = np.zeros(sol.positions.size)
    for body in sol.scene.bodies.values():
        if body.mass > 0.0:
            g = k[(k.body == body.name) & (k.point == "cog")]
            total += body.mass * (g.vx.to_numpy() ** 2 + g.vy.to_numpy() ** 2)
        total += body.inertia * b[b.body == body.name].omega.to_numpy() ** 2
    return sol.positions, total


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("speed, acc", STATES)
def test_reduced_moments_add_up_to_minus_me(name, speed, acc):
    """Eq. 2.73 at every row, for any speed and acceleration (speed 0 with 5 rad/s^2 used
    to miss by 2 % of max|Me|, with M_red_inertia of the wrong sign)."""
    sol = ks.solve(load(name, speed, acc))
    m_red, m_fric, m_inertia, i_red, di_red = columns(sol)
    me = np.asarray(sol.Me)
    # measured <= 5.1e-16 of max|Me| over these scenes and states
    assert np.abs(m_red + m_fric + m_inertia + me).max() <= 4e-15 * np.abs(me).max()
    assert np.allclose(m_inertia, -(i_red * acc + 0.5 * di_red * speed**2), rtol=0,
                       atol=1e-14 * max(np.abs(m_inertia).max(), 1e-300))


@pytest.mark.parametrize("name", ["four_bar", "slotted_lever", "sliding_driver"])
def test_i_red_and_its_derivative_against_an_independent_computation(name):
    """I_red (m_red) from the speed-0 scene equals the table computation at unit speed,
    and dI_red its fourth-order finite differences on a fine grid."""
    count = 3601 if name != "sliding_driver" else 1201
    pos, ref = independent_i_red(name, count)
    sol = ks.solve(load(name, speed=0.0, acceleration=5.0, count=count))
    _m, _f, m_inertia, i_red, di_red = columns(sol)
    assert np.allclose(i_red, ref, rtol=2e-15, atol=0)        # measured 4.4e-16
    assert np.allclose(m_inertia, -5.0 * i_red, rtol=1e-15, atol=0)   # omega = 0
    q = np.deg2rad(pos) if sol.drive.kind == "R" else pos
    h = q[1] - q[0]
    fd = (-ref[4:] + 8.0 * ref[3:-1] - 8.0 * ref[1:-3] + ref[:-4]) / (12.0 * h)
    err = np.abs(fd - di_red[2:-2]).max() / np.abs(di_red).max()
    # measured 1.0e-10 (four-bar), 2.2e-10 (lever), 3.1e-9 (sliding driver, h = 1e-4 m)
    assert err <= {"four_bar": 5e-10, "slotted_lever": 1e-9, "sliding_driver": 1e-8}[name]


@pytest.mark.parametrize("name", ["four_bar", "slotted_lever", "scotch_yoke"])
def test_reduction_does_not_depend_on_speed(name):
    """I_red, dI_red and M_red are properties of the position: the same at speed 0 and
    at speed 20 with any acceleration (the loads here do not depend on the motion)."""
    a = columns(ks.solve(load(name, 0.0, 0.0)))
    b = columns(ks.solve(load(name, 20.0, -3.0)))
    for x, y in ((a[0], b[0]), (a[3], b[3]), (a[4], b[4])):
        assert np.allclose(x, y, rtol=0, atol=1e-14 * np.abs(y).max())


def test_lone_crank_closed_form():
    """A crank with its cog at a = 0.04 m: I_red = I_G + m a^2, dI_red = 0, M_red the
    moment of its weight, M_red_inertia = -I_red eps."""
    m, a, ig, eps = 2.0, 0.04, 0.003, 5.0
    scene = {
        "gravity": [0.0, -9.81],
        "ground": {"A": [0.0, 0.0]},
        "driver": {"body": "crank", "joint": "A", "speed": 0.0, "acceleration": eps,
                   "start": 0.0, "stop": 360.0, "count": 37},
        "bodies": [{"name": "crank", "mass": m, "inertia": ig, "cog": [a, 0.0],
                    "points": {"A": [0.0, 0.0]}}],
        "joints": [{"name": "A", "kind": "R", "bodies": ["ground", "crank"]}],
    }
    sol = ks.solve(scene)
    m_red, m_fric, m_inertia, i_red, di_red = columns(sol)
    phi = np.deg2rad(sol.positions)
    assert np.allclose(i_red, ig + m * a * a, rtol=1e-15, atol=0)
    assert np.abs(di_red).max() <= 1e-18
    assert np.allclose(m_red, -m * 9.81 * a * np.cos(phi), rtol=0, atol=1e-15)
    assert np.allclose(m_inertia, -(ig + m * a * a) * eps, rtol=1e-15, atol=0)
    assert not m_fric.any()


@pytest.mark.parametrize("model", [{"kind": "static", "points": ["B", "C"]},
                                   {"kind": "dynamic", "point": "B"}])
def test_mass_models_reduce_consistently(model):
    """With concentrated masses the reduced inertia is that of the masses the
    kinetostatics uses, so eq. 2.73 still closes at speed 0 and at speed."""
    for speed, acc in ((0.0, 5.0), (20.0, 3.0)):
        d = load("four_bar", speed, acc)
        coupler = next(b for b in d["bodies"] if b["name"] == "coupler")
        coupler["cog"] = [0.125, 0.0]
        coupler["mass_model"] = model
        sol = ks.solve(d)
        m_red, m_fric, m_inertia, _i, _di = columns(sol)
        me = np.asarray(sol.Me)
        assert np.abs(m_red + m_fric + m_inertia + me).max() <= 1e-13 * np.abs(me).max()


def test_friction_reduces_with_the_self_locking_rows_left_empty():
    sol = ks.solve(with_friction(load("slider_crank"), 1.3, radius=0.03, length=0.08))
    locked = sol.driver.self_locking.to_numpy()
    m_red, m_fric, m_inertia, i_red, _di = columns(sol)
    assert np.isnan(m_fric[locked]).all() and np.isfinite(m_fric[~locked]).all()
    assert np.isfinite(m_red).all() and np.isfinite(i_red).all()
    me = np.asarray(sol.Me)[~locked]
    total = (m_red + m_fric + m_inertia)[~locked]
    assert np.abs(total + me).max() <= 1e-13 * np.abs(me).max()


@pytest.mark.parametrize("speed, acc", [(1.5, 0.0), (0.0, 5.0), (-2.0, 3.0)])
def test_sliding_driver_that_carries_the_guide(speed, acc):
    """A sliding driver whose body carries the guide moves against the line direction as
    its position grows: its reduced forces still add up to -Fe (along the line, like Fe),
    and the power table (P_driver = Fe v) still closes, with friction in the guide."""
    d = load("sliding_driver", speed, acc)
    d["joints"][0].update(guide="slider", slider="ground", line_point="C", slider_point="S0",
                          friction={"mu": 0.2})
    sol = ks.solve(d)
    f_red, f_fric, f_inertia, m_red, dm_red = columns(sol)
    fe = np.asarray(sol.Me)                     # Fe of the sliding driver
    assert np.abs(f_red + f_fric + f_inertia + fe).max() <= 4e-15 * np.abs(fe).max()
    p = sol.powers
    total = p.drop(columns="position").sum(axis=1).to_numpy()
    assert np.abs(total).max() <= 4e-15 * max(np.abs(p.P_driver).max(), 1e-300)
    assert (p.P_friction <= 0.0).all()          # measured: both sums <= 3e-16
