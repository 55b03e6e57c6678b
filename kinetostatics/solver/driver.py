"""Motion of a body over the sweep, and of the driving element (seed 000 ch. 4).

A :class:`BodyMotion` holds, per position, the cos and sin of a body's angle, its angular
velocity and acceleration, and the global position, velocity and acceleration of its
local origin; :func:`driver_motion` gives the crank's or the sliding driver's.
"""

from __future__ import annotations

import numpy as np

from ..model.scene import GROUND, Scene
from . import arith as A


class BodyMotion:
    """Planar motion of a body over the sweep: cos and sin of its angle, angular velocity
    and acceleration, and the global position, velocity and acceleration of its local
    origin. Any of them may be a scalar (a fixed pivot, a constant speed); ``theta``
    (rad) is computed when first asked for unless given."""

    FIELDS = ("cos", "sin", "omega", "alpha", "ox", "oy", "vx", "vy", "ax", "ay")
    __slots__ = (*FIELDS, "_theta", "_origin_arm", "_arms")

    def __init__(self, theta, cos, sin, omega, alpha, ox, oy, vx, vy, ax, ay):
        self._theta = theta
        self._origin_arm = None
        self._arms = None
        self.cos, self.sin = cos, sin
        self.omega, self.alpha = omega, alpha
        self.ox, self.oy, self.vx, self.vy, self.ax, self.ay = ox, oy, vx, vy, ax, ay

    @property
    def theta(self):
        if self._theta is None:
            self._theta = np.arctan2(self.sin, self.cos)
        return self._theta

    def rotate(self, lx: float, ly: float):
        """A local vector turned into global axes: R(theta) l (the lever arm from the
        origin of a local point). The arm of the origin itself, asked for by most
        loads and joints, is worked out once."""
        if type(lx) is float and type(ly) is float and lx == 0.0 and ly == 0.0:
            arm = self._origin_arm
            if arm is None:
                arm = self._origin_arm = A.rotate(self.cos, self.sin, lx, ly)
            return arm
        return A.rotate(self.cos, self.sin, lx, ly)

    def arm(self, local: tuple):
        """:meth:`rotate` of a named point of the body, ``local`` the tuple of its local
        coordinates the scene's Body holds (the same object each time it is asked for:
        a joint's point is asked for by the kinematics and again by the reactions),
        worked out once while the motion keeps its arms (:meth:`forget_arms`)."""
        arms = getattr(self, "_arms", None)     # (None too in a motion built by fields)
        if arms is None:
            arms = self._arms = []
        for t, a in arms:
            if t is local:
                return a
        a = self.rotate(*local)
        arms.append((local, a))
        return a

    def keep_arm(self, local: tuple, arm: tuple) -> None:
        """Keep ``arm``, worked out elsewhere as :meth:`rotate` of ``local`` with this
        motion's own cos and sin, for :meth:`arm`."""
        arms = getattr(self, "_arms", None)
        if arms is None:
            arms = self._arms = []
        arms.append((local, arm))

    def forget_arms(self) -> None:
        """Let go of the arms :meth:`arm` kept and of :meth:`omega2` (arrays over the
        rows)."""
        self._arms = None

    def omega2(self):
        """omega^2, worked out once as :meth:`arm` keeps an arm (the accelerations of
        the body's points each ask for it; the
        square the kinematics worked out, the same product: :meth:`keep_omega2`)."""
        arms = getattr(self, "_arms", None)
        if arms is not None:
            for t, a in arms:
                if t is _OMEGA2:
                    return a
        w2 = A.mul(self.omega, self.omega)
        self.keep_arm(_OMEGA2, w2)
        return w2

    def keep_omega2(self, w2) -> None:
        """Keep ``w2``, this motion's omega * omega worked out elsewhere, for
        :meth:`omega2`."""
        self.keep_arm(_OMEGA2, w2)

    def point(self, local: tuple[float, float]):
        """Global position of a local point."""
        rx, ry = self.rotate(*local)
        return A.add(self.ox, rx), A.add(self.oy, ry)

    def vel_arm(self, rx, ry):
        """Velocity of the body point at the arm (rx, ry) from the origin: v_O + omega k x r."""
        return A.sub_mul(self.vx, self.omega, ry), A.add_mul(self.vy, self.omega, rx)

    def acc_arm(self, rx, ry):
        """Acceleration of the body point at the arm r: a_O + eps k x r - omega^2 r
        (seed 001 eq. 9)."""
        w2 = self.omega2()
        return (A.sub_mul(A.sub_mul(self.ax, self.alpha, ry), w2, rx),
                A.sub_mul(A.add_mul(self.ay, self.alpha, rx), w2, ry))

    def vel_at(self, x, y):
        """Velocity of the body's point that is at the global position (x, y)."""
        return self.vel_arm(A.sub(x, self.ox), A.sub(y, self.oy))

    def acc_at(self, x, y):
        """Acceleration of the body's point at the global position (x, y)."""
        return self.acc_arm(A.sub(x, self.ox), A.sub(y, self.oy))

    def take(self, index) -> BodyMotion:
        """The motion at some rows only (scalars stay scalars); one row (an int
        ``index``) as Python floats."""
        def t(a):
            if type(index) is int:
                return float(a[index]) if np.ndim(a) else float(a)
            return a[index] if np.ndim(a) else a
        th = None if self._theta is None else t(self._theta)
        return BodyMotion(th, *(t(getattr(self, f)) for f in self.FIELDS))


