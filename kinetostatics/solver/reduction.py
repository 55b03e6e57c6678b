"""Reduction of forces and masses to the driving element (seed 002 s. 2.5).

The reduced moment M_r (force F_r) develops the same power as all the loads it
replaces (eqs 2.71-2.72): M_r omega_1 = sum(F_k . v_k + M_k omega_k). The reduced
moment of inertia I_r (mass m_r) stores the same kinetic energy (eqs 2.74-2.75):
I_r omega_1^2 = sum(m_k v_Gk^2 + I_Gk omega_k^2). With the inertia forces included the
reduced moment is -Me (eq. 2.73).

Both depend on the mechanism's position only, through the velocity ratios
v_k / omega_1 and omega_k / omega_1: they are read from the motion at unit driver speed
and zero driver acceleration, where every velocity is its ratio k1 and every
acceleration is k2 = d k1 / d phi. So the reduction holds at any speed, zero included.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd

from ..model.scene import GROUND
from .kinematics import Kinematics, solve_kinematics
from .loads import concentrated_masses

if TYPE_CHECKING:
    from ..results import Solution  # noqa: F401  (a name for the type hints only)


LOAD_KINDS = ("applied", "gravity", "inertia", "friction")


def _powers_by_kind(sol: Solution, kin: Kinematics) -> dict[str, np.ndarray]:
    """Sum of F . v + M omega of the solution's loads, per kind, with the velocities of
    ``kin`` (W at the scene's speed; the reduced moments at unit speed)."""
    n = sol.kin.n
    out = {k: np.zeros(n) for k in LOAD_KINDS}
    for ld in sol.loads:
        out[ld.kind] = out[ld.kind] + np.broadcast_to(ld.power(kin), (n,))
    return out


def unit_kinematics(sol: Solution) -> Kinematics:
    """The solution's mechanism at unit driver speed (1 rad/s or 1 m/s) and zero driver
    acceleration, at the same positions and in the same assembly: its velocities are the
    velocity ratios k1 = v / omega_1 and its accelerations k2 = d k1 / d phi."""
    drv = sol.scene.driver
    if drv.speed == 1.0 and drv.acceleration == 0.0:
        return sol.kin
    scene = replace(sol.scene, driver=replace(drv, speed=1.0, acceleration=0.0))
    return solve_kinematics(scene, sol.kin.structure)


def driver_direction(sol: Solution) -> float:
    """+1, or -1 for a sliding driver that carries the guide: its position grows as it
    moves against the line direction, along which Fe acts (so its power is -Fe v)."""
    drv = sol.scene.driver
    if drv.kind == "R":
        return 1.0
    return 1.0 if sol.scene.joints[drv.joint].guide == GROUND else -1.0


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
    powers = _powers_by_kind(sol, sol.kin)
    speed = sol.scene.driver.speed * driver_direction(sol)
    drive = np.asarray(sol.Me, dtype=float) * speed                     # Me w1 or Fe v
    return pd.DataFrame({"position": sol.positions, "P_driver": drive,
                         **{f"P_{k}": powers[k] for k in LOAD_KINDS}})


def reduced_inertia(sol: Solution, kin1: Kinematics) -> tuple[np.ndarray, np.ndarray]:
    """I_r (eq. 2.75) and d I_r / d phi from the unit-speed motion ``kin1``.

    I_r = sum m_k |k1_k|^2 + I_G k1_omega^2 over the masses the kinetostatics uses (each
    body's cog and I_G, or the concentrated masses of its ``mass_model``, seed 002 eqs
    2.9-2.15, which carry no I_G), so that its inertia forces reduce to -(I_r eps +
    1/2 dI_r omega^2); dI_r / d phi = 2 sum (m_k k1_k . k2_k + I_G k1_omega k2_omega).
    """
    n = sol.kin.n
    i_red = np.zeros(n)
    di_red = np.zeros(n)
    for name, body in sol.scene.bodies.items():
        if body.mass == 0.0 and body.inertia == 0.0:
            continue
        m = kin1.bodies[name]
        if body.mass_model is None:
            masses = [(body.cog or (0.0, 0.0), body.mass)]
            inertia = body.inertia
        else:
            masses, inertia = concentrated_masses(body), 0.0
        for loc, mk in masses:
            rx, ry = m.rotate(*loc)
            vx, vy = m.vel_arm(rx, ry)
            ax, ay = m.acc_arm(rx, ry)
            i_red = i_red + mk * (vx * vx + vy * vy)
            di_red = di_red + 2.0 * mk * (vx * ax + vy * ay)
        i_red = i_red + inertia * m.omega * m.omega
        di_red = di_red + 2.0 * inertia * m.omega * m.alpha
    return np.broadcast_to(i_red, (n,)), np.broadcast_to(di_red, (n,))


def reduced_table(sol: Solution) -> pd.DataFrame:
    """The loads and masses reduced to the driver, for the scene as given (any speed and
    acceleration, zero included).

    Columns ``position``; ``M_red`` (or ``F_red``) of the applied loads and gravity
    (eq. 2.72: their power at unit driver speed); ``M_red_friction`` of the friction
    loads (zero without friction, NaN at ``self_locking`` rows); ``M_red_inertia`` =
    -(I_red eps + 1/2 dI_red omega^2) (eq. 2.73 with eq. 4.9's kinetic-energy
    derivative; eps, omega the driver's); ``I_red`` (or ``m_red``, eq. 2.75) and
    ``dI_red`` (d I_red / d position, per rad or per m). The three reduced moments add
    up to -Me at every row (eq. 2.73). A sliding driver's reduced forces act along the
    line, like Fe (for a driver that carries the guide, whose position grows as it moves
    against the line, they change sign with its velocity)."""
    drv = sol.scene.driver
    kin1 = unit_kinematics(sol)
    powers = _powers_by_kind(sol, kin1)
    i_red, di_red = reduced_inertia(sol, kin1)
    w, eps = drv.speed, drv.acceleration
    rot = drv.kind == "R"
    k = driver_direction(sol)       # reduced forces act along Fe, like Fe
    return pd.DataFrame({
        "position": sol.positions,
        "M_red" if rot else "F_red": k * (powers["applied"] + powers["gravity"]),
        "M_red_friction" if rot else "F_red_friction": k * powers["friction"],
        "M_red_inertia" if rot else "F_red_inertia":
            -k * (i_red * eps + 0.5 * di_red * w * w),
        "I_red" if rot else "m_red": i_red,
        "dI_red" if rot else "dm_red": di_red,
    })
