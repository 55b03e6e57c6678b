"""Issue 18: rows in any order, angles that follow the true motion between far rows,
friction at rest, and a dyad that cannot close between rows.

References are independent of the code under test: the sorted sweep, the fine sweep,
the limit speed -> 0 and the lever's turn computed here from the geometry alone."""

from __future__ import annotations

import copy
import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import SceneError
from kinetostatics.solver.friction import against_motion
from tests.kinetostatics import scenes


def double_crank(positions=None, count=361, speed=10.0, acc=0.0, friction=None) -> dict:
    """A Grashof double crank: the ground link (0.1 m) is the shortest; crank 0.3,
    coupler 0.35, output crank 0.28 (0.1 + 0.35 <= 0.3 + 0.28): both cranks turn fully."""
    pins = {j: {"mu": friction, "radius": 0.01} for j in "ABCD"} if friction else None
    return scenes.four_bar(0.3, 0.35, 0.28, 0.1, cogs=([0.1, 0.0], [0.15, 0.02], [0.1, 0.0]),
                           speed=speed, acceleration=acc, count=count, positions=positions,
                           loads=[{"body": "rocker", "moment": -3.0}], near=[0.2, 0.3],
                           friction=pins)


def angles(sol, body: str) -> np.ndarray:
    b = sol.bodies
    return b[b.body == body].angle.to_numpy()


# -- 1. rows in any order ---------------------------------------------------------------

def test_permuted_positions_give_the_sorted_rows_and_summary() -> None:
    """Issue 18: [0, 180, 90, 360, 270] gave Me_mean 2.2217 (the trapezoid in file
    order); the sorted positions give another value. Now both are the sorted sweep's."""
    mixed = ks.solve(double_crank([0, 180, 90, 360, 270]))
    ref = ks.solve(double_crank([0, 90, 180, 270, 360]))
    assert mixed.summary() == ref.summary()
    assert mixed.driver.position.tolist() == [0, 180, 90, 360, 270]   # the list's order
    back = [0, 2, 1, 4, 3]                  # the sorted rows, in the list's order
    for table in ("driver", "bodies", "kinematics", "reactions", "dyads", "frame", "reduced"):
        a = getattr(mixed, table)
        b = getattr(ref, table)
        blocks = len(a) // 5
        idx = np.concatenate([np.array(back) + 5 * k for k in range(blocks)])
        np.testing.assert_array_equal(a.select_dtypes("number").to_numpy(),
                                      b.select_dtypes("number").to_numpy()[idx], err_msg=table)


def test_a_backwards_sweep_is_the_forward_one_reversed() -> None:
    fwd = ks.solve(double_crank(count=13))
    d = double_crank(count=13)
    d["driver"].update(start=360.0, stop=0.0)
    rev = ks.solve(d)
    assert rev.summary() == fwd.summary()
    for body in ("coupler", "rocker"):
        np.testing.assert_array_equal(angles(rev, body), angles(fwd, body)[::-1])
    np.testing.assert_array_equal(np.asarray(rev.Me), np.asarray(fwd.Me)[::-1])


@pytest.mark.parametrize("positions", [[0.0, 90.0, 0.0], [10.0, 20.0, 30.0, 20.0]])
def test_a_repeated_position_is_refused(positions) -> None:
    with pytest.raises(SceneError, match=r"is listed more than once"):
        ks.solve(double_crank(positions))
    with pytest.raises(SceneError, match=r"is listed more than once"):
        ks.solve(double_crank([0.0]), positions=positions)


@pytest.mark.parametrize(("positions", "message"), [
    ([], r"^positions is empty; list at least one position$"),
    (np.zeros(0), r"^positions is empty"),
    ([0.0, float("nan")], r"^positions\[1\] must be a finite number, not nan$"),
    (np.array([10.0, np.inf]), r"^positions\[1\] must be a finite number, not inf$"),
    ([10.0, "20"], r"^positions\[1\] must be a number, not a string$"),
    ([True, 20.0], r"^positions\[0\] must be a number, not true/false$"),
    ([10.0, [20.0, 30.0]], r"^positions\[1\] must be a number, not a list$"),
    ([[10.0], [20.0]], r"^positions\[0\] must be a number, not a list$"),
    (np.array([[10.0, 20.0]]), r"^positions must be numbers in one list"),
])
def test_bad_positions_given_to_solve_are_refused_in_one_line(positions, message) -> None:
    """What the scene's own driver.positions refuses, the positions given to solve
    refuse too (a SceneError naming the entry), never a numpy error or a misleading
    assembly message."""
    with pytest.raises(SceneError, match=message):
        ks.solve(double_crank(), positions=positions)


