"""The bodies' continuous angles of a long sweep, gathered block by block.

:func:`kinetostatics.solver.continuity.body_angles` unwraps every body's angle along the
whole sweep at once (numpy's ``unwrap``, then the turns between rows that the rows alone
do not tell, found by probing the mechanism). A streamed write
(:mod:`kinetostatics.results.streamed`) never holds the sweep's motion whole, so here the
same steps are taken block after block along increasing driver position, each carrying
what the next block needs (the previous row, the running sum of the corrections): the
same operations on the same numbers in the same order, so the same angles, bit for bit.
What is held over the sweep is one angle array per turning body.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ..model.units import degrees
from ..solver.continuity import (
    Probe,
    anchor,
    body_angles,
    needs_probe,
    probed_turns,
    row_ratios,
    sweep_coordinates,
    sweep_order,
    turn_estimate,
)

PERIOD = 2 * np.pi              # numpy.unwrap's default period and its derived bounds
HIGH = PERIOD / 2
LOW = -HIGH


def degree_angles(kin) -> dict[str, np.ndarray]:
    """Every body's angle (deg) per row, as the ``bodies`` table shows it: the continuous
    radians of :func:`~kinetostatics.solver.continuity.body_angles` in degrees, shifted by
    whole turns so that the row of the smallest driver position lies in (-180, 180]; a
    crank's angle is its positions as typed (the tables' labels, to the bit)."""
    found = body_angles(kin)
    pos = np.asarray(kin.positions, dtype=float)
    drv = kin.scene.driver
    at = int(sweep_order(pos)[0]) if pos.size else 0
    out = {}
    for b, a in found.items():
        if b == drv.body and drv.kind == "R":
            out[b] = pos.copy()
        else:
            a = degrees(a)
            out[b] = anchor(a, at) if a.size else a
    return out


def laid_out(found: dict[str, np.ndarray], scene, n: int
             ) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Every body's ``n`` angles (``found``, as :func:`degree_angles` gives them) laid out
    body after body, in the scene's order, in one array (the ``bodies`` table's
    ``angle`` column): body name -> its view, and the array."""
    whole = np.empty(n * len(scene.bodies))
    out = {}
    for i, b in enumerate(scene.bodies):
        whole[i * n:(i + 1) * n] = found.pop(b)
        out[b] = whole[i * n:(i + 1) * n]
    return out, whole


