"""Joint friction (seed 002 s. 2.4): friction circle rho = r mu, prismatic friction."""

import copy
import re
import tomllib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinetostatics as ks
from kinetostatics.model.errors import SceneError
from tests.helpers import OWN_CASES
from tests.kinetostatics.scenes import with_friction


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
    sol = ks.solve(with_friction(load("slider_crank"), 1.3, radius=0.03, length=0.08))
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


# -- friction solved row by row: closed forms, self-locking, the power balance ---------

R_CRANK, L_ROD, E_OFFSET, RESIST = 0.05, 0.12, 0.03, 100.0


def offset_slider_crank(mu, positions=None, count=721, r=R_CRANK, length=L_ROD, e=E_OFFSET):
    """Massless offset slider-crank (crank r, rod ``length``, guide e above the crank
    pivot), friction in the guide only, a ``resist`` force on the slider."""
    drv = {"body": "crank", "joint": "A", "speed": 10.0}
    drv.update({"positions": list(positions)} if positions is not None else
               {"start": 0.0, "stop": 360.0, "count": count})
    return {
        "ground": {"A": [0.0, 0.0], "O": [0.0, e]},
        "driver": drv,
        "bodies": [{"name": "crank", "points": {"A": [0.0, 0.0], "B": [r, 0.0]}},
                   {"name": "rod", "points": {"B": [0.0, 0.0], "C": [length, 0.0]}},
                   {"name": "slider", "points": {"C": [0.0, 0.0]}}],
        "joints": [{"name": "A", "kind": "R", "bodies": ["ground", "crank"]},
                   {"name": "B", "kind": "R", "bodies": ["crank", "rod"]},
                   {"name": "C", "kind": "R", "bodies": ["rod", "slider"]},
                   {"name": "slide", "kind": "T", "guide": "ground", "slider": "slider",
                    "line_point": "O", "slider_point": "C", "friction": {"mu": mu}}],
        "loads": [{"body": "slider", "point": "C", "resist": RESIST}],
        "near": {"C": [r + length, e]},
    }


def slider_crank_closed_form(mu, positions_deg, speed_sign, r=R_CRANK, length=L_ROD,
                             e=E_OFFSET):
    """Me and mu tan(psi) per row. The rod (massless) pushes the slider with T along
    C - B; along the guide T cos(psi) = sgn(v) (R + mu |T sin(psi)|), so with v > 0
    T = R / (cos(psi) - mu |sin(psi)|), which exists only while mu tan(psi) < 1; then
    Me = (B x T (C - B) / l)."""
    phi = np.deg2rad(np.asarray(positions_deg, dtype=float))
    bx, by = r * np.cos(phi), r * np.sin(phi)
    c = np.sqrt(length**2 - (e - by) ** 2) / length                 # cos(psi)
    s = (e - by) / length                                           # sin(psi)
    with np.errstate(divide="ignore"):
        t = speed_sign * RESIST / (c - mu * np.abs(s))
    me = (bx * s - by * c) * t
    return me, mu * np.abs(s) / c


def slider_velocity_sign(sol):
    k = sol.kinematics
    return np.sign(k[(k.body == "slider") & (k.point == "C")].vx.to_numpy())


