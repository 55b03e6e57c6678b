"""Speed against error: positions per second of the kinematics and of the whole
kinetostatic solve, with the error against independent closed forms.

``python -m kinetostatics bench`` prints three tables:

* kinematics of the four-bar and the slider-crank at 1e3, 1e5 and 1e6 positions,
  against closed forms written here independently of the dyad solver (the four-bar's
  half-angle solution with Norton's velocity and acceleration formulas; the
  slider-crank of seed 004 eqs (1)-(3));
* reactions and Me of a four-bar at 1e6 positions against a global matrix solution
  (the nine Newton-Euler equations of the three bodies, one 9 x 9 system per position);
* the hand-written baseline's ``fourbar_kin`` and ``fourbar_dyad``
  (:mod:`kinetostatics.bench.reference`, or another module of the same names given with
  ``--reference PATH``) timed side by side, in one process, with the workbench on the
  same four-bar: ratios of the best of several runs.
"""

from __future__ import annotations

import contextlib
import copy
import gc
import importlib.util
import math
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pandas as pd

from ..common.angles import radian_column
from ..model.scene import load_scene
from ..results import solve
from ..solver.kinematics import solve_kinematics
from ..solver.structure import analyse

# the baseline's four-bar: a = 0.1, b = 0.25, c = 0.2, d = 0.3, cogs at mid-links,
# 500 N down at C on the rocker, no gravity
FB = {"a": 0.1, "b": 0.25, "c": 0.2, "d": 0.3, "m2": 1.2, "m3": 2.0, "m4": 1.5,
      "I2": 0.004, "I3": 0.012, "I4": 0.006, "P": (0.0, -500.0)}
SC = {"r": 0.150, "l": 0.350, "rpm": 1500.0}      # the bundled slider_crank


def _bundled(name: str) -> dict:
    from ..model.examples import example
    from ..model.scene import load_scene
    return copy.deepcopy(load_scene(example(name)).raw)


def fourbar_scene(count: int, speed: float = 20.0, p: dict = FB) -> dict:
    """The baseline's four-bar as a scene dict (crank 0..360 deg, open assembly): the
    bundled ``four_bar`` (its lengths are the baseline's) with the baseline's masses,
    inertias and mid-link cogs, 500 N down at C on the rocker and no gravity; its extra
    points (coupler P, rocker E) dropped."""
    d = _bundled("four_bar")
    d["title"] = "four-bar (benchmark)"
    d["gravity"] = [0.0, 0.0]
    d["ground"]["D"] = [p["d"], 0.0]
    d["driver"].update(speed=speed, start=0.0, stop=360.0, count=int(count))
    shape = {"crank": ("a", "m2", "I2", "A", "B"), "coupler": ("b", "m3", "I3", "B", "C"),
             "rocker": ("c", "m4", "I4", "D", "C")}
    for body in d["bodies"]:
        length, m, inertia, start, end = shape[body["name"]]
        body.update(mass=p[m], inertia=p[inertia], cog=[p[length] / 2, 0.0],
                    points={start: [0.0, 0.0], end: [p[length], 0.0]})
    d["loads"] = [{"body": "rocker", "point": "C", "force": list(p["P"])}]
    return d


def slider_crank_reference_scene(count: int, p: dict) -> dict:
    """The baseline's slider-crank (``SC`` of :mod:`kinetostatics.bench.reference`: r, l, masses,
    inertias, speed ``w2``, cogs at mid-link and on the piston pin, no gravity, no load)
    as a scene dict over ``count`` positions of a turn: the bundled ``slider_crank``
    with those numbers."""
    d = _bundled("slider_crank")
    d["title"] = "slider-crank (benchmark)"
    d["gravity"] = [0.0, 0.0]
    d["driver"].update(speed=float(p["w2"]), start=0.0, stop=360.0, count=int(count))
    shape = {"crank": (p["r"], "m2", p["I2"], "A", "B"), "rod": (p["l"], "m3", p["I3"], "B", "C")}
    for body in d["bodies"]:
        if body["name"] in shape:
            length, m, inertia, start, end = shape[body["name"]]
            body.update(mass=p[m], inertia=inertia, cog=[length / 2, 0.0],
                        points={start: [0.0, 0.0], end: [length, 0.0]})
        else:                                           # the piston: a point mass
            body.update(mass=p["m4"], inertia=0.0, cog=[0.0, 0.0])
    d["loads"] = []
    return d


