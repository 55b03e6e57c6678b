"""Joint friction (seed 002 s. 2.4): friction circle rho = r mu, prismatic friction."""

import copy
import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.errors import SceneError
from tests.helpers import OWN_CASES


def load(name):
    with open(OWN_CASES / f"{name}.toml", "rb") as fh:
        return tomllib.load(fh)


def test_crank_bearing_friction_circle():
    """A lone crank with a force at B: Me = moment of the load + rho |F01| (eq. 2.62)."""
    scene = {
        "ground": {"A": [0.0, 0.0]},
        "driver": {"body": "crank", "joint": "A", "speed": 1e-3, "start": 0.0, "stop": 360.0,
                   "count": 73},
        "bodies": [{"name": "crank", "points": {"A": [0.0, 0.0], "B": [0.1, 0.0]}}],
        "joints": [{"name": "A", "kind": "R", "bodies": ["ground", "crank"],
                    "friction": {"mu": 0.2, "radius": 0.01}}],
        "loads": [{"body": "crank", "point": "B", "force": [0.0, -100.0]}],
    }
    sol = ks.solve(scene)
    phi = np.deg2rad(sol.positions)
    assert np.allclose(sol.Me, 0.1 * 100.0 * np.cos(phi) + 0.2 * 0.01 * 100.0, atol=1e-12)
    assert not sol.driver.self_locking.any()


def test_sliding_driver_friction_adds_mu_n():
    """Friction in the driver's own guide acts along the line through the slider point:
    it changes neither N nor the other reactions, and Fe by mu |N| sign(v)."""
    d0 = load("sliding_driver")
    d1 = copy.deepcopy(d0)
    d1["joints"][0]["friction"] = {"mu": 0.15}
    s0, s1 = ks.solve(d0), ks.solve(d1)
    n0 = s0.reactions.query("joint == 'slide'").N.to_numpy()
    n1 = s1.reactions.query("joint == 'slide'").N.to_numpy()
    assert np.allclose(n0, n1, rtol=0, atol=1e-12 * np.abs(n0).max())
    assert np.allclose(s1.Me, s0.Me + 0.15 * np.abs(n0), rtol=1e-12)


@pytest.mark.parametrize("name", ["four_bar", "slider_crank", "slotted_lever", "scotch_yoke"])
def test_friction_dissipates_and_balances_power(name):
    d = load(name)
    s0 = ks.solve(d)
    for j in d["joints"]:
        j["friction"] = {"mu": 0.1, "radius": 0.015} if j["kind"] == "R" else \
            {"mu": 0.1, "length": 0.05}
    s1 = ks.solve(d)
    w = s1.scene.driver.speed
    n = s1.positions.size
    power = s1.Me * w + sum(np.broadcast_to(ld.power(s1.kin), (n,)) for ld in s1.loads)
    assert np.abs(power).max() <= 1e-9 * np.abs(s1.Me * w).max()
    friction_power = sum(np.broadcast_to(ld.power(s1.kin), (n,)) for ld in s1.loads
                         if ld.kind == "friction")
    assert (friction_power <= 1e-9 * np.abs(s1.Me * w).max()).all()
    assert np.trapezoid(s1.Me, s1.positions) > np.trapezoid(s0.Me, s0.positions)
    assert "self_locking" in s1.driver and not s1.driver.self_locking.any()


def test_friction_table_checked():
    d = load("four_bar")
    d["joints"][0]["friction"] = {"mu": 0.1}
    with pytest.raises(SceneError, match="radius"):
        ks.load_scene(d)
    d["joints"][0]["friction"] = {"mu": 0.1, "radius": 0.01, "lenght": 1}
    with pytest.raises(SceneError, match="unknown key .lenght."):
        ks.load_scene(d)
