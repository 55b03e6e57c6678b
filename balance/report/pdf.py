"""The balancing report as a PDF document: A4 pages, the sections of the HTML report
(the scene's data, the results, the ISO check, the warnings, the pictures) in a
proportional font, the text flowed from page to page, each picture scaled to the page
width under its caption, every page numbered.
"""

from __future__ import annotations

import io
import textwrap
from pathlib import Path
from typing import Any

__all__ = ["A4", "write_pdf"]

A4 = (8.27, 11.69)          # inches
_MARGIN = 0.75              # inches
_BODY = 10.0                # points
_HEAD = 14.0
_LINE = 1.45                # line height, in font sizes
_WRAP = 92                  # characters of body text on a line of the A4 width


class _Pages:
    """A4 pages written one after the other; text flows down and onto a new page."""

    def __init__(self, pdf, title: str) -> None:
        self.pdf, self.title = pdf, title
        self.fig = None
        self.y = 0.0            # inches from the top of the page
        self.number = 0

    def _new(self) -> None:
        import matplotlib.pyplot as plt
        self._flush()
        self.fig = plt.figure(figsize=A4)
        self.number += 1
        self.fig.text(0.5, 0.3 / A4[1], f"{self.title}, page {self.number}", ha="center",
                      va="bottom", fontsize=9 + 1, color="0.4")
        self.y = _MARGIN

    def _flush(self) -> None:
        import matplotlib.pyplot as plt
        if self.fig is not None:
            self.pdf.savefig(self.fig)
            plt.close(self.fig)
            self.fig = None

    def _room(self, inches: float) -> None:
        if self.fig is None or self.y + inches > A4[1] - _MARGIN + 1e-9:
            self._new()

    def line(self, text: str, size: float = _BODY, weight: str = "normal",
             color: str = "0.1", indent: float = 0.0) -> None:
        h = size * _LINE / 72.0
        self._room(h)
        self.fig.text((_MARGIN + indent) / A4[0], 1.0 - self.y / A4[1], text, ha="left",
                      va="top", fontsize=size, fontweight=weight, color=color,
                      family="sans-serif")
        self.y += h

    def heading(self, text: str) -> None:
        self._room(3 * _HEAD * _LINE / 72.0)        # never alone at a page's foot
        self.y += 0.12
        self.line(text, _HEAD, "bold")
        self.y += 0.04

    def paragraph(self, text: str, color: str = "0.1") -> None:
        for raw in text.splitlines() or [""]:
            lead = len(raw) - len(raw.lstrip(" "))
            indent = 0.09 * lead
            width = max(20, _WRAP - lead)
            for k, part in enumerate(textwrap.wrap(raw.strip(), width) or [""]):
                self.line(part, color=color, indent=indent + (0.25 if k else 0.0))

    def picture(self, caption: str, fig: Any, dpi: float = 150,
                heading: str | None = None) -> None:
        """The picture at the text width under ``heading`` (kept on its page), its
        caption under it. A figure wider than the text is drawn at the printed size (its
        fonts stay >= 10 pt), its panels side by side stacked one above the other at
        the full width."""
        import matplotlib.pyplot as plt
        text_width = A4[0] - 2 * _MARGIN
        if fig.get_size_inches()[0] > text_width:
            _full_width(fig, text_width)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight", pad_inches=0.05)
        plt.close(fig)
        buf.seek(0)
        img = plt.imread(buf)
        width = A4[0] - 2 * _MARGIN
        height = width * img.shape[0] / img.shape[1]
        caption_room = 2 * _BODY * _LINE / 72.0
        head = 0.2 + _HEAD * _LINE / 72.0 if heading is not None else 0.0
        room = A4[1] - 2 * _MARGIN - head - caption_room     # a page under the heading
        if height > room:                           # a tall picture: fit the height
            height = room
            width = height * img.shape[1] / img.shape[0]
        need = height + caption_room
        if heading is not None:     # the heading never alone at the foot of a page
            self._room(need + head)
            self.heading(heading)
        self._room(need)
        left = (A4[0] - width) / 2.0
        ax = self.fig.add_axes([left / A4[0], 1.0 - (self.y + height) / A4[1],
                                width / A4[0], height / A4[1]])
        ax.imshow(img)
        ax.set_axis_off()
        self.y += height + 0.05
        self.line(caption, color="0.3")
        self.y += 0.15

    def close(self) -> None:
        self._flush()


def _full_width(fig: Any, width: float) -> None:
    """Lay a figure out at ``width`` inches: panels side by side (one row of a grid)
    go one above the other, each at the full width with its own aspect; a single panel
    is scaled. Its labels are placed again on the new layout."""
    from kinetostatics.plot.place import settle
    w0, h0 = fig.get_size_inches()
    panels = [ax for ax in fig.axes if ax.get_subplotspec() is not None]
    cols = {ax.get_subplotspec().colspan.start for ax in panels}
    rows = {ax.get_subplotspec().rowspan.start for ax in panels}
    if len(cols) > 1 and len(rows) == 1:
        grid = fig.add_gridspec(len(panels), 1)
        for k, ax in enumerate(sorted(panels, key=lambda a: a.get_subplotspec().colspan.start)):
            ax.set_subplotspec(grid[k])
        fig.set_layout_engine("constrained")
        fig.set_size_inches(width, min(len(panels) * h0 * width / (w0 / len(cols)),
                                       A4[1] - 2 * _MARGIN - 0.6))
    else:
        fig.set_layout_engine("constrained")
        fig.set_size_inches(width, h0 * width / w0)
    settle(fig)


def write_pdf(path: Path, stamp: str, source: str, lines: list[str], iso_line: str | None,
              warns: list[str], figs: list, dpi: float = 150) -> None:
    """Write the report as an A4 PDF, section by section as in the HTML.

    Parameters
    ----------
    path : Path
    stamp : str
        When it was made (the first line under the title).
    source : str
        The scene file's text (the "Data" section; empty: no such section).
    lines : list of str
        The results, as the command line prints them.
    iso_line : str, optional
        The ISO 21940-11 verdict.
    warns : list of str
    figs : list of (caption, Figure)
    dpi : float
        Dots per inch of the pictures.
    """
    from matplotlib.backends.backend_pdf import PdfPages

    with PdfPages(path) as pdf:
        pages = _Pages(pdf, "Balancing report")
        pages.line("Balancing report", 18.0, "bold")
        pages.line(f"Made {stamp} by python -m balance.", color="0.4")
        if source:
            pages.heading("Data (the scene)")
            pages.paragraph(source.rstrip())
        pages.heading("Results")
        pages.paragraph("\n".join(lines))
        if iso_line:
            pages.y += 0.08
            pages.paragraph(iso_line)
        pages.heading("Warnings")
        if warns:
            for w in warns:
                pages.paragraph("- " + w, color="#a04000")
        else:
            pages.paragraph("None: every result is determined by the data.", color="#007000")
        for k, (caption, fig) in enumerate(figs):
            pages.picture(caption, fig, dpi, heading="Pictures" if k == 0 else None)
        pages.close()
