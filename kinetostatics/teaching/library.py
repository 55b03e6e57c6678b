"""The exercise library: ready exercises of the course.

========================  ==========================================================
name                      exercise
========================  ==========================================================
``four_bar``              kinetostatics of a crank-rocker four-bar (seed 002 s. 2.3)
``slider_crank``          kinetostatics of a piston machine (RRT dyad)
``slotted_lever``         kinetostatics of a crank and slotted lever (RTR dyad)
``rotor_two_plane``       dynamic balancing of a rotor in two planes (eqs 3.9-3.14)
``resonance_three_run``   balancing at resonance, three runs (eqs 3.22-3.31)
========================  ==========================================================
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable, Mapping

import pandas as pd

from ..common.angles import radian_value
from ..model.errors import WorkbenchError
from .variants import Exercise

__all__ = ["EXERCISES", "exercise", "four_bar_exercise", "list_exercises",
           "resonance_exercise", "rotor_exercise", "slider_crank_exercise",
           "slotted_lever_exercise"]

STEEL_BAR = 7.8            # kg/m: the bars' mass per length
# the pictures of the handed-out sheets in the lecture style (150 dpi, text >= 10 pt)
MECHANISM_PICTURE = ("%matplotlib inline\nfrom kinetostatics.plot import draw_mechanism, "
                     "lecture_style\n\nlecture_style()\n"
                     "draw_mechanism(ks.solve(scene), {pos});   # your mechanism")
ROTOR_PICTURE = """%matplotlib inline
import matplotlib.pyplot as plt
import numpy as np

from kinetostatics.plot import lecture_style

lecture_style()
fig, ax = plt.subplots(figsize=(4.5, 4.5), layout="constrained")   # seen along the axis
for k, u in enumerate(scene["rotor"]["unbalance"], 1):
    t = np.radians(u["angle"])
    ax.annotate("", (u["radius"] * np.cos(t), u["radius"] * np.sin(t)), (0, 0),
                arrowprops={"arrowstyle": "-|>"})
    ax.annotate(f"m{k}", (u["radius"] * np.cos(t), u["radius"] * np.sin(t)),
                xytext=(6 * np.cos(t), 6 * np.sin(t)), textcoords="offset points",
                ha="left" if np.cos(t) >= 0 else "right",
                va="bottom" if np.sin(t) >= 0 else "top")
ax.set_aspect("equal")
ax.set_xlim(-0.16, 0.16)
ax.set_ylim(-0.16, 0.16)
ax.set_title("the eccentric masses (end view)");"""


_FACTORY_DOC = """Parameters
----------
seed : int, optional
    The exercise's seed (default: a secret one; keep it private for marked work).

