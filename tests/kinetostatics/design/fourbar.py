"""An independent four-bar A-B-C-D for the design tests: closed-form positions (two
circles), velocities and accelerations from the loop equation's derivatives (2 x 2
systems), Me by the power balance (no dyads, no reactions), and the classical
transmission angle (between coupler BC and rocker DC)."""

from __future__ import annotations

import numpy as np


def _body(scene: dict, name: str) -> dict:
    return next(b for b in scene["bodies"] if b["name"] == name)


def four_bar(scene: dict) -> dict[str, np.ndarray]:
    """``Me`` (N m) and ``transmission`` (deg) over the sweep of a four-bar scene dict
    shaped as the bundled four_bar (crank A-B, coupler B-C-P, rocker D-C-E, the load on
    E, gravity, C above AD)."""
    crank, coupler, rocker = (_body(scene, n) for n in ("crank", "coupler", "rocker"))
    a = crank["points"]["B"][0]
    b = coupler["points"]["C"][0]
    c = rocker["points"]["C"][0]
    dx, dy = scene["ground"]["D"]
    drv = scene["driver"]
    th2 = np.deg2rad(np.linspace(drv["start"], drv["stop"], drv["count"]))
    w2 = drv["speed"]
    bx, by = a * np.cos(th2), a * np.sin(th2)
    # C: the intersection of the circles (B, b) and (D, c) on the open side (left of B->D)
    ex, ey = dx - bx, dy - by
    L = np.hypot(ex, ey)
    u = (b**2 - c**2 + L**2) / (2 * L)
    h = np.sqrt(b**2 - u**2)
    cx = bx + (u * ex - h * ey) / L
    cy = by + (u * ey + h * ex) / L
    th3 = np.arctan2(cy - by, cx - bx)
    th4 = np.arctan2(cy - dy, cx - dx)
    s2, c2, s3, c3, s4, c4 = (np.sin(th2), np.cos(th2), np.sin(th3), np.cos(th3),
                              np.sin(th4), np.cos(th4))
    # a w2 e2' + b w3 e3' = c w4 e4'  (e' = (-sin, cos)): [-b s3, c s4; b c3, -c c4] [w3 w4]
    det = b * c * (s3 * c4 - c3 * s4)
    r1, r2 = a * w2 * s2, -a * w2 * c2
    w3 = (r1 * (-c * c4) - c * s4 * r2) / det
    w4 = (-b * s3 * r2 - b * c3 * r1) / det
    # accelerations (alpha2 = 0): the same matrix, the centripetal terms on the right
    q1 = a * w2**2 * c2 + b * w3**2 * c3 - c * w4**2 * c4
    q2 = a * w2**2 * s2 + b * w3**2 * s3 - c * w4**2 * s4
    al3 = (q1 * (-c * c4) - c * s4 * q2) / det
    al4 = (-b * s3 * q2 - b * c3 * q1) / det
    g = np.array(scene.get("gravity", [0.0, 0.0]))
    origin = {"crank": (0.0, 0.0, th2, w2, 0.0 * th2, (0.0, 0.0), (0.0, 0.0)),
              "coupler": (bx, by, th3, w3, al3, (-a * w2 * s2, a * w2 * c2),
                          (-a * w2**2 * c2, -a * w2**2 * s2)),
              "rocker": (dx, dy, th4, w4, al4, (0.0, 0.0), (0.0, 0.0))}
    power = np.zeros_like(th2)
    for body in (crank, coupler, rocker):
        ox, oy, th, w, al, (vx, vy), (ax, ay) = origin[body["name"]]
        gx, gy = _point(body["cog"], th, ox, oy)
        rx, ry = gx - ox, gy - oy
        vgx, vgy = vx - w * ry, vy + w * rx
        agx = ax - al * ry - w**2 * rx
        agy = ay + al * rx - w**2 * ry
        m, inertia = body.get("mass", 0.0), body.get("inertia", 0.0)
        power += (m * (g[0] - agx)) * vgx + (m * (g[1] - agy)) * vgy - inertia * al * w
    for ld in scene.get("loads", []):
        body = next(bb for bb in (crank, coupler, rocker) if bb["name"] == ld["body"])
        ox, oy, th, w, al, (vx, vy), _ = origin[body["name"]]
        px, py = _point(body["points"][ld["point"]], th, ox, oy)
        fx, fy = ld["force"]
        power += fx * (vx - w * (py - oy)) + fy * (vy + w * (px - ox)) + ld["moment"] * w
    mu = np.rad2deg(np.abs(np.arctan2(np.sin(th3 - th4), np.cos(th3 - th4))))
    return {"Me": -power / w2, "transmission": np.minimum(mu, 180.0 - mu),
            "C": (cx, cy)}


def _point(local, th, ox, oy):
    x, y = local
    return ox + np.cos(th) * x - np.sin(th) * y, oy + np.sin(th) * x + np.cos(th) * y
