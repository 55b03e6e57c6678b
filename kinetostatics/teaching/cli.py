"""The ``exercises`` command: the teacher's loop (hooked into ``kinetostatics/cli.py``).

``python -m kinetostatics exercises list`` prints the library;
``exercises generate EXERCISE --students IDS.txt --out DIR [--seed S]`` writes a sealed
class folder; ``exercises grade DIR SUBMISSIONS... [--out grades.csv]`` grades what
came back and prints broken submissions, unknown ids and missing students loudly.
"""

from __future__ import annotations

import time
from pathlib import Path

__all__ = ["add_commands"]


def add_commands(sub) -> None:
    """Add the ``exercises`` subcommand to an argparse subparsers object."""
    e = sub.add_parser("exercises", help="exercises for a class: list, generate, grade",
                       description="The teacher's loop: sealed exercises per student, "
                                   "and the grading of what comes back.")
    es = e.add_subparsers(dest="exercises_command", required=True)
    ls = es.add_parser("list", help="the exercises of the library")
    ls.set_defaults(func=_cmd_list)
    g = es.add_parser("generate", help="a sealed notebook and a handout per student",
                      description="Write DIR/students/<id>.ipynb and DIR/handouts/<id>.html "
                                  "for the students, and DIR/key.csv, DIR/variants.csv, "
                                  "DIR/answer_form.csv, DIR/teacher.json for the teacher.")
    g.add_argument("exercise", help="a name from 'exercises list'")
    g.add_argument("--students", required=True, metavar="IDS.txt",
                   help="the class list: one student id per line")
    g.add_argument("--out", required=True, metavar="DIR", help="the class folder (new)")
    g.add_argument("--seed", type=int,
                   help="the exercise's seed (default: a random secret one, kept in "
                        "DIR/teacher.json)")
    g.set_defaults(func=_cmd_generate)
    r = es.add_parser("grade", help="grade notebooks, CSV answer forms and JSON dicts",
                      description="Grade the submissions of a class folder: notebooks "
                                  "run in a clean kernel first, CSV forms and JSON dicts "
                                  "are read; ids come from the submissions themselves.")
    r.add_argument("dir", metavar="DIR", help="the class folder written by 'generate'")
    r.add_argument("submissions", nargs="+", metavar="SUBMISSION",
                   help="notebooks, CSV or JSON files, or folders of them")
    r.add_argument("--out", metavar="grades.csv",
                   help="write one row per student and question (with the tolerance)")
    r.add_argument("--no-execute", action="store_true",
                   help="read the saved answer cells without running the notebooks")
    r.add_argument("--timeout", type=float, default=60.0,
                   help="seconds allowed per notebook cell (default 60)")
    r.add_argument("--jobs", type=int,
                   help="notebooks run at the same time (default: cores, at most 4)")
    r.set_defaults(func=_cmd_grade)


def _cmd_list(args) -> int:
    from .library import list_exercises

    for row in list_exercises().itertuples():
        print(f"{row.name:22s}{row.title}")
        print(f"{'':22s}asks: {row.questions}")
    return 0


def _cmd_generate(args) -> int:
    from .classroom import generate_class

    res = generate_class(args.exercise, args.students, args.out, seed=args.seed)
    d = Path(res["folder"])
    n = len(res["students"])
    print(f"{res['exercise']}: {n} students")
    print(f"seed: {res['seed_source']}, kept in {d / 'teacher.json'} (keep that file, "
          "key.csv and variants.csv away from the students)")
    print(f"for the students: {d / 'students'}/<id>.ipynb ({n} notebooks), "
          f"{d / 'handouts'}/<id>.html ({n} pages)")
    print(f"for the teacher: {d / 'key.csv'}, {d / 'variants.csv'}, "
          f"{d / 'answer_form.csv'}, {d / 'teacher.json'}")
    print(f"grade with: python -m kinetostatics exercises grade {d} SUBMISSIONS...")
    return 0


def _cmd_grade(args) -> int:
    from .classroom import grade_class
    from .questions import TOLERANCE_RULE

    t = time.perf_counter()
    rep = grade_class(args.dir, args.submissions, execute=not args.no_execute,
                      timeout=args.timeout, jobs=args.jobs)
    dt = time.perf_counter() - t
    print(f"tolerance: {TOLERANCE_RULE}")
    how = "read as saved" if args.no_execute else "run in a clean kernel"
    print(f"read {len(rep.submissions) + len(rep.broken)} submission(s) in {dt:.1f} s "
          f"(notebooks {how})")
    loud = []
    for b in rep.broken:
        who = f"{b['student']} graded 0" if b["student"] else "no known id: not graded"
        loud.append(f"BROKEN  {b['file']}: {b['reason']} ({who})")
    for u in rep.unknown:
        loud.append(f"UNKNOWN student id {u['student']!r} in {u['file']}: not in the "
                    "class list, not graded")
    for c in rep.conflicts:
        loud.append(f"ID CONFLICT in {c['file']}: ids {', '.join(map(repr, c['ids']))}; "
                    f"graded as {c['graded_as']!r}")
    for dup in rep.duplicates:
        loud.append(f"DUPLICATE {dup['student']}: {' and '.join(dup['files'])}; kept "
                    f"{dup['kept']}")
    if rep.missing:
        loud.append(f"MISSING {len(rep.missing)} student(s) handed in nothing (graded 0): "
                    f"{', '.join(rep.missing)}")
    for line in loud:
        print("!! " + line)
    sc = rep.scores
    print(f"{'student':16s} {'score':>7s} {'right':>7s}  failed")
    for row in sc.itertuples():
        print(f"{row.student:16s} {row._4:6.1f}% {row.passed:3d}/{row.total:<3d}  "
              f"{row.failed}")
    print(f"class: {len(sc)} students, mean {sc['score %'].mean():.1f} %")
    if loud:
        print(f"!! {len(loud)} problem(s) listed above (lines starting with !!)")
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        rep.graded.to_csv(args.out, index=False)
        print(f"wrote {args.out} ({len(rep.graded)} rows: student, question, expected, "
              "answer, unit, error, tolerance, passed, status, source)")
    return 0
