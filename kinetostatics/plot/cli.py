"""The pictures on the command line: ``solve SCENE --plot DIR`` and ``demo SCENE``.

The figures are made by :func:`cli_figures` (one place, so that a test can check every
figure the command line writes) and saved as PNG by :func:`write_pictures`.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from ..model.errors import WorkbenchError
from ..model.outputs import staged_folder
from ..results import Solution
from .centres import plot_instant_centres
from .curves import overview, plot_driver, plot_polar
from .freebody import dyad_free_body
from .mechanism import draw_mechanism
from .place import settle, settled_later
from .plans import acceleration_plan, velocity_plan
from .style import lecture_style, save_laid_out

__all__ = ["cli_figures", "position_unit", "run_demo", "write_pictures"]


def position_unit(sol: Solution) -> str:
    """``deg`` for a crank, ``m`` for a sliding driver: the unit of a driver position."""
    return "deg" if sol.scene.driver.kind == "R" else "m"


def _default_positions(sol: Solution) -> list[float]:
    """Where the driver's |Me| (|Fe|) is largest."""
    me = np.abs(np.asarray(sol.Me, dtype=float))
    return [float(sol.positions[int(np.nanargmax(me))])] if me.size else []


def _tag(sol: Solution, pos: float) -> str:
    return f"{pos:g}{position_unit(sol)}".replace("-", "m").replace(".", "p")


def cli_figures(sol: Solution, positions: list[float] | None = None) -> dict[str, Figure]:
    """Every figure of ``solve --plot``, by file stem.

    ``overview`` (its drawing at the first position), ``driver`` (Me or Fe over the
    cycle), ``polar_<joint>`` (the polar diagram of each joint's reaction, numbered
    positions along it), and at each position: ``mechanism_<pos>`` (with the loads and
    the reactions), ``velocity_plan_<pos>``, ``acceleration_plan_<pos>``,
    ``instant_centres_<pos>``, ``free_body_<pos>_driver`` and ``free_body_<pos>_dyad<k>``
    (the free-body diagram beside the force polygon; dyads numbered from 1, as
    ``structure`` and the summary number them).

    Parameters
    ----------
    sol : Solution
    positions : list of float, optional
        Driver positions (deg or m); default: where |Me| is largest.

    Returns
    -------
    dict of str to Figure
    """
    lo, hi = float(np.min(sol.positions)), float(np.max(sol.positions))
    positions = _default_positions(sol) if positions is None else list(positions)
    for p in positions:
        if not lo - 1e-9 <= p <= hi + 1e-9:
            raise WorkbenchError(f"--plot-at {p:g}: outside the sweep [{lo:g}, {hi:g}] "
                                 f"{position_unit(sol)}")
    with settled_later():       # each figure is settled below: its labels placed there
        figs = _drawn(sol, positions)
    # (a free-body figure comes settled, its labels placed first as it is drawn: placed by
    # settle alone, its narrow diagram was drawn with less room and a label left out)
    for p in positions:
        for d in range(len(sol.kin.dyads) + 1):
            figs[f"free_body_{_tag(sol, p)}_" + (f"dyad{d}" if d else "driver")] = \
                dyad_free_body(sol, d, p)
    # (the overview and a free-body figure come settled: settling them again drew them
    # three or four times more and changed no pixel)
    for stem, fig in figs.items():
        if stem != "overview" and not stem.startswith("free_body_"):
            settle(fig)
    return figs


def _drawn(sol: Solution, positions: list[float]) -> dict[str, Figure]:
    """The figures of :func:`cli_figures` by stem, drawn (not yet settled)."""
    figs = {"overview": overview(sol, positions[0] if positions else None),
            "driver": plot_driver(sol).figure}
    for j in sol.scene.joints:
        figs[f"polar_{j}"] = plot_polar(sol, j).figure
    for p in positions:
        t = _tag(sol, p)
        figs[f"mechanism_{t}"] = draw_mechanism(sol, p, forces=True, loads=True).figure
        figs[f"velocity_plan_{t}"] = velocity_plan(sol, p).figure
        figs[f"acceleration_plan_{t}"] = acceleration_plan(sol, p).figure
        figs[f"instant_centres_{t}"] = plot_instant_centres(sol, p).figure
    return figs


# the pictures' files in a folder (an earlier run's not drawn again are removed when a new
# run ends well: kinetostatics.model.outputs)
PICTURES = ("overview.png", "driver.png", "polar_*.png", "mechanism_*.png",
            "velocity_plan_*.png", "acceleration_plan_*.png", "instant_centres_*.png",
            "free_body_*.png")


def write_pictures(sol: Solution, directory: str | Path,
                   positions: list[float] | None = None, dpi: float = 150) -> list[Path]:
    """Save :func:`cli_figures`, drawn in the :func:`~kinetostatics.plot.lecture_style`
    at ``dpi``, as ``DIR/<stem>.png``, all or none (:mod:`kinetostatics.model.outputs`);
    the paths written."""
    out = Path(directory)
    if out.exists() and not out.is_dir():
        raise WorkbenchError(f"--plot {out}: is a file, not a folder")
    with staged_folder(out, PICTURES) as stage:
        stems = _save_pictures(sol, stage.path, positions, dpi)
    return [out / f"{stem}.png" for stem in stems]


def _save_pictures(sol: Solution, folder: Path, positions: list[float] | None,
                   dpi: float) -> list[str]:
    """Draw and save the pictures into ``folder``; their stems."""
    stems = []
    with lecture_style(dpi):
        for stem, fig in cli_figures(sol, positions).items():
            save_laid_out(fig, folder / f"{stem}.png", dpi=dpi)
            plt.close(fig)
            stems.append(stem)
    return stems


def _refuse_cam_scene(path: Path) -> None:
    """A [cam] scene is for the ``cam`` command: say so instead of a key error."""
    from ..model.tomlio import read_source
    try:
        raw = read_source(path)
    except WorkbenchError:
        return          # the solver reports the problem
    if isinstance(raw, dict) and "cam" in raw and "driver" not in raw:
        raise WorkbenchError(f"{path.stem} is a cam scene: run "
                             f"python -m kinetostatics cam {path.stem}")


def run_demo(args) -> int:
    """``demo SCENE``: solve a scene (a bundled name or a file), write its tables and
    pictures to ``--out``, print the key numbers with their units."""
    import matplotlib
    matplotlib.use("Agg")
    from ..model.examples import scene_path
    from ..results import solve
    from ..results.output import summary_with_units
    from ..results.text import summary_text
    path = scene_path(args.scene or args.example)
    _refuse_cam_scene(path)
    sol = solve(path)
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise WorkbenchError(f"--out {out}: is a file, not a folder")
    # the tables and the pictures, one run: all in place, or none
    at = _default_positions(sol)
    with staged_folder(out, Solution.OUTPUT_KIND + PICTURES) as stage:
        written = sol.to_csv(stage.path)
        written += write_pictures(sol, stage.path, at, dpi=getattr(args, "dpi", 150))
    written = [out / p.name for p in written]
    pu = position_unit(sol)
    q = sol.driver_quantity
    print(summary_text(summary_with_units(sol.summary(), sol.scene.units,
                                          sol.scene.warnings, pu)))
    if at:
        print(f"  pictures at {'φ' if pu == 'deg' else 's'} = {at[0]:g} {pu}, where "
              f"|{q}| is largest (the overview's drawing too)")
    print("wrote: " + ", ".join(str(p) for p in written))
    return 0
