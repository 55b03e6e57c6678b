"""The command line of the kinetostatics workbench.

Every user mistake prints one line ``error: ...`` on stderr and exits with code 2.
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings

from . import scene_path
from .common.cli import (
    OneLineParser,
    Terminated,
    add_dpi_option,
    add_memory_option,
    failure_code,
    print_warning,
    stopped_cleanly,
)
from .model.errors import WorkbenchError


def _cmd_solve(args) -> int:
    from .model.outputs import failure_noted
    from .results import Solution
    with failure_noted(args.out, Solution.OUTPUT_KIND, "solve"):
        return _solve(args)


def _solve(args) -> int:
    from .results import solve
    from .results.output import summary_with_units
    from .results.text import summary_text
    if args.out and args.format == "parquet":
        from .results.output import parquet_available
        parquet_available()
    if args.out and not args.plot:
        # a sweep too long to hold is streamed: its tables written block by block
        from .results.streamed import open_solve
        sol = open_solve(scene_path(args.scene))
    else:
        sol = solve(scene_path(args.scene))
    summary = summary_with_units(sol.summary(), sol.scene.units, sol.scene.warnings,
                                 "deg" if sol.scene.driver.kind == "R" else "m")
    written = []
    if args.out:
        def announce(line: str) -> None:
            print(f"warning: {line}", file=sys.stderr, flush=True)
        written += sol.write(args.out, args.format, announce, summary)
    if args.plot:
        from .plot.cli import write_pictures
        written += write_pictures(sol, args.plot, args.plot_at, dpi=args.dpi)
    if args.json:               # stdout is the JSON alone (| jq works)
        print(json.dumps(summary, indent=2))
        return 0
    for p in written:
        print(p)
    print(summary_text(summary))
    return 0


def _cmd_demo(args) -> int:
    if args.scene and args.example:
        raise WorkbenchError(f"demo: give a scene ({args.scene}) or --example "
                             f"{args.example}, not both")
    args.example = args.example or "four_bar"
    from .plot.cli import run_demo
    return run_demo(args)


def _cmd_structure(args) -> int:
    from .model.scene import load_scene
    from .solver.structure import analyse
    for line in analyse(load_scene(scene_path(args.scene))).describe():
        print(line)
    return 0


def _cmd_motion(args) -> int:
    from .motion.scene import MOTION_UNITS, simulate_motion
    res = simulate_motion(scene_path(args.scene))
    if args.json:
        print(json.dumps(res.to_json()))
    else:
        for k, v in res.summary.items():     # each number with its unit (SI)
            unit = MOTION_UNITS.get(k, "1")
            # six digits, as solve's text (--json keeps every digit)
            shown = f"{v:.6g}" if isinstance(v, float) else v
            print(f"{k}: {shown}" + ("" if unit == "1" or isinstance(v, bool) else f" {unit}"))
        print("warnings: " + ("; ".join(res.warnings) or "none"))
        if not res.units.is_default:
            print(f"scene units: {res.units.describe()} (the numbers above are SI: rad/s, "
                  "s, kg m^2)")
        if args.out:
            from .model.outputs import atomic_file
            with atomic_file(args.out) as tmp:
                res.motion.to_csv(tmp, index=False, float_format="%.17g")
            print(f"wrote {args.out}")
    return 0


CAM_FILES = ("motion.csv", "geometry.csv", "forces.csv", "summary.json")


def _cmd_cam(args) -> int:
    from .cams import solve_cam
    from .cams.units import cam_summary_units
    from .model.outputs import failure_noted, staged_folder
    from .model.units import labelled
    from .results.output import write_summary
    with failure_noted(args.out, CAM_FILES, "cam run"):
        res = solve_cam(scene_path(args.scene))
        summary = labelled(res.summary, res.scene.units, cam_summary_units(res.summary),
                           res.scene.warnings)
        if args.out:
            with staged_folder(args.out, CAM_FILES) as stage:
                for name in ("motion", "geometry", "forces"):
                    getattr(res, name).to_csv(stage.file(f"{name}.csv"), index=False,
                                              float_format="%.17g")
                write_summary(stage.file("summary.json"), summary)
    print(json.dumps(summary, indent=2))
    return 0


def _cmd_bench(args) -> int:
    if args.tables:
        from .bench.tables import run_table_bench
        run_table_bench(quick=args.quick, repeat=args.repeat or 3)
        return 0
    from .bench.accuracy import run_bench
    from .bench.speed import run_speed
    run_bench(quick=args.quick, reference=args.reference, repeat=args.repeat)
    run_speed(quick=args.quick, reference=args.reference, repeat=args.repeat)
    return 0


SOLVE_COST = """\
What count costs: every position is one row of driver.csv and frame.csv, one row per
joint of reactions.csv, per named point and cog of kinematics.csv, per body of
bodies.csv and per dyad of dyads.csv. The bundled four_bar (4 joints, 11 points,
3 bodies) writes about 2.2 kB of CSV per position. Measured on the 2-core development
machine (busy): count = 1e5 writes 220 MB in about 2 s (1.4-1.7 s of CPU, the whole
command); count = 1e6 writes 2.2 GB in about 15 s (14 s of CPU) with 0.6 GB of memory.
A table of more than 1e6 rows is announced on stderr with its size and time.
--format parquet writes about 3x less and keeps the dtypes. A sweep whose solve is over
the memory budget is streamed with --out: solved and written block by block (count = 1e7:
22 GB of CSV with under 1 GB of memory; docs/limits.md)."""


# the commands of this module: their parser is built without the teaching package's
# (which loads pandas and matplotlib), so that ``solve`` starts quickly
CORE_COMMANDS = ("solve", "demo", "structure", "bench", "motion", "cam", "design")


def build_parser(extras: bool = True) -> argparse.ArgumentParser:
    p = OneLineParser(prog="python -m kinetostatics",
                      description="Kinetostatics of planar mechanisms.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=OneLineParser)
    s = sub.add_parser("solve", help="solve a scene; write the tables as CSV",
                       epilog=SOLVE_COST, formatter_class=argparse.RawDescriptionHelpFormatter)
    s.add_argument("scene", help="scene file (.toml)")
    s.add_argument("--out", help="folder for reactions.csv, driver.csv, ... and summary.json")
    s.add_argument("--format", choices=("csv", "parquet"), default="csv",
                   help="table files for --out: csv (17 significant digits, the default) or "
                   "parquet (needs pyarrow: the [parquet] extra)")
    s.add_argument("--json", action="store_true", help="print the summary as JSON, and "
                   "nothing else on stdout (without it: readable lines with units)")
    s.add_argument("--plot", metavar="DIR", help="folder for the pictures (PNG): overview, "
                   "Me, polar diagrams, mechanism with loads, plans, force polygons")
    s.add_argument("--plot-at", metavar="POS", type=float, nargs="+",
                   help="driver positions (deg, or m) of those pictures (default: max |Me|)")
    add_dpi_option(s, "dots per inch of the pictures (default 150, the lecture-room size; "
                   "200 or more for a large room)")
    add_memory_option(s)
    s.set_defaults(func=_cmd_solve)
    d = sub.add_parser("demo", help="solve a scene; write its tables and pictures")
    d.add_argument("scene", nargs="?", help="bundled scene name or scene file")
    d.add_argument("--example", help="bundled scene (default four_bar); not with a scene")
    d.add_argument("--out", default="demo-out", help="output folder (default demo-out)")
    add_dpi_option(d, "dots per inch of the pictures (default 150)")
    d.set_defaults(func=_cmd_demo)
    t = sub.add_parser("structure", help="print the driver and the dyads of a scene")
    t.add_argument("scene")
    t.set_defaults(func=_cmd_structure)
    b = sub.add_parser("bench", help="positions per second and error against closed forms")
    b.add_argument("--quick", action="store_true", help="small sizes only")
    b.add_argument("--reference", help="a baseline module to time side by side "
                   "(default: the bundled kinetostatics/bench/reference.py)")
    b.add_argument("--tables", action="store_true", help="time the result tables and the "
                   "CSV writer (four-bar at 1e4, 1e5, 1e6 positions) with peak memory")
    b.add_argument("--repeat", type=int, default=None, help="runs per size for --tables "
                   "(best and median are reported; default 3), rounds of every timed row "
                   "otherwise (default: each row's own, 3 to 25)")
    b.set_defaults(func=_cmd_bench)
    m = sub.add_parser("motion", help="motion under forces of a scene with [motion]")
    m.add_argument("scene")
    m.add_argument("--json", action="store_true", help="print summary and motion table as JSON")
    m.add_argument("--out", help="CSV file for the motion table")
    add_memory_option(m)
    m.set_defaults(func=_cmd_motion)
    c = sub.add_parser("cam", help="solve a [cam] scene (docs/cam-scenes.md)")
    c.add_argument("scene")
    c.add_argument("--out", help="folder for motion.csv, geometry.csv, forces.csv, summary.json")
    add_memory_option(c)
    c.set_defaults(func=_cmd_cam)
    from .design.cli import add_command as add_design_command
    add_design_command(sub)
    if extras:
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


def main(argv: list[str] | None = None) -> int:
    words = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(extras=not (words and words[0] in CORE_COMMANDS))
    args = parser.parse_args(words)
    try:
        with warnings.catch_warnings(), stopped_cleanly():
            warnings.simplefilter("default")
            warnings.showwarning = print_warning
            return args.func(args)
    except BrokenPipeError:
        raise                   # the reader went away (| head): run_command's
    except (Terminated, WorkbenchError, OSError, MemoryError) as exc:
        return failure_code(exc)

