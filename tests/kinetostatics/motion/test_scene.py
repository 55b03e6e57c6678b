"""Motion under forces of a mechanism scene (contract: "Motion under forces").

The reference is an independent forward-dynamics simulation of the whole four-bar: every
body's Newton-Euler equations with the joint constraints and their multipliers (no
reduction to the driver), positions found by Newton's method on the constraints,
integrated in time by classical Runge-Kutta on the crank angle and speed.
"""

import copy
import json
import math
import tomllib

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.errors import SceneError, WorkbenchError
from tests.helpers import OWN_CASES, run_main, to_toml


def four_bar_motion(**motion):
    with open(OWN_CASES / "four_bar.toml", "rb") as fh:
        d = tomllib.load(fh)
    d["motion"] = {"motor": {"stall_moment": 60.0, "no_load_speed": 32.0}, "flywheel": 0.02,
                   "omega0": 20.0, "cycles": 3, **motion}
    return d


class ForwardFourBar:
    """Constrained multibody dynamics of the scene's revolute-jointed bodies."""

    def __init__(self, d, motor, flywheel):
        self.sc = ks.load_scene(d)
        self.names = list(self.sc.bodies)
        self.motor, self.flywheel = motor, flywheel
        self.q = None

    def _coords(self, q):
        return {b: q[3 * i:3 * i + 3] for i, b in enumerate(self.names)}

    def _local(self, body, point):
        """Point relative to the body's cog (body coordinates = cog position, angle)."""
        b = self.sc.bodies[body]
        p = np.array(b.local(point)) - np.array(b.cog)
        return p

    def _joint_terms(self, q, qd):
        """Constraint residual, Jacobian (8 x 9) and gamma (8)."""
        c = self._coords(q)
        rows, res, gam = [], [], []
        for j in self.sc.joints.values():
            J = np.zeros((2, 9))
            r = np.zeros(2)
            g = np.zeros(2)
            for sign, body, pt in ((1.0, j.bodies[0], j.points[0]),
                                   (-1.0, j.bodies[1], j.points[1])):
                if body == "ground":
                    r += sign * np.array(self.sc.ground[pt])
                    continue
                i = self.names.index(body)
                x, y, th = c[body]
                s = self._local(body, pt)
                R = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
                Rs = R @ s
                r += sign * (np.array([x, y]) + Rs)
                J[:, 3 * i:3 * i + 2] += sign * np.eye(2)
                J[:, 3 * i + 2] += sign * np.array([-Rs[1], Rs[0]])
                g += sign * Rs * qd[3 * i + 2] ** 2
            rows.append(J)
            res.append(r)
            gam.append(g)
        return np.concatenate(res), np.vstack(rows), np.concatenate(gam)

    def assemble(self, phi):
        """Positions for the crank angle phi by Newton's method on the constraints."""
        ic = self.names.index("crank") * 3 + 2
        q = self.q.copy()
        q[ic] = phi
        free = [k for k in range(9) if k != ic]
        for _ in range(50):
            res, J, _ = self._joint_terms(q, np.zeros(9))
            dq = np.linalg.solve(J[:, free], -res)
            q[free] += dq
            if np.abs(dq).max() < 1e-15:
                break
        self.q = q
        return q

    def accel(self, phi, w, t):
        q = self.assemble(phi)
        ic = self.names.index("crank") * 3 + 2
        _, J, _ = self._joint_terms(q, np.zeros(9))
        # velocities: J qd = 0 with the crank's speed given
        A = np.vstack([J, np.eye(9)[ic]])
        qd = np.linalg.solve(A, np.concatenate([np.zeros(8), [w]]))
        _, J, gamma = self._joint_terms(q, qd)
        M = np.zeros(9)
        Q = np.zeros(9)
        gx, gy = self.sc.gravity
        for i, b in enumerate(self.names):
            body = self.sc.bodies[b]
            M[3 * i:3 * i + 3] = (body.mass, body.mass, body.inertia)
            Q[3 * i:3 * i + 2] = (body.mass * gx, body.mass * gy)
        M[ic] += self.flywheel
        for ld in self.sc.loads:
            i = self.names.index(ld.body)
            th = q[3 * i + 2]
            s = self._local(ld.body, ld.point)
            Rs = np.array([math.cos(th) * s[0] - math.sin(th) * s[1],
                           math.sin(th) * s[0] + math.cos(th) * s[1]])
            f = np.array(ld.force)
            Q[3 * i:3 * i + 2] += f
            Q[3 * i + 2] += Rs[0] * f[1] - Rs[1] * f[0] + ld.moment
        Q[ic] += self.motor(w)
        K = np.zeros((17, 17))
        K[:9, :9] = np.diag(M)
        K[:9, 9:] = -J.T
        K[9:, :9] = J
        rhs = np.concatenate([Q, gamma])
        # J qdd = -(dJ/dt) qd; our gamma is +R s w^2 from differentiating the constraints
        return np.linalg.solve(K, rhs)[ic]

    def run(self, phi0, w0, t_end, dt):
        sol = ks.solve(self.sc)
        self.q = np.zeros(9)
        for i, b in enumerate(self.names):
            self.q[3 * i:3 * i + 2] = [np.ravel(v)[0] for v in
                                       sol.kin.bodies[b].point(self.sc.bodies[b].cog)]
            self.q[3 * i + 2] = float(np.ravel(sol.kin.bodies[b].theta)[0])
        phi, w, t = phi0, w0, 0.0
        out = [(t, phi, w)]
        while t < t_end - 1e-12:
            def f(p, ww, tt):
                return ww, self.accel(p, ww, tt)
            k1 = f(phi, w, t)
            k2 = f(phi + dt / 2 * k1[0], w + dt / 2 * k1[1], t + dt / 2)
            k3 = f(phi + dt / 2 * k2[0], w + dt / 2 * k2[1], t + dt / 2)
            k4 = f(phi + dt * k3[0], w + dt * k3[1], t + dt)
            phi += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            w += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            t += dt
            out.append((t, phi, w))
        return np.array(out)


