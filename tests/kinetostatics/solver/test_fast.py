"""The compiled path (kinetostatics.solver.fast) against the numpy path, and its switch.

The two paths are tested against each other, never against themselves: over random
geometry of every dyad kind (RRR, RRT, TRR, TRT, RTR, RTT, TTR) and both drivers (crank,
sliding), every body's motion, every dyad's closeness to a dead centre, every joint
reaction and Me/Fe agree within ``TOL`` of each column's scale, relative to the
conditioning near a dead centre; where the numpy path refuses a scene, the compiled
path refuses it with the same message. Inside the compiled path, solve_many equals
solve bit for bit.
"""

from __future__ import annotations

import copy
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import kinetostatics as ks
from kinetostatics import solve
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.model.scene import load_scene
from kinetostatics.solver.fast import choice, use

numba = pytest.importorskip("numba")

# the tests that run the compiled kernels: a fresh machine compiles them first (about 2
# minutes of processor time for every dyad kind), so they stand in the slow tier; the
# switch's rules that compile nothing stay quick
slow_compile = pytest.mark.slow

DATA = Path(__file__).resolve().parents[2] / "data" / "scenes"
# every dyad kind and both drivers, from the bundled examples and the test scenes
KINDS = {
    "RRR crank": ks.example("four_bar"),
    "RRR sliding driver": ks.example("sliding_driver"),
    "RRT": ks.example("slider_crank"),
    "TRR": DATA / "trr_slider_crank.toml",
    "TRT": DATA / "trt_slotted_crank.toml",
    "RTR": ks.example("slotted_lever"),
    "RTR + RRT (shaper)": ks.example("shaper"),
    "RTT": DATA / "rtt_scotch_yoke.toml",
    "TTR": ks.example("scotch_yoke"),
}
# Measured 2026-11-28, 25 draws per kind at spread 0.15: worst |fast - numpy| over the
# column's scale 6.7e-15 (the shaper), 7e-16 once divided by the conditioning 1/sin^2 tau
# of the closest row to a dead centre (errors grow so near one; the prototype:
# 9e-14 at h^2/b^2 = 5e-4). The issue asks for 1e-12; held here to 1e-13.
TOL = 1e-13


@pytest.fixture
def path():
    """The solve path set for one test, put back after."""
    yield use
    use(None)


def both(scene, positions=None):
    """The numpy path's and the compiled path's Solutions (or exceptions)."""
    out = []
    for p in ("numpy", "fast"):
        use(p)
        try:
            out.append(solve(scene, positions))
        except WorkbenchError as exc:
            out.append(exc)
        finally:
            use(None)
    return out


def columns(sol) -> dict[str, np.ndarray]:
    """Every array behind the tables, by name, over the rows."""
    n = sol.positions.size
    out = {"Me/Fe": sol.drive.value}
    for b, m in sol.kin.bodies.items():
        for f in m.FIELDS:
            out[f"{b}.{f}"] = getattr(m, f)
    for i, d in enumerate(sol.kin.dyads):
        out[f"dyad {i} closeness2"] = d.closeness2
        out[f"dyad {i} sin tau"] = d.sin_tau
    for j, r in sol.joint_reactions.items():
        out[f"{j}.Fx"], out[f"{j}.Fy"] = r.force(n)
        for f in ("N", "M"):
            if getattr(r, f) is not None:
                out[f"{j}.{f}"] = getattr(r, f) * r.sign
    return {k: np.broadcast_to(np.asarray(v, dtype=float), (n,)) for k, v in out.items()}


def conditioning(sol) -> float:
    """1 / sin^2 of the smallest transmission angle over the rows (at least 1)."""
    least = min((float(np.min(d.closeness2)) for d in sol.kin.dyads), default=1.0)
    return 1.0 / min(max(least, 1e-6), 1.0)


# a vector's components: each measured against the vector's scale
PARTNER = {"ox": "oy", "oy": "ox", "vx": "vy", "vy": "vx", "ax": "ay", "ay": "ax",
           "cos": "sin", "sin": "cos", "Fx": "Fy", "Fy": "Fx"}