@pytest.mark.parametrize("mu", [1.0, 1.2, 1.5])
def test_offset_slider_crank_locks_exactly_where_mu_tan_psi_reaches_1(mu):
    """Every row settles on its own scale: rows with mu tan(psi) up to 0.997 hold their
    closed-form Me (a fixed-point iteration stalls there), and the flag falls exactly
    where mu tan(psi) >= 1."""
    sol = ks.solve(offset_slider_crank(mu))
    me, mutan = slider_crank_closed_form(mu, sol.positions, slider_velocity_sign(sol))
    locked = sol.driver.self_locking.to_numpy()
    assert np.array_equal(locked, mutan >= 1.0)
    free = ~locked & ~sol.driver.undefined_load.to_numpy()
    assert ((mutan > 0.86) & free).sum() >= 20          # the rows that used not to settle
    err = np.abs(sol.Me[free] - me[free]).max() / np.abs(me[free]).max()
    assert err <= 2e-13                                 # measured 3.5e-14 (mu = 1.5)
    assert np.isnan(sol.Me[locked]).all() and np.isfinite(sol.Me[~locked]).all()
    r = sol.reactions
    lk = np.tile(locked, len(sol.scene.joints))
    assert r[lk][["Fx", "Fy", "F"]].isna().all().all()
    assert r[lk & (r.joint == "slide")][["N", "M"]].isna().all().all()   # pins: N = M = 0
    assert np.isfinite(r[~lk][["Fx", "Fy", "F", "N", "M"]].to_numpy()).all()
    s = sol.summary()
    assert s["self_locking_rows"] == int(locked.sum())
    assert np.isfinite([s["Me_mean"], s["Me_max"], s["Me_min"]]).all()
    assert s["Me_max"] == np.nanmax(sol.Me)


def test_rows_next_to_the_locking_limit_hold_their_true_values():
    """mu tan(psi) = 1 - delta: Me grows like 1 / delta and is given in full; past 1 the
    row is flagged."""
    mu = 1.2
    deltas = np.array([1e-2, 1e-4, 1e-6, 1e-9, -1e-9, -1e-4])
    t = (1.0 - deltas) / mu                                   # tan(psi)
    s = t / np.sqrt(1.0 + t * t)
    phi = np.rad2deg(np.arcsin((E_OFFSET - L_ROD * s) / R_CRANK))   # in (-90, 0) deg
    sol = ks.solve(offset_slider_crank(mu, positions=phi))
    me, mutan = slider_crank_closed_form(mu, sol.positions, slider_velocity_sign(sol))
    locked = sol.driver.self_locking.to_numpy()
    assert locked.tolist() == [False] * 4 + [True] * 2
    rel = np.abs(sol.Me[:4] / me[:4] - 1.0)
    # measured 1.6e-9 at delta = 1e-9 (the closed form's own rounding: about eps / delta)
    assert (rel <= 20 * np.finfo(float).eps / deltas[:4]).all(), rel
    assert abs(sol.Me[3]) > 1e9


def test_virtual_power_with_friction_closes_at_every_free_row():
    """The balance Me w + loads + inertia + friction power (from the reactions table and
    the scene's coefficients only) closes to rounding at every row that is not locked,
    also with friction strong enough to lock three quarters of the sweep."""
    from tests.kinetostatics.checks import virtual_power_with_friction
    for name, mu in [("four_bar", 0.1), ("slotted_lever", 0.1), ("slider_crank", 1.3),
                     ("sliding_driver", 0.3)]:
        d = load(name)
        for j in d["joints"]:
            j["friction"] = {"mu": mu, "radius": 0.03} if j["kind"] == "R" else \
                {"mu": mu, "length": 0.08}
        sol = ks.solve(d)
        assert virtual_power_with_friction(sol) <= 1e-14, name     # measured <= 8e-16


def _sliding_driver_with_pin_friction(moment):
    d = load("sliding_driver")
    for j in d["joints"]:
        if j["name"] == "A":
            j["friction"] = {"mu": 2.0, "radius": 0.05}       # rho = 0.1 > crank 0.09
    d["loads"][0]["moment"] = moment
    return d


