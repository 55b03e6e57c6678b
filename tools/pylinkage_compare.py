"""design beside pylinkage, at equal evaluations (docs/design.md, "Beside pylinkage").

pylinkage's optimisation example: a crank-rocker, crank 1, coupler 3.5, rocker 3, frame 4
(A = (0, 0), D = (4, 0)); maximise the horizontal stroke of the coupler-rocker pin C;
the three link lengths free within pylinkage's default bounds (generate_bounds: a fifth to
five times each). pylinkage runs its particle swarm (kinematics only, an unbuildable
candidate scored -inf); design runs NSGA-II on the same mechanism as a scene (with
masses: the same kinematics, and Me), the same bounds and the same number of
evaluations, then once more with Me_peak and the transmission angle as further axes.

pylinkage is not a dependency of the workbench: ``pip install pylinkage`` to run this.
Usage: python tools/pylinkage_compare.py [--particles 40] [--iterations 25]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import kinetostatics as ks


def four_bar_scene() -> dict:
    """pylinkage's crank-rocker as a scene (links of 1 kg per metre, centres mid-link)."""
    links = (("crank", "A", "B", 1.0, 0.1), ("coupler", "B", "C", 3.5, 3.6),
             ("rocker", "D", "C", 3.0, 2.25))         # name, pins, length (m), inertia
    pins = (("A", "ground", "crank"), ("B", "crank", "coupler"), ("C", "coupler", "rocker"),
            ("D", "ground", "rocker"))
    return {
        "title": "pylinkage's crank-rocker (crank 1, coupler 3.5, rocker 3, frame 4)",
        "gravity": [0.0, -9.81], "ground": {"A": [0.0, 0.0], "D": [4.0, 0.0]},
        "driver": {"body": "crank", "joint": "A", "speed": 10.0, "start": 0.0, "stop": 360.0,
                   "count": 361},
        "bodies": [{"name": n, "mass": length, "inertia": i, "cog": [length / 2, 0.0],
                    "points": {p: [0.0, 0.0], q: [length, 0.0]}}
                   for n, p, q, length, i in links],
        "joints": [{"name": j, "kind": "R", "bodies": [b1, b2]} for j, b1, b2 in pins],
        "near": {"C": [3.5, 2.5]},
    }


def run_pylinkage(particles: int, iterations: int) -> dict:
    from pylinkage.mechanism import fourbar
    from pylinkage.optimization import (
        generate_bounds,
        kinematic_maximization,
        particle_swarm_optimization,
    )
    linkage = fourbar(crank=1.0, coupler=3.5, rocker=3.0, ground=4.0)
    calls = [0]

    @kinematic_maximization
    def stroke(loci, **_):
        # the coupler-rocker pin C: of the loci's joints (their order is not fixed), the
        # one whose distance from A varies (the ground pins stand, B keeps the crank's)
        xy = np.array(loci, dtype=float)                    # (frames, joints, 2)
        j = int(np.argmax(np.ptp(np.hypot(xy[:, :, 0], xy[:, :, 1]), axis=0)))
        return float(np.ptp(xy[:, j, 0]))

    def counted(*args, **kwargs):
        calls[0] += 1
        return stroke(*args, **kwargs)
    bounds = generate_bounds(list(linkage.get_constraints()))
    t = time.perf_counter()
    best = particle_swarm_optimization(counted, linkage, bounds=bounds,
                                       n_particles=particles, iterations=iterations,
                                       verbose=False)
    seconds = time.perf_counter() - t
    member = best[0]
    return {"stroke": float(member.score), "lengths": list(member.dimensions),
            "evaluations": calls[0], "time_s": seconds,
            "bounds": [list(map(float, b)) for b in bounds]}


def run_design(evaluations: int, bounds, objectives, constraints) -> dict:
    raw = four_bar_scene()
    names = ["bodies.crank.points.B.0", "bodies.coupler.points.C.0",
             "bodies.rocker.points.C.0"]
    raw["design"] = {"seed": 1, "objectives": objectives, "constraints": constraints,
                     "variables": {n: [lo, hi] for n, lo, hi in zip(names, *bounds,
                                                                     strict=True)},
                     "follow": {n.replace("points.B", "cog").replace("points.C", "cog"): n
                                for n in names}}
    population = 40
    t = time.perf_counter()
    res = ks.design(raw, population=population, generations=max(1, evaluations // population))
    seconds = time.perf_counter() - t
    return {"result": res, "time_s": seconds}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--particles", type=int, default=40)
    p.add_argument("--iterations", type=int, default=25)
    a = p.parse_args()
    pyl = run_pylinkage(a.particles, a.iterations)
    print(f"pylinkage PSO: stroke {pyl['stroke']:.4f}, lengths {np.round(pyl['lengths'], 4)}"
          f", {pyl['evaluations']} evaluations, {pyl['time_s']:.2f} s; bounds {pyl['bounds']}")
    lo, hi = pyl["bounds"]
    one = run_design(pyl["evaluations"], (lo, hi), ["max stroke:C"], ["full_turn"])
    r = one["result"]
    best = r.front.iloc[0]
    sol = r.solve(0)
    s = sol.summary()
    print(f"design NSGA-II: stroke {best['stroke:C']:.4f}, lengths "
          f"{np.round(r.X[0], 4)}, {r.summary['evaluations']} evaluations, "
          f"{one['time_s']:.2f} s; Me peak {np.max(np.abs(sol.Me)):.1f} N m, "
          f"transmission min {s['transmission_angle_min']:.1f} deg")
    from kinetostatics.design import evaluate
    ev = evaluate(r.spec, np.array([pyl["lengths"]]))
    print("pylinkage's best judged by design: "
          + ("feasible" if ev.feasible[0] else f"infeasible ({ev.reasons[0]})")
          + (f", stroke {ev.values[0, 0]:.4f}" if ev.solved[0] else ""))
    two = run_design(pyl["evaluations"], (lo, hi), ["max stroke:C", "min Me_peak"],
                     ["transmission_min >= 30", "full_turn"])
    f = two["result"].front
    print(f"design with Me and transmission >= 30 deg: {len(f)} designs, stroke "
          f"{f['stroke:C'].min():.3f}..{f['stroke:C'].max():.3f}, Me peak "
          f"{f.Me_peak.min():.1f}..{f.Me_peak.max():.1f} N m, {two['time_s']:.2f} s")


if __name__ == "__main__":
    main()
