"""The order of the motion over a sweep, and continuous angles that follow it.

A sweep's rows may come in any order (a ``positions`` list, scene-format section 1,
Results): each row is solved on its own, so only what joins rows depends on the order.
That is taken along increasing driver position, once, by :func:`sweep_order`: the
continuity of the angles, the dead points between rows, the means, maxima and integrals
over the sweep. A repeated position is refused (:func:`check_distinct`).

Continuous angles (:func:`body_angles`). Between two neighbouring rows (in increasing
driver position phi) a body turns by the integral of its velocity ratio
r = d theta / d phi = omega / phidot. The rows know theta only modulo 2 pi; the nearest
value (numpy's ``unwrap``) is right only where the body turns by less than 180 deg
between the rows. Each interval is checked against the Hermite estimate of the turn
from the rows' ratios and their derivatives r' = d r / d phi = (alpha - r phiddot) /
phidot^2 (seed 001: omega = r phidot, alpha = r' phidot^2 + r phiddot):

    E = h (r_a + r_b) / 2 + h^2 (r'_a - r'_b) / 12,

and an interval whose wrapped turn d (in (-pi, pi]) is large (|d| > 90 deg) or
disagrees with E by more than 90 deg is sub-sampled: the same mechanism, in the same
assembly, at unit driver speed (so that omega = r, alpha = r' at the probes, also for a
scene at rest), split into 8 parts, the parts that fail the same test split again, up
to the resolution of the positions. The turn over the interval is the sum of its parts'
wrapped turns; it replaces the nearest value by whole turns. A block passing within
1e-9 m of its lever's pivot between rows (the lever turns by about 180 deg in a tiny
part of the interval) is resolved by that zoom, and a link that turns more than
180 deg between two rows shows the angle it really reached. Where the dyad cannot close
inside an interval there is no motion between its rows: the nearest value is kept
(:mod:`kinetostatics.solver.deadpoints` reports such intervals).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from ..model.errors import SceneError

if TYPE_CHECKING:
    from .kinematics import Kinematics

TURN_CHECK = 0.5 * np.pi    # |d| or |E - d| above this (rad): the interval is sub-sampled
SPLIT = 8                   # parts per sub-sampled interval and round
MAX_ROUNDS = 40             # zoom rounds (8^40: far below the positions' resolution)


def sweep_order(positions: np.ndarray) -> np.ndarray:
    """The rows in increasing driver position (a stable argsort; the identity for an
    increasing sweep)."""
    pos = np.asarray(positions, dtype=float)
    if pos.size < 2 or bool(np.all(pos[1:] > pos[:-1])):
        return np.arange(pos.size)
    return np.argsort(pos, kind="stable")


def given_positions(positions) -> np.ndarray:
    """The driver positions given to a solve (``solve(scene, positions)``) as a float
    array, checked as the scene's own ``driver.positions`` are: at least one, each a
    finite number (one line, :class:`SceneError`, naming the first bad entry)."""
    try:
        arr = np.asarray(positions)
    except ValueError:          # ragged nesting
        arr = None
    # (numpy reads true/false among numbers as 1/0: a list is looked at item by item)
    mixed = isinstance(positions, list | tuple) and any(
        isinstance(v, bool | np.bool_) for v in positions)
    if mixed or arr is None or arr.dtype.kind not in "iuf" or arr.ndim > 1:
        if isinstance(positions, np.ndarray):
            raise SceneError(f"positions must be numbers in one list, not an array of "
                             f"{positions.dtype} with shape {positions.shape}")
        items = list(positions) if isinstance(positions, Iterable) else [positions]
        for i, v in enumerate(items):
            if isinstance(v, bool | np.bool_) or not isinstance(v, int | float | np.number):
                raise SceneError(f"positions[{i}] must be a number, not {_kind_of(v)}")
    pos = np.atleast_1d(arr.astype(float, copy=False))
    if pos.size == 0:
        raise SceneError("positions is empty; list at least one position")
    bad = np.flatnonzero(~np.isfinite(pos))
    if bad.size:
        raise SceneError(f"positions[{bad[0]}] must be a finite number, not {pos[bad[0]]:g}")
    return pos


def _kind_of(v) -> str:
    return {str: "a string", list: "a list", tuple: "a list", dict: "a table",
            bool: "true/false"}.get(type(v), f"a {type(v).__name__}")


def check_distinct(positions: np.ndarray, unit: str, factor: float = 1.0) -> None:
    """Refuse a sweep that lists a driver position twice (one line, :class:`SceneError`),
    the position quoted in ``unit``, of which one is ``factor`` contract units (deg or
    m): as the scene typed it."""
    pos = np.asarray(positions, dtype=float)
    if pos.size < 2 or bool((pos[1:] > pos[:-1]).all()):
        return                  # strictly increasing: each position once
    p = pos[np.argsort(pos, kind="stable")]
    same = np.flatnonzero(p[1:] == p[:-1])
    if same.size:
        rows = sorted(np.flatnonzero(pos == p[same[0]]).tolist())
        raise SceneError(
            f"driver positions: {p[same[0]] / factor:g} {unit} is listed more than once (rows "
            f"{', '.join(str(r + 1) for r in rows[:4])}); each position must appear once "
            "(start = stop with count > 1 repeats it too)")


def open_rows(kin: Kinematics) -> np.ndarray:
    """Rows of a kinematics solved with ``strict = False`` (probes between rows) where
    some dyad cannot close: its links do not reach by more than 1e-9 of the mechanism's
    size (the closed forms clip there, so the motion arrays alone do not show it)."""
    from .closure import DyadSolver
    out = np.zeros(kin.n, dtype=bool)
    for dm in kin.dyads:
        gap = DyadSolver(kin.scene, dm.dyad).positions(dm.params, dm.k)[2]
        if gap is not None:
            with np.errstate(invalid="ignore"):
                out |= ~(np.broadcast_to(gap, (kin.n,)) <= 1e-9 * kin.scene.size)
    return out


def _wrap(d: np.ndarray) -> np.ndarray:
    """Angles in [-pi, pi)."""
    return np.mod(d + np.pi, 2.0 * np.pi) - np.pi


def turn_estimate(h, ra, rb, pa, pb):
    """Hermite estimate of the turn over an interval of length h."""
    with np.errstate(all="ignore"):
        return 0.5 * h * (ra + rb) + h * h * (pa - pb) / 12.0


def needs_probe(d, est) -> np.ndarray:
    """Intervals (any body) whose nearest turn d cannot be trusted."""
    with np.errstate(invalid="ignore"):
        bad = (np.abs(d) > TURN_CHECK) | ~(np.abs(est - d) <= TURN_CHECK)
    return bad.any(axis=0)


class Probe:
    """The mechanism at unit driver speed, at any driver positions in SI (rad or m), in
    the sweep's assembly: theta, r = d theta / d phi and r' per body (rows: bodies)."""

    def __init__(self, kin: Kinematics, names: list[str]):
        from .kinematics import choose_assembly
        self.driver = replace(kin.scene.driver, speed=1.0, acceleration=0.0)
        self.scene = replace(kin.scene, driver=self.driver)
        structure = kin.structure
        if len(structure.assembly) != len(structure.dyads):      # (the sweep's first row)
            structure = replace(structure, assembly=choose_assembly(self.scene, structure))
        self.structure = structure
        self.names = names

    def __call__(self, coordinates: np.ndarray):
        from .kinematics import solve_kinematics
        scene = replace(self.scene, driver=self.driver.at(coordinates))
        k = solve_kinematics(scene, self.structure, strict=False)
        n = coordinates.size
        th = np.stack([np.broadcast_to(k.bodies[b].theta, (n,)) for b in self.names])
        th = np.where(open_rows(k)[None, :], np.nan, th)    # no motion there
        r = np.stack([np.broadcast_to(k.bodies[b].omega, (n,)) for b in self.names])
        rp = np.stack([np.broadcast_to(k.bodies[b].alpha, (n,)) for b in self.names])
        return th, r, rp


def _split(first: np.ndarray, mid: np.ndarray, last: np.ndarray, keep: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray]:
    """Values at the ends of the parts of the intervals ``keep``: (bodies, parts) at
    their lower and upper ends, from the intervals' ends and the interior probes."""
    full = np.concatenate([first[:, keep, None], mid, last[:, keep, None]], axis=2)
    nb = full.shape[0]
    return full[:, :, :-1].reshape(nb, -1), full[:, :, 1:].reshape(nb, -1)