Returns
-------
Exercise"""


def _factory(make: Callable[..., Exercise]) -> Callable[..., Exercise]:
    """An exercise factory of the library: its docstring ends with the Parameters and
    Returns every factory shares (written once, here)."""
    make.__doc__ = inspect.cleandoc(make.__doc__ or "") + "\n\n" + _FACTORY_DOC
    return make


def _bar(name: str, length: float, points: dict) -> dict:
    """A bar of STEEL_BAR kg/m along its local x axis, centre of mass at mid-length."""
    m = STEEL_BAR * length
    return {"name": name, "mass": m, "inertia": m * length * length / 12,
            "cog": [length / 2, 0.0], "points": points}


def _pins(*joints: str) -> list[dict]:
    """Revolute joints, each written ``"name body-body"``."""
    out = []
    for j in joints:
        name, pair = j.split(" ")
        out.append({"name": name, "kind": "R", "bodies": pair.split("-")})
    return out


def _lengths_data(p: dict, scene: dict) -> list:
    words = {"a": ("m", "crank AB"), "b": ("m", "coupler BC"), "c": ("m", "rocker CD"),
             "d": ("m", "frame AD"), "r": ("m", "crank"), "l": ("m", "connecting rod"),
             "e": ("m", "distance between the crank's and the lever's pivots"),
             "L": ("m", "lever length"), "rpm": ("rpm", "crank speed n, counter-clockwise"),
             "load": ("N", "resisting force P"), "mp": ("kg", "piston mass"),
             "mb": ("kg", "block mass")}
    sym = {"rpm": "n", "load": "P", "mp": "m_p", "mb": "m_b"}
    return [(sym.get(k, k), p[k], *words[k]) for k in words if k in p]


def _prose(text: str) -> str:
    """A paragraph written over several source lines, as one line of text."""
    return " ".join(text.split())


def _mechanism_exercise(seed: int | None, name: str, title: str, text: str, pos: float,
                        template: Callable[[Mapping[str, float]], dict],
                        **fields) -> Exercise:
    """An exercise on a mechanism: its data are the lengths (and the rest of the drawn
    values), its picture the mechanism at the driver position ``pos`` (deg)."""
    return Exercise(template=template, seed=seed, title=title, text=text, name=name,
                    data=_lengths_data, picture=MECHANISM_PICTURE.format(pos=pos), **fields)


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
            *_pins("A ground-crank", "B crank-coupler", "C coupler-rocker", "D ground-rocker"),
        ],
        "loads": [{"body": "rocker", "point": "E", "resist": float(p["load"])}],
        "near": {"C": [d, 0.8 * c]},
    }


def _grashof_crank_rocker(scene: dict, key: dict) -> bool:
    return key.get("tau_min", 90.0) >= 25.0


@_factory
def four_bar_exercise(seed: int | None = None) -> Exercise:
    """The four-bar exercise of the sheets: a crank-rocker with lengths, speed and load
    drawn per student; asked: Me at 30 deg, the mean and largest Me, |F_B| max, |F_C|
    at 30 deg, the rocker's angle and angular velocity at 30 deg, the smallest
    transmission angle. Variants with a transmission angle below 25 deg are redrawn."""
    text = _prose("""A crank-rocker four-bar ABCD (crank AB = a, coupler BC = b, rocker CD = c,
        frame AD = d; bars of 7.8 kg/m with their centres of mass at mid-length) turns at n rpm,
        counter-clockwise. A force P resists the motion of the rocker's point E (DE = 0.6 c);
        gravity acts. Find, by kinetostatics (course text 002, s. 2.3): the equilibrating moment
        Me at φ = 30°, its mean and largest values over the cycle, the largest reaction in B,
        the reaction in C at φ = 30°, the rocker's angle and angular velocity at φ = 30°, and
        the smallest transmission angle min(τ, 180° − τ).""")
    return _mechanism_exercise(
        seed, "four_bar", "Kinetostatics of a four-bar", text, 30, _four_bar_scene,
        ranges={"a": (0.08, 0.12, 0.005), "b": (0.26, 0.34, 0.01), "c": (0.20, 0.28, 0.01),
                "d": (0.28, 0.34, 0.01), "rpm": (150.0, 400.0, 10.0),
                "load": (100.0, 300.0, 10.0)},
        questions=["Me@30", "Me_mean", "Me_max", "Fmax[B]", "F[C]@30", "angle[rocker]@30",
                   "omega[rocker]@30", "tau_min"],
        check=_grashof_crank_rocker)


@_factory
def rotor_exercise(seed: int | None = None) -> Exercise:
    """The rotor exercise of the sheets: three eccentric masses in three planes, two
    correction planes (dynamic balancing by design, seed 002 eqs 3.9-3.14); masses,
    radii and angles drawn per student; asked: both correction masses and angles and
    the initial resultant force. Variants with a correction mass below 1 g are redrawn."""
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
    text = _prose("""A rigid rotor turning at 1500 rpm carries three eccentric masses m_k at
        radii r_k, angles θ_k, in planes z_k. Balance it in the planes z = 0 and z = 0.30 m with
        masses fixed at 0.12 m (course text 002, eqs 3.9-3.14): give both correction masses and
        their angles, and the resultant inertia force before balancing.""")

    def big_enough(scene: dict, key: dict) -> bool:      # angles of tiny masses mean little
        return min(key["mass[1]"], key["mass[2]"]) >= 1e-3

    return Exercise(template=template, ranges=ranges,
                    questions=["mass[1]", "angle[1]", "mass[2]", "angle[2]", "initial_force"],
                    seed=seed, title="Dynamic balancing of a rotor", text=text,
                    check=big_enough, name="rotor_two_plane", data=_rotor_data,
                    picture=ROTOR_PICTURE)


def _rotor_data(p: dict, scene: dict) -> list:
    rot = scene["rotor"]
    rows = [("n", rot["speed_rpm"], "rpm", "rotor speed")]
    for k, u in enumerate(rot["unbalance"], 1):
        rows += [(f"m{k}", u["mass"], "kg", f"eccentric mass {k}"),
                 (f"r{k}", u["radius"], "m", f"radius of mass {k}"),
                 (f"theta{k}", u["angle"], "deg", f"angle of mass {k}"),
                 (f"z{k}", u["z"], "m", f"plane of mass {k}")]
    for k, pl in enumerate(rot["planes"], 1):
        rows += [(f"z_{'I' * k}", pl["z"], "m", f"correction plane {'I' * k}"),
                 (f"r_{'I' * k}", pl["radius"], "m", f"correction radius in plane {'I' * k}")]
    return rows


# ------------------------------------------------------------------- slider-crank
def _slider_crank_scene(p: Mapping[str, float]) -> dict:
    """A centred slider-crank A-B-C from the crank r and rod l (steel bars), a piston of
    mass m_p pushed back by a force P opposite to its velocity, and gravity."""
    r, ln, mp = float(p["r"]), float(p["l"]), float(p["mp"])
    return {
        "title": "Slider-crank (exercise)",
        "gravity": [0.0, -9.81],
        "ground": {"A": [0.0, 0.0], "O": [0.0, 0.0]},
        "driver": {"body": "crank", "joint": "A", "speed_rpm": float(p["rpm"]),
                   "start": 0.0, "stop": 360.0, "count": 361},
        "bodies": [
            _bar("crank", r, {"A": [0.0, 0.0], "B": [r, 0.0]}),
            _bar("rod", ln, {"B": [0.0, 0.0], "C": [ln, 0.0]}),
            {"name": "piston", "mass": mp, "inertia": 1e-3, "cog": [0.0, 0.0],
             "points": {"C": [0.0, 0.0]}},
        ],
        "joints": [
            *_pins("A ground-crank", "B crank-rod", "C rod-piston"),
            {"name": "C-slide", "kind": "T", "guide": "ground", "slider": "piston",
             "line_point": "O", "line_angle": 0.0, "slider_point": "C"},
        ],
        "loads": [{"body": "piston", "point": "C", "resist": float(p["load"])}],
        "near": {"C": [r + ln, 0.0]},
    }


@_factory
def slider_crank_exercise(seed: int | None = None) -> Exercise:
    """A piston machine: a centred slider-crank with crank, rod, piston mass, speed and
    working force drawn per student; asked: Me at 60 deg, its mean and largest values,
    the reaction in B and the piston's normal force at 60 deg, the piston's speed and
    acceleration at 60 deg, the smallest transmission angle."""
    text = ("A centred slider-crank ABC (crank AB = r, connecting rod BC = l, steel bars "
            f"of {STEEL_BAR} kg/m with their centres of mass at mid-length; piston of mass "
            "m_p at C sliding on the x axis through A) turns at n rpm, counter-clockwise. "
            "A force P opposite to the piston's velocity works on the piston; gravity "
            "acts (-y). Find by kinetostatics: the equilibrating moment Me at φ = 60°, its "
            "mean and largest values over the cycle, the reaction in B and the normal "
            "force of the cylinder on the piston at φ = 60°, the piston's speed and "
            "acceleration at φ = 60°, and the smallest transmission angle min(τ, 180° − τ).")
    return _mechanism_exercise(
        seed, "slider_crank", "Kinetostatics of a slider-crank", text, 60, _slider_crank_scene,
        ranges={"r": (0.06, 0.12, 0.005), "l": (0.30, 0.45, 0.01), "rpm": (300.0, 900.0, 20.0),
                "mp": (1.0, 4.0, 0.1), "load": (500.0, 3000.0, 50.0)},
        questions=["Me@60", "Me_mean", "Me_max", "F[B]@60", "N[C-slide]@60",
                   "v[piston.C]@60", "a[piston.C]@60", "tau_min"],
        labels={"N[C-slide]@60": "normal force of the cylinder on the piston at phi = 60 deg, "
                                 "positive along +y"})


# ------------------------------------------------------------------ slotted lever
def _slotted_lever_scene(p: Mapping[str, float]) -> dict:
    """Crank O2-A (length r) above the lever's pivot O4 at distance e; the block at A
    slides in the lever's slot (RTR dyad); a horizontal force P at the lever's tip."""
    r, e, L, mb = float(p["r"]), float(p["e"]), float(p["L"]), float(p["mb"])
    return {
        "title": "Crank and slotted lever (exercise)",
        "gravity": [0.0, -9.81],
        "ground": {"O2": [0.0, e], "O4": [0.0, 0.0]},
        "driver": {"body": "crank", "joint": "O2", "speed_rpm": float(p["rpm"]),
                   "start": 0.0, "stop": 360.0, "count": 361},
        "bodies": [
            _bar("crank", r, {"O2": [0.0, 0.0], "A": [r, 0.0]}),
            {"name": "block", "mass": mb, "inertia": 4e-4, "cog": [0.0, 0.0],
             "points": {"A": [0.0, 0.0]}},
            _bar("lever", L, {"O4": [0.0, 0.0], "E": [L, 0.0]}),
        ],
        "joints": [
            *_pins("O2 ground-crank", "A crank-block"),
            {"name": "A-slot", "kind": "T", "guide": "lever", "slider": "block",
             "line_point": "O4", "line_angle": 0.0, "slider_point": "A"},
            *_pins("O4 ground-lever"),
        ],
        "loads": [{"body": "lever", "point": "E", "force": [-float(p["load"]), 0.0]}],
        "near": {"lever.E": [0.0, L]},
    }


@_factory
def slotted_lever_exercise(seed: int | None = None) -> Exercise:
    """A crank and slotted lever (quick return, RTR dyad) with the crank, the distance
    of the pivots, the lever, the block mass, the speed and the force drawn per
    student; asked: Me at 45 deg and its largest value, the normal force of the block
    on the slot and the reaction in O4 at 45 deg, the largest reaction in O4, the
    lever's angle, angular velocity and angular acceleration at 45 deg."""
    text = _prose("""A crank O2A (length r, steel bar of 7.8 kg/m) turns at n rpm,
        counter-clockwise, about O2, a distance e above the pivot O4 of a slotted lever O4E
        (length L, steel bar of 7.8 kg/m); a block of mass m_b pinned to the crank at A slides
        in the lever's slot along O4E. A horizontal force P acts at E in the -x direction;
        gravity acts (-y). Find by kinetostatics: the equilibrating moment Me at φ = 45° and its
        largest value over the cycle, the normal force of the slot on the block and the reaction
        in O4 at φ = 45°, the largest reaction in O4, and the lever's angle, angular velocity
        and angular acceleration at φ = 45°.""")
    return _mechanism_exercise(
        seed, "slotted_lever", "Kinetostatics of a crank and slotted lever", text, 45,
        _slotted_lever_scene,
        ranges={"r": (0.08, 0.14, 0.005), "e": (0.25, 0.40, 0.01), "L": (0.50, 0.70, 0.01),
                "mb": (0.3, 1.0, 0.1), "rpm": (60.0, 240.0, 10.0),
                "load": (100.0, 500.0, 10.0)},
        questions=["Me@45", "Me_max", "N[A-slot]@45", "F[O4]@45", "Fmax[O4]",
                   "angle[lever]@45", "omega[lever]@45", "alpha[lever]@45"],
        labels={"N[A-slot]@45": "normal force of the slot on the block at phi = 45 deg, "
                                "positive along the lever's left normal (O4E turned +90 deg)"})