def slider_crank_scene(count: int) -> dict:
    """The bundled centred slider-crank (r = 0.150 m, l = 0.350 m, 1500 rpm, seed 004)
    with ``count`` positions over a turn."""
    d = _bundled("slider_crank")
    d["driver"].update(start=0.0, stop=360.0, count=int(count))
    return d


def fourbar_closed_form(th: np.ndarray, w2: float, p: dict = FB) -> dict:
    """Four-bar by the half-angle (Freudenstein) solution, open branch; Norton's
    velocity and acceleration formulas (alpha2 = 0)."""
    a, b, c, d = p["a"], p["b"], p["c"], p["d"]
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    A = np.cos(th) - k1 - k2 * np.cos(th) + k3
    B = -2.0 * np.sin(th)
    C = k1 - (k2 + 1.0) * np.cos(th) + k3
    t4 = 2.0 * np.arctan2(-B - np.sqrt(B * B - 4 * A * C), 2 * A)   # open (crossed: +)
    k4, k5 = d / b, (c * c - d * d - a * a - b * b) / (2 * a * b)
    D = np.cos(th) - k1 + k4 * np.cos(th) + k5
    E = -2.0 * np.sin(th)
    F = k1 + (k4 - 1.0) * np.cos(th) + k5
    t3 = 2.0 * np.arctan2(-E - np.sqrt(E * E - 4 * D * F), 2 * D)
    w3 = a * w2 / b * np.sin(t4 - th) / np.sin(t3 - t4)
    w4 = a * w2 / c * np.sin(th - t3) / np.sin(t4 - t3)
    Ac = c * np.sin(t4)
    Bc = b * np.sin(t3)
    Cc = a * w2**2 * np.cos(th) + b * w3**2 * np.cos(t3) - c * w4**2 * np.cos(t4)
    Dc = c * np.cos(t4)
    Ec = b * np.cos(t3)
    Fc = -a * w2**2 * np.sin(th) - b * w3**2 * np.sin(t3) + c * w4**2 * np.sin(t4)
    al3 = (Cc * Dc - Ac * Fc) / (Ac * Ec - Bc * Dc)
    al4 = (Cc * Ec - Bc * Fc) / (Ac * Ec - Bc * Dc)
    return {"Cx": d + c * np.cos(t4), "Cy": c * np.sin(t4), "w3": w3, "w4": w4,
            "al3": al3, "al4": al4}


def slider_closed_form(th: np.ndarray, w: float) -> dict:
    """Piston of the centred slider-crank, seed 004 eqs (1)-(3), exact:
    x = r cos th + sqrt(l^2 - r^2 sin^2 th) and its first two time derivatives."""
    r, l = SC["r"], SC["l"]
    s, c = np.sin(th), np.cos(th)
    S = np.sqrt(l * l - r * r * s * s)
    x = r * c + S
    dx = -r * s - r * r * s * c / S
    ddx = -r * c - r * r * (c * c - s * s) / S - r**4 * s * s * c * c / S**3
    return {"x": x, "v": w * dx, "a": w * w * ddx}


FROZEN = [0]    # frozen_heap's depth: the outermost one unfreezes


@contextlib.contextmanager
def frozen_heap() -> Iterator[None]:
    """The timing loops' garbage collections made cheap: what lives when the loop starts
    is collected and then frozen (:func:`gc.freeze`), so that the collection before each
    timed call walks only what was made since, not the whole heap (numba, pandas, the
    variants: 63 ms a collection, 4.9 s of the 11.4 s of CPU of ``bench --quick
    --repeat 1``, measured 2026-11-30). Nested, only the outermost unfreezes: a whole
    bench run is frozen once (:func:`run_bench`), each loop freezing what it finds new.
    The collections stay outside the clocks and leave no garbage either way; a timed
    call's own automatic collections skip the frozen heap too."""
    gc.collect()
    gc.freeze()
    FROZEN[0] += 1
    try:
        yield
    finally:
        FROZEN[0] -= 1
        if not FROZEN[0]:
            gc.unfreeze()


def _best(f, repeat: int = 5) -> float:
    times = []
    with frozen_heap():
        for _ in range(repeat):
            gc.collect()
            t = time.perf_counter()
            f()
            times.append(time.perf_counter() - t)
    return min(times)


