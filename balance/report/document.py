"""A balancing report for the customer file: ``python -m balance solve SCENE --report
FILE.html`` (or ``FILE.pdf``).

The HTML report is one self-contained file: the scene's data, the pictures (PNG,
embedded as base64 ``data:`` URIs: the unbalance and moment polygons of
``[rotor]``, the amplitude parallelogram or circles of each ``[[resonance_test]]``,
the reading and correction vectors of each ``[[influence]]``, the tolerances and
residuals of ``[iso]``), the corrections with
their intervals, the ISO 21940-11 check and every warning. The PDF
(:mod:`~balance.report.pdf`) is a document of A4 pages with the same sections in the
same order (the data, the results, the ISO check, the warnings, the pictures); only the
results as JSON, for machines, are left to the HTML.
"""

from __future__ import annotations

import base64
import html
import io
import json
import math
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from kinetostatics.common.jsontext import json_default
from kinetostatics.model.outputs import atomic_file
from kinetostatics.plot.notation import reading
from kinetostatics.plot.place import settle

from ..errors import BalanceError
from .pdf import write_pdf
from .text import noise_lines, result_warnings, summary_text, unit_text

__all__ = ["influence_figure", "iso_figure", "json_default", "report_figures", "report_scene",
           "write_report"]


def influence_figure(result: Any, *, mass_unit: str = "", vib_unit: str = ""):
    """Readings and corrections of an influence-coefficient result, as vectors.

    Left: each measurement point's reading before correction (solid), the readings
    balanced (after trim runs) and the predicted residual (dotted). Right: each
    plane's correction vector with the wedge of its angle interval and the arc
    of its mass interval.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    vib_unit = unit_text(vib_unit)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11.0, 6.5), layout="constrained")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    pts = result.points or tuple(f"point {i + 1}" for i in range(result.initial.size))
    lim = 0.0
    for i, (v0, vc, vr) in enumerate(zip(result.initial, result.current, result.residual,
                                         strict=True)):
        c = colors[i % len(colors)]
        ax1.annotate("", (v0.real, v0.imag), (0, 0),
                     arrowprops={"arrowstyle": "-|>", "color": c, "lw": 1.8})
        ax1.plot([], [], color=c, label=f"{pts[i]}: {abs(v0):.3g} {vib_unit} at "
                 f"{math.degrees(np.angle(v0)) % 360:.1f} deg")
        if result.trim_runs:
            ax1.annotate("", (vc.real, vc.imag), (0, 0),
                         arrowprops={"arrowstyle": "-|>", "color": c, "lw": 1.2, "ls": "--"})
        ax1.plot([vr.real], [vr.imag], "o", color=c, ms=4)
        lim = max(lim, abs(v0), abs(vc))
    ax1.set_title("initial readings (arrows), " + ("after the trim runs (dashed), "
                  if result.trim_runs else "") + "predicted residual (dots)", fontsize=10)
    ax1.set_xlabel(f"Re ({vib_unit or 'reading unit'})")
    ax1.set_ylabel(f"Im ({vib_unit or 'reading unit'})")
    ax1.legend(fontsize=10, loc="upper center", bbox_to_anchor=(0.5, -0.14),
               borderaxespad=0.0)
    lim2 = 0.0
    for j, w in enumerate(result.corrections):
        c = colors[j % len(colors)]
        ax2.annotate("", (w.real, w.imag), (0, 0),
                     arrowprops={"arrowstyle": "-|>", "color": c, "lw": 2.0})
        ax2.plot([], [], color=c, label=f"plane {j + 1}: {abs(w):.4g} {mass_unit} at "
                 f"{math.degrees(np.angle(w)) % 360:.1f} deg")
        iv = result.intervals[j] if result.intervals else None
        if iv and iv["angle"] is not None and iv["mass"][1] is not None:
            lo, hi = iv["angle"]
            span = (hi - lo) % 360.0 if iv["angle"] != [0.0, 360.0] else 360.0
            t = np.radians(lo + np.linspace(0.0, span, 60))
            m_lo, m_hi = iv["mass"]
            ring = np.concatenate([m_hi * np.exp(1j * t), m_lo * np.exp(1j * t[::-1])])
            ax2.fill(ring.real, ring.imag, color=c, alpha=0.2, lw=0)
            lim2 = max(lim2, m_hi)
        lim2 = max(lim2, abs(w))
    conf = 100.0 * result.noise.confidence
    ax2.set_title(f"corrections with their {conf:g} % intervals (shaded)", fontsize=10)
    ax2.set_xlabel(f"mass x cos(angle) ({mass_unit or 'trial mass unit'})")
    ax2.set_ylabel(f"mass x sin(angle) ({mass_unit or 'trial mass unit'})")
    ax2.legend(fontsize=10, loc="upper center", bbox_to_anchor=(0.5, -0.14),
               borderaxespad=0.0)
    for ax, r in ((ax1, lim), (ax2, lim2)):
        r = 1.15 * r if r > 0 else 1.0
        ax.set_xlim(-r, r)
        ax.set_ylim(-r, r)
        ax.set_aspect("equal")
        ax.axhline(0.0, color="0.85", lw=0.8, zorder=0)
        ax.axvline(0.0, color="0.85", lw=0.8, zorder=0)
        ax.grid(True, color="0.93")
    fig.suptitle(result.name or "influence coefficients", fontsize=11)
    return fig


def iso_figure(iso: dict[str, Any]):
    """ISO 21940-11 tolerances per plane as bars, with the residuals as dots (the
    ``iso`` result dict, in its units).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 4.0), layout="constrained")
    names, per, res = [], [], []
    check = iso.get("check") or {}
    bear = check.get("bearing_residual")
    for k, b in enumerate(iso.get("bearing_planes", [])):
        names.append(f"bearing {b['name']}")
        per.append(b["permissible"])
        res.append(None if bear is None else bear[k])
    for k, c in enumerate(iso.get("correction_planes", [])):
        if c["permissible"] is not None:
            names.append(f"plane {c['plane']}")
            per.append(c["permissible"])
            res.append(check["residual"][k] if check.get("bearing_residual") else None)
    if not names:
        names, per = ["rotor"], [iso["U_per"]]
        res = [check["residual"][0]] if check else [None]
    x = np.arange(len(names))
    ax.bar(x, per, color="tab:green", alpha=0.35, label="permissible")
    pts = [(i, r) for i, r in zip(x, res, strict=True) if r is not None]
    if pts:
        ok = [r <= p for (i, r), p in zip(pts, [per[i] for i, _ in pts], strict=True)]
        ax.scatter([i for i, _ in pts], [r for _, r in pts], zorder=3,
                   c=["tab:green" if o else "tab:red" for o in ok], label="residual")
    ax.set_xticks(x, names)
    ax.set_ylabel(f"unbalance ({iso['unbalance_unit']})")
    ax.set_title(f"ISO 21940-11, G {iso['grade']:g}: $U_{{\\mathrm{{per}}}}$ = "
                 f"{reading(iso['U_per'])} "
                 f"{iso['unbalance_unit']}", fontsize=10)
    ax.legend(fontsize=10)
    ax.grid(True, axis="y", color="0.9")
    return fig