@pytest.mark.slow
def test_agrees_with_forward_dynamics_of_all_bodies():
    d = four_bar_motion(cycles=1)
    res = ks.simulate_motion(d)
    ms, w0 = 60.0, 32.0
    fwd = ForwardFourBar(d, lambda w: ms * (1 - w / w0), 0.02)
    # dt = 5e-4 (400 RK4 steps): the forward integration's own error, measured 6.7e-10 of
    # omega and 1.8e-11 s (1.7e-11 / 4.3e-13 at dt = 2e-4, 2.3 times the CPU; 1.1e-8 /
    # 3.0e-10 at dt = 1e-3, order 4)
    track = fwd.run(0.0, 20.0, 0.2, 5e-4)
    w_ref = res.solution.omega(track[:, 1])
    t_ref = res.solution.state(track[:, 1])[1]
    assert np.abs(track[:, 2] - w_ref).max() <= 3e-9 * np.abs(w_ref).max()
    assert np.abs(track[:, 0] - t_ref).max() <= 1e-10


def test_summary_and_table_contract():
    res = ks.simulate_motion(four_bar_motion())
    s = res.summary
    for key in ("omega_mean", "omega_max", "omega_min", "delta", "chi", "period", "steady"):
        assert key in s
    m = res.motion
    assert list(m.columns) == ["cycle", "position", "time", "omega", "alpha"]
    assert m.cycle.min() == 1 and m.cycle.max() == 3
    assert len(m) == 3 * 361
    assert s["delta"] == pytest.approx((s["omega_max"] - s["omega_min"]) / s["omega_mean"])
    assert s["omega_mean"] == pytest.approx(2 * math.pi / s["period"])
    # the speeds alone (the flywheel search's delta): the same numbers, without alpha
    full, speeds = res.solution.cycle_stats(), res.solution.cycle_stats(alpha=False)
    assert set(full) - set(speeds) == {"alpha_max", "chi", "alpha_max_at"}
    assert speeds == {k: full[k] for k in speeds} and speeds["delta"] == s["delta"]
    last = m[m.cycle == 3]
    assert s["omega_max"] >= last.omega.max() - 1e-12
    assert s["omega_min"] <= last.omega.min() + 1e-12
    # alpha = d omega / dt along the table
    t, w = last.time.to_numpy(), last.omega.to_numpy()
    fd = np.gradient(w, t)
    assert np.abs(fd - last.alpha)[2:-2].max() < 1e-3 * np.abs(last.alpha).max()


@pytest.mark.slow     # 60 cycles to the steady state (2.6 s)
def test_flywheel_for_target_reproduces_delta():
    d = four_bar_motion(cycles=2, target_delta=0.05)
    res = ks.simulate_motion(d)
    j = res.summary["flywheel_for_target"]
    assert j > 0
    d2 = copy.deepcopy(d)
    d2["motion"].pop("target_delta")
    d2["motion"]["flywheel"] = j
    # the periodic steady state: start from its omega (the cycle repeats)
    d2["motion"]["cycles"] = 60
    res2 = ks.simulate_motion(d2)
    assert res2.summary["steady"]
    assert res2.summary["delta"] == pytest.approx(0.05, rel=1e-5)


def test_stall_is_an_error_naming_the_position():
    d = four_bar_motion(motor={"stall_moment": 1.0, "no_load_speed": 32.0}, flywheel=0.0,
                        omega0=1.0)
    with pytest.raises(WorkbenchError) as exc:
        ks.simulate_motion(d)
    assert "stall" in str(exc.value) and "deg" in str(exc.value)