# ------------------------------------------------------------- resonance, 3 runs
def _resonance_scene(p: Mapping[str, float]) -> dict:
    """Three amplitudes (um, read to 0.1 um) of a rotor whose unbalance U = ratio m r at
    angle theta from the 0 deg mark is excited at resonance (amplitude k |U + Q|, eqs
    3.22-3.28): alone, with the trial unbalance Q = m r at 0 deg, and at 180 deg (a
    ratio near 1 lets three readings fix the correction)."""
    q = float(p["trial_mass"]) * float(p["trial_radius"])
    u = float(p["ratio"]) * q * complex(math.cos(radian_value(p["theta"])),
                                        math.sin(radian_value(p["theta"])))
    k = float(p["k"])
    return {"title": "Resonance-speed balancing, three runs (exercise)",
            "resonance_test": [{
                "plane": 1, "trial_mass": float(p["trial_mass"]),
                "trial_radius": float(p["trial_radius"]),
                "correction_radius": float(p["correction_radius"]),
                "A1": round(k * abs(u), 1), "A2": round(k * abs(u + q), 1),
                "A3": round(k * abs(u - q), 1)}]}


def _resonance_data(p: dict, scene: dict) -> list:
    t = scene["resonance_test"][0]
    return [("m", t["trial_mass"], "kg", "trial mass"),
            ("r", t["trial_radius"], "m", "radius of the trial mass"),
            ("r_c", t["correction_radius"], "m", "radius of the correction mass"),
            ("A1", t["A1"], "um", "amplitude without the trial mass"),
            ("A2", t["A2"], "um", "amplitude, trial mass at the 0 deg mark"),
            ("A3", t["A3"], "um", "amplitude, trial mass at the 180 deg mark")]


