"""Independent checks of a kinetostatic solution, written from the scene and the tables only.

* loop closure: every joint holds at every position (points coincide, sliders on lines);
* finite differences: velocities and accelerations are the derivatives of positions;
* the virtual-power balance Me omega_1 + power of loads and inertia forces = 0;
* a global matrix solution: all bodies' Newton-Euler equations in one linear system
  per position, solved with numpy.linalg.solve, against the dyad-by-dyad reactions;
* the equilibrium of each body with the reactions table's forces (Newton's third law:
  the force in a joint enters its two bodies with opposite signs).

Nothing here calls the workbench's solvers: only its tables and the scene.
"""

from __future__ import annotations

import numpy as np

GROUND = "ground"


class Tables:
    """Arrays from a solution's tables, indexed by body/point, one row per position."""

    def __init__(self, sol):
        self.sol = sol
        self.scene = sol.scene
        self.pos = sol.positions
        self.n = self.pos.size
        k = sol.kinematics
        self.pt = {}
        for (b, p), g in k.groupby(["body", "point"], sort=False):
            self.pt[(b, p)] = {c: g[c].to_numpy() for c in ("x", "y", "vx", "vy", "ax", "ay")}
        bt = sol.bodies
        self.body = {b: {c: g[c].to_numpy() for c in ("angle", "omega", "alpha")}
                     for b, g in bt.groupby("body", sort=False)}

    def point(self, body, name):
        if body == GROUND:
            x, y = self.scene.ground[name]
            z = np.zeros(self.n)
            return {"x": z + x, "y": z + y, "vx": z, "vy": z, "ax": z, "ay": z}
        return self.pt[(body, name)]

    def angle(self, body):
        if body == GROUND:
            return np.zeros(self.n)
        return np.deg2rad(self.body[body]["angle"])

    def omega(self, body):
        return np.zeros(self.n) if body == GROUND else self.body[body]["omega"]

    def alpha(self, body):
        return np.zeros(self.n) if body == GROUND else self.body[body]["alpha"]

    def size(self):
        xs = [abs(v) for d in self.pt.values() for c in ("x", "y") for v in (d[c].max(),
                                                                            d[c].min())]
        return max(xs + [1e-3])


def loop_closure(sol) -> float:
    """Largest joint violation (m): revolute points apart, slider point off the line, and
    (radians x size) the slider's angle off the guide's plus the line angle."""
    t = Tables(sol)
    worst = 0.0
    for j in t.scene.joints.values():
        if j.kind == "R":
            a = t.point(j.bodies[0], j.points[0])
            b = t.point(j.bodies[1], j.points[1])
            worst = max(worst, float(np.hypot(a["x"] - b["x"], a["y"] - b["y"]).max()))
        else:
            ang = t.angle(j.guide) + j.beta
            ux, uy = np.cos(ang), np.sin(ang)
            lp = t.point(j.guide, j.points[0])
            sp = t.point(j.slider, j.points[1])
            off = np.abs(ux * (sp["y"] - lp["y"]) - uy * (sp["x"] - lp["x"]))
            dang = np.angle(np.exp(1j * (t.angle(j.slider) - ang)))
            worst = max(worst, float(off.max()), float(np.abs(dang).max()) * t.size())
    return worst


def _loads(t: Tables):
    """(body, x, y, vx, vy, fx, fy, m) for gravity, applied loads and inertia (exact torsor)."""
    sc = t.scene
    gx, gy = sc.gravity
    out = []
    for name, body in sc.bodies.items():
        if body.cog is None:
            continue
        g = t.point(name, "cog")
        out.append((name, g["x"], g["y"], g["vx"], g["vy"],
                    body.mass * (gx - g["ax"]), body.mass * (gy - g["ay"]),
                    -body.inertia * t.alpha(name)))
    undefined = t.sol.undefined_load
    for ld in sc.loads:
        if ld.point is None:
            z = np.zeros(t.n)
            out.append((ld.body, z, z, z, z, z, z, z + ld.moment))
            continue
        p = t.point(ld.body, ld.point)
        if ld.resist is not None:
            sp = np.hypot(p["vx"], p["vy"])
            with np.errstate(invalid="ignore", divide="ignore"):
                fx = np.where(undefined, 0.0, -ld.resist * p["vx"] / sp)
                fy = np.where(undefined, 0.0, -ld.resist * p["vy"] / sp)
        else:
            fx, fy = np.full(t.n, ld.force[0]), np.full(t.n, ld.force[1])
            if ld.when == "resisting":          # on the working stroke only: F.v < 0
                on = (fx * p["vx"] + fy * p["vy"] < 0.0) & ~undefined
                fx, fy = np.where(on, fx, 0.0), np.where(on, fy, 0.0)
        out.append((ld.body, p["x"], p["y"], p["vx"], p["vy"], fx, fy, np.full(t.n, ld.moment)))
    return out


