"""A design search's files: front.csv, designs/*.toml, summary.json, front.png and the
drawing of the compromise (compromise.png), written whole or not at all
(:func:`~kinetostatics.model.outputs.staged_folder`)."""

from __future__ import annotations

import shutil
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..model.outputs import staged_folder
from ..results.output import write_summary
from .plots import draw_design, plot_front
from .tomltext import toml_text

DESIGN_FILES = ("front.csv", "summary.json", "front.png", "compromise.png")


def write_result(result, out: Path, *, dpi: float = 150) -> list[Path]:
    """Write ``result`` (a :class:`~kinetostatics.design.result.DesignResult`) into
    ``out``; the paths written (the designs' folder once). An earlier run's files there
    are replaced as a whole (its designs/ folder too) once every new file is complete;
    a run that fails leaves them as they were."""
    with staged_folder(out, DESIGN_FILES) as stage:
        _write_files(result, stage.path, dpi)
        old = out / "designs"
        if old.is_dir():            # (the earlier run's designs: replaced by the new)
            shutil.rmtree(old)
    return [out / "front.csv", out / "designs", out / "summary.json", out / "front.png",
            out / "compromise.png"]


def _write_files(result, folder: Path, dpi: float) -> None:
    (folder / "designs").mkdir()
    front = result.front
    title = result.spec.scene.title
    for i, (scene, rel) in enumerate(zip(result.scenes, front["scene"], strict=True)):
        head = (f"Design {i} of the front of {title!r} (python -m kinetostatics design).\n"
                + "; ".join(f"{n} = {float(front.at[i, n])!r}" for n in front.columns[:-1]))
        (folder / rel).write_text(toml_text(scene, head), encoding="utf-8")
    front.to_csv(folder / "front.csv", index=False, float_format="%.17g")
    summary = dict(result.summary)
    summary["compromise"] = {"design": result.compromise,
                             "scene": result.scene_file(result.compromise),
                             "rule": "nearest the ideal point, the objectives normalised "
                                     "by the front's ideal and nadir"}
    write_summary(folder / "summary.json", summary)
    fig = Figure(figsize=(6.4, 4.6), layout="constrained")
    FigureCanvasAgg(fig)
    plot_front(result, fig.add_subplot())
    fig.savefig(folder / "front.png", dpi=dpi)
    draw_design(result, result.compromise).savefig(folder / "compromise.png", dpi=dpi)
