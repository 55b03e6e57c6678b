"""The numbers each compiled kernel reads, from a scene (no numba here).

Each kernel reads its geometry from one array (:mod:`~kinetostatics.solver.fast.layout`):
``(k, 1)`` for a scene, ``(k, scenes)`` when some number is an array over the scenes of
a stack (:meth:`~kinetostatics.solver.stack.Stacker.table`: a column per scene, each
row's scene given to the kernels), with its stride (0 or 1) beside it.
:func:`not_covered` names what the kernels leave to the numpy path.
"""

from __future__ import annotations

import math

import numpy as np

from ...model.scene import GROUND, Scene
from .. import arith as A
from ..loads import RESIST_STILL, concentrated_masses, motion_scales
from . import layout as L


def not_covered(scene: Scene) -> str | None:
    """Why the compiled path does not solve ``scene`` (solved on the numpy path), or
    None: joint friction (solved by iteration)."""
    if any(j.friction is not None for j in scene.joints.values()):
        return "joint friction"
    return None


def swept_load(ld) -> bool:
    """A load whose rows are told by the whole sweep (its top speed or power)."""
    return ld.resist is not None or (ld.force is not None and ld.when == "resisting")


def pack(values: dict[int, object], k: int) -> tuple[np.ndarray, int]:
    """A geometry array of ``k`` rows from ``{row: number or array over the scenes}``
    (the rows not given are 0; a column per scene of a stack) and its stride over the
    rows' scenes (0: one column, every row's)."""
    n = max((v.shape[0] for v in values.values()
             if isinstance(v, np.ndarray) and v.ndim), default=0)
    if not n:       # one scene: its numbers in a list, one array made of it (3 us, not 8)
        column = [0.0] * k
        for row, v in values.items():
            column[row] = v
        return np.array(column, dtype=float).reshape(k, 1), 0
    g = np.zeros((k, n))
    for row, v in values.items():
        g[row] = v
    return g, 1


def _local(scene: Scene, body: str, point: str):
    """A named point in its body's frame (the ground's: the ground point)."""
    if body == GROUND:
        return scene.ground[point]
    return scene.bodies[body].local(point)


def driver_geometry(scene: Scene) -> tuple[np.ndarray, int]:
    """The driver's motion and reaction geometry (the numpy path's ``driver_motion`` and
    ``_solve_driver``)."""
    drv = scene.driver
    joint = scene.joints[drv.joint]
    body = scene.bodies[drv.body]
    if drv.kind == "R":
        (px, py), (lx, ly) = scene.ground[joint.point_on(GROUND)], body.local(
            joint.point_on(drv.body))
        return pack({L.D_PX: px, L.D_PY: py, L.D_LX: lx, L.D_LY: ly}, L.DRIVER_GEOMETRY)
    beta = joint.beta
    if joint.guide == GROUND:
        th, ux, uy = float(beta), float(np.cos(beta)), float(np.sin(beta))
        (lx, ly), loc, sign = scene.ground[joint.points[0]], body.local(joint.points[1]), 1.0
        on, (sx, sy) = 1.0, body.local(joint.points[1])
        rux, ruy = ux, uy
    else:
        th, ux, uy = -float(beta), 1.0, 0.0
        (lx, ly), loc, sign = scene.ground[joint.points[1]], body.local(joint.points[0]), -1.0
        on, (sx, sy) = 0.0, scene.ground[joint.points[1]]
        rux, ruy = 1.0, 0.0
    c, s = float(np.cos(th)), float(np.sin(th))
    rx, ry = A.rotate(c, s, *loc)
    return pack({L.T_TH: th, L.T_C: c, L.T_S: s, L.T_UX: ux, L.T_UY: uy, L.T_LX: lx,
                 L.T_LY: ly, L.T_RX: rx, L.T_RY: ry, L.T_SIGN: sign, L.T_RUX: rux,
                 L.T_RUY: ruy, L.T_ON: on, L.T_SX: sx, L.T_SY: sy}, L.DRIVER_GEOMETRY)