def bench_kinematics(sizes=(1_000, 100_000, 1_000_000), repeat: int = 3) -> pd.DataFrame:
    """Positions per second of the kinematics and the largest error against the closed
    forms (relative to each quantity's largest magnitude)."""
    rows = []
    for n in sizes:
        sc = load_scene(fourbar_scene(n))
        st = analyse(sc)
        t = _best(lambda sc=sc, st=st: solve_kinematics(sc, st), repeat)
        kin = solve_kinematics(sc, st)
        ref = fourbar_closed_form(sc.driver.angles, sc.driver.speed)
        cpl, rck = kin.bodies["coupler"], kin.bodies["rocker"]
        cx, cy = rck.point((FB["c"], 0.0))
        got = {"Cx": cx, "Cy": cy, "w3": cpl.omega, "w4": rck.omega,
               "al3": cpl.alpha, "al4": rck.alpha}
        err = max(float(np.max(np.abs(got[k] - v)) / np.max(np.abs(v))) for k, v in ref.items())
        rows.append({"mechanism": "four-bar", "positions": n, "seconds": t,
                     "positions_per_s": n / t, "max_rel_error": err})
        sc = load_scene(slider_crank_scene(n))
        st = analyse(sc)
        t = _best(lambda sc=sc, st=st: solve_kinematics(sc, st), repeat)
        kin = solve_kinematics(sc, st)
        ref = slider_closed_form(sc.driver.angles, sc.driver.speed)
        p = kin.bodies["piston"]
        got = {"x": np.broadcast_to(p.ox, (n,)), "v": np.broadcast_to(p.vx, (n,)),
               "a": np.broadcast_to(p.ax, (n,))}
        err = max(float(np.max(np.abs(got[k] - v)) / np.max(np.abs(v))) for k, v in ref.items())
        rows.append({"mechanism": "slider-crank", "positions": n, "seconds": t,
                     "positions_per_s": n / t, "max_rel_error": err})
    return pd.DataFrame(rows)


def fourbar_matrix_solution(th: np.ndarray, w2: float, p: dict = FB, chunk: int = 100_000):
    """Reactions and Me of the benchmark four-bar from the nine Newton-Euler equations,
    one 9 x 9 linear system per position (numpy.linalg.solve, in chunks).
    Returns an (N, 9) array [F12x, F12y, F23x, F23y, F34x, F34y, F14x, F14y, Me]
    (F_ij on body j; 1 ground, 2 crank, 3 coupler, 4 rocker)."""
    out = []
    for s in range(0, th.size, chunk):
        t = th[s:s + chunk]
        k = fourbar_closed_form(t, w2, p)
        n = t.size
        a = p["a"]
        Bx, By = a * np.cos(t), a * np.sin(t)
        Cx, Cy = k["Cx"], k["Cy"]
        aBx, aBy = -w2 * w2 * Bx, -w2 * w2 * By
        t4 = np.arctan2(Cy, Cx - p["d"])
        aCx = -k["al4"] * p["c"] * np.sin(t4) - k["w4"] ** 2 * (Cx - p["d"])
        aCy = k["al4"] * p["c"] * np.cos(t4) - k["w4"] ** 2 * Cy
        G = [(Bx / 2, By / 2), ((Bx + Cx) / 2, (By + Cy) / 2), ((Cx + p["d"]) / 2, Cy / 2)]
        aG = [(aBx / 2, aBy / 2), ((aBx + aCx) / 2, (aBy + aCy) / 2), (aCx / 2, aCy / 2)]
        m = [p["m2"], p["m3"], p["m4"]]
        inertia = [p["I2"], p["I3"], p["I4"]]
        alpha = [np.zeros(n), k["al3"], k["al4"]]
        M = np.zeros((n, 9, 9))
        rhs = np.zeros((n, 9))
        # unknown columns: F12 (0,1) at A, F23 (2,3) at B, F34 (4,5) at C, F14 (6,7) at D, Me 8
        joints = [(0, 0.0, 0.0, None, 0), (2, Bx, By, 0, 1), (4, Cx, Cy, 1, 2),
                  (6, p["d"], 0.0, None, 2)]
        for col, x, y, frm, to in joints:
            for body, sign in ((to, 1.0), (frm, -1.0)):
                if body is None:
                    continue
                gx, gy = G[body]
                r = 3 * body
                M[:, r, col] = sign
                M[:, r + 1, col + 1] = sign
                M[:, r + 2, col] = -sign * (y - gy)
                M[:, r + 2, col + 1] = sign * (x - gx)
        M[:, 2, 8] = 1.0
        for i in range(3):
            r = 3 * i
            rhs[:, r] = m[i] * aG[i][0]
            rhs[:, r + 1] = m[i] * aG[i][1]
            rhs[:, r + 2] = inertia[i] * alpha[i]
        px, py = p["P"]
        gx, gy = G[2]
        rhs[:, 6] -= px
        rhs[:, 7] -= py
        rhs[:, 8] -= (Cx - gx) * py - (Cy - gy) * px
        out.append(np.linalg.solve(M, rhs[..., None])[..., 0])
    return np.concatenate(out)


