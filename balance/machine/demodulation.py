"""The amplitude of the frame's vibration at the rotor's frequency: a lock-in against the
rotor's 0 deg mark (:func:`envelope`) and the peak of the envelope (:func:`peak`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import BalanceError

ENVELOPE_PASSES = 3
"""One-turn moving averages applied to the demodulated signal (:func:`envelope`)."""


def envelope(x: Any, angle: Any, passes: int = ENVELOPE_PASSES) -> np.ndarray:
    """Complex amplitude of a signal at the rotor's frequency, turn by turn (a lock-in
    against the rotor's 0 deg mark, as a balancing machine's phase reference does).

    ``z = x e^(-i angle)`` is averaged over one turn of the rotor (the angle interval
    [angle - pi, angle + pi]), ``passes`` times over. A part of x that turns with the
    rotor, Re(C e^(i angle)) with C slowly varying, becomes C / 2; the part that turns
    the other way becomes C* e^(-2 i angle) / 2, which a whole turn's average removes
    (a constant exactly, a slowly varying one to a residue that every further pass
    makes smaller by about its relative change over a turn). The integrals are the
    trapezoid rule on the samples, the window's ends interpolated consistently with
    it (the samples' linear interpolant integrated exactly).

    Parameters
    ----------
    x : array_like
        Samples of the signal.
    angle : array_like
        The rotor's angle at the same instants (rad, increasing).
    passes : int
        Number of one-turn averages (1: a boxcar over a turn; 3: a smooth window of
        three turns).

    Returns
    -------
    ndarray of complex
        C at each sample: x ~ Re(C e^(i angle)), so |C| is the envelope and -arg C the
        phase (x ~ |C| cos(angle - phase)); NaN where the windows do not fit.
    """
    th = np.asarray(angle, dtype=float)
    z = np.asarray(x, dtype=float) * np.exp(-1j * th)
    if th.size < 3 or not np.all(np.diff(th) > 0.0):
        raise BalanceError("envelope: give at least 3 samples with an increasing angle")
    if int(passes) != passes or passes < 1:
        raise BalanceError(f"envelope: passes = {passes!r}; give a whole number >= 1")
    h = np.diff(th)
    ok = np.ones(th.size, dtype=bool)
    for _ in range(int(passes)):
        zf = np.where(ok, z, 0.0)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (zf[1:] + zf[:-1]) * h)])

        def integral(a: np.ndarray, zf=zf, cum=cum) -> np.ndarray:
            k = np.clip(np.searchsorted(th, a, side="right") - 1, 0, th.size - 2)
            s = a - th[k]
            return cum[k] + s * zf[k] + 0.5 * s * s * (zf[k + 1] - zf[k]) / h[k]

        lo, hi = th - math.pi, th + math.pi
        fits = (lo >= th[0]) & (hi <= th[-1])
        # a window fits where every sample in it was valid in the pass before
        bad = np.concatenate([[0], np.cumsum(~ok)])
        ilo = np.searchsorted(th, lo, side="left")
        ihi = np.searchsorted(th, hi, side="right")
        # samples ilo - 1 .. ihi are used (the ends are interpolated)
        fits &= (bad[np.clip(ihi + 1, 0, th.size)] - bad[np.clip(ilo - 1, 0, th.size)]) == 0
        z = np.where(fits, (integral(np.clip(hi, th[0], th[-1]))
                            - integral(np.clip(lo, th[0], th[-1]))) / (2.0 * math.pi),
                     np.nan + 0j)
        ok = fits
    return 2.0 * z


def peak(t: Any, values: Any) -> tuple[float, float, int]:
    """The largest of sampled values, refined by the parabola through it and its two
    neighbours: (time, value, index of the largest sample). NaNs are skipped."""
    t = np.asarray(t, dtype=float)
    v = np.asarray(values, dtype=float)
    if not np.any(np.isfinite(v)):
        raise BalanceError("peak: no finite value")
    k = int(np.nanargmax(v))
    if k == 0 or k == v.size - 1 or not (np.isfinite(v[k - 1]) and np.isfinite(v[k + 1])):
        return float(t[k]), float(v[k]), k
    y0, y1, y2 = v[k - 1], v[k], v[k + 1]
    den = y0 - 2.0 * y1 + y2
    d = 0.5 * (y0 - y2) / den if den < 0.0 else 0.0       # vertex offset, in samples
    d = max(-0.5, min(0.5, d))
    tk = t[k] + d * (t[k + 1] - t[k] if d > 0 else t[k] - t[k - 1])
    return float(tk), float(y1 - 0.25 * (y0 - y2) * d), k
