"""Cam mechanisms (seed 002 ch. 1): motion laws, base circle, profile, follower forces.

Conventions (the workbench's: SI units, angles in degrees in files and tables, radians in
the Python functions below unless a name ends in ``_deg``):

- The cam turns about A at the origin with a constant speed omega; ``phi`` is its angle of
  rotation from the start of the program (the start of the first segment). The geometry
  is worked out for a counter-clockwise cam; a clockwise cam is the mirror image (the
  profile's coordinates are mirrored, every angle and force is the same).
- Motion laws give the follower's lift ``s`` (m for a translating follower, rad for an
  oscillating one) and its derivatives with respect to the cam angle: ``ds = v / omega``
  and ``dds = a / omega^2`` (the seed's v/omega and a/omega^2, eqs 1.2-1.3).
- Translating follower (fig. 1.10): its axis is the line x = e, the follower point B (the
  knife edge or the roller centre) is at (e, s0 + s) with s0 = sqrt(r0^2 - e^2) (eq. 1.27).
  The offset e is positive on the side where the cam's surface moves in the follower's
  rise direction: a positive offset lowers the pressure angle during the rise.
- Oscillating follower (fig. 1.12): pivot C at (d, 0) (d = AC, ``pivot_distance``), arm
  L = CB (``arm``), psi = beta0 + beta the angle at C between CA and CB, r0 from eq. 1.35.
  ``rise_sense = "same"`` (the seed's figure: eqs 1.34 and 1.38 hold as printed) when the
  arm turns in the cam's sense of rotation while it rises, ``"opposite"`` otherwise.
- r0 is the base radius of the theoretical (pitch) profile, the path of B in the cam's
  frame (eq. 1.37: "the theoretical profile passes through the roller centre"). The
  working profile of a roller follower is the inner envelope of the roller (offset of the
  pitch curve by the roller radius along its normal); the outer envelope is also given
  (the outer wall of a groove cam).
- The transmission angle tau (between the contact normal and the follower's direction of
  motion's normal, eqs 1.28/1.34) is reported in (0, 90] deg; the pressure angle is
  90 deg - tau (alpha + tau = 90 deg, s. 1.3.5).

The ``[cam]`` scene (``docs/cam-scenes.md``) is loaded by :func:`load_cam_scene` and
solved by :func:`solve_cam`.
"""

from __future__ import annotations

from ..common.lazy import group, lazy_names

# public name -> its module, imported on first use
_NAMES = {
    **group(("Follower", "OscillatingFollower", "TranslatingFollower", "base_radius_oscillating",
             "base_radius_translating", "check_tau", "cross2", "follower_points", "optimal_offset",
             "perp", "polar_profile_oscillating", "polar_profile_translating", "profile", "tau_of",
             "transmission_angle"), "followers"),
    **group(("cam_table", "critical_transmission_angle", "critical_transmission_angle_oscillating",
             "oscillating_follower_force", "translating_follower_forces"), "forces"),
    **group(("ALIASES", "LAW_COEFFICIENTS", "LAWS", "SAMPLES", "TWO_PI", "CamError", "CamLaw",
             "LawValues", "Segment", "constant_acceleration", "cosine_acceleration",
             "cycle_extreme", "fall", "law_name", "law_peaks", "rise", "sine_acceleration",
             "zero_acceleration"), "laws"),
    **group(("CAM_KEYS", "FOLLOWER_KEYS", "LOAD_KEYS", "SEGMENT_KEYS", "TOP_KEYS", "CamLoads",
             "CamResults", "CamScene", "load_cam_scene", "solve_cam"), "scene"),
}
__all__ = sorted(_NAMES)
__getattr__, __dir__ = lazy_names(__name__, _NAMES, globals(), __all__)
