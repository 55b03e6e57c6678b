"""The virtual balancing machine: a rotor with a known unbalance on a spring-damper
mount in pymunk; its resonance amplitudes, fed to the amplitude parallelogram and to the
four-run method, give back the unbalance put in.

The design's targets were 0.3 % and 0.6 deg at dt = 1e-4 s; measured (pymunk 7.3.1):
1.4e-5 to 8.7e-5 of m r and 1e-6 to 0.0025 deg (the rest is the method's own error:
the trial mass detunes the resonance a little). The tolerances are a few times the
measured values, written next to them.
"""

import math

import numpy as np
import pytest

from balance import BalanceError, Unbalance, parallelogram
from balance.machine import BalancingMachine, unbalance_vector

TRIAL = dict(trial_mass=0.01, trial_radius=0.08, correction_radius=0.08)


def random_unbalance(rng):
    return [Unbalance(rng.uniform(0.005, 0.03), rng.uniform(0.04, 0.1), rng.uniform(0, 360))]


def angle_off(angle, unbalances):
    """How far a correction angle (deg) is from the true one, the resultant's + 180."""
    U = unbalance_vector(unbalances)
    true = math.degrees(math.atan2(U.imag, U.real)) + 180.0
    return abs((angle - true + 180.0) % 360.0 - 180.0)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_seeded_unbalances_are_recovered_at_dt_1e4(seed):
    rng = np.random.default_rng(seed)
    u = random_unbalance(rng)
    bm = BalancingMachine(dt=1e-4)
    three = bm.three_run(u, **TRIAL)
    four = bm.four_run(u, **TRIAL)
    for r in (three, four):
        assert r.unbalance_error <= 3e-4                  # measured 1.4e-5 to 8.7e-5
    # the angle errors are those of the angles reported
    assert four.angle_error == angle_off(four.result.angle, u)
    assert four.angle_error <= 4e-5                       # measured 1.4e-6 to 1.3e-5 deg
    assert four.result.mirror_angle is None and four.mirror_angle_error is None
    assert three.angle_error == angle_off(three.result.angle, u)
    assert three.mirror_angle_error == angle_off(three.result.mirror_angle, u)
    # one of the three-run method's two candidates is right (it cannot tell which)
    assert min(three.angle_error, three.mirror_angle_error) <= 8e-3   # measured 2.5e-3
    # the correction mass at the correction radius cancels the unbalance
    assert four.result.correction_mass * TRIAL["correction_radius"] == pytest.approx(
        abs(unbalance_vector(u)), rel=3e-4)               # measured 1.4e-5 to 8.7e-5


@pytest.mark.slow     # a fine time step (the dt 1e-4 runs stay quick)
def test_seeded_unbalance_is_recovered_at_dt_3e5():
    rng = np.random.default_rng(11)
    u = random_unbalance(rng)
    bm = BalancingMachine(dt=3e-5)
    three, four = bm.three_run(u, **TRIAL), bm.four_run(u, **TRIAL)
    for r in (three, four):
        assert r.unbalance_error <= 4e-5                  # measured 1.08e-5, 1.07e-5
    assert four.angle_error <= 1.5e-5                     # measured 3.7e-6 deg
    assert min(three.angle_error, three.mirror_angle_error) <= 1e-3  # measured 2.7e-4


def test_several_eccentric_masses_act_as_their_resultant():
    u = [Unbalance(0.01, 0.1, 30.0), (0.02, 0.05, 200.0), {"mass": 0.005, "radius": 0.08,
                                                          "angle": 95.0}]
    r = BalancingMachine().four_run(u, **TRIAL)
    assert r.unbalance == pytest.approx(unbalance_vector(u))
    assert r.unbalance_error <= 1e-4                      # measured 3.3e-5
    assert r.angle_error <= 4e-5                          # measured 1.0e-5 deg