def probed_turns(probe: Probe, lo, hi, ends) -> np.ndarray:
    """The turn of every body over each interval (lo, hi), by zooming sub-samples.

    ``lo``, ``hi``: the driver's positions in SI (rad or m, :attr:`Driver.coordinates`);
    ``ends``: (theta, r, r') at lo and at hi, each (bodies, intervals). Returns
    (bodies, intervals); NaN where the mechanism cannot close inside an interval."""
    nb, m = ends[0][0].shape[0], lo.size
    total = np.zeros((nb, m))
    lost = np.zeros(m, dtype=bool)
    span = float(np.max(np.abs(np.concatenate([lo, hi])))) + float(np.max(hi - lo))
    tiny = 1e-13 * span
    parent = np.arange(m)
    (tha, ra, pa), (thb, rb, pb) = ends
    a, b = lo.copy(), hi.copy()
    t = np.arange(1, SPLIT) / SPLIT
    for round_ in range(MAX_ROUNDS + 1):
        h = b - a
        d = _wrap(thb - tha)
        bad = needs_probe(d, turn_estimate(h, ra, rb, pa, pb)) & (h > tiny)
        if round_ == MAX_ROUNDS:
            bad[:] = False
        nan = ~np.isfinite(d).all(axis=0)
        lost[parent[nan]] = True
        ok = ~bad & ~nan
        np.add.at(total.T, parent[ok], d[:, ok].T)
        keep = np.flatnonzero(bad & ~nan)
        if keep.size == 0:
            break
        inner = a[keep, None] + h[keep, None] * t[None, :]          # (k, SPLIT - 1)
        shape = (nb, keep.size, SPLIT - 1)
        th, r, rp = (v.reshape(shape) for v in probe(inner.ravel()))
        pts = np.concatenate([a[keep, None], inner, b[keep, None]], axis=1)
        a, b = pts[:, :-1].ravel(), pts[:, 1:].ravel()
        parent = np.repeat(parent[keep], SPLIT)
        tha, thb = _split(tha, th, thb, keep)
        ra, rb = _split(ra, r, rb, keep)
        pa, pb = _split(pa, rp, pb, keep)
    total[:, lost] = np.nan
    return total


