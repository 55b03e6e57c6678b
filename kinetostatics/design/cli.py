"""``python -m kinetostatics design SCENE --out DIR``: the command of the design search."""

from __future__ import annotations

import sys
import time
from concurrent.futures import ProcessPoolExecutor

PARTS_PER_JOB = 2       # parts of a generation per worker (--jobs)


def add_command(sub) -> None:
    """The ``design`` subcommand, on the subparsers ``sub`` of the workbench's CLI."""
    d = sub.add_parser("design", help="search a scene's [design] section: the front of "
                       "its objectives (docs/design.md)")
    d.add_argument("scene", help="scene file (.toml) with a [design] section, or a bundled "
                   "one (four_bar_design)")
    d.add_argument("--out", required=True, help="folder for front.csv, designs/*.toml, "
                   "summary.json, front.png and compromise.png")
    d.add_argument("--population", type=int, help="designs per generation (default: the "
                   "section's, else 100)")
    d.add_argument("--generations", type=int, help="generations (default: the section's, "
                   "else 60)")
    d.add_argument("--seed", type=int, help="the search's seed (default: the section's)")
    d.add_argument("--jobs", type=int, default=1, help="worker processes for each "
                   "generation (default 1: one stacked solve in this process)")
    d.add_argument("--quiet", action="store_true", help="no progress line")
    d.set_defaults(func=run)


def run(args) -> int:
    from ..model.errors import SceneError
    from ..model.examples import scene_path
    from ..model.outputs import failure_noted
    from .output import DESIGN_FILES
    if args.jobs < 1:
        raise SceneError(f"--jobs = {args.jobs}: give a whole number >= 1")
    t0 = time.perf_counter()
    progress = None if args.quiet else _progress
    with failure_noted(args.out, DESIGN_FILES, "design run"):
        res = _search(args, scene_path(args.scene), progress)
        if progress is not None and sys.stderr.isatty():
            print(file=sys.stderr)
        written = res.write(args.out)
    for p in written:
        print(p)
    s = res.summary
    print(f"{s['front_size']} designs on the front of {s['evaluations']} evaluated "
          f"({s['infeasible']} infeasible), hypervolume {s['hypervolume']['value']:.4g}; "
          f"{time.perf_counter() - t0:.1f} s")
    return 0


def _search(args, path, progress):
    """The search of the command's scene (through ``--jobs`` processes)."""
    from .result import design
    if args.jobs > 1:
        with ProcessPoolExecutor(args.jobs) as pool:
            res = design(path, population=args.population, generations=args.generations,
                         seed=args.seed, executor=pool, parts=PARTS_PER_JOB * args.jobs,
                         progress=progress)
    else:
        res = design(path, population=args.population, generations=args.generations,
                     seed=args.seed, progress=progress)
    return res


def _progress(generation: int, evaluations: int, front: int) -> None:
    """One line per generation on stderr (rewritten in place on a terminal)."""
    line = f"generation {generation}: {evaluations} evaluations, front {front} designs"
    if sys.stderr.isatty():
        print(f"\r{line}", end="", file=sys.stderr, flush=True)
    else:
        print(line, file=sys.stderr, flush=True)
