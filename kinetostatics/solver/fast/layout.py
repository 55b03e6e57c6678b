"""Where each number sits in the compiled path's arrays (no numba here).

A body's motion over a block of rows is one ``(10, rows)`` array, its rows in the order
of :attr:`BodyMotion.FIELDS <kinetostatics.solver.driver.BodyMotion.FIELDS>`; a dyad's
solved data, its reactions, a body's load resultants are arrays of their own layout. The
geometry of a kernel (local points, ground points, line angles, masses, the assembly) is
one ``(k, 1)`` array, or ``(k, scenes)`` for a stack of scenes whose numbers differ from
scene to scene (a column per scene; its stride is then 1, else 0): a kernel reads row
``i``'s from column ``own[i * stride]``, ``own`` each row's scene in the stack (``[0]``
for one scene).
"""

from __future__ import annotations

# a body's motion: cos, sin, omega, alpha, origin x, y, its velocity and acceleration
C, S, OM, AL, OX, OY, VX, VY, AX, AY = range(10)
MOTION = 10

# a dyad's kind code: bit 0 outer joint 1 revolute (its body turns about P: "rot"), bit 1
# outer joint 2 revolute, bit 2 inner joint revolute
ROT1, ROT2, INNER_R = 1, 2, 4
KINDS = {"RRR": ROT1 | ROT2 | INNER_R, "RRT": ROT1 | INNER_R, "TRR": ROT2 | INNER_R,
         "TRT": INNER_R, "RTR": ROT1 | ROT2, "RTT": ROT1, "TTR": ROT2}
# bits a fused kernel adds to its kind's code: outer joint 1 (2)'s known body the ground
# (at rest: its guide's or pivot's motion constants, the rows' arithmetic on them skipped
# where it gives +0 exactly for finite rows, kernels.dyad_row, kernels.ground_param); the
# crank-and-dyad kernels (fused_kernels) set them on prismatic joints only, the six-bars'
# (guide_kernels) on revolute ones too
G1, G2 = 8, 16

# a dyad's geometry, per outer joint i (rows 8 i ...): the known body's point of the joint
# (rot) or of the guide's line (trans), the dyad body's point, and for trans the line
# angle's cos, +-sin, whether the known body carries the guide, and whether the known body
# is the ground (both kinds)
P_KX, P_KY, P_BX, P_BY, P_CB, P_SB, P_GK, P_GROUND = range(8)
PARAM = 8
# the inner joint: revolute, each body's local point of it; prismatic, the line angle's
# cos, sin and angle, the slider's point, the guide's line point, whether body 1 is the
# slider, and the RTR constant c (seed 000 ch. 6-7)
Q1X, Q1Y, Q2X, Q2Y = 16, 17, 18, 19
I_CB, I_SB, I_BETA, I_SX, I_SY, I_LX, I_LY, I_SFIRST, I_RTR = range(16, 25)
SIZE, NORM2, ASSEMBLY = 25, 26, 27
# an outer prismatic joint's slider point (reactions): where it is (0 the ground, 1 the
# dyad body, 2 the known body) and its local (or ground) coordinates, per outer joint
O_WHERE, O_X, O_Y = 28, 29, 30          # + 3 i
# a revolute inner joint: each body's (q - p) / |q - p|^2, the closure's constant factors
# (the numpy path's rotation angle, ``rot_angle`` here: lx / r2 and ly / r2, worked out once)
W1X, W1Y, W2X, W2Y = 34, 35, 36, 37
DYAD_GEOMETRY = 38

# a dyad's solved data: the closing point X, the velocity system's columns and
# determinant, the prismatic inner joint's normal, the closeness to a dead centre, and per
# outer joint (rows 10 + 4 i ...) P (rot) or u and the line's base point b (trans)
XX, XY, C1X, C1Y, C2X, C2Y, DET, NX, NY, CL2 = range(10)
D_PA, D_PB, D_PC, D_PD = range(4)       # + 10 + 4 i
DYAD_OUT = 18

# a dyad's reactions: the inner joint's (on body 2, or on the slider: Fx, Fy, N, M) and
# per outer prismatic joint (rows 4 + 6 i ...) Fx, Fy, N, M and the slider point
R_FX, R_FY, R_N, R_M, R_SX, R_SY = range(6)
REACTIONS = 16

# the driver: a crank's ground pivot and its point on the crank; a sliding driver's
# angle, cos, sin, line direction, line point, its point's arm and the sign
D_PX, D_PY, D_LX, D_LY = range(4)
T_TH, T_C, T_S, T_UX, T_UY, T_LX, T_LY, T_RX, T_RY, T_SIGN = range(10)
# the sliding driver's reaction: the line's direction, where the slider point is (1 on
# the driver, 0 on the ground) and its local (or ground) coordinates
T_RUX, T_RUY, T_ON, T_SX, T_SY = range(10, 15)
DRIVER_GEOMETRY = 15

# a body's loads: its inertia about the cog, a constant couple, then per point load
# (lx, ly, Fx, Fy, m): a force at a local point and a mass there whose inertia force
# -m a joins it (the cog's mass, or a concentrated mass of the body's mass model)
L_I, L_M0 = 0, 1
L_POINT = 5


def padded_width(width: int) -> int:
    """A row length of at least ``width`` values whose rows lie an odd number of cache
    lines (64 bytes) apart: rows a power of two bytes apart (a block of 16384 rows, a
    run of 12288) fall in the same few sets of the processor's caches, and a kernel reads
    and writes some 60 rows at once (measured: 5-20x slower)."""
    stride = -(-width // 8) * 8
    return stride + 8 if (stride // 8) % 2 == 0 else stride