_OMEGA2 = ("omega^2",)      # (the key omega2 keeps its square under)


def ground_motion() -> BodyMotion:
    """The fixed body: zero everything, unit rotation."""
    return BodyMotion(0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def driver_motion(scene: Scene) -> BodyMotion:
    """Motion of the driving element (seed 000 ch. 4): a crank turning about its ground
    joint (position = angle of its local x axis) or a slider on a ground guide (position
    = distance of its slider point from the line point along the line)."""
    drv = scene.driver
    joint = scene.joints[drv.joint]
    body = scene.bodies[drv.body]
    w, eps = float(drv.speed), float(drv.acceleration)
    if drv.kind == "R":
        trig = scene.__dict__.get("driver_trig")    # (a stack's run: worked out per sweep)
        th, c, s = trig if trig is not None else (drv.angles, None, None)
        if trig is None:
            c, s = drv.trig()
        px, py = scene.ground[joint.point_on(GROUND)]
        rax, ray = A.rotate(c, s, *body.local(joint.point_on(drv.body)))   # o = P - R a
        w2 = w * w
        return BodyMotion(th, c, s, w, eps, A.sub(A.scalar(px), rax), A.sub(A.scalar(py), ray),
                          A.mul(w, ray), A.mul(-w, rax),
                          A.mul_add(eps, ray, w2, rax),
                          A.mul_add(-eps, rax, w2, ray))
    return _sliding(scene, drv.positions, w, eps)


def driver_at_first_row(scene: Scene) -> BodyMotion:
    """The driving element at the scene's first row, in Python numbers (the doubles of
    :func:`driver_motion`'s first row: the same operations): its angle and origin; a
    crank's speeds left at zero (a first row's assembly reads positions alone)."""
    drv = scene.driver
    if drv.kind != "R":
        return _sliding(scene, float(drv.positions[0]), float(drv.speed),
                        float(drv.acceleration))
    joint = scene.joints[drv.joint]
    # (cos and sin of one row, as of a one-row sweep; the row's angle alone worked out:
    # a long sweep the compiled path solves never makes its driver's angles)
    th = drv.angles_into(slice(0, 1), np.empty(1))
    c, s = float(np.cos(th)[0]), float(np.sin(th)[0])
    px, py = scene.ground[joint.point_on(GROUND)]
    rax, ray = A.rotate(c, s, *scene.bodies[drv.body].local(joint.point_on(drv.body)))
    return BodyMotion(float(th[0]), c, s, 0.0, 0.0, A.sub(float(px), rax),
                      A.sub(float(py), ray), 0.0, 0.0, 0.0, 0.0)


def _sliding(scene: Scene, pos, w: float, eps: float) -> BodyMotion:
    """A sliding driver at positions ``pos`` (an array, or a number)."""
    drv = scene.driver
    joint = scene.joints[drv.joint]
    body = scene.bodies[drv.body]
    beta = joint.beta
    if joint.guide == GROUND:
        th = float(beta)
        ux, uy = float(np.cos(beta)), float(np.sin(beta))
        lx, ly = scene.ground[joint.points[0]]
        loc = body.local(joint.points[1])
        sign = 1.0
    else:   # the driver carries the guide and slides along a ground slider point
        th = -float(beta)
        ux, uy = 1.0, 0.0
        lx, ly = scene.ground[joint.points[1]]
        loc = body.local(joint.points[0])
        sign = -1.0
    c, s = float(np.cos(th)), float(np.sin(th))
    rx, ry = A.rotate(c, s, *loc)
    ox = A.add(A.mul(sign * ux, pos), lx - rx)
    oy = A.add(A.mul(sign * uy, pos), ly - ry)
    v, a = sign * w, sign * eps
    return BodyMotion(th, c, s, 0.0, 0.0, ox, oy, v * ux, v * uy, a * ux, a * uy)
