"""Project tables: reduction, frame force, the t/n split, transmission angle, summary."""

import numpy as np
import pytest

import kinetostatics as ks
from tests.helpers import OWN_CASES, SCENES


@pytest.fixture(scope="module", params=["four_bar", "slider_crank", "slotted_lever",
                                        "scotch_yoke"])
def sol(request):
    return ks.solve(OWN_CASES / f"{request.param}.toml")


def test_reduced_moment_is_minus_me(sol):
    """Eq. 2.73: with the inertia forces, the reduced moment is -Me."""
    r = sol.reduced
    total = r.M_red + r.M_red_inertia
    assert np.allclose(total, -sol.Me, rtol=0, atol=1e-9 * np.abs(sol.Me).max())


def test_reduced_inertia_is_kinetic_energy(sol):
    """Eq. 2.75: I_red w1^2 / 2 is the kinetic energy of all bodies; at constant speed the
    inertia part of the reduced moment is -(1/2) dI_red/dphi w1^2 (eq. 4.9)."""
    w = sol.scene.driver.speed
    k = sol.kinematics.query("point == 'cog'")
    b = sol.bodies
    energy = np.zeros(sol.positions.size)
    for name, body in sol.scene.bodies.items():
        g = k[k.body == name]
        om = b[b.body == name].omega.to_numpy()
        energy += 0.5 * body.mass * (g.vx.to_numpy() ** 2 + g.vy.to_numpy() ** 2)
        energy += 0.5 * body.inertia * om**2
    r = sol.reduced
    assert np.allclose(0.5 * r.I_red * w * w, energy, rtol=1e-12)
    assert np.allclose(r.M_red_inertia, -0.5 * r.dI_red * w * w,
                       atol=1e-9 * np.abs(r.M_red_inertia).max())
    # dI/dphi by finite differences of I_red over the sweep
    phi = np.deg2rad(sol.positions)
    fd = np.gradient(r.I_red.to_numpy(), phi)
    assert np.abs(fd - r.dI_red)[2:-2].max() < 1e-3 * np.abs(r.dI_red).max()


def test_frame_force_balances_all_loads(sol):
    """The frame receives the resultant of every load on the moving bodies (applied,
    gravity, inertia): the whole mechanism is in d'Alembert equilibrium."""
    n = sol.positions.size
    fx = sum(np.broadcast_to(ld.fx, (n,)) for ld in sol.loads)
    fy = sum(np.broadcast_to(ld.fy, (n,)) for ld in sol.loads)
    scale = max(sol.reactions.F.max(), 1.0)
    assert np.abs(sol.frame.Fx - fx).max() < 1e-9 * scale
    assert np.abs(sol.frame.Fy - fy).max() < 1e-9 * scale
    mz = sum(np.broadcast_to(ld.position(sol.kin)[0] * ld.fy - ld.position(sol.kin)[1] * ld.fx
                             + ld.m, (n,)) for ld in sol.loads)
    assert np.abs(sol.frame.M - mz).max() < 1e-9 * scale


def test_reaction_split_recombines(sol):
    sp = sol.reaction_split
    for (joint, _body), g in sp.groupby(["joint", "body"]):
        fx, fy = sol.reaction(joint)
        mag = np.hypot(fx, fy)
        assert np.allclose(np.hypot(g.Fn, g.Ft), mag, atol=1e-9 * mag.max())


def test_rrr_tangential_component_from_moment():
    """Eq. 2.17: the tangential component of F12 from the moment about the inner joint of
    the loads on the first link: F12^t l = -(sum of moments about C of the link's loads)."""
    sol = ks.solve(SCENES.parent / "cases" / "four_bar.toml")
    sp = sol.reaction_split.query("body == 'coupler'")
    assert len(sp) == sol.positions.size
    # the coupler's other loads: inertia + gravity about C, and the link length 0.25 m
    n = sol.positions.size
    xc, yc = [np.broadcast_to(v, (n,)) for v in (sol.kin.dyads[0].xx, sol.kin.dyads[0].xy)]
    moment = np.zeros(n)
    for ld in sol.loads:
        if ld.body != "coupler":
            continue
        x, y = ld.position(sol.kin)
        moment += np.broadcast_to((x - xc) * ld.fy - (y - yc) * ld.fx + ld.m, (n,))
    # Ft acts at B, arm from C to B is -l e; its moment about C is -l Ft (e x J e = 1)
    assert np.allclose(-0.25 * sp.Ft.to_numpy() + moment, 0.0, atol=1e-9 * np.abs(moment).max())


def test_low_transmission_and_summary():
    sol = ks.solve(OWN_CASES / "four_bar.toml")
    s = sol.summary()
    t = sol.dyads.transmission_angle
    worst = np.minimum(t, 180 - t)
    assert s["transmission_angle_min"] == pytest.approx(worst.min())
    low = sol.low_transmission(admissible=worst.min() + 5.0)
    assert 0 < len(low) < len(t)
    assert (np.minimum(low.transmission_angle, 180 - low.transmission_angle)
            < worst.min() + 5.0).all()
    assert s["Me_mean"] == pytest.approx(np.trapezoid(sol.Me, sol.positions) / 360.0)
    for j in sol.scene.joints:
        assert s["reaction_max"][j]["F"] == pytest.approx(
            sol.reactions.query("joint == @j").F.max())