class SweepAngles:
    """Every body's angle (deg) over a sweep of strictly increasing driver positions, fed
    one block of rows at a time (:meth:`add`, in row order) and finished with
    :meth:`angles`.

    Parameters
    ----------
    scene, structure
        The whole sweep's scene and its structure (assemblies chosen): the probes between
        rows solve the mechanism there.
    positions : ndarray
        The sweep's driver positions, strictly increasing.
    """

    def __init__(self, scene, structure, positions: np.ndarray):
        self.scene, self.structure = scene, structure
        self.positions = positions
        self.coordinates = sweep_coordinates(scene, positions)     # rad or m
        self.n = positions.size
        self.names: list[str] | None = None      # the bodies unwrapped (known at block 1)
        self.fixed: dict[str, np.ndarray] = {}
        self.base: np.ndarray | None = None       # (bodies, rows): unwrapped, radians
        self.last: tuple | None = None            # the previous row: pos, th, r, rp, C
        self.found: list[tuple] = []              # intervals to probe and their ends

    def add(self, rows: slice, kin) -> None:
        """The block ``rows`` of the sweep, solved (its :class:`Kinematics`)."""
        if self.names is None:
            self._first(kin)
        if not self.names:
            return
        m = rows.stop - rows.start
        th = np.stack([np.broadcast_to(kin.bodies[b].theta, (m,)) for b in self.names])
        ps = self.coordinates[rows]
        if self.scene.driver.speed != 0.0:
            r, rp = row_ratios(kin, self.names)
        else:
            _, r, rp = Probe(kin, self.names)(ps)
        self._unwrap(rows, th)
        self._screen(rows, ps, th, r, rp)

    def _first(self, kin) -> None:
        """Which bodies turn (an array of angles), which are the driver or fixed."""
        drv = self.scene.driver
        self.names = []
        for b in self.scene.bodies:
            m = kin.bodies[b]
            if b == drv.body and drv.kind == "R":
                self.fixed[b] = self.positions
            elif np.ndim(m.cos) == 0 and np.ndim(m.sin) == 0:
                a = anchor(np.full(1, float(np.rad2deg(m.theta))))
                self.fixed[b] = np.broadcast_to(a, (self.n,))
            else:
                self.names.append(b)
        if self.names:
            self.base = np.empty((len(self.names), self.n))

    def _unwrap(self, rows: slice, th: np.ndarray) -> None:
        """``numpy.unwrap`` of the rows, its running sum carried from the block before."""
        out = self.base[:, rows]
        if self.last is None:
            dd = np.diff(th, axis=1)
        else:
            dd = np.diff(np.concatenate([self.last[1][:, None], th], axis=1), axis=1)
        ddmod = np.mod(dd - LOW, PERIOD) + LOW
        np.copyto(ddmod, HIGH, where=(ddmod == LOW) & (dd > 0))
        correct = ddmod - dd
        np.copyto(correct, 0, where=abs(dd) < HIGH)
        if self.last is None:
            total = correct.cumsum(axis=1)
            out[:, :1] = th[:, :1]
            out[:, 1:] = th[:, 1:] + total
        else:
            total = np.concatenate([self.last[4][:, None], correct], axis=1).cumsum(axis=1)
            total = total[:, 1:]
            out[:] = th + total
        self._carry = total[:, -1] if total.shape[1] else None

    def _screen(self, rows: slice, ps, th, r, rp) -> None:
        """The intervals whose turn the rows do not tell (to be probed at the end)."""
        base = self.base[:, rows]
        start = rows.start
        if self.last is not None:
            p0, th0, r0, rp0, _ = self.last
            ps = np.concatenate([[p0], ps])
            th = np.concatenate([th0[:, None], th], axis=1)
            r = np.concatenate([r0[:, None], r], axis=1)
            rp = np.concatenate([rp0[:, None], rp], axis=1)
            base = np.concatenate([self.base[:, start - 1:start], base], axis=1)
            start -= 1
        h = np.diff(ps)
        step = np.diff(base, axis=1)
        check = needs_probe(step, turn_estimate(h, r[:, :-1], r[:, 1:], rp[:, :-1], rp[:, 1:]))
        iv = np.flatnonzero(check)
        if iv.size:
            self.found.append((iv + start, ps[iv], ps[iv + 1], th[:, iv], r[:, iv],
                               rp[:, iv], th[:, iv + 1], r[:, iv + 1], rp[:, iv + 1]))
        carry = self._carry
        if carry is None:           # (a first block of one row)
            carry = np.zeros(len(self.names))
        self.last = (ps[-1], th[:, -1].copy(), r[:, -1].copy(), rp[:, -1].copy(), carry)

    def angles(self) -> dict[str, np.ndarray]:
        """Body name -> angles (deg) per row, in the scene's order of bodies (the arrays of
        :func:`degree_angles`)."""
        out = dict(self.fixed)
        if self.names:
            if self.found and self.n > 1:
                self.probed_turns()
            np.rad2deg(self.base, out=self.base)
            for i, b in enumerate(self.names):
                a = self.base[i]
                a += 180.0 - np.mod(180.0 - a[0], 360.0) - a[0]
                out[b] = a
        return {b: out[b] for b in self.scene.bodies}

    def probed_turns(self) -> None:
        """The probed turns added as whole turns to the rows after them (as
        ``base + 2 pi cumsum(extra)``: every row, with the running sum's own roundings)."""
        parts = list(zip(*self.found, strict=True))
        iv = np.concatenate(parts[0])
        lo, hi = np.concatenate(parts[1]), np.concatenate(parts[2])
        ends = tuple(tuple(np.concatenate(p, axis=1) for p in parts[k:k + 3]) for k in (3, 6))
        probe = Probe(SimpleNamespace(scene=self.scene, structure=self.structure),
                       self.names)
        true = probed_turns(probe, lo, hi, ends)
        step = self.base[:, iv + 1] - self.base[:, iv]
        with np.errstate(invalid="ignore"):
            k = np.round((true - step) / (2.0 * np.pi))
        k = np.where(np.isfinite(k), k, 0.0)
        self.found = []
        twopi = 2.0 * np.pi
        # the running sum over the intervals: interval j's value applies to row j + 1;
        # the rows before the first probed interval add 0.0, as the zeros' sum does
        nb = len(self.names)
        self.base[:, :iv[0] + 1] += twopi * np.zeros((nb, 1))
        value = None
        for j, idx in enumerate(iv):
            if value is None:
                value = k[:, j].copy() if idx == 0 else np.zeros(nb) + k[:, j]
            else:
                if idx > iv[j - 1] + 1:
                    value = value + 0.0
                value = value + k[:, j]
            self.base[:, idx + 1:idx + 2] += (twopi * value)[:, None]
            stop = iv[j + 1] + 1 if j + 1 < iv.size else self.n
            if stop > idx + 2:
                self.base[:, idx + 2:stop] += (twopi * (value + 0.0))[:, None]
