"""Static balancing of a mechanism scene (seed 002 s. 3.4): the entry point, its result
and the numerical checks of the closed forms.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import pandas as pd

import kinetostatics as ks
from kinetostatics.common.angles import degree_value
from kinetostatics.model.memory import check_memory
from kinetostatics.model.scene import Scene
from kinetostatics.model.tomlio import read_source
from kinetostatics.solver.footprint import solve_bytes
from kinetostatics.solver.kinematics import Kinematics

from ..common import deg360
from ..errors import BalanceError
from .counterweights import CounterRotatingPair, Counterweight
from .linkage import assign_roles, read_spec, recognise, vec
from .methods import (
    four_bar_full,
    slider_crank_only,
    slider_full,
    slider_line,
    turn_kinematics,
)
from .shaking import centre_of_mass, h_vectors, harmonic_amplitude, shaking_force

__all__ = [
    "CHECK",
    "MechanismBalancing",
    "balanced_scene",
    "shaking_tables",
    "solve_mechanism_balancing",
]

CHECK = 1e-9             # a balanced quantity is zero within CHECK x its scale
# the peak of a balancing against that of a solve of the same rows (its kinematics whole,
# the shaking force and moment before and after): four_bar_balancing at 1e6 positions
# peaked at 607 MB (/usr/bin/time -v), its solve estimate is 692 MB
BALANCING_FACTOR = 1.2


@dataclass
class MechanismBalancing:
    """The result of a mechanism's static balancing (seed 002 s. 3.4).

    Attributes
    ----------
    scene : kinetostatics.Scene
        The mechanism scene (its ``[balancing]`` as read).
    kind : str
        ``"four-bar"`` or ``"slider-crank"``.
    method : str
        One of :data:`METHODS`.
    procedure : str
        How the counterweights were found (the seed's equations, or the more general
        method used where the seed's does not apply).
    counterweights : tuple of Counterweight
    pair : CounterRotatingPair or None
        ``counter-rotating`` only.
    kin : kinetostatics.Kinematics
        The motion over the scene's sweep.
    masses : dict
        The seed's concentrated masses (eq. 3.38 or 3.42; the along-line parts where
        a cog is off its line), kg.
    fraction : float or None
        ``partial``: the fraction of the reciprocating first harmonic balanced.
    A1 : float or None
        Slider-crank: the first-harmonic coefficient of the piston travel, in units
        of the crank length (1 for a centred slider-crank, eq. 3.51).
    checks : dict
        Numerical checks: the drift of the centre of mass over the sweep before and
        after (m); for a slider-crank the first harmonic of the shaking force along the
        slider's line before and after (N, FFT over a full turn).
    """

    scene: Scene
    kind: str
    method: str
    procedure: str
    counterweights: tuple[Counterweight, ...]
    pair: CounterRotatingPair | None
    kin: Kinematics
    masses: dict[str, float]
    fraction: float | None = None
    A1: float | None = None
    checks: dict[str, float] = dataclasses.field(default_factory=dict)

    @cached_property
    def before(self) -> pd.DataFrame:
        """Shaking force and moment over the sweep without counterweights
        (:func:`shaking_force`)."""
        return shaking_force(self.kin)

    @cached_property
    def after(self) -> pd.DataFrame:
        """Shaking force and moment over the sweep with the counterweights (and pair)."""
        return shaking_force(self.kin, self.counterweights, self.pair)

    @property
    def shaking_force_before(self) -> float:
        """Largest |F| over the sweep before balancing (N)."""
        return float(self.before["F"].max()) if len(self.before) else 0.0

    @property
    def shaking_force_after(self) -> float:
        """Largest |F| over the sweep after balancing (N)."""
        return float(self.after["F"].max()) if len(self.after) else 0.0

    def centre_of_mass(self, after: bool = True) -> pd.DataFrame:
        """The mechanism's centre of mass over the sweep (:func:`centre_of_mass`)."""
        return centre_of_mass(self.kin, self.counterweights if after else ())

    def h_vectors(self, after: bool = True) -> pd.DataFrame:
        """The seed's h vectors over the sweep (:func:`h_vectors`)."""
        return h_vectors(self.kin, self.counterweights if after else ())

    @property
    def centre(self) -> tuple[float, float] | None:
        """The fixed centre of mass after ``full`` balancing (its mean over the sweep,
        m); None for the other methods."""
        if self.method != "full":
            return None
        c = self.centre_of_mass(after=True)
        return float(c["x"].mean()), float(c["y"].mean())

    def to_dict(self) -> dict[str, Any]:
        """The contract's ``balancing`` result, JSON-ready, plus the project's keys."""
        out: dict[str, Any] = {
            "method": self.method,
            "mechanism": self.kind,
            "procedure": self.procedure,
            "counterweights": [c.to_dict() for c in self.counterweights],
        }
        if self.pair is not None:
            out["counter_rotating"] = self.pair.to_dict()
        out["shaking_force_before"] = self.shaking_force_before
        out["shaking_force_after"] = self.shaking_force_after
        out["shaking_moment_before"] = float(self.before["M"].abs().max()) \
            if len(self.before) else 0.0
        out["shaking_moment_after"] = float(self.after["M"].abs().max()) \
            if len(self.after) else 0.0
        centre = self.centre
        out["centre_of_mass"] = None if centre is None else [centre[0], centre[1]]
        out["concentrated_masses"] = {k: float(v) for k, v in self.masses.items()}
        if self.fraction is not None:
            out["fraction"] = float(self.fraction)
        if self.A1 is not None:
            out["A1"] = float(self.A1)
        out["checks"] = {k: float(v) for k, v in self.checks.items()}
        return out


