"""The exercise library: ready exercises of the course."""

from __future__ import annotations

from collections.abc import Mapping

from .variants import Exercise

__all__ = ["four_bar_exercise", "rotor_exercise"]


# ---------------------------------------------------------------- ready exercises
def _four_bar_scene(p: Mapping[str, float]) -> dict:
    """A crank-rocker four-bar A-B-C-D from the lengths a (crank), b (coupler), c
    (rocker), d (frame), with mid-link centres of mass, a force resisting the motion of
    the rocker's point E and gravity."""
    a, b, c, d = (float(p[k]) for k in ("a", "b", "c", "d"))
    ma, mb, mc = 7.8 * a, 7.8 * b, 7.8 * c          # kg: 7.8 kg/m, steel bars
    return {
        "title": "Four-bar crank-rocker (exercise)",
        "gravity": [0.0, -9.81],
        "ground": {"A": [0.0, 0.0], "D": [d, 0.0]},
        "driver": {"body": "crank", "joint": "A", "speed_rpm": float(p["rpm"]),
                   "start": 0.0, "stop": 360.0, "count": 361},
        "bodies": [
            {"name": "crank", "mass": ma, "inertia": ma * a * a / 12, "cog": [a / 2, 0.0],
             "points": {"A": [0.0, 0.0], "B": [a, 0.0]}},
            {"name": "coupler", "mass": mb, "inertia": mb * b * b / 12, "cog": [b / 2, 0.0],
             "points": {"B": [0.0, 0.0], "C": [b, 0.0]}},
            {"name": "rocker", "mass": mc, "inertia": mc * c * c / 12, "cog": [c / 2, 0.0],
             "points": {"D": [0.0, 0.0], "C": [c, 0.0], "E": [0.6 * c, 0.0]}},
        ],
        "joints": [
            {"name": "A", "kind": "R", "bodies": ["ground", "crank"]},
            {"name": "B", "kind": "R", "bodies": ["crank", "coupler"]},
            {"name": "C", "kind": "R", "bodies": ["coupler", "rocker"]},
            {"name": "D", "kind": "R", "bodies": ["ground", "rocker"]},
        ],
        "loads": [{"body": "rocker", "point": "E", "resist": float(p["load"])}],
        "near": {"C": [d, 0.8 * c]},
    }


def _grashof_crank_rocker(scene: dict, key: dict) -> bool:
    return key.get("tau_min", 90.0) >= 25.0


def four_bar_exercise(seed: int = 2024) -> Exercise:
    """The four-bar exercise of the sheets: a crank-rocker with lengths, speed and load
    drawn per student; asked: Me at 30 deg, the mean and largest Me, |F_B| max, |F_C|
    at 30 deg, the rocker's angle and angular velocity at 30 deg, the smallest
    transmission angle. Variants with a transmission angle below 25 deg are redrawn.

    Parameters
    ----------
    seed : int
        The exercise's seed (keep it private for marked work).

    Returns
    -------
    Exercise
    """
    text = ("A crank-rocker four-bar ABCD (crank AB = a, coupler BC = b, rocker CD = c, frame "
            "AD = d; bars of 7.8 kg/m with their centres of mass at mid-length) turns at n "
            "rpm, counter-clockwise. A force P resists the motion of the rocker's point E (DE = "
            "0.6 c); gravity acts. Find, by kinetostatics (seed 002 s. 2.3): the equilibrating "
            "moment Me at φ = 30°, its mean and largest values over the cycle, the largest "
            "reaction in B, the reaction in C at φ = 30°, the rocker's angle and angular "
            "velocity at φ = 30°, and the smallest transmission angle.")
    return Exercise(
        template=_four_bar_scene,
        ranges={"a": (0.08, 0.12, 0.005), "b": (0.26, 0.34, 0.01), "c": (0.20, 0.28, 0.01),
                "d": (0.28, 0.34, 0.01), "rpm": (150.0, 400.0, 10.0),
                "load": (100.0, 300.0, 10.0)},
        questions=["Me@30", "Me_mean", "Me_max", "Fmax[B]", "F[C]@30", "angle[rocker]@30",
                   "omega[rocker]@30", "tau_min"],
        seed=seed, title="Kinetostatics of a four-bar", text=text,
        check=_grashof_crank_rocker)


def rotor_exercise(seed: int = 2024) -> Exercise:
    """The rotor exercise of the sheets: three eccentric masses in three planes, two
    correction planes (dynamic balancing by design, seed 002 eqs 3.9-3.14); masses,
    radii and angles drawn per student; asked: both correction masses and angles and
    the initial resultant force. Variants with a correction mass below 1 g are redrawn.

    Parameters
    ----------
    seed : int
        The exercise's seed.

    Returns
    -------
    Exercise
    """
    template = {
        "title": "Rotor, dynamic balancing (exercise)",
        "rotor": {
            "speed_rpm": 1500.0,
            "unbalance": [
                {"mass": 0.020, "radius": 0.10, "angle": 30.0, "z": 0.05},
                {"mass": 0.015, "radius": 0.12, "angle": 150.0, "z": 0.15},
                {"mass": 0.010, "radius": 0.08, "angle": 260.0, "z": 0.25},
            ],
            "planes": [{"z": 0.0, "radius": 0.12}, {"z": 0.30, "radius": 0.12}],
        },
    }
    ranges = {}
    for k in range(3):
        ranges[f"rotor.unbalance.{k}.mass"] = (0.005, 0.030, 0.001)
        ranges[f"rotor.unbalance.{k}.radius"] = (0.06, 0.14, 0.01)
        ranges[f"rotor.unbalance.{k}.angle"] = (0.0, 355.0, 5.0)
    text = ("A rigid rotor turning at 1500 rpm carries three eccentric masses m_k at radii "
            "r_k, angles θ_k, in planes z_k. Balance it in the planes z = 0 and z = 0.30 m "
            "with masses fixed at 0.12 m (seed 002 eqs 3.9-3.14): give both correction masses "
            "and their angles, and the resultant inertia force before balancing.")

    def big_enough(scene: dict, key: dict) -> bool:      # angles of tiny masses mean little
        return min(key["mass[1]"], key["mass[2]"]) >= 1e-3

    return Exercise(template=template, ranges=ranges,
                    questions=["mass[1]", "angle[1]", "mass[2]", "angle[2]", "initial_force"],
                    seed=seed, title="Dynamic balancing of a rotor", text=text,
                    check=big_enough)
