"""The lowest floor: the command lines' shared pieces, plain JSON, the lazy loader and
angles in messages."""

from __future__ import annotations

import json
import math
import types
import warnings

import numpy as np
import pytest

from kinetostatics.common.angles import degrees_text
from kinetostatics.common.cli import OneLineParser, dpi_argument, one_line
from kinetostatics.common.jsontext import json_default, plain
from kinetostatics.common.lazy import lazy_names, moved_names


def test_degrees_text_is_the_old_format() -> None:
    for rad in (0.0, -0.0, 1.0, math.pi, -2.5, 1e-9, 1e6):
        assert degrees_text(rad) == f"{math.degrees(rad):.6g}"
    assert degrees_text(math.pi / 2) == "90" and degrees_text(1.0, ".3f") == "57.296"


def test_plain_json() -> None:
    value = {1: (np.int64(2), np.float64(0.5)), "a": np.array([[1.0, np.nan]]),
             "b": [np.bool_(True), float("inf")]}
    kept = plain(value)                     # NaN and infinities kept as floats
    assert kept["1"] == [2, 0.5] and kept["b"] == [True, math.inf]
    assert kept["a"][0][0] == 1.0 and math.isnan(kept["a"][0][1])
    clean = plain(value, finite=True)
    assert clean == {"1": [2, 0.5], "a": [[1.0, None]], "b": [True, None]}
    assert type(clean["1"][0]) is int and type(clean["b"][0]) is bool
    assert json.dumps({"x": np.float32(1.5), "y": np.arange(2)}, default=json_default) == \
        '{"x": 1.5, "y": [0, 1]}'
    with pytest.raises(TypeError):
        json.dumps({"x": object()}, default=json_default)


def test_lazy_names_import_on_first_use() -> None:
    namespace: dict = {}
    get, listing = lazy_names("kinetostatics", {"degrees_text": "common.angles"}, namespace,
                              ["degrees_text"], kept=lambda n: n != "other")
    assert get("degrees_text") is degrees_text and namespace["degrees_text"] is degrees_text
    assert isinstance(get("common"), types.ModuleType)       # a subpackage
    with pytest.raises(AttributeError, match="has no attribute 'nothing'"):
        get("nothing")
    assert "degrees_text" in listing()
    get2, _ = lazy_names("kinetostatics", {}, {}, subpackages=False)
    with pytest.raises(AttributeError):
        get2("common")


def test_moved_names_warn() -> None:
    get = moved_names("old.place", {"f": ("kinetostatics.common.angles", "degrees_text")})
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        assert get("f") is degrees_text
    assert "old.place.f is now kinetostatics.common.angles.degrees_text" in str(w[0].message)
    with pytest.raises(AttributeError):
        get("g")


def test_one_line_parser_and_dpi(capsys) -> None:
    p = OneLineParser(prog="prog")
    p.add_argument("--dpi", type=dpi_argument)
    assert p.parse_args(["--dpi", "120"]).dpi == 120.0
    for bad in ("12", "nan", "x", "700"):
        with pytest.raises(SystemExit) as out:
            p.parse_args(["--dpi", bad])
        assert out.value.code == 2
        err = capsys.readouterr().err
        assert err.startswith("error: argument --dpi: ") and err.count("\n") == 1
        assert "give a number from 50 to 600 (see prog --help)" in err
    assert one_line("a\n  b\tc ") == "a b c"