def bench_reactions(n: int = 1_000_000, repeat: int = 3) -> pd.DataFrame:
    """Positions per second of ``solve`` (reactions and Me, reading the driver table) on
    the benchmark four-bar, and the largest error against the global matrix solution."""
    scene = fourbar_scene(n)
    t = _best(lambda: solve(scene).driver, repeat)
    sol = solve(scene)
    ref = fourbar_matrix_solution(radian_column(sol.positions), sol.scene.driver.speed)
    got = np.column_stack([*sol.reaction("A"), *sol.reaction("B"), *sol.reaction("C"),
                           *sol.reaction("D"), sol.Me])
    scale = np.abs(ref).max(axis=0)
    err = float((np.abs(got - ref) / scale).max())
    return pd.DataFrame([{"mechanism": "four-bar", "positions": n, "seconds": t,
                          "positions_per_s": n / t, "max_rel_error_vs_matrix": err}])


def load_reference(path: str | Path | None = None):
    """The hand-written baseline (a module with ``fourbar_kin``, ``fourbar_dyad``,
    ``slider_dyad`` and ``SC``): :mod:`kinetostatics.bench.reference`, or one loaded
    from ``path``."""
    if path is None or Path(path).resolve() == find_reference():
        from . import reference
        return reference
    spec = importlib.util.spec_from_file_location("reference_fourbar", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def find_reference() -> Path:
    """The repository's own baseline, :mod:`kinetostatics.bench.reference`."""
    return Path(__file__).resolve().with_name("reference.py")


def bench_against_reference(path: str | Path, n: int = 200_001, repeat: int = 7) -> pd.DataFrame:
    """The baseline's ``fourbar_kin`` / ``fourbar_dyad`` and the workbench on the same
    four-bar, side by side in one process (alternating runs, best of ``repeat``)."""
    ref = load_reference(path)
    scene = fourbar_scene(n)
    th = radian_column(np.linspace(0.0, 360.0, n))
    sc = load_scene(scene)
    st = analyse(sc)
    jobs = {
        "reference fourbar_kin": lambda: ref.fourbar_kin(th, 20.0),
        "workbench kinematics": lambda: solve_kinematics(sc, st),
        "reference fourbar_dyad": lambda: ref.fourbar_dyad(th, 20.0),
        "workbench solve(scene).driver": lambda: solve(scene).driver,
    }
    best = {k: math.inf for k in jobs}
    with frozen_heap():
        for _ in range(repeat):
            for k, f in jobs.items():
                gc.collect()
                t = time.perf_counter()
                f()
                best[k] = min(best[k], time.perf_counter() - t)
    r = ref.fourbar_dyad(th, 20.0)
    sol = solve(scene)
    me_err = float(np.abs(sol.Me - r["Me"]).max() / np.abs(r["Me"]).max())
    rows = [{"job": k, "seconds": v, "positions_per_s": n / v} for k, v in best.items()]
    df = pd.DataFrame(rows)
    df["ratio_to_reference"] = [1.0, best["workbench kinematics"] / best["reference fourbar_kin"],
                                1.0, best["workbench solve(scene).driver"]
                                / best["reference fourbar_dyad"]]
    df.attrs["Me_rel_difference"] = me_err
    return df


def run_bench(quick: bool = False, reference: str | None = None,
              repeat: int | None = None) -> dict[str, pd.DataFrame]:
    """Run the benchmarks and print their tables (the ratios to baselines follow from
    :func:`kinetostatics.bench.speed.run_speed`; ``repeat``: the runs of every timing,
    None: each one's own, 3 or 7)."""
    sizes = (1_000, 10_000) if quick else (1_000, 100_000, 1_000_000)
    with frozen_heap():
        out = {"kinematics": bench_kinematics(sizes, repeat=repeat or 3)}
        out["reactions"] = bench_reactions(10_000 if quick else 1_000_000,
                                           repeat=repeat or 3)
        out["reference"] = bench_against_reference(reference or find_reference(),
                                                   20_001 if quick else 200_001,
                                                   repeat=repeat or 7)
    pd.set_option("display.width", 160)
    for name, df in out.items():
        print(f"\n== {name} ==")
        print(df.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    print(f"Me vs reference fourbar_dyad: max relative difference "
          f"{out['reference'].attrs['Me_rel_difference']:.2e}")
    return out
