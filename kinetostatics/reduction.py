"""Reduction of forces and masses to the driving element (seed 002 s. 2.5).

The reduced moment M_r (force F_r) develops the same power as all the loads it
replaces (eqs 2.71-2.72): M_r omega_1 = sum(F_k . v_k + M_k omega_k). The reduced
moment of inertia I_r (mass m_r) stores the same kinetic energy (eqs 2.74-2.75):
I_r omega_1^2 = sum(m_k v_Gk^2 + I_Gk omega_k^2). With the inertia forces included the
reduced moment is -Me (eq. 2.73).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

if TYPE_CHECKING:
    from .results import Solution


def reduced_table(sol: Solution) -> pd.DataFrame:
    """``position, M_red`` (or ``F_red``) of the applied loads and gravity, ``M_red_inertia``
    of the inertia forces, ``I_red`` (or ``m_red``), and ``dI_red`` (d I_red / d position, per
    rad or per m), from the velocity ratios of the solved kinematics."""
    scene = sol.scene
    kin = sol.kin
    speed = scene.driver.speed
    if speed == 0.0:
        from dataclasses import replace

        from .solver import solve
        drv = replace(scene.driver, speed=1.0, acceleration=0.0)
        sol = solve(replace(scene, driver=drv))
        kin = sol.kin
        speed = 1.0
    n = kin.n
    p_loads = np.zeros(n)
    p_inertia = np.zeros(n)
    for ld in sol.loads:
        p = np.broadcast_to(ld.power(kin), (n,))
        if ld.kind == "inertia":
            p_inertia = p_inertia + p
        else:
            p_loads = p_loads + p
    energy2 = np.zeros(n)      # sum m v_G^2 + I omega^2 (twice the kinetic energy)
    denergy = np.zeros(n)      # its time derivative / 2: sum m v.a + I omega alpha
    for name, body in scene.bodies.items():
        m = kin.bodies[name]
        if body.mass > 0.0:
            x, y = m.point(body.cog)
            vx, vy = m.vel_at(x, y)
            ax, ay = m.acc_at(x, y)
            energy2 = energy2 + body.mass * (vx * vx + vy * vy)
            denergy = denergy + body.mass * (vx * ax + vy * ay)
        energy2 = energy2 + body.inertia * m.omega * m.omega
        denergy = denergy + body.inertia * m.omega * m.alpha
    rot = scene.driver.kind == "R"
    acc = scene.driver.acceleration if sol.scene.driver.speed != 0.0 else 0.0
    i_red = energy2 / speed**2
    # d I_r / d phi = 2 (sum m v.a + I w a - I_r w1 eps1) / w1^3    (from eq. 2.75)
    di_red = 2.0 * (denergy - i_red * speed * acc) / speed**3
    return pd.DataFrame({
        "position": sol.positions,
        "M_red" if rot else "F_red": p_loads / speed,
        "M_red_inertia" if rot else "F_red_inertia": p_inertia / speed,
        "I_red" if rot else "m_red": i_red,
        "dI_red" if rot else "dm_red": di_red,
    })
