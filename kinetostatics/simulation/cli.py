"""The ``crosscheck`` command: pymunk against kinetostatics (hooked into ``cli.py``).

``python -m kinetostatics crosscheck SCENE`` simulates a scene with a constant-speed
driver and prints, per joint and for the driving moment (force), the largest
simulated and computed values and the relative error; ``--json`` prints one JSON
object (``dt``, ``iterations``, ``seconds_per_revolution``, ``max_error``,
``errors``, ``derived_errors``...). A run that diverged prints one line ``error: the
simulation diverged at ...`` and exits with code 2. ``--study`` sweeps the time step
and the solver iterations and prints wall time per simulated revolution against
error, with the observed order (diverged settings listed as such, out of the fit);
its runs go to one process per core (each times itself), or one after another with
``--serial``.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path

from ..common.jsontext import plain
from ..model.outputs import atomic_file

__all__ = ["add_commands"]


def _error(msg: str) -> Exception:
    """A :class:`~kinetostatics.simulation.SimulationError` (pymunk is imported only
    when a command runs, not when the parser is built)."""
    from .errors import SimulationError
    return SimulationError(msg)


def add_commands(sub) -> None:
    """Add the ``crosscheck`` subcommand to an argparse subparsers object."""
    from ..common.cli import add_dpi_option  # the --dpi of every command that draws
    c = sub.add_parser(
        "crosscheck", help="simulate a scene in pymunk and compare with kinetostatics",
        description="Simulate a mechanism scene in pymunk at its driver's constant speed "
                    "and compare the joint reactions and the driving moment with "
                    "kinetostatics at the simulated positions.")
    c.add_argument("scene", help="scene file (.toml) or the name of a bundled example")
    c.add_argument("--dt", type=float, help="time step in s (default: --steps)")
    c.add_argument("--steps", type=int,
                   help="steps per revolution (sliding driver: per sweep); default: chosen "
                        "for the scene (its fastest body and smallest link, then the dt^2 "
                        "law towards an error of 1e-5)")
    c.add_argument("--iterations", type=int,
                   help="solver iterations (default: 30, doubled until the readings settle; "
                        "a count whose run diverged is passed over)")
    c.add_argument("--revolutions", type=float, default=2.0,
                   help="driver turns simulated (default 2; the first is not compared)")
    c.add_argument("--samples", type=int, default=360,
                   help="readings per revolution (default 360)")
    c.add_argument("--speed", type=float,
                   help="run at this driver speed instead (rad/s or m/s)")
    c.add_argument("--error-bias", type=float, default=0.0,
                   help="joint error_bias (default 0; pymunk's own default is 0.9**60)")
    for switch, text in (
            ("--no-ballast", "never build the driver's side heavy for the solver (by default "
                             "a run that diverges with the driver solved last is run once "
                             "more with that ballast before the driver is solved first)"),
            ("--public", "only pymunk's public API in the stepping loop (slower)"),
            ("--json", "print one JSON object")):
        c.add_argument(switch, action="store_true", help=text)
    c.add_argument("--rows", metavar="CSV", help="write the per-position comparison as CSV")
    c.add_argument("--plot", metavar="PNG", help="write the comparison (or study) picture")
    add_dpi_option(c, "dots per inch of the --plot picture (default 150)")
    c.add_argument("--study", action="store_true",
                   help="sweep dt and iterations: wall time per revolution against error")
    c.add_argument("--study-steps", metavar="LIST",
                   help="steps per revolution to try, e.g. 500,1000,2000 (study)")
    c.add_argument("--study-dts", metavar="LIST", help="time steps to try instead (study)")
    c.add_argument("--study-iterations", metavar="LIST", default="10,30",
                   help="iterations to try (study; default 10,30)")
    c.add_argument("--repeats", type=int, default=1,
                   help="runs per study setting; the fastest wall time is kept")
    c.add_argument("--serial", action="store_true",
                   help="run the study's settings one after another in this process "
                        "(steadier wall times; default: one process per core)")
    c.set_defaults(func=_cmd_crosscheck)


def _scene_source(name: str, speed: float | None):
    """A path or bundled example name; with ``speed``, a dict copy with that speed."""
    from .. import scene_path
    from ..model.scene import load_scene
    path = scene_path(name)
    if speed is None:
        return path
    if not math.isfinite(speed) or speed == 0.0:
        raise _error(f"--speed {speed!r}: give a non-zero speed (rad/s or m/s)")
    raw = copy.deepcopy(load_scene(path).raw)
    drv = dict(raw["driver"])
    drv.pop("speed_rpm", None)
    drv["speed"] = float(speed)
    raw["driver"] = drv
    if raw.get("title"):
        raw["title"] = f"{raw['title']} at {speed:g}"
    return raw


def _numbers(text: str | None, kind, what: str):
    if text is None:
        return None
    try:
        vals = tuple(kind(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise _error(f"{what}: {text!r} is not a comma-separated list of numbers; "
                     "write e.g. 1000,2000,4000") from None
    if not vals or any(not (v > 0) for v in vals):
        raise _error(f"{what}: give positive numbers, e.g. 1000,2000,4000")
    return vals


def _cmd_crosscheck(args) -> int:
    from .runner import crosscheck
    from .studies import study
    src = _scene_source(args.scene, args.speed)
    fast = False if args.public else None
    if args.samples < 1:
        raise _error(f"--samples {args.samples}: give at least 1")
    if args.study:
        steps = _numbers(args.study_steps, int, "--study-steps")
        dts = _numbers(args.study_dts, float, "--study-dts")
        its = _numbers(args.study_iterations, int, "--study-iterations")
        st = study(src, steps=steps, dts=dts, iterations=its, revolutions=args.revolutions,
                   samples_per_revolution=args.samples, repeats=args.repeats, fast=fast,
                   executor="serial" if args.serial else None, ballast=not args.no_ballast)
        if args.plot:
            _save(lambda: _plot_study(st), args.plot, args.dpi)
        if args.json:
            print(json.dumps(plain(st.summary(), finite=True), indent=2))
            return 0
        print(st.formatted().to_string(index=False))
        print(f"wall time: the best of {st.repeats} run(s) per setting"
              + ("" if args.serial else " (runs side by side: use --serial for steady times)"))
        for it in st.order:
            print(f"observed order ({it} iterations): {st.order_line(it)}")
        for thr in (1e-5, 1e-6):
            b = st.best(thr)
            print(f"cheapest run with error <= {thr:g}: " + (
                "none" if b is None else
                f"dt = {b['dt']:.3g} s, {b['iterations']} iterations, "
                f"{b['ms_per_revolution']:.1f} ms per revolution, error {b['max_error']:.2g}"))
        return 0
    cc = crosscheck(src, dt=args.dt, steps_per_revolution=args.steps,
                    iterations=args.iterations, revolutions=args.revolutions,
                    samples_per_revolution=args.samples, error_bias=args.error_bias,
                    fast=fast, ballast=not args.no_ballast)
    if args.rows:
        with atomic_file(args.rows) as tmp:     # the whole table, or the earlier one kept
            cc.wide().to_csv(tmp, index=False, float_format="%.17g")
    if args.plot:
        from .plots import plot_comparison
        _save(lambda: plot_comparison(cc), args.plot, args.dpi)
    if args.json:
        print(json.dumps(plain(cc.summary(), finite=True), indent=2))
        return 0
    s = cc.settings
    per = s["seconds_per_revolution"] if s["seconds_per_revolution"] is not None \
        else s["seconds_per_sweep"]
    unit = "revolution" if s["seconds_per_revolution"] is not None else "sweep"
    print(f"{cc.scene.title}: pymunk {s['pymunk']}, dt = {s['dt']:.4g} s "
          f"({s['steps_per_revolution']:.0f} steps per {unit}), {s['iterations']} iterations, "
          f"error_bias = {s['error_bias']:g}")
    print(f"  wall time {1e3 * per:.2f} ms per simulated {unit}; max error {cc.max_error:.3g}")
    table = cc.error_table()
    print(table.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    for n in cc.notes:
        print("  note: " + n)
    return 0


def _plot_study(st):
    from .plots import plot_study
    return plot_study(st)


def _save(draw, path: str, dpi: float = 150) -> None:
    """Draw the picture in the lecture style (150 dpi or ``--dpi``, text >= 10 pt) and
    write it."""
    import matplotlib
    matplotlib.use("Agg")
    from ..plot.style import lecture_style
    with lecture_style(dpi):
        fig = draw()
        with atomic_file(path) as tmp:
            fig.savefig(tmp, dpi=dpi, format=Path(path).suffix.lstrip(".").lower() or None)

