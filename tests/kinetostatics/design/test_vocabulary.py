"""Each quantity of the vocabulary against the solution's own tables or a brute force."""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.design.vocabulary import quantity


@pytest.fixture(scope="module")
def sol():
    return ks.solve("four_bar")


def q(name, sol, targets=None):
    return quantity(name, sol.scene, targets or {}, "test").of(sol)


def test_against_the_tables(sol):
    s = sol.summary()
    assert q("Me_peak", sol) == sol.driver.Me.abs().max()
    assert q("transmission_min", sol) == s["transmission_angle_min"]
    assert q("reaction_peak", sol) == max(v["F"] for v in s["reaction_max"].values())
    assert q("frame_force_peak", sol) == sol.frame.F.max()
    me = sol.driver.sort_values("position")
    rms = math.sqrt(np.trapezoid(me.Me**2, me.position) / 360.0)
    assert q("Me_rms", sol) == pytest.approx(rms, rel=1e-15)
    k = sol.kinematics
    c = k[(k.body == "rocker") & (k.point == "C")]
    assert q("stroke:rocker.C", sol) == c.x.max() - c.x.min()
    assert q("stroke:rocker.C@90", sol) == pytest.approx(c.y.max() - c.y.min(), rel=1e-14)
    # a joint's name is its point: C on the coupler (the same place as the rocker's C)
    assert q("stroke:C", sol) == pytest.approx(q("stroke:rocker.C", sol), rel=1e-12)
    g = k[(k.body == "coupler") & (k.point == "cog")]
    assert q("stroke:coupler.cog", sol) == g.x.max() - g.x.min()


def test_path_error(sol):
    k = sol.kinematics
    p = k[(k.body == "coupler") & (k.point == "P")]
    on = [[p.x.iloc[10], p.y.iloc[10]], [p.x.iloc[200], p.y.iloc[200]]]
    assert q("path_error:coupler.P", sol, {"coupler.P": on}) == 0.0
    off = [[0.0, 1.0], [1.0, 0.0]]
    d = [np.hypot(p.x - x, p.y - y).min() for x, y in off]
    assert q("path_error:coupler.P", sol, {"coupler.P": off}) == pytest.approx(
        math.sqrt((d[0] ** 2 + d[1] ** 2) / 2), rel=1e-14)


def test_sliding_driver():
    sol = ks.solve("sliding_driver")
    assert q("Fe_peak", sol) == sol.driver.Fe.abs().max()