def dyad_geometry(scene: Scene, dyad, k) -> tuple[np.ndarray, int]:
    """A dyad's geometry: its outer joints' parameters (``dyad_param``), its inner
    joint (``DyadSolver``), the mechanism's size, the closeness constant and the
    assembly ``k`` (a number, or an array over the rows of a stack)."""
    v: dict[int, object] = {L.SIZE: scene.size, L.ASSEMBLY: k}
    bodies = [scene.bodies[n] for n in dyad.bodies]
    local = []                          # each body's outer joint point (rot) or (0, 0)
    for i, (name, joint) in enumerate(zip(dyad.bodies, dyad.outer, strict=True)):
        b = L.PARAM * i
        kname = joint.other(name)
        v[b + L.P_GROUND] = 1.0 if kname == GROUND else 0.0
        if joint.kind == "R":
            v[b + L.P_KX], v[b + L.P_KY] = _local(scene, kname, joint.point_on(kname))
            v[b + L.P_BX], v[b + L.P_BY] = bodies[i].local(joint.point_on(name))
            local.append((v[b + L.P_BX], v[b + L.P_BY]))
            continue
        local.append((0.0, 0.0))
        beta = joint.beta
        v[b + L.P_CB] = float(np.cos(beta))
        sb = float(np.sin(beta))
        carried = joint.guide == kname
        v[b + L.P_SB], v[b + L.P_GK] = (sb, 1.0) if carried else (-sb, 0.0)
        kp, bp = (joint.points[0], joint.points[1]) if carried else joint.points[::-1]
        v[b + L.P_KX], v[b + L.P_KY] = _local(scene, kname, kp)
        v[b + L.P_BX], v[b + L.P_BY] = bodies[i].local(bp)
        o = 3 * i
        where = (0.0 if joint.slider == GROUND else 1.0 if joint.slider == name else 2.0)
        v[L.O_WHERE + o] = where
        v[L.O_X + o], v[L.O_Y + o] = _local(scene, joint.slider, joint.points[1])
    inner = dyad.inner
    if inner.kind == "R":
        q = [bodies[i].local(inner.point_on(dyad.bodies[i])) for i in range(2)]
        (v[L.Q1X], v[L.Q1Y]), (v[L.Q2X], v[L.Q2Y]) = q
        norm2 = 1.0     # |c1|^2 |c2|^2, a constant (velocity_system.column_norm2)
        for i, joint in enumerate(dyad.outer):
            if joint.kind == "R":
                norm2 = norm2 * ((q[i][0] - local[i][0]) ** 2 + (q[i][1] - local[i][1]) ** 2)
        v[L.NORM2] = norm2
        for i, (wx, wy) in enumerate(((L.W1X, L.W1Y), (L.W2X, L.W2Y))):
            if dyad.outer[i].kind != "R":
                continue
            # (x * x, not x ** 2: as the numpy path's DyadSolver._inner_r)
            ax, ay = q[i][0] - local[i][0], q[i][1] - local[i][1]
            r2 = ax * ax + ay * ay
            v[wx], v[wy] = ax / r2, ay / r2
        return pack(v, L.DYAD_GEOMETRY)
    sfirst = inner.slider == dyad.bodies[0]
    i_s, i_g = (0, 1) if sfirst else (1, 0)
    beta = inner.beta
    cb, sb = np.cos(beta), np.sin(beta)
    s_loc = bodies[i_s].local(inner.points[1])
    l_loc = bodies[i_g].local(inner.points[0])
    v.update({L.I_CB: cb, L.I_SB: sb, L.I_BETA: beta, L.I_SX: s_loc[0], L.I_SY: s_loc[1],
              L.I_LX: l_loc[0], L.I_LY: l_loc[1], L.I_SFIRST: 1.0 if sfirst else 0.0})
    if dyad.outer[0].kind == "R" and dyad.outer[1].kind == "R":
        # RTR (seed 000 ch. 6-7): c, the line's offset from the guide's pivot
        asx, asy = s_loc[0] - local[i_s][0], s_loc[1] - local[i_s][1]
        vx_ = cb * asx - sb * asy - (l_loc[0] - local[i_g][0])
        vy_ = sb * asx + cb * asy - (l_loc[1] - local[i_g][1])
        v[L.I_RTR] = cb * vy_ - sb * vx_
    return pack(v, L.DYAD_GEOMETRY)


def body_loads_geometry(scene: Scene, name: str) -> tuple[np.ndarray, int, int]:
    """A body's loads for :func:`~kinetostatics.solver.fast.kernels.body_loads`: its
    inertia about the cog (0 with a mass model), the couples, and its point loads (the
    cog's weight and inertia force, a mass model's concentrated masses, the scene's
    forces), with their count."""
    body = scene.bodies[name]
    gx, gy = scene.gravity
    points = []                             # (lx, ly, Fx, Fy, m)
    weight = (body.mass * gx, body.mass * gy) if (gx or gy) and body.mass > 0.0 else None
    inertia = 0.0
    if body.mass_model is None:
        cog = body.cog or (0.0, 0.0)
        fx, fy = weight if weight is not None else (0.0, 0.0)
        points.append((*cog, fx, fy, body.mass))
        inertia = body.inertia
    else:
        if weight is not None:
            points.append((*body.cog, *weight, 0.0))
        points += [(*loc, 0.0, 0.0, mk) for loc, mk in concentrated_masses(body)]
    m0 = 0.0
    for ld in scene.loads:
        if ld.body != name:
            continue
        m0 = m0 + ld.moment
        if ld.point is not None and ld.force is not None and not swept_load(ld):
            points.append((*body.local(ld.point), float(ld.force[0]), float(ld.force[1]), 0.0))
    v: dict[int, object] = {L.L_I: inertia, L.L_M0: m0}
    for q, p in enumerate(points):
        for f, x in enumerate(p):
            v[2 + L.L_POINT * q + f] = x
    g, gs = pack(v, 2 + L.L_POINT * len(points))
    return g, gs, len(points)


NO_SWEPT_LOADS: tuple[np.ndarray, int, list] = (np.zeros((1, 1)), 0, [])  # (never run)


def swept_loads_geometry(scene: Scene, name: str) -> tuple[np.ndarray, int, list]:
    """A body's ``resist`` and ``when = "resisting"`` loads for
    :func:`~kinetostatics.solver.fast.kernels.swept_loads` (per load: its point, kind,
    R, the force and the still threshold at the mechanism's own scale), and each one's
    floor of the top (:func:`~kinetostatics.solver.loads.motion_scales`)."""
    mine = [ld for ld in scene.loads
            if ld.body == name and ld.point is not None and swept_load(ld)]
    if not mine:
        return NO_SWEPT_LOADS
    vscale = motion_scales(scene)[0]
    v: dict[int, object] = {}
    floors = []
    for ld in mine:
        b = 7 * len(floors)
        v[b], v[b + 1] = scene.bodies[name].local(ld.point)
        if ld.resist is not None:
            v[b + 2], v[b + 3] = 1.0, float(ld.resist)
            floor = vscale
        else:
            fx, fy = float(ld.force[0]), float(ld.force[1])
            v[b + 2], v[b + 4], v[b + 5] = 2.0, fx, fy
            floor = math.hypot(fx, fy) * vscale
        v[b + 6] = RESIST_STILL * floor
        floors.append(floor)
    g, gs = pack(v, max(7 * len(floors), 1))
    return g, gs, floors
