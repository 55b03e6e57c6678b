"""Joint friction (seed 002 s. 2.4): friction circle rho = r mu, prismatic friction."""

import copy
import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import SceneError
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


@pytest.mark.parametrize("name", ["four_bar", "slider_crank"])
def test_power_table_and_reduced_moments_with_friction(name):
    """``Solution.powers`` splits the balance by load kind; it adds up to zero, friction
    never gives power, and the three reduced moments add up to -Me (eq. 2.73)."""
    d = load(name)
    for j in d["joints"]:
        j["friction"] = {"mu": 0.1, "radius": 0.015} if j["kind"] == "R" else \
            {"mu": 0.1, "length": 0.05}
    sol = ks.solve(d)
    p = sol.powers
    assert list(p.columns) == ["position", "P_driver", "P_applied", "P_gravity", "P_inertia",
                               "P_friction"]
    scale = np.abs(p.P_driver).max()
    assert np.abs(p.drop(columns="position").sum(axis=1)).max() <= 1e-9 * scale
    assert (p.P_friction <= 1e-12 * scale).all() and p.P_friction.min() < 0.0
    assert np.allclose(p.P_driver, sol.Me * sol.scene.driver.speed)
    r = sol.reduced
    total = r.M_red + r.M_red_friction + r.M_red_inertia
    assert np.allclose(total, -sol.Me, rtol=0, atol=1e-9 * np.abs(sol.Me).max())
    assert np.allclose(r.M_red_friction * sol.scene.driver.speed, p.P_friction)


def test_summary_leaves_self_locking_rows_out():
    """With friction enough to lock the slider-crank near its dead centres, the summary
    counts the locked rows and takes Me and the reactions over the others."""
    d = load("slider_crank")
    for j in d["joints"]:
        j["friction"] = {"mu": 1.3, "radius": 0.03} if j["kind"] == "R" else \
            {"mu": 1.3, "length": 0.08}
    sol = ks.solve(d)
    locked = sol.driver.self_locking.to_numpy()
    assert 0 < locked.sum() < locked.size
    s = sol.summary()
    assert s["self_locking_rows"] == int(locked.sum())
    free = sol.driver.Me.to_numpy()[~locked]
    assert s["Me_max"] == free.max() and s["Me_min"] == free.min()
    pos = sol.positions[~locked]
    for joint, r in s["reaction_max"].items():
        assert r["position"] in pos, joint
    assert "self_locking_rows" not in ks.solve(load("slider_crank")).summary()