def report_figures(results: dict[str, Any], out: dict[str, Any]) -> list[tuple[str, Any]]:
    """(caption, Figure) for every picture the report shows."""
    import matplotlib.pyplot as plt

    from .. import plot as bplot

    figs: list[tuple[str, Any]] = []
    if "rotor" in results:
        r = results["rotor"]
        two = len(r.corrections) == 2       # one above the other: each at a page's width
        fig, axes = plt.subplots(1 + two, 1, figsize=(6.8, 4.8 * (1 + two)),
                                 layout="constrained", squeeze=False)
        bplot.plot_unbalance_polygon(r, axes[0, 0])
        if two:
            bplot.plot_moment_polygon(r, axes[1, 0])
        figs.append(("rotor: unbalance polygon closed by the corrections", fig))
    units = out.get("scene_units") or {}
    vib = unit_text(units.get("vibration", "")) or "amplitude unit"
    for k, t in enumerate(results.get("resonance_test", [])):
        if t.A is None:
            continue
        if t.method == "three-run":
            figs.append((f"resonance test {k + 1}: the amplitude parallelogram",
                         bplot.plot_parallelogram(t, unit=vib).figure))
        else:
            figs.append((f"resonance test {k + 1}: each run's amplitude circle",
                         bplot.plot_amplitude_circles(t, unit=vib).figure))
    for r in results.get("influence", []):
        figs.append((f"{r.name or 'influence coefficients'}: readings and corrections",
                     influence_figure(r, mass_unit=units.get("mass", ""),
                                      vib_unit=units.get("vibration", ""))))
    if "iso" in out:
        figs.append(("ISO 21940-11: tolerances (bars) and residuals (dots)",
                     iso_figure(out["iso"])))
    for _caption, fig in figs:
        settle(fig)             # labels clear of the vectors, on the final layout
    return figs


def _png(fig: Any, dpi: float = 150) -> str:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight", pad_inches=0.05)
    plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode("ascii")