def _driver_power(sol, t) -> np.ndarray:
    """The power of Me (or Fe along the line, at the slider point) on the driver."""
    sc = t.scene
    drv = sc.driver
    if drv.kind == "R":
        p = sol.Me * drv.speed
    else:
        j = sc.joints[drv.joint]
        sp = t.point(j.slider if j.slider != GROUND else j.guide,
                     j.points[1] if j.slider != GROUND else j.points[0])
        beta = j.beta if j.guide == GROUND else 0.0
        p = sol.Me * (np.cos(beta) * sp["vx"] + np.sin(beta) * sp["vy"])
    return p


def virtual_power(sol) -> float:
    """max |Me w1 + sum of powers| / scale, the scale being the largest term."""
    t = Tables(sol)
    total = np.zeros(t.n)
    scale = np.zeros(t.n)
    p = _driver_power(sol, t)
    total += p
    scale = np.maximum(scale, np.abs(p))
    for body, _x, _y, vx, vy, fx, fy, m in _loads(t):
        pw = fx * vx + fy * vy + m * t.omega(body)
        total += pw
        scale = np.maximum(scale, np.abs(pw))
    return float(np.abs(total).max() / max(scale.max(), 1e-300))


def matrix_solution(sol):
    """Reactions by one linear system per position. Returns {joint: (Fx, Fy on the
    joint's on-body, N, M)}, and Me/Fe."""
    t = Tables(sol)
    sc = t.scene
    bodies = list(sc.bodies)
    col = {}
    ncol = 0
    for name in sc.joints:
        col[name] = ncol
        ncol += 2
    me_col = ncol
    ncol += 1
    nrow = 3 * len(bodies)
    assert nrow == ncol, "not statically determinate"
    A = np.zeros((t.n, nrow, ncol))
    b = np.zeros((t.n, nrow))
    row = {name: 3 * i for i, name in enumerate(bodies)}

    def put(body, c, fx, fy, x, y, sign, couple=None):
        """Unknown in column c acts on body with force (fx, fy) per unit at (x, y)."""
        if body == GROUND:
            return
        r = row[body]
        A[:, r, c] += sign * fx
        A[:, r + 1, c] += sign * fy
        A[:, r + 2, c] += sign * (x * fy - y * fx)
        if couple is not None:
            A[:, r + 2, c] += sign * couple

    one = np.ones(t.n)
    zero = np.zeros(t.n)
    geo = {}
    for name, j in sc.joints.items():
        c = col[name]
        if j.kind == "R":
            b1, b2 = j.bodies
            p = t.point(b2, j.points[1]) if b2 != GROUND else t.point(b1, j.points[0])
            x, y = p["x"], p["y"]
            # unknowns: force on bodies[1] from bodies[0]
            for comp, (fx, fy) in enumerate(((one, zero), (zero, one))):
                put(b2, c + comp, fx, fy, x, y, 1.0)
                put(b1, c + comp, fx, fy, x, y, -1.0)
            geo[name] = (x, y)
        else:
            ang = t.angle(j.guide) + j.beta
            nx, ny = -np.sin(ang), np.cos(ang)
            sp = t.point(j.slider, j.points[1])
            x, y = sp["x"], sp["y"]
            # unknowns: N (force N n at S on the slider) and M (couple on the slider)
            put(j.slider, c, nx, ny, x, y, 1.0)
            put(j.guide, c, nx, ny, x, y, -1.0)
            put(j.slider, c + 1, zero, zero, x, y, 1.0, couple=one)
            put(j.guide, c + 1, zero, zero, x, y, -1.0, couple=one)
            geo[name] = (x, y, nx, ny)
    drv = sc.driver
    if drv.kind == "R":
        A[:, row[drv.body] + 2, me_col] = 1.0
    else:
        j = sc.joints[drv.joint]
        if j.guide == GROUND:
            beta = j.beta
            sp = t.point(drv.body, j.points[1])
        else:
            beta = 0.0
            sp = t.point(GROUND, j.points[1])
        put(drv.body, me_col, np.cos(beta) * one, np.sin(beta) * one, sp["x"], sp["y"], 1.0)
    for body, x, y, _vx, _vy, fx, fy, m in _loads(t):
        r = row[body]
        b[:, r] -= fx
        b[:, r + 1] -= fy
        b[:, r + 2] -= x * fy - y * fx + m
    sol_x = np.linalg.solve(A, b[..., None])[..., 0]
    out = {}
    for name, j in sc.joints.items():
        c = col[name]
        on, _by = j.on_by
        if j.kind == "R":
            fx, fy = sol_x[:, c], sol_x[:, c + 1]
            s = 1.0 if on == j.bodies[1] else -1.0
            out[name] = (s * fx, s * fy, None, None)
        else:
            _x, _y, nx, ny = geo[name]
            nn, mm = sol_x[:, c], sol_x[:, c + 1]
            s = 1.0 if on == j.slider else -1.0
            out[name] = (s * nn * nx, s * nn * ny, nn, mm)
    return out, sol_x[:, me_col]


