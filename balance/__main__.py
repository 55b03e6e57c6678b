"""Command line: ``python -m balance solve SCENE [--json] [--report FILE.html]`` and
``python -m balance examples``.

Bad input prints ``error: <one line>`` on stderr and exits with code 2, never a
traceback; every entry of a result's ``warnings`` list (and every Python warning)
prints as one ``warning: <section>: <text>`` line on stderr, the exit code unchanged.
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings
from typing import Any

from kinetostatics.common.cli import (
    OneLineParser,
    Terminated,
    add_dpi_option,
    add_memory_option,
    failure_code,
    one_line,
    run_command,
    stopped_cleanly,
)
from kinetostatics.common.jsontext import json_default

from .api import example_path, examples, results_to_dict, solve_results
from .errors import WorkbenchError
from .model.scene import SCENES
from .model.units import SI
from .report.text import result_warnings, summary_text


def _parser() -> argparse.ArgumentParser:
    p = OneLineParser(prog="python -m balance",
                      description="Rotor and resonance balancing (seed 002 ch. 3).")
    sub = p.add_subparsers(dest="command", required=True, parser_class=OneLineParser)
    s = sub.add_parser("solve", help="solve a balancing scene")
    s.add_argument("scene", help="a scene .toml file, or the name of a bundled example")
    s.add_argument("--json", action="store_true", help="print the result dict as JSON")
    s.add_argument("--report", metavar="FILE",
                   help="write a balancing report: FILE.html (pictures embedded) or FILE.pdf")
    add_dpi_option(s, "dots per inch of the report's pictures (default 150)")
    add_memory_option(s)
    sub.add_parser("examples", help="list the bundled example scenes")
    return p


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code."""
    args = _parser().parse_args(argv)
    if args.command == "examples":
        for name in examples():
            print(f"{name}\t{example_path(name)}")
        return 0
    try:
        with warnings.catch_warnings(record=True) as caught, stopped_cleanly():
            warnings.simplefilter("always")
            results = solve_results(args.scene)
            out = results_to_dict(results)
        if args.json:
            text = json.dumps(out, indent=2, allow_nan=False, default=json_default)
        else:
            speed = "rotor" in results and results["rotor"].speed_rpm is not None
            text = summary_text(out, speed) + _units_line(out)
        if args.report:
            from .report.document import write_report

            write_report(args.report, results, out, SCENES.resolve(args.scene), dpi=args.dpi)
    except (Terminated, WorkbenchError, MemoryError) as exc:
        return failure_code(exc)
    except Exception as exc:  # a bug, still one line (the contract: never a traceback)
        print(f"error: internal error, please report: {type(exc).__name__}: {one_line(exc)}",
              file=sys.stderr)
        return 1
    shown = set()
    for where, msg in result_warnings(out):
        line = one_line(msg)
        shown.add(line)
        section = where.split("[")[0].split(".")[0]
        print(f"warning: {line if line.startswith(section) else f'{where}: {line}'}",
              file=sys.stderr)
    for w in caught:
        if one_line(w.message) not in shown:
            shown.add(one_line(w.message))
            print(f"warning: {one_line(w.message)}", file=sys.stderr)
    print(text)
    return 0


def _units_line(out: dict[str, Any]) -> str:
    """The units of each section's numbers (``result_units``), when the scene was typed in
    other units than the defaults."""
    u = out.get("scene_units") or {}
    named = ", ".join(f'{k} = "{v}"' for k, v in u.items() if v != SI.get(k))
    if not named:
        return ""
    return ("\nscene units: " + named + "\n" + "\n".join(
        f"  {k}: {v}" for k, v in out.get("result_units", {}).items()))


if __name__ == "__main__":
    sys.exit(run_command(main))
