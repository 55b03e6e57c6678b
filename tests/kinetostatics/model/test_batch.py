"""load_scenes: many dicts of one form read at once give, scene by scene, exactly what
load_scene gives (field by field, bit for bit), or exactly its error."""

from __future__ import annotations

import copy
import dataclasses
import math
import warnings

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model import batch
from kinetostatics.model.batch import load_scenes
from kinetostatics.model.scene import load_scene


def same(a, b, where="scene") -> None:
    """Equal values, types and bits (-0.0 is not 0.0), dict keys in order."""
    assert type(a) is type(b), where
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes(), where
    elif dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            same(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}")
    elif isinstance(a, dict):
        assert list(a) == list(b), where
        for k in a:
            same(a[k], b[k], f"{where}[{k!r}]")
    elif isinstance(a, list | tuple):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            same(x, y, f"{where}[{i}]")
    elif isinstance(a, float):
        assert a == b and math.copysign(1.0, a) == math.copysign(1.0, b) or \
            (math.isnan(a) and math.isnan(b)), where
    else:
        assert a == b, where


def variants(name: str, count: int, seed: int = 0) -> list[dict]:
    """Dicts of one form: every decimal number of the bundled scene scaled by 1 +- 10 %."""
    base = load_scene(ks.example(name)).raw
    rng = np.random.default_rng(seed)

    def scaled(v):
        if type(v) is float:
            return v * rng.uniform(0.9, 1.1)
        if type(v) is list:
            return [scaled(x) for x in v]
        if type(v) is dict:
            return {k: scaled(x) for k, x in v.items()}
        return v
    out = []
    for _ in range(count):
        d = copy.deepcopy(base)
        for key in ("ground", "bodies", "near", "gravity", "loads"):
            if key in d:
                d[key] = scaled(d[key])
        d["driver"]["speed"] = scaled(d["driver"]["speed"])
        out.append(d)
    return out


@pytest.mark.parametrize("name", ["four_bar", "four_bar_motion", "scotch_yoke", "shaper",
                                  "slider_crank", "sliding_driver", "slotted_lever"])
def test_same_scenes_as_load_scene(name, monkeypatch) -> None:
    built = []
    real = batch._Family.build

    def spy(self, d):
        sc = real(self, d)
        built.append(sc is not None)
        return sc
    monkeypatch.setattr(batch._Family, "build", spy)
    ds = variants(name, 8)
    ds[3]["driver"] = {k: v for k, v in ds[3]["driver"].items()
                       if k not in ("start", "stop", "count")} | {"positions": [1.5, 2.5, 7.0]}
    for got, d in zip(load_scenes(ds), ds, strict=True):
        same(got, load_scene(d))
    assert built == [True] * 6          # the first read by load_scene; the 4th of another form


def test_another_form_and_other_sources() -> None:
    ds = variants("four_bar", 4)
    ds[1]["bodies"][0]["mass"] = 2          # a whole number where the first has a decimal
    ds[2]["title"] = "another"
    ds[0]["title"], ds[3]["title"] = 1.5, 7.25      # a title written as a number: its text
    srcs = [*ds, ks.example("slider_crank"), load_scene(ks.example("shaper"))]
    for got, src in zip(load_scenes(srcs), srcs, strict=True):
        same(got, load_scene(src))


@pytest.mark.parametrize("change", [
    lambda d: d["bodies"][1].__setitem__("mass", -2.0),
    lambda d: d["bodies"][2].__setitem__("inertia", -0.0 - 1e-9),
    lambda d: d["ground"].__setitem__("D", [float("nan"), 0.0]),
    lambda d: d["bodies"][0]["points"].__setitem__("B", [float("inf"), 0.0]),
    lambda d: d["near"].__setitem__("C", [1e13, 0.19]),
    lambda d: d["driver"].__setitem__("speed", True),
    lambda d: d["driver"].__setitem__("count", 12.5),
    lambda d: d["loads"][0].__setitem__("moment", float("-inf")),
    lambda d: d.__setitem__("format", 2.0),
])
def test_a_bad_value_gives_load_scenes_error(change) -> None:
    ds = variants("four_bar", 4, seed=1)
    for d in ds:                        # decimals where whole numbers are meant
        d["driver"]["count"] = 361.0
        d["format"] = 1.0
    change(ds[2])
    with pytest.raises(ks.SceneError) as alone:
        load_scene(ds[2])
    got = load_scenes(ds)
    assert isinstance(got[2], ks.SceneError) and str(got[2]) == str(alone.value)
    for g, d in zip(got[:2] + got[3:], ds[:2] + ds[3:], strict=True):
        same(g, load_scene(d))


def _loaded(d):
    try:
        return load_scene(d)
    except ks.SceneError as exc:
        return exc


def test_a_value_rule_and_warnings_as_load_scene() -> None:
    ds = variants("four_bar", 4, seed=2)
    for d in ds:                        # a crank without a cog: its mass must be 0
        d["bodies"][0].pop("cog")
        d["bodies"][0]["mass"] = 0.0
    ds[1]["bodies"][0]["mass"] = 1.0
    ds[2]["bodies"][2]["points"]["E"] = [120.0, 30.0]      # mm among metres: a warning
    with warnings.catch_warnings(record=True) as alone:
        warnings.simplefilter("always")
        want = [_loaded(d) for d in ds]
    with warnings.catch_warnings(record=True) as many:
        warnings.simplefilter("always")
        got = load_scenes(ds)
    assert [str(w.message) for w in many] == [str(w.message) for w in alone] != []
    assert isinstance(got[1], ks.SceneError) and str(got[1]) == str(want[1])
    for g, w in zip(got[:1] + got[2:], want[:1] + want[2:], strict=True):
        same(g, w)


def test_a_resisting_force_with_a_moment_as_load_scene() -> None:
    ds = variants("shaper", 3, seed=3)
    at = [i for i, ld in enumerate(ds[0]["loads"]) if ld.get("when") == "resisting"][0]
    for d in ds:
        d["loads"][at]["moment"] = 0.0
    ds[2]["loads"][at]["moment"] = 5.0
    got = load_scenes(ds)
    assert isinstance(got[2], ks.SceneError) and str(got[2]) == str(_loaded(ds[2]))
    same(got[1], load_scene(ds[1]))
