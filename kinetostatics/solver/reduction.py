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
    from ..results import Solution


LOAD_KINDS = ("applied", "gravity", "inertia", "friction")


def _powers_by_kind(sol: Solution) -> dict[str, np.ndarray]:
    """Sum of F . v + M omega of the solution's loads, per kind (W, arrays over rows)."""
    n = sol.kin.n
    out = {k: np.zeros(n) for k in LOAD_KINDS}
    for ld in sol.loads:
        out[ld.kind] = out[ld.kind] + np.broadcast_to(ld.power(sol.kin), (n,))
    return out


def power_table(sol: Solution) -> pd.DataFrame:
    """The power balance at every position (bilanțul puterilor), W.

    Columns ``position, P_driver`` (Me omega_1, or Fe v for a sliding driver, from the
    driver's equilibrium),
    ``P_applied`` (the scene's loads), ``P_gravity``, ``P_inertia`` (the inertia forces,
    -dEc/dt, eq. 4.34) and ``P_friction`` (the passive resistances, never positive).
    By the principle of virtual power (eqs 2.72-2.73) they add up to zero at every
    position (a check of the reactions, which gave Me). The useful work of a cycle is
    minus the integral of ``P_applied`` where it resists, the motor work that of
    ``P_driver`` (eqs 4.22-4.25).
    """
    powers = _powers_by_kind(sol)
    drive = np.asarray(sol.Me, dtype=float) * sol.scene.driver.speed    # Me w1 or Fe v
    return pd.DataFrame({"position": sol.positions, "P_driver": drive,
                         **{f"P_{k}": powers[k] for k in LOAD_KINDS}})


def reduced_table(sol: Solution) -> pd.DataFrame:
    """``position, M_red`` (or ``F_red``) of the applied loads and gravity (eq. 2.72),
    ``M_red_friction`` of the friction forces (zero without friction), ``M_red_inertia``
    of the inertia forces, ``I_red`` (or ``m_red``), and ``dI_red`` (d I_red / d position,
    per rad or per m), from the velocity ratios of the solved kinematics. The three
    reduced moments add up to -Me (eq. 2.73)."""
    scene = sol.scene
    kin = sol.kin
    speed = scene.driver.speed
    if speed == 0.0:
        from dataclasses import replace

        from .pipeline import solve
        drv = replace(scene.driver, speed=1.0, acceleration=0.0)
        sol = solve(replace(scene, driver=drv))
        kin = sol.kin
        speed = 1.0
    n = kin.n
    powers = _powers_by_kind(sol)
    p_loads = powers["applied"] + powers["gravity"]
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
        "M_red_friction" if rot else "F_red_friction": powers["friction"] / speed,
        "M_red_inertia" if rot else "F_red_inertia": powers["inertia"] / speed,
        "I_red" if rot else "m_red": i_red,
        "dI_red" if rot else "dm_red": di_red,
    })