def shaking_tables(result: MechanismBalancing) -> dict[str, pd.DataFrame]:
    """``{"before": table, "after": table}``: :func:`shaking_force` without and with the
    result's counterweights (columns ``position, Fx, Fy, F, M``)."""
    return {"before": result.before, "after": result.after}


# -- the entry point ----------------------------------------------------------------------------

def solve_mechanism_balancing(scene: Any, *, method: str | None = None,
                              counterweights: list[Mapping[str, Any]] | None = None,
                              fraction: float | None = None,
                              pair_radius: float | None = None) -> MechanismBalancing:
    """Static balancing of a four-bar or slider-crank scene (seed 002 s. 3.4).

    Parameters
    ----------
    scene : pathlib.Path, str, dict or kinetostatics.Scene
        A mechanism scene (scene-format.md section 1) with a ``[balancing]`` table:
        ``method`` (``full``, ``partial``, ``first-harmonic``, ``counter-rotating``),
        ``counterweights`` (a list of ``{body, about, radius}``) and, as project
        additions, ``fraction`` (``partial``: the share in [0, 1] of the piston's first
        harmonic balanced besides the rotating masses, default 0 as in eq. 3.46) and
        ``pair_radius`` (``counter-rotating``: the radius of the pair's masses, m,
        default the crank counterweight's radius).
    method, counterweights, fraction, pair_radius : optional
        Replace the corresponding entries of the scene's ``[balancing]``.

    Returns
    -------
    MechanismBalancing
        ``.to_dict()`` gives the contract's keys: ``counterweights`` (``{body, about,
        mass, position}``), ``counter_rotating`` (``{mass, radius}``) and
        ``shaking_force_before``, ``shaking_force_after`` (N).

    Raises
    ------
    BalanceError, SceneError
        One line: no ``[balancing]``, an unknown method, body or point, a radius <= 0,
        a method that does not apply to the mechanism, a mechanism that is neither a
        four-bar nor a slider-crank.

    Examples
    --------
    >>> import kinetostatics as ks
    >>> raw = ks.load_scene(ks.example("four_bar")).raw
    >>> raw["balancing"] = {"method": "full", "counterweights": [
    ...     {"body": "crank", "about": "A", "radius": 0.06},
    ...     {"body": "rocker", "about": "D", "radius": 0.08}]}
    >>> res = solve_mechanism_balancing(raw)
    >>> res.shaking_force_after < 1e-9 * res.shaking_force_before
    True
    """
    raw = scene.raw if isinstance(scene, Scene) else read_source(scene, "mechanism scene")
    raw = dict(raw)
    table = dict(raw.get("balancing") or {})
    for key, value in (("method", method), ("counterweights", counterweights),
                       ("fraction", fraction), ("pair_radius", pair_radius)):
        if value is not None:
            table[key] = value
    if not table:
        raise BalanceError("the scene has no [balancing] table: give method and "
                           "counterweights (scene-format.md section 2)")
    raw["balancing"] = table
    sc = ks.load_scene(raw)
    table = sc.raw["balancing"]     # in the contract's units, as the mechanism (a radius in mm)
    rows = sc.driver.positions.size      # the peak memory known before it is spent
    check_memory(BALANCING_FACTOR * solve_bytes(sc, rows),
                 f"the balancing of {sc.title!r} at {rows:,} positions",
                 "use fewer positions (driver.count)")
    lk = recognise(sc)
    method_, specs, fraction_, pair_radius_ = read_spec(sc, table)
    roles = assign_roles(lk, method_, specs)
    kin = ks.solve_kinematics(sc, ks.analyse(sc))
    pair = None
    A1 = None
    u = None
    gk = None
    if lk.kind == "four-bar":
        cws, proc, masses = four_bar_full(sc, lk, roles)
    else:
        gk = turn_kinematics(sc)
        if method_ == "full":
            cws, proc, masses = slider_full(sc, lk, roles)
            u = slider_line(gk, lk)[0]
        else:
            cws, pair, proc, masses, A1, u = slider_crank_only(
                sc, lk, roles, method_, fraction_, pair_radius_, gk)
    res = MechanismBalancing(scene=sc, kind=lk.kind, method=method_, procedure=proc,
                             counterweights=tuple(cws), pair=pair, kin=kin, masses=masses,
                             fraction=(fraction_ or 0.0) if method_ == "partial" else None,
                             A1=A1)
    res.checks = _checks(res, gk, u)
    return res