_CSS = """body{font-family:sans-serif;max-width:60em;margin:2em auto;color:#222}
h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #ccc}
pre{background:#f6f6f6;padding:.6em;overflow-x:auto;font-size:.85em}
.warn{color:#a40}.ok{color:#070}figure{margin:1em 0}img{max-width:100%}
figcaption{font-size:.9em;color:#555}"""


def _textsummary_text(results: dict[str, Any], out: dict[str, Any]) -> list[str]:

    speed = "rotor" in results and results["rotor"].speed_rpm is not None
    return summary_text(out, speed).splitlines()


def write_report(path: str | Path, results: dict[str, Any], out: dict[str, Any],
                 scene: Any = None, dpi: float = 150) -> Path:
    """Write the balancing report as HTML (pictures embedded) or PDF.

    Parameters
    ----------
    path : str or Path
        ``.html`` / ``.htm`` or ``.pdf``.
    results, out : dict
        :func:`balance.solve_results` and :func:`balance.results_to_dict` of the scene.
    scene : path or str, optional
        The scene file: its text is shown as the data.
    dpi : float
        Dots per inch of the pictures (150, the lecture-room default).

    Returns
    -------
    Path
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".html", ".htm", ".pdf"):
        raise BalanceError(f"--report {path}: give a file ending in .html or .pdf")
    source = ""
    if scene is not None and Path(str(scene)).is_file():
        source = Path(str(scene)).read_text(encoding="utf-8")
    lines = _textsummary_text(results, out) + noise_lines(results, out)
    warns = [f"{w}: {m}" if w else m for w, m in result_warnings(out)]
    figs = report_figures(results, out)
    try:
        with atomic_file(path) as tmp:          # the whole report, or the earlier one kept
            if suffix == ".pdf":
                write_pdf(tmp, datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"), source,
                          lines, _iso_line(out), warns, figs, dpi)
            else:
                tmp.write_text(_html(lines, warns, figs, source, out, dpi), encoding="utf-8")
    except OSError as exc:
        raise BalanceError(f"--report {path}: cannot write the file ({exc.strerror})") from exc
    return path


def report_scene(scene: Any, path: str | Path) -> Path:
    """Solve a balancing scene and write its report (HTML or PDF): the Python side of
    ``python -m balance solve SCENE --report FILE``.

    Parameters
    ----------
    scene : path, str or dict
        As :func:`balance.solve`.
    path : str or Path
        ``.html`` or ``.pdf``.

    Returns
    -------
    Path
    """
    from ..api import results_to_dict, solve_results

    results = solve_results(scene)
    return write_report(path, results, results_to_dict(results), scene)


def _html(lines: list[str], warns: list[str], figs: list, source: str,
          out: dict[str, Any], dpi: float = 150) -> str:
    esc = html.escape
    stamp = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    parts = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
             "<title>Balancing report</title>", f"<style>{_CSS}</style></head><body>",
             "<h1>Balancing report</h1>", f"<p>Made {esc(stamp)} by python -m balance.</p>"]
    if source:
        parts += ["<h2>Data (the scene)</h2>", f"<pre>{esc(source)}</pre>"]
    parts += ["<h2>Results</h2>", f"<pre>{esc(chr(10).join(lines))}</pre>"]
    iso = _iso_line(out)
    if iso:
        ok = out["iso"]["check"]["ok"]
        parts.append(f"<p class=\"{'ok' if ok else 'warn'}\">{esc(iso)}</p>")
    parts.append("<h2>Warnings</h2>")
    if warns:
        parts.append("<ul>" + "".join(f"<li class=\"warn\">{esc(w)}</li>" for w in warns)
                     + "</ul>")
    else:
        parts.append("<p class=\"ok\">None: every result is determined by the data.</p>")
    if figs:
        parts.append("<h2>Pictures</h2>")
        for caption, fig in figs:
            parts.append(f"<figure><img alt=\"{esc(caption)}\" src=\"data:image/png;base64,"
                         f"{_png(fig, dpi)}\"><figcaption>{esc(caption)}</figcaption></figure>")
    parts += ["<h2>Results as JSON</h2>",
              f"<pre>{esc(json.dumps(out, indent=1, allow_nan=False, default=json_default))}</pre>",
              "</body></html>"]
    return "\n".join(parts)


def _iso_line(out: dict[str, Any]) -> str | None:
    """The ISO 21940-11 verdict, or None without a check."""
    if "iso" not in out or "check" not in out["iso"]:
        return None
    return "ISO 21940-11 check: " + ("the residual unbalance is within tolerance"
                                     if out["iso"]["check"]["ok"] else "NOT within tolerance")