def row_ratios(kin: Kinematics, names: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """r = d theta / d phi and r' = d r / d phi per body at the rows, from the rows' omega
    and alpha (a moving driver: omega = r phidot, alpha = r' phidot^2 + r phiddot)."""
    n = kin.n
    drv = kin.scene.driver
    w, eps = float(drv.speed), float(drv.acceleration)
    om = np.stack([np.broadcast_to(kin.bodies[b].omega, (n,)) for b in names])
    al = np.stack([np.broadcast_to(kin.bodies[b].alpha, (n,)) for b in names])
    r = om / w
    return r, (al - r * eps) / (w * w)


def sweep_coordinates(scene, positions) -> np.ndarray:
    """A sweep's driver positions (deg or m, the tables' labels) in SI, rad or m: the
    scene's own :attr:`Driver.coordinates`, or those of its driver at ``positions``
    (converted where drivers are made, :mod:`kinetostatics.model`)."""
    drv = scene.driver
    if positions is drv.positions:
        return drv.coordinates
    return replace(drv, positions=np.asarray(positions, dtype=float)).coordinates


def anchor(a: np.ndarray, at: int = 0) -> np.ndarray:
    """Shift a continuous angle (deg) by whole turns so that its value at row ``at`` lies
    in (-180, 180]."""
    first = 180.0 - np.mod(180.0 - a[at], 360.0)
    return a + (first - a[at])


def body_angles(kin: Kinematics) -> dict[str, np.ndarray]:
    """Every moving body's angle (rad) over the sweep, continuous along increasing driver
    position and following the true motion between rows, as unwrapped from the row of
    the smallest driver position (its own value there). A rotating driver's angle is its
    :attr:`Driver.coordinates`. Rows in the sweep's own order. (The tables' degrees,
    anchored in (-180, 180] at that row: :func:`kinetostatics.results.sweepangles.degree_angles`.)

    Parameters
    ----------
    kin : Kinematics
        The solved sweep (its scene, structure and assembly are probed between rows where
        the rows alone do not tell the turn).

    Returns
    -------
    dict
        Body name -> angles (rad), one per row.
    """
    scene = kin.scene
    n = kin.n
    pos = np.asarray(kin.positions, dtype=float)
    out: dict[str, np.ndarray] = {}
    names = []
    x = sweep_coordinates(scene, kin.positions)
    for b in scene.bodies:
        if b == scene.driver.body and scene.driver.kind == "R":
            out[b] = x.copy()
        elif np.ndim(kin.bodies[b].cos) == 0 and np.ndim(kin.bodies[b].sin) == 0:
            out[b] = np.full(n, float(kin.bodies[b].theta))
        else:
            names.append(b)
    if not names:
        return out
    order = sweep_order(pos)
    ps = x[order]           # rad or m: the turns' scale
    th = np.stack([np.broadcast_to(kin.bodies[b].theta, (n,))[order] for b in names])
    base = np.unwrap(th, axis=1)
    if n > 1:
        probe = Probe(kin, names)
        drv = scene.driver
        if drv.speed != 0.0:
            r, rp = row_ratios(kin, names)
            r, rp = r[:, order], rp[:, order]
        else:               # at rest every omega is 0: the ratios at unit speed
            _, r, rp = probe(ps)
        h = np.diff(ps)
        step = np.diff(base, axis=1)
        check = needs_probe(step, turn_estimate(h, r[:, :-1], r[:, 1:], rp[:, :-1], rp[:, 1:]))
        iv = np.flatnonzero(check)
        if iv.size:
            ends = ((th[:, iv], r[:, iv], rp[:, iv]),
                    (th[:, iv + 1], r[:, iv + 1], rp[:, iv + 1]))
            true = probed_turns(probe, ps[iv], ps[iv + 1], ends)
            with np.errstate(invalid="ignore"):
                k = np.round((true - step[:, iv]) / (2.0 * np.pi))
            k = np.where(np.isfinite(k), k, 0.0)
            extra = np.zeros_like(step)
            extra[:, iv] = k
            base = base + 2.0 * np.pi * np.concatenate(
                [np.zeros((len(names), 1)), np.cumsum(extra, axis=1)], axis=1)
    for i, b in enumerate(names):
        res = np.empty(n)
        res[order] = base[i]
        out[b] = res
    return out
