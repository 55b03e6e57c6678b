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
    g.add_argument("--pdf", action="store_true",
                   help="also write DIR/handouts/<id>.pdf (matplotlib, no browser)")
    g.add_argument("--jobs", type=int, default=1,
                   help="students prepared at the same time, in processes (default 1)")
    g.set_defaults(func=_cmd_generate)
    r = es.add_parser("grade", help="grade notebooks, CSV answer forms and JSON dicts",
                      description="Grade the submissions of a class folder: notebooks "
                                  "run in a clean kernel first, CSV forms and JSON dicts "
                                  "are read; ids come from the submissions themselves.")
    r.add_argument("dir", metavar="DIR", help="the class folder written by 'generate'")
    r.add_argument("submissions", nargs="+", metavar="SUBMISSION",
                   help="notebooks, CSV or JSON files, or folders of them")
    r.add_argument("--out", metavar="grades.csv",
                   help="write one row per student and question (with the tolerance), "
                        "one per submission not graded, and beside it "
                        "grades_students.csv (one row per student)")
    r.add_argument("--no-execute", action="store_true",
                   help="read the saved answer cells without running the notebooks")
    r.add_argument("--timeout", type=float, default=60.0,
                   help="seconds allowed per notebook cell (default 60)")
    _limit_options(r)
    r.add_argument("--jobs", type=int,
                   help="notebooks run at the same time, in processes (default: cores, "
                        "at most 4)")
    r.add_argument("--on-error", choices=["saved", "zero"], default="saved",
                   help="a notebook that does not run: graded on its answers cell as "
                        "saved, flagged (default), or 0 ('zero')")
    r.add_argument("--unit-slip-credit", type=float, default=0.0, metavar="0..1",
                   help="credit of an answer that is the key times a unit factor "
                        "(N mm for N m, rad for deg, a flipped sign...; default 0)")
    r.add_argument("--prefer", action="append", default=[], metavar="PATH",
                   help="when a student handed in several files, keep this one (a file "
                        "or a folder; repeatable); default: the newest readable one")
    r.add_argument("--lms", nargs=2, metavar=("moodle|canvas", "FILE.csv"),
                   help="write the per-student totals for a gradebook import")
    r.set_defaults(func=_cmd_grade)


def _limit_options(r) -> None:
    from .sandbox import Limits

    lim = Limits()
    r.add_argument("--unsandboxed", action="store_true",
                   help="run the notebooks as you, with no isolation (only where bubblewrap "
                        "cannot run; every run and grades_students.csv say so)")
    for name, kind, what in (
            ("memory_mb", int, "address space of each kernel process, MB"),
            ("notebook_seconds", float, "wall time of a whole notebook, s"),
            ("cpu_seconds", int, "CPU seconds of each kernel process"),
            ("processes", int, "processes and threads of a kernel"),
            ("file_mb", int, "size of a file a notebook writes, MB"),
            ("output_mb", float, "what a notebook prints and displays, MB")):
        r.add_argument("--" + name.replace("_", "-"), type=kind, default=getattr(lim, name),
                       help=f"sandbox limit: {what} (default {getattr(lim, name):g})")


def _limits(args):
    from .sandbox import Limits

    return Limits(memory_mb=args.memory_mb, cell_seconds=args.timeout,
                  notebook_seconds=args.notebook_seconds, cpu_seconds=args.cpu_seconds,
                  processes=args.processes, file_mb=args.file_mb, output_mb=args.output_mb)


def _cmd_list(args) -> int:
    from .library import list_exercises

    for row in list_exercises().itertuples():
        print(f"{row.name:22s}{row.title}")
        print(f"{'':22s}asks: {row.questions}")
    return 0


def _cmd_generate(args) -> int:
    from .classroom import generate_class

    res = generate_class(args.exercise, args.students, args.out, seed=args.seed,
                         pdf=args.pdf, jobs=args.jobs)
    for w in res["warnings"]:
        print(f"warning: {w}")
    d = Path(res["folder"])
    ids = res["students"]
    n = len(ids)
    print(f"{res['exercise']}: {n} students: {', '.join(ids[:12])}"
          + (f", ... ({n - 12} more)" if n > 12 else ""))
    print(f"seed: {res['seed_source']}, kept in {d / 'teacher.json'} (keep that file, "
          "key.csv and variants.csv away from the students)")
    pdf = " and <id>.pdf" if args.pdf else ""
    print(f"for the students: {d / 'students'}/<id>.ipynb ({n} notebooks), "
          f"{d / 'handouts'}/<id>.html{pdf} ({n} pages)")
    print(f"for the teacher: {d / 'key.csv'}, {d / 'variants.csv'}, "
          f"{d / 'answer_form.csv'}, {d / 'teacher.json'}")
    print(f"grade with: python -m kinetostatics exercises grade {d} SUBMISSIONS...")
    return 0