def test_positions_given_as_any_sequence_of_numbers() -> None:
    ref = ks.solve(double_crank(), positions=[0.0, 10.0, 20.0]).driver
    for given in ((0, 10, 20), np.array([0, 10, 20]), range(0, 30, 10),
                  [np.float64(0.0), 10, np.float32(20.0)]):
        got = ks.solve(double_crank(), positions=given).driver
        np.testing.assert_array_equal(got.to_numpy(), ref.to_numpy())


def test_start_equal_to_stop_with_several_rows_is_refused() -> None:
    d = double_crank()
    d["driver"].update(start=40.0, stop=40.0, count=3)
    with pytest.raises(SceneError, match=r"40 deg is listed more than once"):
        ks.solve(d)


# -- 2. true motion between rows ---------------------------------------------------------

@pytest.mark.parametrize("count", [2, 3, 4, 5, 7])
def test_coarse_rows_of_a_double_crank_follow_the_fine_sweep(count) -> None:
    """Issue 18: with count = 3 the output went 93.82 -> 253.74 -> 93.82 deg (truly 453.82
    at 360). Reference: the fine sweep (1 deg rows) at the same positions."""
    fine = ks.solve(double_crank(count=1441))
    coarse = ks.solve(double_crank(count=count))
    shared = np.linspace(0.0, 1440.0, count).astype(int)
    for body in ("coupler", "rocker"):
        # measured 0 (both sweeps give the same anchored unwrap at shared rows)
        np.testing.assert_allclose(angles(coarse, body), angles(fine, body)[shared],
                                   rtol=0, atol=1e-9)
    assert angles(coarse, "rocker")[-1] - angles(coarse, "rocker")[0] == pytest.approx(360.0)


def test_coarse_rows_at_rest_follow_the_fine_sweep() -> None:
    """At speed 0 every omega is 0: the turns come from the mechanism at unit speed."""
    fine = ks.solve(double_crank(count=721, speed=0.0, acc=5.0))
    coarse = ks.solve(double_crank(count=3, speed=0.0))
    for body in ("coupler", "rocker"):
        np.testing.assert_allclose(angles(coarse, body), angles(fine, body)[[0, 360, 720]],
                                   rtol=0, atol=1e-9)


def slotted_lever(miss: float, positions) -> dict:
    """The bundled slotted lever with its pivot O4 placed so that the block passes at
    `miss` m from it (outside the crank circle for miss > 0) at crank angle 200 deg."""
    with open(ks.example("slotted_lever"), "rb") as fh:
        d = tomllib.load(fh)
    o2 = np.array(d["ground"]["O2"])
    crank = d["bodies"][0]["points"]["A"][0]
    e = np.array([np.cos(np.deg2rad(200.0)), np.sin(np.deg2rad(200.0))])
    d["ground"]["O4"] = (o2 + (crank + miss) * e).tolist()
    d["driver"].pop("start"), d["driver"].pop("stop"), d["driver"].pop("count")
    d["driver"]["positions"] = list(positions)
    return d, o2, crank


def lever_turn(o2, crank, o4, a: float, b: float) -> float:
    """The turn (deg) of the line O4 -> A from crank angle a to b, by dense sampling (1e6
    points, geometric near 200 deg): independent of the workbench."""
    near = 200.0 + np.concatenate([-np.geomspace(1.0, 1e-12, 200000),
                                   np.geomspace(1e-12, 1.0, 200000)])
    phi = np.sort(np.concatenate([np.linspace(a, b, 600001), near[(near > a) & (near < b)]]))
    t = np.deg2rad(phi)
    v = o2[:, None] + crank * np.stack([np.cos(t), np.sin(t)]) - o4[:, None]
    th = np.unwrap(np.arctan2(v[1], v[0]))
    return float(np.rad2deg(th[-1] - th[0]))


