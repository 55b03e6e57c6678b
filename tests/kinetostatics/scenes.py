"""The tests' scene factory: a four-bar as a scene dict, every number given.

One home for the four-bar the property, invariance and dead-point tests vary (crank A-B
about A = (0, 0), coupler B-C, rocker D-C about D = (d, 0)). The oracle tests keep
their own hand-written copy (tests/kinetostatics/solver/test_textbook.py), so that a
mistake here cannot hide in both.
"""

from __future__ import annotations

import copy
import math
from typing import Any


def four_bar(a: float, b: float, c: float, d: float, *,
             masses: tuple = (1.0, 2.0, 1.5), inertias: tuple = (1e-3, 1e-2, 5e-3),
             cogs: tuple | None = None, speed: float = 10.0, start: float = 0.0,
             stop: float | None = None, count: int = 361,
             acceleration: float | None = None, gravity: list | None = None,
             coupler_point: list | None = None, loads: list | None = None,
             near: list | None = None, friction: dict | None = None,
             positions: list | None = None) -> dict[str, Any]:
    """A four-bar scene dict.

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths (m).
    masses, inertias : tuple
        Of the crank, coupler and rocker (kg, kg m^2).
    cogs : tuple of [x, y], optional
        Their centres of mass in their own frames (default: mid-links).
    speed, start, stop, count, acceleration
        The driver (rad/s; deg; ``stop`` default ``start + 360``; rad/s^2, left out if
        None).
    gravity : [gx, gy], optional
        Left out if None (the scene's default).
    coupler_point : [x, y], optional
        A point P on the coupler.
    loads : list, optional
        The scene's loads (default none).
    near : [x, y], optional
        The hint for C (default: above D, 10 x the size away: the open assembly).
    friction : dict, optional
        Joint name -> its friction table.
    positions : list, optional
        The driver's positions (deg) in place of start, stop and count.
    """
    cogs = cogs if cogs is not None else ([a / 2, 0.0], [b / 2, 0.0], [c / 2, 0.0])
    driver: dict[str, Any] = {"body": "crank", "joint": "A", "speed": speed}
    if acceleration is not None:
        driver["acceleration"] = acceleration
    if positions is not None:
        driver["positions"] = [float(p) for p in positions]
    else:
        driver.update(start=start, stop=start + 360.0 if stop is None else stop, count=count)
    coupler = {"B": [0.0, 0.0], "C": [b, 0.0]}
    if coupler_point is not None:
        coupler["P"] = list(coupler_point)
    shapes = (("crank", {"A": [0.0, 0.0], "B": [a, 0.0]}), ("coupler", coupler),
              ("rocker", {"D": [0.0, 0.0], "C": [c, 0.0]}))
    scene: dict[str, Any] = {}
    if gravity is not None:
        scene["gravity"] = list(gravity)
    scene.update(ground={"A": [0.0, 0.0], "D": [d, 0.0]}, driver=driver)
    scene["bodies"] = [{"name": name, "mass": m, "inertia": i, "cog": list(g),
                        "points": points}
                       for (name, points), m, i, g in zip(shapes, masses, inertias, cogs,
                                                          strict=True)]
    scene["joints"] = [{"name": name, "kind": "R", "bodies": list(pair)}
                       for name, pair in (("A", ("ground", "crank")),
                                          ("B", ("crank", "coupler")),
                                          ("C", ("coupler", "rocker")),
                                          ("D", ("ground", "rocker")))]
    for j in scene["joints"]:
        if friction and j["name"] in friction:
            j["friction"] = dict(friction[j["name"]])
    scene["loads"] = list(loads) if loads is not None else []
    scene["near"] = {"C": list(near) if near is not None else [d, 10.0 * (a + b + c + d)]}
    return scene


def offset_slider_crank(r: float, rod: float, e: float, angle: float, *, start: float = 0.0,
                        stop: float = 360.0, count: int = 2001,
                        friction: dict | None = None) -> dict[str, Any]:
    """An offset slider-crank (RRT) with an inclined guide: crank ``r`` about A = (0, 0),
    rod ``rod``, the piston's pin C on the line through O at ``angle`` deg, O ``e`` from
    A across the line; 300 N against the piston. ``friction``: joint name -> its
    friction table."""
    beta = math.radians(angle)
    scene: dict[str, Any] = {
        "gravity": [0.0, -9.81],
        "ground": {"A": [0.0, 0.0], "O": [-e * math.sin(beta), e * math.cos(beta)]},
        "driver": {"body": "crank", "joint": "A", "speed": 50.0, "start": start,
                   "stop": stop, "count": count},
        "bodies": [
            {"name": "crank", "mass": 1.0, "inertia": 0.01, "cog": [r / 2, 0.0],
             "points": {"A": [0.0, 0.0], "B": [r, 0.0]}},
            {"name": "rod", "mass": 2.0, "inertia": 0.03, "cog": [rod / 3, 0.01],
             "points": {"B": [0.0, 0.0], "C": [rod, 0.0]}},
            {"name": "piston", "mass": 1.5, "inertia": 0.002, "cog": [0.02, 0.0],
             "points": {"C": [0.0, 0.0]}},
        ],
        "joints": [
            {"name": "A", "kind": "R", "bodies": ["ground", "crank"]},
            {"name": "B", "kind": "R", "bodies": ["crank", "rod"]},
            {"name": "C", "kind": "R", "bodies": ["rod", "piston"]},
            {"name": "C-slide", "kind": "T", "guide": "ground", "slider": "piston",
             "line_point": "O", "line_angle": angle, "slider_point": "C"},
        ],
        "loads": [{"body": "piston", "point": "C", "force": [-300.0, 10.0]}],
        "near": {"C": [rod * math.cos(beta), rod * math.sin(beta)]},
    }
    for j in scene["joints"]:
        if friction and j["name"] in friction:
            j["friction"] = dict(friction[j["name"]])
    return scene


def with_friction(d: dict, mu: float, radius: float = 0.01,
                  length: float | None = None) -> dict:
    """A copy of the scene dict ``d`` with the friction coefficient ``mu`` in every joint:
    pins of ``radius`` (m), sliders of ``length`` (m, left out when None)."""
    d = copy.deepcopy(d)
    for j in d["joints"]:
        j["friction"] = {"mu": mu, "radius": radius} if j["kind"] == "R" else \
            {"mu": mu, **({"length": length} if length is not None else {})}
    return d


def varied_slotted_lever(base: dict, r: float, h: float, e: float, beta: float,
                         count: int) -> dict:
    """A copy of the slotted-lever scene ``base`` (crank O2-A first, the lever third, its
    slot the third joint) with the crank ``r``, O2 ``h`` above the lever's pivot, the
    slot through S, ``e`` off the pivot at ``beta`` deg in the lever's frame, and
    ``count`` rows."""
    d = copy.deepcopy(base)
    d["ground"]["O2"] = [0.0, h]
    d["bodies"][0]["points"]["A"] = [r, 0.0]
    d["bodies"][2]["points"]["S"] = [0.0, e]
    d["joints"][2]["line_point"] = "S"
    d["joints"][2]["line_angle"] = beta
    d["driver"]["count"] = count
    return d
