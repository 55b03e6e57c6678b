"""Pictures: the mechanism, plans, force polygons, curves. Every function takes data and
returns matplotlib Figures/Axes.
"""

from __future__ import annotations

from .core import (
    LOAD_COLORS,
    PATH_COLORS,
    REACTION_COLOR,
    acceleration_plan,
    animate,
    draw_gear_pair,
    draw_mechanism,
    force_polygon,
    overview,
    plot_accelerations,
    plot_angular,
    plot_driver,
    plot_polar,
    plot_speeds,
    plot_trajectories,
    plot_transmission,
    velocity_plan,
)

__all__ = [
    "LOAD_COLORS",
    "PATH_COLORS",
    "REACTION_COLOR",
    "acceleration_plan",
    "animate",
    "draw_gear_pair",
    "draw_mechanism",
    "force_polygon",
    "overview",
    "plot_accelerations",
    "plot_angular",
    "plot_driver",
    "plot_polar",
    "plot_speeds",
    "plot_trajectories",
    "plot_transmission",
    "velocity_plan",
]