@pytest.mark.parametrize("miss", [1e-9, -1e-9])
def test_a_block_passing_near_the_pivot_between_rows(miss) -> None:
    """Issue 18: the lever showed -69.75 deg after the pass (truly 290.25): the nearest
    value of a turn of about 180 deg. Reference: the turn of O4 -> A sampled here."""
    d, o2, crank = slotted_lever(miss, [199.5, 200.5])
    o4 = np.array(d["ground"]["O4"])
    sol = ks.solve(d)
    lever = angles(sol, "lever")
    ref = lever_turn(o2, crank, o4, 199.5, 200.5)
    assert abs(ref) > 179.0
    # measured 5.7e-14 deg
    assert lever[1] - lever[0] == pytest.approx(ref, abs=1e-12)
    # the same from a coarse sweep over the whole turn, and in any order
    many = ks.solve(slotted_lever(miss, [270.0, 20.0, 199.5, 200.5])[0])
    got = angles(many, "lever")
    assert got[3] - got[2] == pytest.approx(ref, abs=1e-12)
    total = lever_turn(o2, crank, o4, 20.0, 270.0)
    assert got[0] - got[1] == pytest.approx(total, abs=1e-12)     # measured 2.8e-14 deg


# -- 3. friction at rest -------------------------------------------------------------------

P15 = np.arange(0.0, 360.0, 15.0)


@pytest.mark.parametrize("acc", [400.0, -400.0])
def test_friction_at_rest_is_the_limit_of_a_vanishing_speed(acc) -> None:
    """Issue 18: at speed 0 the friction was left out (Me = the frictionless value).
    Reference: speed -> 0 from the side the acceleration points to (1e-7 rad/s)."""
    rest = ks.solve(double_crank(P15, speed=0.0, acc=acc, friction=0.3))
    near = ks.solve(double_crank(P15, speed=1e-7 * np.sign(acc), acc=acc, friction=0.3))
    plain = ks.solve(double_crank(P15, speed=0.0, acc=acc))
    me, me_near = np.asarray(rest.Me), np.asarray(near.Me)
    # measured 7.1e-15 N m (Me up to 92 N m)
    np.testing.assert_allclose(me, me_near, rtol=0, atol=1e-12)
    ok = ~rest.driver.undefined_load.to_numpy()
    assert np.abs(me - np.asarray(plain.Me))[ok].min() > 0.1      # friction is there
    # coupler and output crank turn alike at 0 and 180 deg: joint C has no relative
    # motion nor relative acceleration there at rest, its friction has no direction
    assert rest.driver.undefined_load.to_numpy().nonzero()[0].tolist() == [0, 12]
    assert rest.summary()["undefined_load_rows"] == 2


def test_friction_at_rest_without_acceleration_is_undefined() -> None:
    sol = ks.solve(double_crank(P15, speed=0.0, acc=0.0, friction=0.3))
    assert sol.driver.undefined_load.all()
    plain = ks.solve(double_crank(P15, speed=0.0, acc=0.0))
    np.testing.assert_array_equal(np.asarray(sol.Me), np.asarray(plain.Me))


def slider_crank(speed: float, acc: float, length: float | None) -> dict:
    with open(ks.example("slider_crank"), "rb") as fh:
        d = tomllib.load(fh)
    d["driver"].pop("speed", None), d["driver"].pop("speed_rpm", None)
    d["driver"].update(speed=speed, acceleration=acc, start=5.0, stop=355.0, count=14)
    d["loads"] = [{"body": "piston", "point": "C", "force": [-6000.0, 0.0]}]   # not resist
    for j in d["joints"]:
        if j["kind"] == "T":
            j["friction"] = {"mu": 0.15} if length is None else {"mu": 0.15, "length": length}
        else:
            j["friction"] = {"mu": 0.15, "radius": 0.02}
    return d