def test_every_row_locked_is_refused_with_the_critical_coefficient():
    """The crank turns clockwise; with a moment that resists it (+12 N m) and a friction
    circle (rho = 0.1 m) larger than the crank (0.09 m), the rod's force can never turn
    it: the scene is refused. The critical coefficient is d / r (d: distance from A to
    the rod's line), largest 0.09 / 0.05 = 1.8, smallest at the sweep's end row."""
    from kinetostatics.solver.friction import SelfLockingError
    d = _sliding_driver_with_pin_friction(12.0)
    with pytest.raises(SelfLockingError) as exc:
        ks.solve(d)
    msg = str(exc.value)
    assert "\n" not in msg and "self-locks at every position" in msg and "'A'" in msg
    ref = ks.solve(load("sliding_driver")).kinematics
    b = ref[(ref.body == "crank") & (ref.point == "B")][["x", "y"]].to_numpy()
    c = ref[(ref.body == "slider") & (ref.point == "C")][["x", "y"]].to_numpy()
    e = (b - c) / np.hypot(*(b - c).T)[:, None]
    dist = np.abs(c[:, 0] * e[:, 1] - c[:, 1] * e[:, 0])      # A = origin to line CB
    high, low = re.findall(r"below ([0-9.e+-]+)", msg)
    assert float(high) == pytest.approx(dist.max() / 0.05, rel=1e-5)
    assert float(low) == pytest.approx(dist.min() / 0.05, rel=1e-5)
    # just below the reported coefficient that position moves, just above it locks
    pos = float(re.search(r"at position ([0-9.e+-]+) m", msg).group(1))
    d["driver"].update(positions=[pos])
    for k in ("start", "stop", "count"):
        d["driver"].pop(k, None)
    d["joints"][-1]["friction"]["mu"] = 0.999 * float(high)
    assert not ks.solve(d).driver.self_locking.any()
    d["joints"][-1]["friction"]["mu"] = 1.001 * float(high)
    with pytest.raises(SelfLockingError):
        ks.solve(d)


def test_cli_refuses_a_sweep_that_locks_everywhere(tmp_path):
    import subprocess
    import sys
    text = (OWN_CASES / "sliding_driver.toml").read_text()
    text = text.replace('bodies = ["ground", "crank"]', 'bodies = ["ground", "crank"]\n'
                        'friction = { mu = 2.0, radius = 0.05 }')
    path = tmp_path / "locked.toml"
    path.write_text(text.replace("moment = -12.0", "moment = 12.0"))
    out = subprocess.run([sys.executable, "-m", "kinetostatics", "solve", str(path)],
                         capture_output=True, text=True, check=False)
    assert out.returncode == 2
    assert out.stderr.startswith("error: the mechanism self-locks") and "Traceback" not in \
        out.stderr and out.stderr.count("\n") == 1


def test_a_load_that_drives_the_crank_is_not_self_locking():
    """The bundled sliding driver's crank turns clockwise and its -12 N m moment drives
    it: with the same oversized friction circle at A the mechanism still moves (the
    slider brakes it). Its branch from no friction is the finite one, |F_A| about
    12 / (rho + d): no row locks, the power balance closes, and the pin's friction
    couple is rho |F_A| at every row."""
    from tests.kinetostatics.checks import virtual_power_with_friction
    sol = ks.solve(_sliding_driver_with_pin_friction(-12.0))
    assert not sol.driver.self_locking.any()
    assert (sol.Me < 0.0).all()                               # the slider holds back
    assert virtual_power_with_friction(sol) <= 1e-14          # measured 7.9e-16
    fa = sol.reactions.query("joint == 'A'").F.to_numpy()
    couple = [ld for ld in sol.loads if ld.kind == "friction"][0]
    assert np.allclose(np.abs(couple.m), 0.1 * fa, rtol=1e-13, atol=0)
    # independent: the global matrix solve gives F_A = F0 + b s and Fe = Fe0 + f s for a
    # couple s on the crank (against omega < 0: counter-clockwise); s = rho |F_A| is a
    # quadratic with two roots >= 0 at every row (rho |b| > 1): the slider braking, or
    # the crank wedged and pushed by it. The kept one is the first.
    from tests.kinetostatics.checks import matrix_solution
    plain = load("sliding_driver")
    unit = copy.deepcopy(plain)
    unit["loads"].append({"body": "crank", "moment": 1.0})
    (ra, fe0), (rb, fe1) = (matrix_solution(ks.solve(x)) for x in (plain, unit))
    f0 = np.stack(ra["A"][:2], axis=1)
    b, f = np.stack(rb["A"][:2], axis=1) - f0, fe1 - fe0
    rho = 0.1
    qa = 1.0 - rho**2 * (b * b).sum(axis=1)
    qb = -2.0 * rho**2 * (f0 * b).sum(axis=1)
    qc = -(rho**2) * (f0 * f0).sum(axis=1)
    roots = (-qb[:, None] + np.array([1.0, -1.0]) * np.sqrt(qb * qb - 4 * qa * qc)[:, None]) \
        / (2.0 * qa[:, None])
    assert (roots >= 0.0).all()
    fe = fe0[:, None] + roots * f[:, None]
    braking = fe[np.arange(fe.shape[0]), np.argmin(fe, axis=1)]
    assert (fe.max(axis=1) > 0.0).all()                       # the wedged root pushes
    assert np.allclose(sol.Me, braking, rtol=1e-13, atol=0)   # measured 1.3e-15


