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
from typing import Any, NoReturn

from .api import example_path, examples, results_to_dict, solve_results
from .errors import WorkbenchError
from .report_text import field_text, result_warnings
from .scene import SCENES


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, exit 2, no usage dump
        print(f"error: {message} (see python -m balance --help)", file=sys.stderr)
        raise SystemExit(2)


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog="python -m balance",
                description="Rotor and resonance balancing (seed 002 ch. 3).")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    s = sub.add_parser("solve", help="solve a balancing scene")
    s.add_argument("scene", help="a scene .toml file, or the name of a bundled example")
    s.add_argument("--json", action="store_true", help="print the result dict as JSON")
    s.add_argument("--report", metavar="FILE",
                   help="write a balancing report: FILE.html (pictures embedded) or FILE.pdf")
    sub.add_parser("examples", help="list the bundled example scenes")
    return p


def _fmt(x: Any, unit: str = "") -> str:
    if x is None:
        return "-"
    return f"{x:.6g}{(' ' + unit) if unit else ''}"


def _report(out: dict[str, Any], speed: bool) -> str:
    lines: list[str] = []
    if "rotor" in out:
        r = out["rotor"]
        fu, mu = ("N", "N m") if speed else ("kg m", "kg m^2")
        kind = "static (one plane)" if len(r["corrections"]) == 1 else "dynamic (two planes)"
        lines.append(f"rotor: {kind} balancing")
        for c in r["corrections"]:
            lines.append(f"  plane {c['plane']} (z = {c['z']:g} m): mass {_fmt(c['mass'], 'kg')}"
                         f" at {_fmt(c['angle'], 'deg')}, radius {c['radius']:g} m, "
                         f"U = {_fmt(c['U'], 'kg m')}")
        lines.append(f"  force  before {_fmt(r['initial_force'], fu)}, "
                     f"after {_fmt(r['residual_force'], fu)}")
        lines.append(f"  moment before {_fmt(r['initial_moment'], mu)}, "
                     f"after {_fmt(r['residual_moment'], mu)} (about z = 0)")
    if "static_test" in out:
        s = out["static_test"]
        lines.append("static balancing device:")
        lines.append(f"  eccentricity {_fmt(s['eccentricity'], 'm')}, correction mass "
                     f"{_fmt(s['correction_mass'], 'kg')}")
    for t in out.get("resonance_test", []):
        lines.append(f"resonance test, plane {t['plane']}:")
        lines.append(f"  A = {_fmt(t['A'])}, phi = {_fmt(t['phi'], 'deg')}, unbalance "
                     f"{_fmt(t['unbalance'], 'kg m')}")
        where = f"at {_fmt(t['angle'], 'deg')}"
        if t["mirror_angle"] is not None:
            where += f" (or at {_fmt(t['mirror_angle'], 'deg')}: the mirror position)"
        lines.append(f"  correction mass {_fmt(t['correction_mass'], 'kg')} {where}")
        if "uncertainty" in t:
            u = t["uncertainty"]
            ang = u["angle"]
            lines.append(f"  with +-{u['dA']:g} on each amplitude: mass {_fmt(u['magnitude'][0])}"
                         f" .. {_fmt(u['magnitude'][1], 'kg')}"
                         + (f", angle {_fmt(ang[0])} .. {_fmt(ang[1], 'deg')}" if ang else ""))
    lines.extend(field_text(out))
    if "balancing" in out:
        b = out["balancing"]
        lines.append(f"mechanism balancing: {b['mechanism']}, method {b['method']}")
        lines.append(f"  procedure: {b['procedure']}")
        for c in b["counterweights"]:
            lines.append(f"  counterweight on {c['body']} about {c['about']}: mass "
                         f"{_fmt(c['mass'], 'kg')} at radius {c['radius']:g} m, angle "
                         f"{_fmt(c['angle'], 'deg')} (body frame)")
        if b.get("counter_rotating"):
            p = b["counter_rotating"]
            lines.append(f"  counter-rotating pair: two masses of {_fmt(p['mass'], 'kg')} at "
                         f"{_fmt(p['radius'], 'm')}")
        lines.append(f"  shaking force max: before {_fmt(b['shaking_force_before'], 'N')}, "
                     f"after {_fmt(b['shaking_force_after'], 'N')}")
        if "shaking_moment_before" in b:
            lines.append(f"  shaking moment max (about the crank axis): before "
                         f"{_fmt(b['shaking_moment_before'], 'N m')}, after "
                         f"{_fmt(b['shaking_moment_after'], 'N m')}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code."""
    args = _parser().parse_args(argv)
    if args.command == "examples":
        for name in examples():
            print(f"{name}\t{example_path(name)}")
        return 0
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            results = solve_results(args.scene)
            out = results_to_dict(results)
        if args.json:
            text = json.dumps(out, indent=2, allow_nan=False, default=_json_default)
        else:
            speed = "rotor" in results and results["rotor"].speed_rpm is not None
            text = _report(out, speed)
        if args.report:
            from .report import write_report

            write_report(args.report, results, out, SCENES.resolve(args.scene))
    except WorkbenchError as exc:
        print(f"error: {_one_line(exc)}", file=sys.stderr)
        return 2
    except Exception as exc:  # a bug, still one line (the contract: never a traceback)
        print(f"error: internal error, please report: {type(exc).__name__}: {_one_line(exc)}",
              file=sys.stderr)
        return 1
    shown = set()
    for where, msg in result_warnings(out):
        line = _one_line(msg)
        shown.add(line)
        section = where.split("[")[0].split(".")[0]
        print(f"warning: {line if line.startswith(section) else f'{where}: {line}'}",
              file=sys.stderr)
    for w in caught:
        if _one_line(w.message) not in shown:
            shown.add(_one_line(w.message))
            print(f"warning: {_one_line(w.message)}", file=sys.stderr)
    print(text)
    return 0


def _one_line(exc: object) -> str:
    return " ".join(str(exc).split())


def _json_default(x: Any) -> Any:
    """numpy scalars and arrays (e.g. from balance.mechanism) as plain JSON values."""
    import numpy as np

    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(f"{type(x).__name__} is not JSON serialisable")


if __name__ == "__main__":
    sys.exit(main())