def test_motor_table_and_refusals():
    d = four_bar_motion(cycles=2)
    d["motion"].pop("motor")
    d["motion"]["motor_table"] = [[0.0, 40.0], [180.0, 60.0], [359.0, 40.0]]
    res = ks.simulate_motion(d)
    assert res.summary["omega_mean"] > 0
    d["motion"]["target_delta"] = 0.02
    with pytest.raises(SceneError, match="motor_table"):
        ks.simulate_motion(d)
    d = four_bar_motion(omega0=-1.0)
    with pytest.raises(SceneError, match="omega0"):
        ks.simulate_motion(d)
    with open(OWN_CASES / "sliding_driver.toml", "rb") as fh:
        s = tomllib.load(fh)
    s["motion"] = {"motor": {"stall_moment": 1.0, "no_load_speed": 1.0}, "omega0": 1.0,
                   "cycles": 1}
    with pytest.raises(SceneError, match="sliding"):
        ks.simulate_motion(s)


def test_cli_motion_json(tmp_path):
    d = four_bar_motion(cycles=2)
    path = tmp_path / "m.toml"
    path.write_text(to_toml(d))
    r = run_main("kinetostatics", "motion", str(path), "--json")
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert set(out) == {"summary", "motion"}
    assert set(out["motion"][0]) == {"cycle", "position", "time", "omega", "alpha"}


def test_cli_motion_text_says_units_and_warnings(tmp_path):
    """The text mode: each number with its unit, and the warnings (or "none") as a line;
    a slip (300 rpm typed as rad/s) is there too, and the exit code stays 0."""
    path = tmp_path / "m.toml"
    path.write_text(to_toml(four_bar_motion(cycles=2)))
    r = run_main("kinetostatics", "motion", str(path))
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert any(x.startswith("omega_mean: ") and x.endswith(" rad/s") for x in lines)
    assert any(x.startswith("period: ") and x.endswith(" s") for x in lines)
    assert "warnings: none" in lines
    # six digits, as solve's text; --json keeps every digit
    full = json.loads(run_main("kinetostatics", "motion", str(path), "--json").stdout)
    omega = full["summary"]["omega_mean"]
    omega = omega["value"] if isinstance(omega, dict) else omega
    assert f"omega_mean: {omega:.6g} rad/s" in lines and repr(omega) != f"{omega:.6g}"
    d = four_bar_motion(cycles=2)
    d["motion"]["omega0"] = 300.0
    path.write_text(to_toml(d))
    r = run_main("kinetostatics", "motion", str(path))
    assert r.returncode == 0 and "warning: motion.omega0 = 300 rad/s" in r.stderr
    assert any(x.startswith("warnings: motion.omega0 = 300 rad/s") for x in r.stdout.splitlines())


def test_solving_ahead_changes_no_bit(monkeypatch):
    """cycle_stats's searches solve I_r and M_r ahead, in batches
    (ReducedMechanism.prefetch): the motion's summary is the same to the bit as without.
    (An angle solved ahead but never asked must not answer for a nearby one asked later,
    the cache's keys being 1e-9 rad: tried, 6 of 8 variants of four_bar_motion moved.)"""
    d = four_bar_motion(cycles=2)
    ahead = ks.simulate_motion(d).summary
    monkeypatch.setattr(ks.motion.ReducedMechanism, "prefetch", lambda self, phis: None)
    assert ks.simulate_motion(d).summary == ahead


def test_keys_of_an_array_are_those_of_each_angle():
    """ReducedMechanism.keys (numpy's remainder, product and rint over an array) gives
    each angle the key of the angle alone, round(((phi - phi0) mod 2 pi) 1e9) as Python
    computes it: half-way products (to even), angles below phi0 and turns away, -0.0;
    angles not all finite one by one, as before (Python refuses them)."""
    from kinetostatics.motion.scene import KEY, ReducedMechanism
    phi0 = 0.25
    rm = ReducedMechanism(ks.load_scene(four_bar_motion()), phi0)
    rng = np.random.default_rng(5)
    half = phi0 + np.arange(1, 6400, 2) / 1024.0    # 1e9 / 1024 = 976562.5: odd multiples
    phi = np.concatenate([rng.uniform(-40.0, 40.0, 20_000), half, [phi0, -0.0, 0.0],
                          phi0 + 2.0 * math.pi * np.arange(-3, 4)])
    alone = [int(round(((p - phi0) % (2.0 * math.pi)) * KEY)) for p in phi.tolist()]
    assert all(((p - phi0) % (2.0 * math.pi)) * KEY % 1.0 == 0.5 for p in half.tolist())
    assert rm.keys(phi) == alone
    assert rm.keys(phi[:15]) == alone[:15] and rm.keys(half[:3]) == alone[20_000:20_003]
    with pytest.raises(ValueError):
        rm.keys(np.append(np.zeros(19), math.nan))