def _problems(rep) -> list[str]:
    """The console's ``!!`` lines: broken, unknown, conflicting, duplicated, flagged
    and missing submissions."""
    loud = []
    for b in rep.broken:
        who = f"{b['student']} graded 0" if b["student"] else "no known id: not graded"
        loud.append(f"BROKEN  {b['file']}: {b['reason']} ({who})")
    for u in rep.unknown:
        loud.append(f"UNKNOWN student id {u['student']!r} in {u['file']}: not in the "
                    "class list, not graded (on record in the grades)")
    for c in rep.conflicts:
        loud.append(f"ID CONFLICT in {c['file']}: ids {', '.join(map(repr, c['ids']))}; "
                    f"graded as {c['graded_as']!r}")
    for dup in rep.duplicates:
        loud.append(f"DUPLICATE {dup['student']}: {' and '.join(dup['files'])}; kept "
                    f"{dup['kept']} ({dup['why']})")
    for s, fl in rep.flags.items():
        for f in fl:
            if f == "no submission" or f.endswith("(graded 0)") or " submissions: kept " in f:
                continue                    # said above: MISSING, BROKEN, DUPLICATE
            tag = "COPY?" if f.startswith(("copy?", "same answers")) else "FLAG"
            loud.append(f"{tag} {s}: {f}")
    if rep.missing:
        loud.append(f"MISSING {len(rep.missing)} student(s) handed in nothing (graded 0): "
                    f"{', '.join(rep.missing)}")
    return loud


def _cmd_grade(args) -> int:
    from ..model.errors import WorkbenchError
    from ..model.outputs import staged_folder
    from .classroom import grade_class
    from .lms import LMS, write_lms
    from .questions import TOLERANCE_RULE

    if not 0.0 <= args.unit_slip_credit <= 1.0:
        raise WorkbenchError(f"--unit-slip-credit {args.unit_slip_credit:g}: give a number "
                             "in 0..1")
    if args.lms and args.lms[0].lower() not in LMS:
        raise WorkbenchError(f"--lms {args.lms[0]!r}: give one of {', '.join(LMS)}")
    t = time.perf_counter()
    hide = [p for p in (args.out, args.lms[1] if args.lms else None) if p]
    rep = grade_class(args.dir, args.submissions, execute=not args.no_execute,
                      jobs=args.jobs, on_error=args.on_error,
                      unit_slip_credit=args.unit_slip_credit, prefer=args.prefer,
                      limits=_limits(args), unsandboxed=args.unsandboxed,
                      hide=[Path(p).resolve().parent / Path(p).name for p in hide])
    dt = time.perf_counter() - t
    if rep.sandbox.startswith("none"):
        print("!! WARNING: --unsandboxed: the notebooks ran as you, with your files, your "
              "network and your processes in their reach (grades_students.csv says so "
              "on every row)")
    elif rep.sandbox:
        print(f"sandbox: {rep.sandbox}")
    credit = f"{100 * args.unit_slip_credit:g} %"
    print(f"tolerance: {TOLERANCE_RULE} A unit slip (the key times a unit factor: N mm "
          f"for N m, rad for deg, rpm for rad/s) or a sign slip (the sign flipped) earns "
          f"{credit} credit.")
    how = ("read as saved" if args.no_execute else
           "run in a fresh kernel, no sandbox" if args.unsandboxed else
           "run in a fresh kernel, each in its sandbox")
    n = len({x["file"] for x in rep.submissions} | {b["file"] for b in rep.broken})
    print(f"read {n} submission(s) in {dt:.1f} s (notebooks {how}; one that does not run "
          f"is graded {'0' if args.on_error == 'zero' else 'on its answers cell as saved'})")
    loud = _problems(rep)
    for line in loud:
        print("!! " + line)
    sc = rep.scores
    print(f"{'student':16s} {'score':>7s} {'points':>9s}  failed")
    for row in sc.to_dict("records"):
        if row["total"]:
            print(f"{row['student']:16s} {row['score %']:6.1f}% "
                  f"{row['points']:4g}/{row['total']:<4d}  {row['failed']}")
    sc_class = sc[sc["total"] > 0]
    print(f"class: {len(sc_class)} students, mean {sc_class['score %'].mean():.1f} %")
    if loud:
        print(f"!! {len(loud)} problem(s) listed above (lines starting with !!)")
    if args.out:
        out = Path(args.out)
        summary = out.with_name(out.stem + "_students.csv")
        with staged_folder(out.parent) as stage:      # both files, or neither
            rep.graded.to_csv(stage.file(out.name), index=False)
            sc.to_csv(stage.file(summary.name), index=False)
        print(f"wrote {out} ({len(rep.graded)} rows: one per student and question, one per "
              f"submission not graded) and {summary} ({len(sc)} rows: one per student, one "
              "per unknown id or unreadable file)")
    if args.lms:
        p = write_lms(sc_class, args.lms[0], args.lms[1], rep.exercise or "exercise")
        print(f"wrote {p} ({args.lms[0].lower()} gradebook import, {len(sc_class)} students, "
              "score in %)")
    return 0
