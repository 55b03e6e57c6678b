"""The balancing report as a PDF document (issue 22, item 8): A4 pages, the sections of
the HTML report, proportional fonts, units in the legends, rounding-level residuals as
"0 (to rounding)"."""

from __future__ import annotations

import re

import matplotlib
import pytest
from matplotlib.backends import backend_pdf
from matplotlib.legend import Legend
from matplotlib.text import Text

from balance.model.scene import SCENES
from balance.report import document, report_figures, report_scene

matplotlib.use("Agg")


def scenes(*names: str) -> list:
    """The report's scenes as parameters: the first in the quick tier, the others ``slow``
    (each PDF draws every picture of its report, 1.5-3.5 s of CPU)."""
    return [pytest.param(n, marks=() if k == 0 else pytest.mark.slow)
            for k, n in enumerate(names)]


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """``written(name)``: the PDF report of a bundled scene, written once per module
    (each PDF draws every picture of its report: the three tests reading one scene's
    wrote it three times), as (the file's bytes, every page figure the PDF writer saved
    as (size in inches, texts, Axes with an image), the report's pictures as
    report_figures made them for this PDF)."""
    cache: dict[str, tuple[bytes, list, list]] = {}

    def get(name: str):
        if name not in cache:
            pages, drawn = [], []
            save = backend_pdf.PdfPages.savefig

            def spy(self, fig=None, **kw):
                texts = [t for t in fig.findobj(Text) if t.get_text().strip()]
                pages.append((tuple(fig.get_size_inches()), texts,
                              [ax for ax in fig.axes if ax.images]))
                return save(self, fig, **kw)

            def made(*args):
                drawn.extend(report_figures(*args))
                return drawn

            # (the pictures counted as the report draws them: drawing them again to count
            # them cost a third of the test)
            with pytest.MonkeyPatch.context() as mp:
                mp.setattr(backend_pdf.PdfPages, "savefig", spy)
                mp.setattr(document, "report_figures", made)
                path = report_scene(SCENES.resolve(name), tmp_path_factory.mktemp(name) / "r.pdf")
            cache[name] = (path.read_bytes(), pages, drawn)
        return cache[name]
    return get


@pytest.mark.parametrize("name", scenes("influence_two_plane", "rotor_two_plane",
                                        "resonance_example"))
def test_pdf_is_an_a4_document_with_the_html_sections(name, written):
    raw, pages, drawn = written(name)
    boxes = re.findall(rb"/MediaBox \[\s*0 0 ([\d.]+) ([\d.]+)\s*\]", raw)
    assert boxes and all(abs(float(w) - 595.4) < 1 and abs(float(h) - 841.7) < 1
                         for w, h in boxes), boxes
    assert all(abs(w - 8.27) < 1e-9 and abs(h - 11.69) < 1e-9 for (w, h), _, _ in pages)
    words = [t.get_text() for _, texts, _ in pages for t in texts]
    heads = [w for w in words if w in ("Data (the scene)", "Results", "Warnings",
                                       "Pictures")]
    assert heads == ["Data (the scene)", "Results", "Warnings", "Pictures"]
    families = {t.get_fontfamily()[0] for _, texts, _ in pages for t in texts}
    assert families == {"sans-serif"}                   # no monospace page
    assert drawn and sum(len(imgs) for _, _, imgs in pages) == len(drawn)  # each on a page
    assert all(len(texts) >= 1 for _, texts, _ in pages)


@pytest.mark.slow     # a whole PDF (test_pdf_is_an_a4_document... keeps one in the quick tier)
def test_residual_at_rounding_and_micrometres(written):
    _raw, pages, _drawn = written("influence_two_plane")
    words = " ".join(t.get_text() for _, texts, _ in pages for t in texts)
    # measured: the predicted residuals are 5.7e-14 and 2.5e-14 um of readings ~170 um
    assert "bearing A 0 (to rounding), bearing B 0 (to rounding)" in words
    assert "e-14" not in words


