"""The handout's picture and its PDF copy.

Each handout shows the student's own mechanism drawn at its first position
(:func:`kinetostatics.plot.draw_mechanism`) with its dimensions beside it, or a
rotor's eccentric masses seen along its axis; the picture is a PNG embedded in the
HTML page (``data:`` URI), so the page stays one file. The PDF copy (one page of
text and tables, one page with the picture) is written with matplotlib's
``PdfPages``: nothing to download.

The embedded picture is checked like the rest of the page: a PNG whose base64 text
happens to spell a key value (to 4 significant digits) or the word "seed" is encoded
again (the same pixels, another zlib level or text chunk: no new drawing).
"""

from __future__ import annotations

import base64
import io
import textwrap
from collections.abc import Mapping
from typing import Any

from ..common.angles import radian_column
from .sheets import data_rows, format_value, key_values, leaked_values, question_rows

__all__ = ["DRAW", "handout_pdf", "picture_figure", "picture_uri"]

#: The default ``figure`` of :func:`picture_uri` and :func:`handout_pdf`: draw the
#: variant's picture there (a student's handout and its PDF draw it once between them).
DRAW = "draw"


def _figure(size=(6.4, 4.8)):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    return fig


def _dimensions(exercise, variant: Mapping) -> str:
    rows = data_rows(exercise, variant)
    return "\n".join(f"{d['symbol']} = {format_value(d['value'])} {d['unit']}".rstrip()
                     for d in rows)


def picture_figure(exercise, variant: Mapping):
    """The student's mechanism at its first position with its dimensions (a rotor: its
    masses seen along the axis); None for a scene with nothing to draw.

    Returns
    -------
    matplotlib.figure.Figure or None
    """
    scene = variant["scene"]
    if "bodies" in scene or "driver" in scene:
        import kinetostatics as ks
        from kinetostatics.plot import draw_mechanism

        fig = _figure()
        ax = fig.add_axes((0.12, 0.1, 0.58, 0.8))
        draw_mechanism(ks.solve(scene), row=0, ax=ax)
    elif "rotor" in scene:
        import numpy as np
        from matplotlib.patches import Circle

        fig = _figure()
        ax = fig.add_axes((0.12, 0.1, 0.58, 0.8))
        rmax = 0.0
        for k, u in enumerate(scene["rotor"]["unbalance"], 1):
            t = radian_column(u["angle"])
            xy = (u["radius"] * np.cos(t), u["radius"] * np.sin(t))
            rmax = max(rmax, u["radius"])
            ax.annotate("", xy, (0, 0), arrowprops={"arrowstyle": "-|>"})
            ax.plot(*xy, "o", ms=4 + 300 * u["mass"], color="C1")
            ax.annotate(f"m{k}", xy, xytext=(4, 4), textcoords="offset points")
        lim = 1.25 * max(rmax, *(p["radius"] for p in scene["rotor"]["planes"]))
        ax.add_patch(Circle((0, 0), lim / 1.25, fill=False, ls="--", color="0.5"))
        ax.set_aspect("equal")
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_title("your rotor seen along its axis (dashed: correction radius)",
                     fontsize=9)
    else:
        return None
    fig.text(0.73, 0.9, "dimensions", fontsize=9, weight="bold", va="top")
    fig.text(0.73, 0.85, _dimensions(exercise, variant), fontsize=8, va="top",
             family="monospace")
    return fig


def _clean(blob: str, values: Mapping[str, float], angles: set, seed: int) -> bool:
    low = blob.lower()
    return (not leaked_values(blob, values, angles) and "seed" not in low
            and "expected" not in low and (len(str(seed)) < 6 or str(seed) not in blob))


def picture_uri(exercise, variant: Mapping, figure: Any = DRAW) -> str | None:
    """The picture as a ``data:image/png;base64,...`` URI (None: nothing to draw),
    with no key value, no ``seed`` and no seed number readable in its text.

    ``figure``: the variant's :func:`picture_figure` when it is drawn already (the
    handout's PDF shows the same one), else it is drawn here."""
    fig = picture_figure(exercise, variant) if figure is DRAW else figure
    if fig is None:
        return None
    values, angles = key_values(variant)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=PICTURE_DPI, metadata={"Software": None})
    for png in _encodings(buf.getvalue()):
        blob = base64.b64encode(png).decode("ascii")
        if _clean(blob, values, angles, int(exercise.seed)):
            return "data:image/png;base64," + blob
    return None             # no clean picture: the page goes without one


PICTURE_DPI = 150         # the lecture style's resolution
_LEVELS = (1, 2, 3, 4, 5, 7, 8, 9)      # zlib levels other than the default 6


def _encodings(first: bytes):
    """The PNG as drawn, then the same pixels encoded otherwise (another zlib level, a
    text chunk of another length): each is another base64 text, without drawing again;
    40 in all."""
    yield first
    from PIL import Image, PngImagePlugin

    image = Image.open(io.BytesIO(first))       # PNG is lossless: the pixels as drawn
    image.load()
    for pad in range(5):
        info = PngImagePlugin.PngInfo()
        if pad:
            info.add_text("Comment", " " * pad)
        for level in _LEVELS[:7 if pad == 4 else 8]:
            buf = io.BytesIO()
            image.save(buf, format="png", compress_level=level, pnginfo=info,
                       dpi=(PICTURE_DPI, PICTURE_DPI))
            yield buf.getvalue()


def handout_pdf(exercise, student: str, variant: Mapping, path: Any,
                figure: Any = DRAW) -> None:
    """Write the handout as a PDF: the statement, the data and the questions on page 1,
    the picture on page 2 (matplotlib ``PdfPages``; ``figure`` as in
    :func:`picture_uri`)."""
    from matplotlib.backends.backend_pdf import PdfPages

    from .questions import TOLERANCE_RULE

    page = _figure((8.27, 11.69))                       # A4
    y = 0.96

    def put(text: str, size: float = 9, width: int = 100, **kw) -> None:
        nonlocal y
        lines = textwrap.wrap(text, width) or [""]
        page.text(0.07, y, "\n".join(lines), fontsize=size, va="top", **kw)
        y -= (len(lines) * 1.45 * size + 6) / (11.69 * 72)

    put(exercise.title, 14, weight="bold")
    put(f"Student: {student}", 10)
    put(exercise.text)
    put("Your data", 11, weight="bold")
    for d in data_rows(exercise, variant):
        put(f"{d['symbol']} = {format_value(d['value'])} {d['unit']}   ({d['meaning']})",
            width=110)
    put("Questions", 11, weight="bold")
    for k, q in enumerate(question_rows(exercise, variant), 1):
        put(f"{k}. {q['question']}: {q['asked']} [{q['unit'] or '-'}]; tolerance "
            f"{q['tolerance']}", width=110)
    put("How the answers are graded. " + TOLERANCE_RULE, 8, width=120)
    pic = picture_figure(exercise, variant) if figure is DRAW else figure
    meta = {"Title": f"{exercise.title} - {student}", "Creator": "kinetostatics",
            "Producer": None, "CreationDate": None}
    with PdfPages(str(path), metadata=meta) as pdf:
        pdf.savefig(page)
        if pic is not None:
            pdf.savefig(pic)