@settings(max_examples=40, deadline=None)
@given(r=st.floats(0.02, 0.2), ratio=st.floats(1.5, 5.0), offset=st.floats(-0.9, 0.9),
       mu=st.floats(0.05, 3.0))
def test_slider_crank_friction_property(r, ratio, offset, mu):
    """Any offset slider-crank, any guide friction: locked exactly where mu tan(psi) >= 1
    (up to rounding at the limit itself) and Me equal to the closed form elsewhere, to
    the problem's own conditioning eps / (1 - mu tan(psi))."""
    from kinetostatics.solver.friction import SelfLockingError
    length = ratio * r
    e = offset * (length - r)
    try:
        sol = ks.solve(offset_slider_crank(mu, count=181, r=r, length=length, e=e))
    except SelfLockingError:                # every row locks: so says the closed form
        _me, mutan = slider_crank_closed_form(mu, np.linspace(0.0, 360.0, 181), 1.0, r,
                                              length, e)
        assert (mutan >= 1.0 - 1e-9).all()
        return
    me, mutan = slider_crank_closed_form(mu, sol.positions, slider_velocity_sign(sol), r,
                                         length, e)
    locked = sol.driver.self_locking.to_numpy()
    # rows at the limit itself (rounding) or where the slider stands still (no friction)
    clear = (np.abs(mutan - 1.0) > 1e-9) & ~sol.driver.undefined_load.to_numpy()
    assert np.array_equal(locked[clear], mutan[clear] >= 1.0)
    free = ~locked & clear
    # the row's own scale: the crank times the rod force |T| = R / |cos(psi) - mu |sin(psi)||,
    # amplified by the conditioning 1 / (1 - mu tan(psi)); measured <= 2.9 of it
    phi = np.deg2rad(sol.positions[free])
    sn = (e - r * np.sin(phi)) / length
    force = RESIST / np.abs(np.sqrt(1.0 - sn * sn) - mu * np.abs(sn))
    bound = 20.0 * np.finfo(float).eps * r * force / (1.0 - mutan[free])
    assert (np.abs(sol.Me[free] - me[free]) <= bound).all()


def test_each_row_is_decided_on_its_own():
    """Rows in a scrambled order, or alone, get the same flags and values as in the
    ordered sweep (each row's friction system is solved and followed by itself)."""
    d = load("slider_crank")
    for j in d["joints"]:
        j["friction"] = {"mu": 1.3, "radius": 0.03} if j["kind"] == "R" else \
            {"mu": 1.3, "length": 0.08}
    whole = ks.solve(d)
    rng = np.random.default_rng(7)
    pick = rng.permutation(whole.positions.size)[:90]
    part = copy.deepcopy(d)
    for k in ("start", "stop", "count"):
        part["driver"].pop(k, None)
    part["driver"]["positions"] = [float(p) for p in whole.positions[pick]]
    sol = ks.solve(part)
    locked = whole.driver.self_locking.to_numpy()[pick]
    assert np.array_equal(sol.driver.self_locking.to_numpy(), locked)
    assert 0 < locked.sum() < locked.size
    me = np.asarray(whole.Me)[pick]
    assert np.allclose(sol.Me[~locked], me[~locked], rtol=1e-13, atol=0)   # measured: equal