@pytest.mark.slow     # the pictures of two whole PDFs (written once, read here too)
def test_legends_carry_units(written):
    _raw, _pages, figs = written("influence_two_plane")        # as the PDF shows them
    labels = [t.get_text() for _, fig in figs for lg in fig.findobj(Legend)
              for t in lg.get_texts()]
    assert any("170 µm at 112.0 deg" in s for s in labels), labels
    assert all(" um" not in s for s in labels)
    _raw, _pages, figs = written("four_run")
    labels = [t.get_text() for _, fig in figs for lg in fig.findobj(Legend)
              for t in lg.get_texts()]
    amplitudes = [s for s in labels if "A1 =" in s or "A =" in s]
    # four_run names no vibration unit: its legends say "amplitude unit"
    assert amplitudes and all(re.search(r"\d (µm|mm|mm/s|amplitude unit)( |$)", s)
                              for s in amplitudes), labels


@pytest.mark.slow     # a whole PDF (test_pdf_is_an_a4_document... keeps one in the quick tier)
@pytest.mark.parametrize("name", scenes("four_run", "influence_two_plane", "rotor_two_plane",
                                        "resonance_example"))
def test_pictures_heading_kept_with_its_picture_and_panels_at_full_width(name, written):
    """The "Pictures" heading stands on the page of the first picture (never alone at a
    page's foot), and every picture is as wide as the text: panels side by side are
    stacked one above the other, not shrunk (issue 33, item 6)."""
    _raw, pages, _drawn = written(name)
    with_heading = [k for k, (_size, texts, _imgs) in enumerate(pages)
                    if any(t.get_text() == "Pictures" for t in texts)]
    assert len(with_heading) == 1
    assert pages[with_heading[0]][2], "the Pictures heading is alone on its page"
    from balance.report.pdf import _MARGIN, A4
    for size, _texts, imgs in pages:
        for ax in imgs:
            width = ax.get_position().width * size[0]
            height = ax.get_position().height * size[1]
            # full text width, or a tall picture fitted to the page's height
            assert width == pytest.approx(A4[0] - 2 * _MARGIN, rel=1e-6) or \
                height > 0.8 * (A4[1] - 2 * _MARGIN), (name, width, height)


def _examples() -> list[str]:
    from balance.api import examples
    return list(examples())


@pytest.mark.parametrize("name", scenes(*_examples()))
def test_report_figures_meet_the_picture_standard(name):
    """Every picture of every bundled balancing report (one example in the quick tier):
    no collision, at most one label not placed, text >= 10 pt, the notation of
    docs/notation.md."""
    import matplotlib.pyplot as plt

    from balance.api import example_path, results_to_dict, solve_results
    from kinetostatics.plot import lecture_style
    from kinetostatics.plot.audit import audit
    bad = {}
    with lecture_style():
        res = solve_results(str(example_path(name)))
        for caption, fig in report_figures(res, results_to_dict(res)):
            problems = audit(fig).problems
            if problems:
                bad[f"{name}: {caption}"] = problems
            plt.close(fig)
    assert not bad, bad


def test_report_states_the_noise_its_intervals_assume():
    """The report says which reading noise and confidence its intervals assume (the
    default 1 % and 1 deg when the scene gives none) and what "not determined" means
    (issue 33, item 8)."""
    from balance.api import example_path, results_to_dict, solve_results
    from balance.report.text import field_text, noise_lines
    res = solve_results(str(example_path("resonance_example")))
    lines = noise_lines(res, results_to_dict(res))
    assert lines == ["resonance test 1: intervals at 95 % for readings with 1 % of each "
                     "amplitude (1 sigma); an estimate is not determined when its interval "
                     "leaves more than 25 % of the unbalance uncorrected (or spans more "
                     "than 14.4 deg)"]
    res = solve_results(str(example_path("influence_two_plane")))
    text = "\n".join(field_text(results_to_dict(res)))
    assert "intervals at 95 % for readings with 1 % of each amplitude (1 sigma), " \
           "1 deg of phase" in text
    assert "that reading noise moves the correction by up to 5.434 %" in text
