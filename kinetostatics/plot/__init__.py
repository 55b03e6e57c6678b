"""Pictures: the mechanism, plans, force polygons, curves. Every function takes data and
returns matplotlib Figures/Axes; none calls ``plt.show``. Units are in every axis label;
geometry and vector diagrams use equal aspect.

- the mechanism at a position, with the joint reactions and the loads as arrows:
  :func:`draw_mechanism`; its motion over the cycle: :func:`animate` (``mechanism``);
- the graphical method of the course (seed 001): the velocity and acceleration plans
  :func:`velocity_plan`, :func:`acceleration_plan` (``plans``);
- the force polygon of a dyad or of the driver (seed 002 figs 2.9-2.19, 2.38, 2.42):
  :func:`force_polygon`, its forces :func:`polygon_forces` (``polygons``);
- curves over the cycle: :func:`plot_driver` (Me), :func:`plot_polar`,
  :func:`plot_transmission`, :func:`plot_trajectories`, :func:`plot_speeds`,
  :func:`plot_accelerations`, :func:`plot_angular`, and :func:`overview` (``curves``);
- the free-body diagram of a dyad beside its force polygon: :func:`dyad_free_body`
  (``freebody``);
- instantaneous centres of velocity (Kennedy): :func:`instant_centres`,
  :func:`plot_instant_centres` (``centres``);
- the flywheel (seed 002 ch. 4): :func:`reduced_cycle` (I_r, M_r, Delta E over a turn),
  :func:`plot_flywheel_curves`, :func:`plot_wittenbauer`, :func:`wittenbauer_flywheel`
  (``flywheel``);
- cams (seed 002 ch. 1): :func:`plot_cam_motion` (s, v, a with the shocks,
  :func:`cam_shocks`), :func:`draw_cam` (the follower on the cam), :func:`plot_cam_diagram`
  (the (ds/dphi, s) diagram of the smallest base circle) (``cams``);
- a gear pair: :func:`draw_gear_pair` (``gears``);
- the lecture-room style of the command line and the sheets :func:`lecture_style`
  (150 dpi, labels >= 10 pt), the larger :func:`projector` style and the label check
  :func:`overlapping_texts` (``style``); every collision of a drawn figure (label on
  label, link, curve or arrow; legend on data) :func:`collisions` (``collide``); labels
  placed clear of them :func:`declutter` (``place``).
"""

from __future__ import annotations

from .base import LOAD_COLORS, PATH_COLORS, REACTION_COLOR
from .cams import cam_shocks, draw_cam, plot_cam_diagram, plot_cam_motion
from .centres import instant_centres, plot_instant_centres
from .collide import collisions
from .curves import (
    overview,
    plot_accelerations,
    plot_angular,
    plot_driver,
    plot_polar,
    plot_speeds,
    plot_trajectories,
    plot_transmission,
)
from .flywheel import (
    plot_flywheel_curves,
    plot_wittenbauer,
    reduced_cycle,
    wittenbauer_flywheel,
)
from .freebody import dyad_free_body, free_body_forces
from .gears import draw_gear_pair
from .mechanism import animate, draw_body, draw_mechanism
from .place import declutter, settle
from .plans import acceleration_plan, velocity_plan
from .polygons import find_dyad, force_on, force_polygon, polygon_forces
from .style import LECTURE, PROJECTOR, lecture_style, overlapping_texts, projector

__all__ = [
    "LECTURE",
    "LOAD_COLORS",
    "PATH_COLORS",
    "PROJECTOR",
    "REACTION_COLOR",
    "acceleration_plan",
    "animate",
    "cam_shocks",
    "collisions",
    "declutter",
    "draw_body",
    "draw_cam",
    "draw_gear_pair",
    "draw_mechanism",
    "dyad_free_body",
    "find_dyad",
    "force_on",
    "force_polygon",
    "instant_centres",
    "lecture_style",
    "free_body_forces",
    "overlapping_texts",
    "overview",
    "plot_accelerations",
    "plot_angular",
    "plot_cam_diagram",
    "plot_cam_motion",
    "plot_driver",
    "plot_flywheel_curves",
    "plot_instant_centres",
    "plot_polar",
    "plot_speeds",
    "plot_trajectories",
    "plot_transmission",
    "plot_wittenbauer",
    "polygon_forces",
    "projector",
    "reduced_cycle",
    "settle",
    "velocity_plan",
    "wittenbauer_flywheel",
]