@pytest.mark.parametrize("mu", [1.4, 1.7])           # |d| / r runs from 1.24 to 1.8
def test_pin_friction_locks_where_the_rod_passes_inside_the_friction_circle(mu):
    """The sliding driver made massless, a moment of 12 N m resisting the crank and
    friction only in its ground pin A (rho = mu 0.05 m). The rod is a two-force member:
    its force t e (e along C -> B) on the crank gives t d + 12 + rho |t| = 0 about A
    (d = B x e, the rod line's signed distance from A; the friction couple against
    omega < 0), which has a solution only while |d| > rho: t = -12 / (d - rho sgn(d)),
    and Fe = t e_x. The flag falls exactly where |d| <= rho."""
    d = load("sliding_driver")
    d["gravity"] = [0.0, 0.0]
    for b in d["bodies"]:
        b["mass"], b["inertia"] = 0.0, 0.0
    d["loads"] = [{"body": "crank", "moment": 12.0}]
    ref = ks.solve(copy.deepcopy(d))
    k = ref.kinematics
    b = k[(k.body == "crank") & (k.point == "B")][["x", "y"]].to_numpy()
    c = k[(k.body == "slider") & (k.point == "C")][["x", "y"]].to_numpy()
    e = (b - c) / np.hypot(*(b - c).T)[:, None]
    dist = b[:, 0] * e[:, 1] - b[:, 1] * e[:, 0]
    assert (ref.bodies.query("body == 'crank'").omega < 0.0).all()
    rho = mu * 0.05
    next(j for j in d["joints"] if j["name"] == "A")["friction"] = {"mu": mu, "radius": 0.05}
    sol = ks.solve(d)
    locked = sol.driver.self_locking.to_numpy()
    assert np.array_equal(locked, np.abs(dist) <= rho)
    assert 0 < locked.sum() < locked.size
    t = -12.0 / (dist - rho * np.sign(dist))
    fe = t * e[:, 0]
    # measured 6.2e-13 (mu = 1.4, a row 2.5e-5 m outside the circle: Fe = 4.8e5 N)
    assert np.allclose(sol.Me[~locked], fe[~locked], rtol=2e-12, atol=0)