def test_amplitude_is_proportional_to_the_unbalance():
    bm = BalancingMachine()
    a1 = bm.amplitude([(0.02, 0.05, 40.0)])
    a2 = bm.amplitude([(0.02, 0.10, 40.0)])     # same mass, twice the radius
    assert a2 / a1 == pytest.approx(2.0, rel=1e-6)
    assert bm.amplitude([]) == 0.0


def test_amplitude_matches_the_exact_steady_state():
    u = [(0.02, 0.1, 30.0)]
    for speed in (None, 45.0):
        bm = BalancingMachine(speed=speed)
        rec = bm.record(u)
        # measured -7.8e-4 (resonance) and 5.5e-4 (45 rad/s)
        assert rec.amplitude == pytest.approx(bm.steady_amplitude(u), rel=2e-3)
        assert rec.speed == pytest.approx(bm.omega)
    # at resonance the amplitude is the largest
    assert BalancingMachine().amplitude(u) > 3 * BalancingMachine(speed=45.0).amplitude(u)


def test_machine_space_holds_only_what_is_needed():
    bm = BalancingMachine()
    space, frame, rotor = bm.build([(0.02, 0.1, 30.0)])
    assert len(space.shapes) == 0
    assert len(space.bodies) == 2
    assert frame.moment == math.inf
    assert rotor.mass == pytest.approx(5.02)
    kinds = sorted(type(c).__name__ for c in space.constraints)
    assert kinds == ["DampedSpring", "GrooveJoint", "PivotJoint", "SimpleMotor"]
    assert all(not c.collide_bodies for c in space.constraints)
    assert space.gravity == (0.0, 0.0)


def test_parallelogram_of_the_machine_amplitudes():
    """The three amplitudes are the sides and diagonals of the parallelogram."""
    u = [(0.015, 0.09, 120.0)]
    r = BalancingMachine().three_run(u, **TRIAL)
    a = r.amplitudes
    again = parallelogram(a["A1"], a["0"], a["180"], **TRIAL)
    assert again.unbalance == pytest.approx(r.result.unbalance)
    assert r.result.mirror_angle is not None
    assert len(r.records) == 3


@pytest.mark.parametrize("kw", [{"dt": 0.0}, {"damping_ratio": 1.5}, {"iterations": 0},
                                {"speed": -1.0}, {"dt": 0.01}, {"frame_mass": float("nan")}])
def test_bad_machine_settings_are_refused(kw):
    with pytest.raises(BalanceError):
        BalancingMachine(**kw)


@pytest.mark.parametrize("u", [[(-0.01, 0.1, 0.0)], [(0.01,)], [{"mass": 0.01}],
                               [("a", 0.1, 0.0)]])
def test_bad_unbalances_are_refused(u):
    with pytest.raises(BalanceError):
        BalancingMachine().amplitude(u)


def test_public_stepping_gives_the_same_amplitude():
    u = [(0.02, 0.1, 30.0)]
    fast = BalancingMachine(fast=True, periods=3).amplitude(u)
    public = BalancingMachine(fast=False, periods=3).amplitude(u)
    assert fast == public


def test_machine_runs_through_a_process_pool_match_serial():
    """The runs of a method are a batch: processes give the same numbers, in order."""
    from concurrent.futures import ProcessPoolExecutor
    u = [(0.015, 0.09, 120.0)]
    bm = BalancingMachine(periods=3)
    serial = bm.four_run(u, **TRIAL, executor="serial")
    with ProcessPoolExecutor(max_workers=2) as pool:
        pooled = bm.four_run(u, **TRIAL, executor=pool)
    assert pooled.amplitudes == serial.amplitudes
    assert pooled.result.unbalance == serial.result.unbalance
    assert [r.wall > 0 for r in pooled.records] == [True] * 4
    assert bm.three_run(u, **TRIAL).amplitudes["A1"] == serial.amplitudes["A1"]  # default pool
    assert BalancingMachine.from_settings(bm.settings()) == bm
    with pytest.raises(BalanceError):
        bm.runs([[(0.01, 0.1, 0.0)], [(-0.01, 0.1, 0.0)]])