def _drift(c: pd.DataFrame) -> float:
    if not len(c):
        return 0.0
    return float(np.hypot(c["x"] - c["x"].mean(), c["y"] - c["y"].mean()).max())


def _checks(res: MechanismBalancing, gk: Kinematics | None, u: np.ndarray | None
            ) -> dict[str, float]:
    """Numerical checks of the closed forms (the balancing is verified, not assumed)."""
    if sum(b.mass for b in res.scene.bodies.values()) == 0.0:
        raise BalanceError("the mechanism has no mass (every body's mass is 0): there is "
                           "nothing to balance")
    out = {"centre_of_mass_drift_before": _drift(res.centre_of_mass(after=False)),
           "centre_of_mass_drift_after": _drift(res.centre_of_mass(after=True))}
    size = res.scene.size
    if res.method == "full" and out["centre_of_mass_drift_after"] > CHECK * size:
        raise BalanceError(f"after full balancing ({res.procedure}) the centre of mass still "
                           f"moves by {out['centre_of_mass_drift_after']:.3g} m (more than "
                           f"{CHECK:g} of the mechanism's size): the closed form fails its own "
                           "check for this mechanism, so its counterweights are refused")
    if gk is not None and u is not None:
        before = shaking_force(gk)
        after = shaking_force(gk, res.counterweights, res.pair)
        fb = before["Fx"].to_numpy() * u[0] + before["Fy"].to_numpy() * u[1]
        fa = after["Fx"].to_numpy() * u[0] + after["Fy"].to_numpy() * u[1]
        out["first_harmonic_before"] = harmonic_amplitude(fb, 1)
        out["first_harmonic_after"] = harmonic_amplitude(fa, 1)
        out["line_angle"] = deg360(degree_value(math.atan2(u[1], u[0])))
        if res.method in ("first-harmonic", "counter-rotating", "full") and \
                out["first_harmonic_after"] > CHECK * max(out["first_harmonic_before"], 1e-300):
            raise BalanceError(f"after {res.method} balancing the first harmonic of the "
                               f"shaking force along the line is still "
                               f"{out['first_harmonic_after']:.3g} N (before: "
                               f"{out['first_harmonic_before']:.3g} N): the closed form fails "
                               "its own check for this mechanism, so its counterweights are "
                               "refused")
    return out


def balanced_scene(result: MechanismBalancing) -> dict[str, Any]:
    """The scene as a dict with each counterweight added to its body's mass, cog and
    moment of inertia (point masses), ready for ``kinetostatics.solve``.

    The ``[balancing]`` table is dropped, and so is the ``mass_model`` of a body that
    takes a counterweight (the new cog need not lie on its two points). The pair of a
    ``counter-rotating`` result is outside the scene and is not added.
    """
    raw = copy.deepcopy(result.scene.raw)
    raw.pop("balancing", None)
    for entry in raw.get("bodies", []):
        name = entry.get("name")
        cws = [c for c in result.counterweights if c.body == name and c.mass != 0.0]
        if not cws:
            continue
        body = result.scene.bodies[name]
        g0 = vec(body.local("cog"))
        m = body.mass + sum(c.mass for c in cws)
        g = (body.mass * g0 + sum((c.mass * vec(c.position) for c in cws), np.zeros(2))) / m
        inertia = body.inertia + body.mass * float((g0 - g) @ (g0 - g)) + sum(
            c.mass * float((vec(c.position) - g) @ (vec(c.position) - g)) for c in cws)
        entry["mass"] = float(m)
        entry["cog"] = [float(g[0]), float(g[1])]
        entry["inertia"] = float(inertia)
        entry.pop("mass_model", None)
    return raw