@pytest.mark.parametrize("length", [None, 0.08])
@pytest.mark.parametrize("acc", [300.0, -300.0])
def test_prismatic_friction_at_rest_is_the_limit(length, acc) -> None:
    """Pins, an open and a closed guide (eqs 2.62-2.65) at rest."""
    rest = ks.solve(slider_crank(0.0, acc, length))
    near = ks.solve(slider_crank(1e-7 * np.sign(acc), acc, length))
    far = ks.solve(slider_crank(-1e-7 * np.sign(acc), acc, length))
    me = np.asarray(rest.Me)
    # measured 0 (Me up to 1.1e3 N m): the same friction directions, speed terms 1e-14
    np.testing.assert_allclose(me, np.asarray(near.Me), rtol=0, atol=1e-13 * np.abs(me).max())
    assert np.abs(me - np.asarray(far.Me)).max() > 1.0   # the other side differs
    assert not rest.driver.undefined_load.any()


def test_against_motion_reads_the_acceleration_only_at_rest() -> None:
    v = np.array([2.0, -1.0, 0.0, 0.0, 0.0, 1e-12])
    a = np.array([-5.0, 5.0, 3.0, -3.0, 0.0, -4.0])
    sign, undefined = against_motion(v, a, 6)
    assert sign.tolist() == [-1.0, 1.0, -1.0, 1.0, 0.0, 1.0]
    assert undefined.tolist() == [False, False, False, False, True, False]


# -- 4. a dyad that cannot close between rows ----------------------------------------------

def triple_rocker(positions) -> dict:
    """A four-bar whose coupler and rocker (0.12, 0.2 m) reach the crank pin only for
    crank angles within about 13..70 deg either side of the ground line."""
    d = double_crank(positions)
    d["ground"]["D"] = [0.3, 0.0]
    b = d["bodies"]
    b[0]["points"]["B"] = [0.25, 0.0]
    b[1]["points"]["C"], b[1]["cog"] = [0.12, 0.0], [0.06, 0.0]
    b[2]["points"]["C"] = [0.2, 0.0]
    d["near"] = {"C": [0.3, 0.3]}
    return d


def test_a_dyad_that_cannot_close_between_rows_is_no_dead_point() -> None:
    """Was: the probe turned the missing closed form into a dead point: both rows flagged
    singular and [-25, 25] listed under dead_points_between_rows."""
    sol = ks.solve(triple_rocker([-65.0, -45.0, -25.0, 25.0, 45.0, 65.0]))
    s = sol.summary()
    assert s["unassembled_between_rows"] == [[-25.0, 25.0]]
    assert s["dead_points_between_rows"] == []
    assert not sol.driver.singular.any()
    with pytest.raises(Exception, match="cannot be assembled"):
        ks.solve(triple_rocker([-25.0, 0.0, 25.0]))
    mixed = ks.solve(triple_rocker([25.0, -65.0, 65.0, -25.0, -45.0, 45.0]))
    assert mixed.summary() == s
    # a regular sweep has none
    assert "unassembled_between_rows" not in ks.solve(double_crank(count=37)).summary()


def test_probe_copies_do_not_change_the_scene() -> None:
    d = double_crank(count=3)
    before = copy.deepcopy(d)
    assert len(ks.solve(d).bodies) == 9
    assert d == before


@pytest.mark.parametrize("positions", [None, [200.0, 10.0, 100.0, 330.0]])
def test_the_solver_keeps_angles_in_radians_and_the_table_shows_degrees(positions) -> None:
    """body_angles is radians (a crank's angle is its Driver.angles, to the bit); the
    bodies table shows those angles in degrees, moved by whole turns (the anchor) and a
    crank's positions as typed."""
    from kinetostatics.solver.continuity import body_angles
    sol = ks.solve(double_crank(positions=positions, count=13))
    rad = body_angles(sol.kin)
    drv = sol.scene.driver
    assert np.array_equal(rad[drv.body], drv.angles)
    assert np.array_equal(angles(sol, drv.body), drv.positions)
    for b in sol.scene.bodies:
        turns = (np.rad2deg(rad[b]) - angles(sol, b)) / 360.0
        assert np.allclose(turns, np.round(turns), rtol=0.0, atol=1e-14)   # measured 8e-17
        assert np.all(np.abs(np.diff(np.round(turns))) == 0)