def matrix_difference(sol) -> float:
    """Largest difference between the dyad reactions (and Me) and the matrix solution,
    relative to the largest force (moment) of the scene."""
    ref, me = matrix_solution(sol)
    r = sol.reactions
    fmax = max(float(r.F.max()), 1e-9)
    worst = float(np.abs(sol.Me - me).max()) / max(float(np.abs(me).max()),
                                                   1e-3 * fmax * 0.1, 1e-9)
    for name, (fx, fy, nn, mm) in ref.items():
        sub = r[r.joint == name]
        worst = max(worst, float(np.abs(sub.Fx.to_numpy() - fx).max()) / fmax,
                    float(np.abs(sub.Fy.to_numpy() - fy).max()) / fmax)
        if nn is not None:
            worst = max(worst, float(np.abs(sub.N.to_numpy() - nn).max()) / fmax)
            mscale = max(float(np.abs(mm).max()), 1e-3 * fmax * 0.1)
            worst = max(worst, float(np.abs(sub.M.to_numpy() - mm).max()) / mscale)
    return worst


def body_equilibrium(sol) -> float:
    """Largest residual of any body's force and moment balance with the table's reactions,
    relative to the largest force (times the mechanism size for moments)."""
    t = Tables(sol)
    sc = t.scene
    r = sol.reactions
    res = {b: [np.zeros(t.n), np.zeros(t.n), np.zeros(t.n)] for b in sc.bodies}

    def add(body, fx, fy, x, y, m=0.0):
        if body == GROUND:
            return
        q = res[body]
        q[0] += fx
        q[1] += fy
        q[2] += x * fy - y * fx + m

    for name, j in sc.joints.items():
        sub = r[r.joint == name]
        on, by = sub.on.iloc[0], sub.by.iloc[0]
        fx, fy = sub.Fx.to_numpy(), sub.Fy.to_numpy()
        if j.kind == "R":
            p = t.point(j.bodies[1], j.points[1]) if j.bodies[1] != GROUND else \
                t.point(j.bodies[0], j.points[0])
            add(on, fx, fy, p["x"], p["y"])
            add(by, -fx, -fy, p["x"], p["y"])          # Newton's third law
        else:
            sp = t.point(j.slider, j.points[1])
            mm = sub.M.to_numpy()
            ms = mm if on == j.slider else -mm
            add(on, fx, fy, sp["x"], sp["y"], ms)
            add(by, -fx, -fy, sp["x"], sp["y"], -ms)
    drv = sc.driver
    if drv.kind == "R":
        res[drv.body][2] += sol.Me
    else:
        j = sc.joints[drv.joint]
        beta = j.beta if j.guide == GROUND else 0.0
        sp = t.point(drv.body, j.points[1]) if j.guide == GROUND else \
            t.point(GROUND, j.points[1])
        add(drv.body, sol.Me * np.cos(beta), sol.Me * np.sin(beta), sp["x"], sp["y"])
    for body, x, y, _vx, _vy, fx, fy, m in _loads(t):
        add(body, fx, fy, x, y, m)
    fmax = max(float(r.F.max()), 1e-9)
    size = t.size()
    worst = 0.0
    for q in res.values():
        worst = max(worst, float(np.abs(q[0]).max()) / fmax, float(np.abs(q[1]).max()) / fmax,
                    float(np.abs(q[2]).max()) / (fmax * size))
    return worst


def _d4(f, h):
    """Fourth-order central difference on a uniform grid (interior points 2..-2)."""
    return (-f[4:] + 8.0 * f[3:-1] - 8.0 * f[1:-3] + f[:-4]) / (12.0 * h)


