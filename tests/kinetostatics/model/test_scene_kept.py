"""Scenes read from dicts kept by their content (kinetostatics.model.scene.load_scene):
the same content read again gives the same frozen Scene; changed content, a dict that
holds more than plain data, or a scene that warned is read anew; the kept scene shares
nothing with the caller's dict."""

from __future__ import annotations

import copy
import math
import tomllib
import warnings

import numpy as np

import kinetostatics as ks
from kinetostatics.model import scene as scene_module


class Typed(float):
    """A number of the caller's own type (the reader takes it as a float)."""


def four_bar() -> dict:
    with open(ks.example("four_bar"), "rb") as fh:
        return tomllib.load(fh)


def test_the_same_content_gives_the_same_scene_and_other_content_another() -> None:
    d = four_bar()
    first = ks.load_scene(d)
    assert ks.load_scene(d) is first
    assert ks.load_scene(copy.deepcopy(d)) is first           # content, not the object
    d["ground"]["D"] = [d["ground"]["D"][0] * 1.01, d["ground"]["D"][1]]
    moved = ks.load_scene(d)
    assert moved is not first and moved.ground["D"] != first.ground["D"]
    # 1 and 1.0 are told apart (another type: read anew, the same numbers)
    e = four_bar()
    e["driver"]["count"] = float(e["driver"]["count"])
    assert ks.load_scene(e) is not first


def test_the_kept_scene_shares_nothing_with_the_callers_dict() -> None:
    d = four_bar()
    d["title"] = "read here first"          # (content no other test reads: read now)
    sc = ks.load_scene(d)
    before = copy.deepcopy(sc.raw)
    d["ground"]["D"][0] = 0.31           # the caller's nested list, changed in place
    d["bodies"][0]["mass"] = 9.0
    assert sc.raw == before and sc.raw["ground"]["D"][0] != 0.31
    fresh = ks.load_scene(d)
    assert fresh is not sc and fresh.ground["D"][0] == 0.31


def test_a_dict_of_other_than_plain_data_is_read_each_time() -> None:
    d = four_bar()
    d["driver"]["speed"] = Typed(10.0)      # (a float of another type: not plain data)
    assert scene_module.snapshot(d) is None
    assert ks.load_scene(d) is not ks.load_scene(d)
    e = four_bar()
    e["driver"].pop("count", None)
    for k in ("start", "stop"):
        e["driver"].pop(k, None)
    e["driver"]["positions"] = list(np.linspace(0.0, 350.0, 36))   # numpy numbers: plain
    assert scene_module.snapshot(e) is not None
    assert ks.load_scene(e) is ks.load_scene(e)


def test_a_scene_that_warned_is_read_and_warned_again() -> None:
    d = four_bar()
    d["units"] = {"speed": "rpm"}
    d["driver"]["speed"] = 3000.0 * 30 / math.pi       # 3000 rad/s typed in rpm
    seen = []
    for _ in range(2):
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            sc = ks.load_scene(d)
        seen.append([str(x.message) for x in w if issubclass(x.category, ks.UnitWarning)])
        assert sc.warnings
    assert seen[0] and seen[0] == seen[1]


def test_a_long_sweep_is_not_kept() -> None:
    d = four_bar()
    d["driver"]["count"] = 200_001
    assert ks.load_scene(d) is not ks.load_scene(d)
