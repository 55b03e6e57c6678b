"""A design search's files: front.csv, designs/*.toml, summary.json, front.png and the
drawing of the compromise (compromise.png)."""

from __future__ import annotations

from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..results.output import write_summary
from .plots import draw_design, plot_front
from .tomltext import toml_text


def write_result(result, out: Path, *, dpi: float = 150) -> list[Path]:
    """Write ``result`` (a :class:`~kinetostatics.design.result.DesignResult`) into
    ``out``; the paths written (the designs' folder once)."""
    out.mkdir(parents=True, exist_ok=True)
    folder = out / "designs"
    folder.mkdir(exist_ok=True)
    for old in folder.glob("*.toml"):       # (a front of an earlier run)
        old.unlink()
    front = result.front
    title = result.spec.scene.title
    for i, (scene, rel) in enumerate(zip(result.scenes, front["scene"], strict=True)):
        head = (f"Design {i} of the front of {title!r} (python -m kinetostatics design).\n"
                + "; ".join(f"{n} = {float(front.at[i, n])!r}" for n in front.columns[:-1]))
        (out / rel).write_text(toml_text(scene, head), encoding="utf-8")
    written = [out / "front.csv", folder]
    front.to_csv(written[0], index=False, float_format="%.17g")
    summary = dict(result.summary)
    summary["compromise"] = {"design": result.compromise,
                             "scene": result.scene_file(result.compromise),
                             "rule": "nearest the ideal point, the objectives normalised "
                                     "by the front's ideal and nadir"}
    write_summary(out / "summary.json", summary)
    written.append(out / "summary.json")
    fig = Figure(figsize=(6.4, 4.6), layout="constrained")
    FigureCanvasAgg(fig)
    plot_front(result, fig.add_subplot())
    fig.savefig(out / "front.png", dpi=dpi)
    fig = draw_design(result, result.compromise)
    fig.savefig(out / "compromise.png", dpi=dpi)
    return [*written, out / "front.png", out / "compromise.png"]
