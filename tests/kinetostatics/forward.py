"""An independent forward dynamics of a whole mechanism scene, for the tests.

Every body is free in the plane (x, y of its cog and its angle); revolute joints keep two
points together, prismatic joints keep the slider's angle at the guide's plus the line
angle and the slider point on the guide's line. The equations of motion are Newton-Euler
for every body with the constraint multipliers (no reduction to the driver, no dyads):

    M qdd - J^T lambda = Q,    J qdd = gamma,

positions by Newton's method on the constraints at a given crank angle, velocities from
J qd = 0 with the crank's speed given, and the crank angle and speed integrated in time
by classical Runge-Kutta. Where a ``resist`` load reverses (its point stands still) the
step is halved until the crossing is bracketed within 1e-10 s, so the force's jump costs
no order. Loads: constant forces and moments, ``resist`` forces, gravity, a motor moment
M(omega) and a flywheel on the crank.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

import kinetostatics as ks


def _rot(th: float) -> np.ndarray:
    c, s = math.cos(th), math.sin(th)
    return np.array([[c, -s], [s, c]])


_J = np.array([[0.0, -1.0], [1.0, 0.0]])        # +90 deg
_EYE = np.eye(2)


class ForwardMechanism:
    """Constrained multibody dynamics of a scene's bodies (R and T joints)."""

    def __init__(self, scene, motor: Callable[[float], float], flywheel: float = 0.0):
        self.sc = ks.load_scene(scene)
        self.names = list(self.sc.bodies)
        self.nq = 3 * len(self.names)
        self.motor, self.flywheel = motor, flywheel
        self.ic = 3 * self.names.index(self.sc.driver.body) + 2
        self.q = np.zeros(self.nq)
        # (the arms and body indices looked up once: the same numbers, a third of the
        # CPU of a run of many steps spent finding them again)
        self.index = {b: i for i, b in enumerate(self.names)}
        self.arms: dict[tuple[str, str], tuple[float, float]] = {}

    # -- geometry ---------------------------------------------------------------------
    def _arm(self, body: str, point: str) -> tuple[float, float]:
        """A point relative to the body's cog, in body axes."""
        arm = self.arms.get((body, point))
        if arm is None:
            b = self.sc.bodies[body]
            arm = self.arms[body, point] = tuple(
                float(v) for v in np.array(b.local(point)) - np.array(b.local("cog")))
        return arm

    def _state(self, q, body):
        if body == "ground":
            return np.zeros(2), 0.0, None
        i = self.index[body]
        return q[3 * i:3 * i + 2], q[3 * i + 2], i

    def _scalars(self, q, qd, body, point):
        """(x, y, vx, vy, R s x, R s y, body index) of a point, as floats."""
        if body == "ground":
            x, y = self.sc.ground[point]
            return float(x), float(y), 0.0, 0.0, 0.0, 0.0, None
        i = self.index[body]
        c, s = math.cos(q[3 * i + 2]), math.sin(q[3 * i + 2])
        ax, ay = self._arm(body, point)
        rx, ry = c * ax - s * ay, s * ax + c * ay              # R s, the arm turned
        w = qd[3 * i + 2]                                       # v = v_cog + w J R s
        return q[3 * i] + rx, q[3 * i + 1] + ry, qd[3 * i] - w * ry, qd[3 * i + 1] + w * rx, \
            rx, ry, i

    def _point(self, q, qd, body, point):
        """Global position, velocity, the arm R s, and the body index of a point."""
        x, y, vx, vy, rx, ry, i = self._scalars(q, qd, body, point)
        return np.array([x, y]), np.array([vx, vy]), np.array([rx, ry]), i

    def constraints(self, q, qd):
        """Residual, Jacobian and gamma (J qdd = gamma) of every joint."""
        res, rows, gam = [], [], []
        for j in self.sc.joints.values():
            if j.kind == "R":
                Jr = np.zeros((2, self.nq))
                r = [0.0, 0.0]
                g = [0.0, 0.0]
                for sign, body, pt in ((1.0, j.bodies[0], j.points[0]),
                                       (-1.0, j.bodies[1], j.points[1])):
                    x, y, _, _, rx, ry, i = self._scalars(q, qd, body, pt)
                    r[0] += sign * x
                    r[1] += sign * y
                    if i is None:
                        continue
                    Jr[0, 3 * i] += sign
                    Jr[1, 3 * i + 1] += sign
                    Jr[0, 3 * i + 2] -= sign * ry                 # sign J R s
                    Jr[1, 3 * i + 2] += sign * rx
                    w2 = qd[3 * i + 2] ** 2
                    g[0] += sign * rx * w2
                    g[1] += sign * ry * w2
                res.append(r)
                rows.append(Jr)
                gam.append(g)
                continue
            # prismatic: theta_s - theta_g - beta = 0 and n . (P_S - P_L) = 0
            beta = j.beta
            _, thg, ig = self._state(q, j.guide)
            _, ths, is_ = self._state(q, j.slider)
            Jt = np.zeros((2, self.nq))
            Jt[0, 3 * is_ + 2] = 1.0
            if ig is not None:
                Jt[0, 3 * ig + 2] = -1.0
            c0 = ths - thg - beta
            n = _rot(thg) @ np.array([-math.sin(beta), math.cos(beta)])
            wg = 0.0 if ig is None else qd[3 * ig + 2]
            ps, vs, rss, _ = self._point(q, qd, j.slider, j.points[1])
            pl, vl, rsl, _ = self._point(q, qd, j.guide, j.points[0])
            d, dd = ps - pl, vs - vl
            Jt[1, 3 * is_:3 * is_ + 2] = n
            Jt[1, 3 * is_ + 2] = n @ (_J @ rss)
            if ig is not None:
                Jt[1, 3 * ig:3 * ig + 2] = -n
                Jt[1, 3 * ig + 2] = (_J @ n) @ d - n @ (_J @ rsl)
            ws = qd[3 * is_ + 2]
            # c2'' = n''.d + 2 n'.d' + n.d'' ; the qdd-free part, moved to the right
            free = (-wg**2 * (n @ d) + 2.0 * wg * ((_J @ n) @ dd)
                    + n @ (-ws**2 * rss + wg**2 * rsl))
            res.append([c0, n @ d])
            rows.append(Jt)
            gam.append([0.0, -free])
        return np.array(res).ravel(), np.vstack(rows), np.array(gam).ravel()

    def assemble(self, phi: float) -> np.ndarray:
        """Positions at the crank angle phi (rad), Newton from the last positions."""
        q = self.q.copy()
        q[self.ic] = phi
        free = [k for k in range(self.nq) if k != self.ic]
        zero = np.zeros(self.nq)
        for _ in range(60):
            res, J, _ = self.constraints(q, zero)
            dq = np.linalg.lstsq(J[:, free], -res, rcond=None)[0]
            q[free] += dq
            if np.abs(dq).max() < 1e-15:
                break
        self.q = q
        return q

    def velocities(self, q, w: float) -> np.ndarray:
        _, J, _ = self.constraints(q, np.zeros(self.nq))
        A = np.vstack([J, np.eye(self.nq)[self.ic]])
        b = np.zeros(A.shape[0])
        b[-1] = w
        return np.linalg.lstsq(A, b, rcond=None)[0]

    def resist_speeds(self, phi: float, w: float) -> list[float]:
        """Signed speed along its first direction of every ``resist`` point (its sign
        changes where the load reverses)."""
        q = self.assemble(phi)
        qd = self.velocities(q, w)
        out = []
        for ld in self.sc.loads:
            if ld.resist is not None:
                _, v, _, _ = self._point(q, qd, ld.body, ld.point)
                out.append(float(v[0] if abs(v[0]) >= abs(v[1]) else v[1]))
        return out

    def accel(self, phi: float, w: float) -> float:
        """The crank's angular acceleration at angle phi and speed w."""
        q = self.assemble(phi)
        qd = self.velocities(q, w)
        _, J, gamma = self.constraints(q, qd)
        M = np.zeros(self.nq)
        Q = np.zeros(self.nq)
        gx, gy = self.sc.gravity
        for i, b in enumerate(self.names):
            body = self.sc.bodies[b]
            M[3 * i:3 * i + 3] = (body.mass, body.mass, body.inertia)
            Q[3 * i:3 * i + 2] = (body.mass * gx, body.mass * gy)
        M[self.ic] += self.flywheel
        for ld in self.sc.loads:
            i = self.names.index(ld.body)
            if ld.point is None:
                Q[3 * i + 2] += ld.moment
                continue
            _, v, rs, _ = self._point(q, qd, ld.body, ld.point)
            if ld.resist is not None:
                f = -ld.resist * v / np.hypot(*v)
            else:
                f = np.array(ld.force if ld.force is not None else (0.0, 0.0))
            Q[3 * i:3 * i + 2] += f
            Q[3 * i + 2] += rs[0] * f[1] - rs[1] * f[0] + ld.moment
        Q[self.ic] += self.motor(w)
        m = J.shape[0]
        K = np.zeros((self.nq + m, self.nq + m))
        K[:self.nq, :self.nq] = np.diag(M)
        K[:self.nq, self.nq:] = -J.T
        K[self.nq:, :self.nq] = J
        # translating bodies with no inertia about their cog: the constraints carry them
        sol = np.linalg.lstsq(K, np.concatenate([Q, gamma]), rcond=None)[0]
        return float(sol[self.ic])

    def start(self) -> None:
        """Positions at the scene's first row (the scene's own assembly)."""
        sol = ks.solve(self.sc)
        for i, b in enumerate(self.names):
            m = sol.kin.bodies[b]
            self.q[3 * i:3 * i + 2] = [float(np.ravel(v)[0]) for v in
                                       m.point(self.sc.bodies[b].local("cog"))]
            self.q[3 * i + 2] = float(np.ravel(m.theta)[0])

    def run(self, phi0: float, w0: float, t_end: float, dt: float) -> np.ndarray:
        """(t, phi, omega) rows from t = 0 to t_end, Runge-Kutta 4 with the resist
        reversals bracketed."""
        self.start()

        def f(p, ww):
            return ww, self.accel(p, ww)

        def step(p, w, h):
            k1 = f(p, w)
            k2 = f(p + h / 2 * k1[0], w + h / 2 * k1[1])
            k3 = f(p + h / 2 * k2[0], w + h / 2 * k2[1])
            k4 = f(p + h * k3[0], w + h * k3[1])
            return (p + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]),
                    w + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]))

        phi, w, t = phi0, w0, 0.0
        out = [(t, phi, w)]
        while t < t_end - 1e-12:
            h = min(dt, t_end - t)
            q_saved = self.q.copy()
            s0 = np.sign(self.resist_speeds(phi, w))
            while True:
                self.q = q_saved.copy()
                p1, w1 = step(phi, w, h)
                if h < 1e-10 or np.array_equal(np.sign(self.resist_speeds(p1, w1)), s0):
                    break
                h /= 2.0
            phi, w, t = p1, w1, t + h
            out.append((t, phi, w))
        return np.array(out)
