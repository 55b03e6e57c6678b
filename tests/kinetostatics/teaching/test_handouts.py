"""The handout's picture: a PNG whose text would show a key value is encoded again (the
same pixels), not drawn again."""

from __future__ import annotations

import base64
import io

import numpy as np
from matplotlib.figure import Figure
from PIL import Image

from kinetostatics.teaching import handouts as H
from kinetostatics.teaching.library import exercise


def _pixels(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGBA"))


def _small(exercise, variant):
    fig = H._figure((1.5, 1.0))
    fig.text(0.1, 0.5, "your mechanism")
    return fig


def test_a_refused_picture_is_encoded_again(monkeypatch) -> None:
    ex = exercise("four_bar", 5)
    v = ex.variant("2026-001")
    seen: list[str] = []

    def clean(blob, values, angles, seed):      # the first three texts "show a key"
        seen.append(blob)
        return len(seen) > 3
    monkeypatch.setattr(H, "_clean", clean)
    drawn = []
    real = Figure.savefig
    monkeypatch.setattr(Figure, "savefig",
                        lambda self, *a, **k: drawn.append(k.get("dpi")) or real(self, *a, **k))
    uri = H.picture_uri(ex, v)                  # the student's mechanism
    assert drawn == [H.PICTURE_DPI]             # drawn once
    assert len(set(seen)) == 4 and uri == "data:image/png;base64," + seen[3]
    first, last = (base64.b64decode(b) for b in (seen[0], seen[3]))
    assert np.array_equal(_pixels(first), _pixels(last))
    assert len(last) < 1.2 * len(first)


def test_forty_texts_then_no_picture(monkeypatch) -> None:
    monkeypatch.setattr(H, "picture_figure", _small)
    monkeypatch.setattr(H, "key_values", lambda v: ({}, set()))
    seen: list[str] = []
    monkeypatch.setattr(H, "_clean", lambda blob, *a: seen.append(blob) or False)
    ex = type("Ex", (), {"seed": 1})()
    assert H.picture_uri(ex, {}) is None
    assert len(seen) == len(set(seen)) == 40
    pixels = {_pixels(base64.b64decode(b)).tobytes() for b in seen}
    assert len(pixels) == 1


def test_the_picture_adds_no_number_to_the_page() -> None:
    """The leak check of a variant reads the handout without its picture: the picture's
    markup must show no number the page does not (a Me_max of 100.04 once leaked
    through ``max-width:100%``; seed 8839582624553955206, slotted lever, 2026-026)."""
    from kinetostatics.teaching.sheets import _NUM, handout_html

    ex = exercise("slotted_lever", 8839582624553955206)
    v = ex.variant("2026-026")
    bare = handout_html(ex, "2026-026", v)
    with_picture = handout_html(ex, "2026-026", v, "data:image/png;base64,AAAA")
    extra = with_picture.replace("data:image/png;base64,AAAA", "")
    assert set(_NUM.findall(extra)) <= set(_NUM.findall(bare))
    assert "img{max-width:100%}" in bare


def test_a_key_value_the_picture_spells_is_not_in_its_text(monkeypatch) -> None:
    """The leak check itself (not a stand-in), on a real picture: a key value that the
    first encoding's base64 text spells (a three-digit run of that text, whatever the
    drawing's bytes are here) is not readable in the picture the page gets, neither as a
    number nor inside one; the pixels are the first encoding's."""
    import re

    ex = exercise("rotor_two_plane", 5)
    v = ex.variant("2026-001")
    fig = H.picture_figure(ex, v)
    monkeypatch.setattr(H, "key_values", lambda variant: ({}, set()))
    first = H.picture_uri(ex, v, fig).split(",", 1)[1]
    spelled = re.search(r"(?<![0-9])[1-9][0-9]{2}(?![0-9])", first).group(0)
    monkeypatch.setattr(H, "key_values", lambda variant: ({"q": float(spelled)}, set()))
    blob = H.picture_uri(ex, v, fig).split(",", 1)[1]
    assert blob != first and spelled not in blob
    assert np.array_equal(_pixels(base64.b64decode(blob)), _pixels(base64.b64decode(first)))