def finite_differences(sol_fine) -> float:
    """Largest mismatch between tabulated velocities/accelerations and fourth-order
    central differences of positions (velocities) and velocities (accelerations, with
    the driver's constant speed and zero acceleration), relative to each quantity's top."""
    t = Tables(sol_fine)
    drv = t.scene.driver
    assert drv.acceleration == 0.0
    q = np.deg2rad(t.pos) if drv.kind == "R" else t.pos.astype(float)
    w = drv.speed
    h = q[1] - q[0]
    assert np.allclose(np.diff(q), h)
    worst = 0.0
    inner = slice(2, -2)
    # scale: each quantity's top, but at least 1e-3 of the top of its kind (cases rule)
    kind_top = {v: max(float(np.abs(d[v]).max()) for d in t.pt.values())
                for v in ("vx", "vy", "ax", "ay")}
    kind_top = {"vx": max(kind_top["vx"], kind_top["vy"]), "ax": max(kind_top["ax"],
                                                                      kind_top["ay"])}
    for d in t.pt.values():
        for p, v in (("x", "vx"), ("y", "vy"), ("vx", "ax"), ("vy", "ay")):
            fd = _d4(d[p], h) * w
            kind = "vx" if v[0] == "v" else "ax"
            top = max(float(np.abs(d[v]).max()), 1e-3 * kind_top[kind])
            worst = max(worst, float(np.abs(fd - d[v][inner]).max()) / top)
    for b in t.body.values():
        ang = np.deg2rad(b["angle"])
        for p, v in ((ang, b["omega"]), (b["omega"], b["alpha"])):
            if float(np.abs(v).max()) < 1e-12:
                continue
            fd = _d4(p, h) * w
            worst = max(worst, float(np.abs(fd - v[inner]).max()) / float(np.abs(v).max()))
    return worst


def friction_power(sol) -> np.ndarray:
    """Power of the joint friction at every position (W, never positive), from the scene's
    ``friction`` tables, the reactions table and the motion tables only (seed 002 s. 2.4):
    a pin loses rho |F| |omega_rel| (rho = mu r, eq. 2.62), a guide mu N0 |v_rel| with
    N0 = |N|, or |N_A| + |N_B| over a bearing of length l (eqs 2.63-2.65)."""
    t = Tables(sol)
    r = sol.reactions
    total = np.zeros(t.n)
    for name, j in t.scene.joints.items():
        fr = j.friction
        if fr is None or fr.mu == 0.0:
            continue
        sub = r[r.joint == name]
        if j.kind == "R":
            wrel = t.omega(j.bodies[1]) - t.omega(j.bodies[0])
            total -= fr.mu * fr.radius * sub.F.to_numpy() * np.abs(wrel)
            continue
        nn, mm = sub.N.to_numpy(), sub.M.to_numpy()         # both on the slider
        if fr.length > 0.0:
            normal = np.abs(0.5 * nn - mm / fr.length) + np.abs(0.5 * nn + mm / fr.length)
        else:
            normal = np.abs(nn)
        ang = t.angle(j.guide) + j.beta
        ux, uy = np.cos(ang), np.sin(ang)
        sp = t.point(j.slider, j.points[1])
        lp = t.point(j.guide, j.points[0])
        wg = t.omega(j.guide)
        vgx = lp["vx"] - wg * (sp["y"] - lp["y"])        # the guide's point under S
        vgy = lp["vy"] + wg * (sp["x"] - lp["x"])
        vrel = ux * (sp["vx"] - vgx) + uy * (sp["vy"] - vgy)
        total -= fr.mu * normal * np.abs(vrel)
    return total


def virtual_power_with_friction(sol) -> float:
    """max |Me w1 + power of loads and inertia + friction power| / scale over the rows
    that are not ``self_locking`` (the scale: the largest term of those rows)."""
    t = Tables(sol)
    p = _driver_power(sol, t)
    terms = [np.asarray(p, dtype=float), friction_power(sol)]
    for body, _x, _y, vx, vy, fx, fy, m in _loads(t):
        terms.append(fx * vx + fy * vy + m * t.omega(body))
    free = ~sol.driver.self_locking.to_numpy() if "self_locking" in sol.driver else \
        np.ones(t.n, dtype=bool)
    total = np.sum(terms, axis=0)[free]
    scale = max(max(float(np.abs(a[free]).max()) for a in terms), 1e-300)
    return float(np.abs(total).max() / scale)