def _phi_clear(scene: dict, key: dict) -> bool:
    """phi away from 0 and 180 deg, where three amplitudes barely fix it."""
    return 20.0 <= key["res_phi[1]"] <= 160.0


@_factory
def resonance_exercise(seed: int | None = None) -> Exercise:
    """Balancing at the resonance speed by the amplitude parallelogram (three runs, seed
    002 eqs 3.22-3.31): the trial mass, the radii and the three amplitudes drawn per
    student (from a hidden unbalance); asked: A, phi, the unbalance, the correction
    mass and both candidate angles."""
    text = _prose("""A rotor swings on a balancing machine about an axis in correction plane II;
        its amplitude at resonance is read three times: A1 without trial mass, A2 with the trial
        mass m at radius r at the 0° mark, A3 with it at the 180° mark. By the amplitude
        parallelogram (course text 002, eqs 3.22-3.31) find: the amplitude A the trial mass
        alone would give, the angle φ between the unbalance and the 0° mark, the unbalance m1 r1
        of plane I, the correction mass at radius r_c, and the two candidate angles of the
        correction mass, 180° + φ and its mirror 180° − φ (three runs cannot tell them apart).""")
    return Exercise(
        template=_resonance_scene,
        ranges={"ratio": (0.7, 1.5, 0.05), "theta": (0.0, 355.0, 5.0),
                "k": (3.0e6, 6.0e6, 0.5e6), "trial_mass": (0.001, 0.003, 0.0005),
                "trial_radius": (0.05, 0.08, 0.01),
                "correction_radius": (0.04, 0.07, 0.01)},
        questions=["res_A[1]", "res_phi[1]", "res_unbalance[1]", "res_mass[1]",
                   "res_angle[1]", "res_mirror[1]"],
        seed=seed, title="Balancing at resonance: the amplitude parallelogram", text=text,
        check=_phi_clear, name="resonance_three_run", data=_resonance_data,
        units={"res_A[1]": "um"}, give_scene=True)


# ----------------------------------------------------------------------- registry
EXERCISES: dict[str, Callable[..., Exercise]] = {
    "four_bar": four_bar_exercise,
    "slider_crank": slider_crank_exercise,
    "slotted_lever": slotted_lever_exercise,
    "rotor_two_plane": rotor_exercise,
    "resonance_three_run": resonance_exercise,
}


def exercise(name: str, seed: int | None = None) -> Exercise:
    """An exercise of the library by name.

    Parameters
    ----------
    name : str
        See :func:`list_exercises`.
    seed : int, optional
        Its seed (default: a secret one).

    Returns
    -------
    Exercise
    """
    key = str(name).strip().replace("-", "_")
    if key not in EXERCISES:
        raise WorkbenchError(f"no exercise {name!r}; the library has: "
                             f"{', '.join(EXERCISES)}")
    return EXERCISES[key](seed)


def list_exercises() -> pd.DataFrame:
    """The library: ``name, title, questions`` (one row per exercise)."""
    rows = []
    for name in EXERCISES:
        ex = exercise(name, seed=0)
        rows.append({"name": name, "title": ex.title, "questions": ", ".join(ex.questions)})
    return pd.DataFrame(rows, columns=["name", "title", "questions"])