def scale_of(cols: dict[str, np.ndarray], k: str) -> float:
    """Column ``k``'s scale: its largest |value|, a vector component's the largest of its
    vector's two components. (A component zero but for rounding, a block's vy on a level
    guide, is noise of some 1e-16 of the vector, the paths' own; since the compiled
    path's cos and sin are its own, 2026-11-30, the noise differs from the numpy path's
    and would be all of such a column's own scale: the TRT example's block vy 5.6e-17,
    ay 1.8e-15 at a few rows, against vx 1.6 and ax 45 at most.)"""
    name, _, f = k.rpartition(".")
    other = f"{name}.{PARTNER[f]}" if f in PARTNER else None
    vs = [cols[k]] + ([cols[other]] if other in cols else [])
    return max(float(np.max(np.abs(v), initial=0.0)) for v in vs)


def agree(a, b) -> float:
    """The largest |b - a| over each column's scale (max |a|, a vector component's its
    vector's: :func:`scale_of`), scaled by the conditioning; asserts the columns, the
    undefined rows and the flags are alike."""
    ca, cb = columns(a), columns(b)
    assert ca.keys() == cb.keys()
    worst = 0.0
    for k, x in ca.items():
        scale = scale_of(ca, k)
        if scale == 0.0:
            assert np.array_equal(x, cb[k]), k
            continue
        err = float(np.max(np.abs(cb[k] - x))) / scale
        worst = max(worst, err / conditioning(a))
        assert err <= TOL * conditioning(a), (k, err)
    assert np.array_equal(a.undefined_load, b.undefined_load)
    return worst


def perturbed(source, seed: int, spread: float) -> dict:
    """The scene with every local point, ground point, cog, mass and inertia scaled by
    a factor within 1 +- spread (its assembly hints kept)."""
    d = copy.deepcopy(load_scene(source).raw)
    rng = np.random.default_rng(seed)

    def f() -> float:
        return float(rng.uniform(1 - spread, 1 + spread))
    for b in d["bodies"]:
        b["points"] = {p: [x * f() for x in v] for p, v in b["points"].items()}
        if "cog" in b:
            b["cog"] = [x * f() for x in b["cog"]]
        for key in ("mass", "inertia"):
            if key in b:
                b[key] *= f()
    d["ground"] = {p: [x * f() for x in v] for p, v in d["ground"].items()}
    return d


@slow_compile
@pytest.mark.parametrize("name", list(KINDS))
def test_the_examples_agree(name: str) -> None:
    a, b = both(KINDS[name])
    assert a.path == "numpy" and b.path == "fast"
    agree(a, b)
    # the tables read from either path's arrays
    for t in ("driver", "reactions", "kinematics", "dyads", "bodies"):
        x, y = getattr(a, t), getattr(b, t)
        assert list(x.columns) == list(y.columns)
        assert len(x) == len(y)


@slow_compile
@pytest.mark.parametrize("name", list(KINDS))
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), spread=st.floats(0.0, 0.15))
def test_random_geometry_agrees(name: str, seed: int, spread: float) -> None:
    d = perturbed(KINDS[name], seed, spread)
    a, b = both(d)
    if isinstance(a, Exception):
        # a refusal is the numpy path's, word for word
        assert isinstance(b, type(a)) and str(b) == str(a)
        assume(False)
    assert not isinstance(b, Exception), b
    agree(a, b)


@slow_compile
def test_a_refusal_is_the_numpy_paths() -> None:
    # a crank-rocker whose coupler cannot reach over part of the turn
    d = load_scene(ks.example("four_bar")).raw
    d = copy.deepcopy(d)
    for b in d["bodies"]:
        if b["name"] == "crank":
            b["points"] = {p: [3.0 * x for x in v] for p, v in b["points"].items()}
    a, b = both(d)
    assert isinstance(a, WorkbenchError), a
    assert type(b) is type(a) and str(b) == str(a)


@slow_compile
def test_a_long_sweep_is_lean_and_solved_again_alike() -> None:
    pos = np.linspace(0.0, 360.0, 40_001)[:-1]
    a, b = both(ks.example("four_bar"), pos)
    # lean: Me/Fe and the flags at first, the kinematics solved again when read
    assert b.path == "fast" and "kin" not in b.__dict__
    assert np.abs(b.driver["Me"].to_numpy() - a.driver["Me"].to_numpy()).max() <= (
        TOL * np.abs(a.driver["Me"].to_numpy()).max())
    me = b.Me.copy()
    agree(a, b)                             # (reads the kinematics: solved again)
    assert np.array_equal(b.Me, me)         # the full solve's Me is the lean one's
    assert b.singular.tolist() == a.singular.tolist()


