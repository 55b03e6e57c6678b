"""Motion of the reduction element under forces (seed 002 ch. 4), generic over callables,
and the ``[motion]`` scene (:func:`simulate_motion`).

The mechanism enters only through its reduced quantities, as functions of the driver angle
phi (rad; arrays in, arrays out):

- ``inertia(phi) -> (I_r, dI_r/dphi)``: the reduced moment of inertia (eq. 2.75, with any
  flywheel) and its derivative, kg m^2 and kg m^2/rad;
- ``moment(phi, omega, t) -> M``: the total reduced moment, N m (motor plus loads,
  M_r = M_m - M_r^r, eqs 4.6-4.7). It is called with arrays of any shape (0-d included).

The motion obeys the equation in differential form (eqs 4.9-4.11)

    d(I_r omega^2 / 2)/dphi = M(phi, omega, t),    i.e.
    I_r omega domega/dphi + omega^2/2 dI_r/dphi = M,    dt/dphi = 1/omega,

whose finite form between two positions is the energy balance (eq. 4.8)
I_2 omega_2^2/2 - I_1 omega_1^2/2 = integral of M dphi.

Solvers:

- :func:`solve_recurrence`: the seed's explicit recurrence (eqs 4.13-4.16), first order;
- :func:`solve_energy`: position-only moments, omega^2 = (I_1 omega_1^2 + 2 int M dphi)/I
  (eq. 4.8) with Gauss-Legendre quadrature (the exact reference the first-order
  recurrence 4.14 is measured against);
- :func:`simulate`: any M(phi, omega, t), a Dormand-Prince 5(4) integrator in phi with step
  control for (u, t), u = I_r omega^2 (twice the kinetic energy: du/dphi = 2M is smooth
  where omega is not), with the quartic dense output of Shampine (1986); optionally on a
  fixed grid per cycle with I_r evaluated once (``periodic_inertia``); the result,
  :class:`MotionSolution`, gives omega(phi), t(phi), alpha(phi), omega(t), eps(t), the
  extremes over the continuous cycle, the ``motion`` table and summary of the contract;
- :func:`periodic_solution`, :func:`flywheel_for_delta`, :func:`stopping`: the phases of
  s. 4.2, the degree of irregularity (eq. 4.20) and the dynamicity coefficient (eq. 4.21);
- :func:`recurrence_convergence`: the recurrence's error against the accurate solution.

Misprints noticed in the seed: the first line of eq. 4.11 drops a factor omega
(I_r omega domega/dphi = I_r domega/dt); eq. 4.14 solved from eq. 4.13 reads
omega_{i+1} = M_i dphi / (I_i omega_i) + omega_i (3 I_i - I_{i+1}) / (2 I_i).
"""

from __future__ import annotations

from .equation import (
    TWO_PI,
    Inertia,
    Moment,
    MotionError,
    golden_max,
    solve_energy,
    solve_recurrence,
)
from .integrator import simulate
from .phases import flywheel_for_delta, periodic_solution, recurrence_convergence, stopping
from .scene import KEY, MotionResult, MotionSpec, ReducedMechanism, motion_spec, simulate_motion
from .solution import MotionSolution

__all__ = [
    "Inertia",
    "KEY",
    "Moment",
    "MotionError",
    "MotionResult",
    "MotionSolution",
    "MotionSpec",
    "ReducedMechanism",
    "TWO_PI",
    "flywheel_for_delta",
    "golden_max",
    "motion_spec",
    "periodic_solution",
    "recurrence_convergence",
    "simulate",
    "simulate_motion",
    "solve_energy",
    "solve_recurrence",
    "stopping",
]