def test_flagged_rows_have_no_equilibrium_by_an_independent_search():
    """Slider-crank, mu = 1.3 in every joint (pins r = 0.03 m, guide l = 0.08 m). The
    friction system is rebuilt here from the tests' global matrix solve (the reactions
    under the scene's loads and under each unit friction load, signs from the relative
    motions) and searched by a damped Newton with a finite-difference Jacobian from 300
    starts per row: at flagged rows no magnitudes s >= 0 satisfy s = h(reactions); at
    free rows the search finds the solver's friction."""
    from tests.kinetostatics.checks import matrix_solution
    mu, r, length = 1.3, 0.03, 0.08
    plain = load("slider_crank")
    sol0 = ks.solve(plain)
    ref, _ = matrix_solution(sol0)
    bt = sol0.bodies
    w = {b: bt.query(f"body == '{b}'").omega.to_numpy() for b in ("crank", "rod")}
    al = {b: bt.query(f"body == '{b}'").alpha.to_numpy() for b in ("crank", "rod")}
    k = sol0.kinematics
    piston = k[(k.body == "piston") & (k.point == "C")]
    vx, ax = piston.vx.to_numpy(), piston.ax.to_numpy()

    def against(v, a):      # at rest (the piston at a dead centre): the acceleration's
        still = np.abs(v) <= 1e-9 * np.abs(v).max()
        return np.where(still, -np.sign(a), -np.sign(v))
    units = {"A": ([("crank", 1.0)], against(w["crank"], al["crank"])),
             "B": ([("rod", 1.0), ("crank", -1.0)],
                   against(w["rod"] - w["crank"], al["rod"] - al["crank"])),
             "C": ([("piston", 1.0), ("rod", -1.0)], -against(w["rod"], al["rod"])),
             "C-slide": (None, against(vx, ax))}
    joints = list(units)

    def quantities(res):
        out = []
        for j in joints:
            fx, fy, nn, mm = res[j]
            out += [fx, fy] if nn is None else [nn, mm]
        return np.stack(out, axis=1)                            # (n, 8)

    q0 = quantities(ref)
    cols = []
    for j in joints:
        d = copy.deepcopy(plain)
        couples, sign = units[j]
        if couples is None:
            d["loads"].append({"body": "piston", "point": "C", "force": [1.0, 0.0]})
        else:
            d["loads"] += [{"body": b, "moment": m} for b, m in couples]
        cols.append((quantities(matrix_solution(ks.solve(d))[0]) - q0) * sign[:, None])
    g = np.stack(cols, axis=2)                                  # (n, 8, 4)

    def h(q):                                                   # (..., 8) -> (..., 4)
        rho = mu * r
        na = 0.5 * q[..., 6] - q[..., 7] / length
        nb = 0.5 * q[..., 6] + q[..., 7] / length
        return np.stack([rho * np.hypot(q[..., 0], q[..., 1]),
                         rho * np.hypot(q[..., 2], q[..., 3]),
                         rho * np.hypot(q[..., 4], q[..., 5]),
                         mu * (np.abs(na) + np.abs(nb))], axis=-1)

    def search(rows, starts):
        """Newton from every start (rows, starts, 4) at once (a row at a time cost 2.3 s
        of CPU, 2026-11-29): the solutions found, and which starts reached one."""
        q, gt = q0[rows][:, None, :], g[rows].transpose(0, 2, 1)     # (rows, 1, 8), (rows, 4, 8)

        def f(s):
            return s - h(q + s @ gt)
        s = starts
        for _ in range(60):
            fs = f(s)
            jac = np.empty(s.shape + (4,))
            step = 1e-7 * (1.0 + np.abs(s).max(axis=(1, 2)))[:, None, None]
            for i in range(4):
                e = np.zeros(4)
                e[i] = 1.0
                jac[..., i] = (f(s + step * e) - fs) / step
            with np.errstate(all="ignore"):
                ds = np.linalg.solve(jac + 1e-300, -fs[..., None])[..., 0]
            s = np.where(np.isfinite(ds), s + np.clip(ds, -1e9, 1e9), s)
        fs = f(s)
        ok = (np.abs(fs).max(axis=2) <= 1e-8 * (1.0 + np.abs(s).max(axis=2))) & \
            (s >= -1e-9 * np.abs(s).max(axis=2, keepdims=True)).all(axis=2)
        return s, ok

    d = copy.deepcopy(plain)
    for j in d["joints"]:
        j["friction"] = {"mu": mu, "radius": r} if j["kind"] == "R" else \
            {"mu": mu, "length": length}
    sol = ks.solve(d)
    locked = sol.driver.self_locking.to_numpy()
    fric = np.stack([np.abs(np.broadcast_to(ld.m if ld.label.startswith("friction couple")
                                            else ld.fx, locked.shape))
                     for ld in sol.loads if ld.kind == "friction"
                     and ld.body == {"A": "crank", "B": "rod", "C": "piston",
                                     "C-slide": "piston"}[ld.label.split()[-1]]], axis=1)
    rng = np.random.default_rng(3)
    scale = np.abs(q0).max(axis=1) * mu * r

    def starts(rows):           # 300 a row, over seven decades of the row's force scale
        n = (rows.size, 300)
        return rng.exponential(1.0, n + (4,)) * 10.0 ** rng.uniform(-2, 5, n + (1,)) * \
            scale[rows][:, None, None]
    rows = np.flatnonzero(locked)[::9]
    _s, ok = search(rows, starts(rows))
    assert rows.size and not ok.any(), sol.positions[rows[ok.any(axis=1)]]
    moving = np.stack([np.abs(units[j][1]) for j in joints], axis=1)   # 0: no friction load
    rows = np.flatnonzero(~locked)[::9]
    # the same random search finds the solver's friction (the search is not blind)
    s, ok = search(rows, starts(rows))
    hit = np.isclose(s * moving[rows][:, None, :], fric[rows][:, None, :], rtol=1e-6).all(
        axis=2) & ok
    assert rows.size and hit.any(axis=1).all(), sol.positions[rows[~hit.any(axis=1)]]