@slow_compile
def test_solve_many_is_solve_bit_for_bit_on_the_compiled_path(path) -> None:
    from kinetostatics.bench.speed import four_bar_variants
    scenes = [load_scene(d) for d in four_bar_variants(40)]
    path("fast")
    many = ks.solve_many(scenes)
    for m, sc in zip(many, scenes, strict=True):
        one = solve(sc)
        assert m.path == one.path == "fast"
        for t in ("driver", "reactions", "kinematics", "dyads"):
            x, y = getattr(m, t), getattr(one, t)
            assert x.equals(y), t


@slow_compile
@pytest.mark.parametrize("name", list(KINDS))
def test_a_stack_of_every_kind_is_each_scenes_solve(path, name: str) -> None:
    """A stack's geometry is a column per scene, each row's scene given to the kernels:
    scenes of unequal lengths (a tile's rows of one scene, tiles cut at each scene's
    end) and a scene's numbers in every row of it, bit for bit as the scene alone."""
    scenes = []
    for seed in range(6):
        d = perturbed(KINDS[name], seed, 0.03)
        d["driver"]["count"] = int(d["driver"]["count"]) - 7 * seed     # 361, 354, ...
        scenes.append(load_scene(d))        # (a resist or "resisting" load stacked too)
    path("fast")
    from kinetostatics.solver.many import CutSolved, solve_all
    assert all(type(a) is CutSolved for a in solve_all(scenes))     # (stacked, not alone)
    many = ks.solve_many(scenes)
    for m, sc in zip(many, scenes, strict=True):
        one = solve(sc)
        assert m.path == one.path == "fast"
        for t in ("driver", "reactions", "kinematics", "dyads"):
            assert getattr(m, t).equals(getattr(one, t)), t
    # a run's, a group's and a scene's calls of a kernel pass the same types: compiled
    # once (a read-only owner array once compiled each fused kernel twice, 7-17 s of
    # processor time each on an empty cache, measured 2026-11-30)
    assert {k: s for k, s in compiled_signatures().items() if len(s) > 1} == {}
    # every helper typed on plain arguments, once for every constant a caller passes (a
    # literal code, each kind's entry's constant, compiled each helper once per kind:
    # measured 2026-11-30, the compiled tests' compiles 216 s of processor time on an
    # empty cache against 151; a literal row or column, outer_param six times, _outer,
    # swept_force, tile_geometry twice: jitbase.PlainArgs). On a warm cache nothing is
    # compiled and this holds as is
    from numba.core.types import Literal
    literal = {k: s for k, s in compiled_signatures(helpers=True).items()
               if any(isinstance(a, Literal) for sig in s for a in sig)}
    assert literal == {}


def compiled_signatures(helpers: bool = False) -> dict[str, list]:
    """The signatures each compiled kernel of the compiled path (a cached entry point,
    not an inlined helper; the module-level inlined helpers instead when ``helpers``)
    has in this process, by name."""
    import importlib

    from numba.core.registry import CPUDispatcher
    out = {}
    for name in ("kernels", "reaction_kernels", "load_kernels", "fused_kernels",
                 "fused_tables", "guide_kernels", "table_kernels", "screen_kernels",
                 "probe_kernels", "closure_kernels", "tail_kernels", "scratch_views", "streams",
                 "jitbase"):
        for v in vars(importlib.import_module(f"kinetostatics.solver.fast.{name}")).values():
            for d in (v.values() if isinstance(v, dict) else [v]):
                if (isinstance(d, CPUDispatcher)
                        and bool(d.targetoptions.get("forceinline")) == helpers):
                    out[f"{name}.{d.py_func.__name__}"] = list(d.signatures)
    return out


@slow_compile
def test_the_switch(path) -> None:
    with pytest.raises(ValueError, match="solve path"):
        path("quick")
    path("numpy")
    assert choice.path_setting() == "numpy" and choice.wanted(10**7) is None
    path("fast")
    assert choice.wanted(1) is not None
    path(None)
    assert choice.path_setting() in choice.PATHS


def _python(code: str, **env) -> subprocess.CompletedProcess:
    full = {**os.environ, **env}
    full.pop("KINETOSTATICS_PATH", None) if "KINETOSTATICS_PATH" not in env else None
    return subprocess.run([sys.executable, "-c", code], env=full, capture_output=True,
                          text=True, check=True)


