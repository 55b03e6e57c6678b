"""The command line of the kinetostatics workbench.

Every user mistake prints one line ``error: ...`` on stderr and exits with code 2.
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings
from pathlib import Path

from . import scene_path
from .model.errors import WorkbenchError


def _cmd_solve(args) -> int:
    from .solver.pipeline import solve
    sol = solve(scene_path(args.scene))
    if args.out:
        for p in sol.to_csv(args.out):
            print(p)
    if args.plot:
        from .plot.cli import write_pictures
        for p in write_pictures(sol, args.plot, args.plot_at):
            print(p)
    if args.json or not args.out:
        print(json.dumps(sol.summary(), indent=2))
    return 0


def _cmd_demo(args) -> int:
    from .plot.cli import run_demo
    return run_demo(args)


def _cmd_structure(args) -> int:
    from .model.scene import load_scene
    from .solver.structure import analyse
    for line in analyse(load_scene(scene_path(args.scene))).describe():
        print(line)
    return 0


def _cmd_motion(args) -> int:
    from .motion.scene import simulate_motion
    res = simulate_motion(scene_path(args.scene))
    if args.json:
        print(json.dumps(res.to_json()))
    else:
        for k, v in res.summary.items():
            print(f"{k}: {v}")
        if args.out:
            Path(args.out).parent.mkdir(parents=True, exist_ok=True)
            res.motion.to_csv(args.out, index=False, float_format="%.17g")
            print(f"wrote {args.out}")
    return 0


def _cmd_cam(args) -> int:
    from .cams import solve_cam
    res = solve_cam(scene_path(args.scene))
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        for name in ("motion", "geometry", "forces"):
            getattr(res, name).to_csv(out / f"{name}.csv", index=False, float_format="%.17g")
        (out / "summary.json").write_text(json.dumps(res.summary, indent=2) + "\n")
    print(json.dumps(res.summary, indent=2))
    return 0


def _cmd_bench(args) -> int:
    from .bench import run_bench
    run_bench(quick=args.quick, reference=args.reference)
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python -m kinetostatics",
                                description="Kinetostatics of planar mechanisms.")
    sub = p.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="solve a scene; write the tables as CSV")
    s.add_argument("scene", help="scene file (.toml)")
    s.add_argument("--out", help="folder for reactions.csv, driver.csv, ... and summary.json")
    s.add_argument("--json", action="store_true", help="print the summary as JSON")
    s.add_argument("--plot", metavar="DIR", help="folder for the pictures (PNG): overview, "
                   "Me, polar diagrams, mechanism with loads, plans, force polygons")
    s.add_argument("--plot-at", metavar="POS", type=float, nargs="+",
                   help="driver positions (deg, or m) of those pictures (default: max |Me|)")
    s.set_defaults(func=_cmd_solve)
    d = sub.add_parser("demo", help="solve a scene; write its tables and pictures")
    d.add_argument("scene", nargs="?", help="bundled scene name or scene file")
    d.add_argument("--example", default="four_bar", help="bundled scene (default four_bar)")
    d.add_argument("--out", default="demo-out", help="output folder (default demo-out)")
    d.set_defaults(func=_cmd_demo)
    t = sub.add_parser("structure", help="print the driver and the dyads of a scene")
    t.add_argument("scene")
    t.set_defaults(func=_cmd_structure)
    b = sub.add_parser("bench", help="positions per second and error against closed forms")
    b.add_argument("--quick", action="store_true", help="small sizes only")
    b.add_argument("--reference", help="path of reference_fourbar.py to time side by side")
    b.set_defaults(func=_cmd_bench)
    m = sub.add_parser("motion", help="motion under forces of a scene with [motion]")
    m.add_argument("scene")
    m.add_argument("--json", action="store_true", help="print summary and motion table as JSON")
    m.add_argument("--out", help="CSV file for the motion table")
    m.set_defaults(func=_cmd_motion)
    c = sub.add_parser("cam", help="solve a [cam] scene (docs/cam-scenes.md)")
    c.add_argument("scene")
    c.add_argument("--out", help="folder for motion.csv, geometry.csv, forces.csv, summary.json")
    c.set_defaults(func=_cmd_cam)
    _extra_commands(sub)
    from .teaching.cli import add_commands as add_exercise_commands
    add_exercise_commands(sub)
    return p


def _extra_commands(sub) -> None:
    """Commands of the optional modules (simulation cross-check, motion)."""
    try:
        from .simulation.cli import add_commands
    except ImportError:
        return
    add_commands(sub)


def _showwarning(message, category, filename, lineno, file=None, line=None) -> None:
    """Python warnings (unit slips, negative concentrated masses, ...) as one line each."""
    print(f"warning: {' '.join(str(message).split())}", file=sys.stderr)


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            warnings.showwarning = _showwarning
            return args.func(args)
    except WorkbenchError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
