"""The handout's picture: a PNG whose text would show a key value is encoded again (the
same pixels), not drawn again."""

from __future__ import annotations

import base64
import io

import numpy as np
from PIL import Image

from kinetostatics.teaching import handouts as H
from kinetostatics.teaching.library import exercise


def _pixels(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGBA"))


def test_a_refused_picture_is_encoded_again(monkeypatch) -> None:
    ex = exercise("four_bar", 5)
    v = ex.variant("2026-001")
    seen: list[str] = []

    def clean(blob, values, angles, seed):      # the first three texts "show a key"
        seen.append(blob)
        return len(seen) > 3
    monkeypatch.setattr(H, "_clean", clean)
    drawn = []
    real = type(H.picture_figure(ex, v)).savefig

    def count(self, *a, **k):
        drawn.append(k.get("dpi"))
        return real(self, *a, **k)
    monkeypatch.setattr(type(H.picture_figure(ex, v)), "savefig", count)
    uri = H.picture_uri(ex, v)
    assert drawn == [H.PICTURE_DPI]                 # drawn once
    assert len(set(seen)) == 4 and uri == "data:image/png;base64," + seen[3]
    first, last = (base64.b64decode(b) for b in (seen[0], seen[3]))
    assert np.array_equal(_pixels(first), _pixels(last))
    assert len(last) < 1.2 * len(first)


def test_forty_texts_then_no_picture(monkeypatch) -> None:
    ex = exercise("four_bar", 5)
    v = ex.variant("2026-002")
    seen: list[str] = []
    monkeypatch.setattr(H, "_clean", lambda blob, *a: seen.append(blob) or False)
    assert H.picture_uri(ex, v) is None
    assert len(seen) == len(set(seen)) == 40