def test_import_and_a_small_solve_do_not_import_numba() -> None:
    out = _python("import sys, kinetostatics as ks\n"
                  "s = ks.solve(ks.example('four_bar'))\n"
                  "print('numba' in sys.modules, s.path)")
    assert out.stdout.split() == ["False", "numpy"]


@slow_compile
def test_the_environment_variable_forces_a_path() -> None:
    code = "import kinetostatics as ks; print(ks.solve(ks.example('four_bar')).path)"
    # the cache folder the other tests of this file fill (an empty one compiled every
    # kernel again: 25 s of CPU)
    fast = _python(code, KINETOSTATICS_PATH="fast")
    slow = _python(code, KINETOSTATICS_PATH="numpy")
    assert (fast.stdout.strip(), slow.stdout.strip()) == ("fast", "numpy")


def test_no_writable_cache_folder_solves_on_numpy_with_one_warning(tmp_path) -> None:
    locked = tmp_path / "locked"
    locked.write_text("a file, not a folder")
    out = _python("import warnings, sys, kinetostatics as ks\n"
                  "with warnings.catch_warnings(record=True) as w:\n"
                  "    warnings.simplefilter('always')\n"
                  "    p = [ks.solve(ks.example('four_bar')).path for _ in range(3)]\n"
                  "print(p, len([x for x in w if 'cache' in str(x.message)]),"
                  " 'numba' in sys.modules)",
                  KINETOSTATICS_PATH="fast", NUMBA_CACHE_DIR=str(locked / "sub"))
    assert out.stdout.strip() == "['numpy', 'numpy', 'numpy'] 1 False"


def test_the_cache_folder_is_named_by_every_kernel_source(tmp_path, monkeypatch) -> None:
    """numba checks a cached kernel against its own file only: a change to any source of
    the compiled path (an inlined helper's module too) must give another cache folder,
    or the kernel loads stale from the cache."""
    import shutil

    from kinetostatics.solver.fast import loader
    copy_ = tmp_path / "fast"
    shutil.copytree(Path(loader.__file__).parent, copy_,
                    ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(loader, "__file__", str(copy_ / "loader.py"))
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    before = loader.cache_folder()
    assert before is not None and before.parent == tmp_path / "cache" and before.is_dir()
    assert loader.cache_folder() == before                  # the same sources: the same
    helper = copy_ / "jitbase.py"
    helper.write_text(helper.read_text() + "\n# changed\n")
    after = loader.cache_folder()
    assert after != before and after.parent == before.parent
    # a process started by one that loaded the kernels inherits NUMBA_CACHE_DIR set to
    # that version's folder: the same folder, not one nested in it (compiled again)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(after))
    assert loader.cache_folder() == after


def test_without_numba_every_setting_solves_on_numpy(path, monkeypatch) -> None:
    from kinetostatics.solver.fast import loader
    monkeypatch.setattr(loader, "installed", lambda: False)
    monkeypatch.setitem(loader._STATE, "kernels", None)
    monkeypatch.setitem(choice._OPTION, "told", None)
    path("fast")
    with pytest.warns(RuntimeWarning, match="numba is not installed") as seen:
        paths = [solve(ks.example("four_bar")).path for _ in range(3)]
    assert paths == ["numpy"] * 3 and len(seen) == 1


@slow_compile
def test_the_kernels_max_and_min_are_numbas() -> None:
    """jitbase.fmax / fmin (no branch: a loop that calls them still vectorises) give what
    numba's max / min give, signed zeros and NaN included."""
    from kinetostatics.solver.fast import loader
    assert loader.kernels() is not None     # (numba loaded, its cache folder settled)
    from numba import njit

    from kinetostatics.solver.fast.jitbase import fmax, fmin

    @njit
    def pair(a, b):
        return fmax(a, b), fmin(a, b), max(a, b), min(a, b)

    nan = float("nan")
    for a, b in [(-0.0, 0.0), (0.0, -0.0), (nan, 1.0), (1.0, nan), (-1.0, 2.0), (3.0, -4.0),
                 (np.inf, -np.inf), (2.0, 2.0)]:
        ours_max, ours_min, its_max, its_min = pair(a, b)
        for x, y in ((ours_max, its_max), (ours_min, its_min)):
            assert np.array_equal(np.float64(x), np.float64(y), equal_nan=True), (a, b)
            assert np.signbit(x) == np.signbit(y), (a, b)
