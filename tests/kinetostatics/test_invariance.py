"""Metamorphic properties of the kinetostatic solve (issue 18, item 6: a, b, d, e, f).

Each is an invariance the physics guarantees, checked with hypothesis (the derandomized
profile of tests/conftest.py) over mechanisms of every dyad kind (RRR, RRT, TRR, RTR,
TRT, RTT, TTR and a sliding driver: the test scenes of tests/data and the shaper) with
random positions, row spacings, speeds, accelerations, masses and friction:

(a) a permuted ``positions`` list gives the sorted rows and the same summary;
(b) a coarse sweep's rows are the fine sweep's at the shared positions, angles included;
(d) the mirror image (y -> -y for every point, load and the gravity; every angle and a
    crank's speed and acceleration negated) gives the mirrored results;
(e) speed -> 0+ is continuous with speed 0 (with and without joint friction);
(f) all masses, inertias and loads times k scale every force and Me by k.

The worst error measured over the examples is written by each assertion.
"""

from __future__ import annotations

import copy
import tomllib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinetostatics as ks
from tests.helpers import OWN_CASES, SCENES
from tests.kinetostatics import scenes

FILES = sorted(OWN_CASES.glob("*.toml")) + sorted(SCENES.glob("*.toml")) + [
    ks.example("shaper")]
IDS = [p.stem for p in FILES]
EXAMPLES = settings(max_examples=4, deadline=None)


def each_scene(test):
    """A property of every bundled scene (``path``), hypothesis drawing from ``data``
    (four examples a scene)."""
    return pytest.mark.parametrize("path", FILES, ids=IDS)(EXAMPLES(given(data=st.data())(test)))


def raw(path) -> dict:
    with open(path, "rb") as fh:
        d = tomllib.load(fh)
    d.pop("motion", None)
    return d


def sweep(d: dict) -> np.ndarray:
    drv = d["driver"]
    return np.linspace(drv["start"], drv["stop"], drv["count"])


def at(d: dict, positions) -> dict:
    d = copy.deepcopy(d)
    for k in ("start", "stop", "count"):
        d["driver"].pop(k, None)
    d["driver"]["positions"] = [float(p) for p in positions]
    return d


def a_few_rows(d: dict, data) -> dict:
    """The scene at 2 to 9 of its own rows, drawn by hypothesis (in increasing order)."""
    pos = sweep(d)
    idx = sorted(data.draw(st.lists(st.integers(0, pos.size - 1), min_size=2, max_size=9,
                                    unique=True), label="indices"))
    return at(d, pos[idx])


def numbers(sol, table: str) -> np.ndarray:
    """A table's numeric columns (NaN-free offsets: 0 where empty), rows as listed."""
    t = getattr(sol, table).select_dtypes("number").astype(float)
    return t.fillna(0.0).to_numpy()


TABLES = ("driver", "kinematics", "bodies", "reactions", "dyads", "frame", "reduced")


# -- (a) order ------------------------------------------------------------------------------

@each_scene
def test_permuted_positions_give_the_sorted_rows(path, data) -> None:
    d = raw(path)
    pos = sweep(d)
    k = data.draw(st.integers(3, 12), label="rows")
    idx = sorted(data.draw(st.lists(st.integers(0, pos.size - 1), min_size=k, max_size=k,
                                    unique=True), label="indices"))
    perm = data.draw(st.permutations(range(len(idx))), label="order")
    ordered = ks.solve(at(d, pos[idx]))
    mixed = ks.solve(at(d, pos[idx][list(perm)]))
    assert mixed.summary() == ordered.summary()
    n = len(idx)
    for table in TABLES:
        a, b = numbers(mixed, table), numbers(ordered, table)
        rows = np.concatenate([np.asarray(perm) + n * j for j in range(a.shape[0] // n)])
        # measured 0: every row is solved alone, the order only enters the summary and
        # the angles' continuity, both taken along increasing position
        np.testing.assert_array_equal(a, b[rows], err_msg=table)


# -- (b) spacing ----------------------------------------------------------------------------

def random_double_crank(g: float, a: float, b: float, c: float) -> dict:
    """A Grashof double crank (ground g the shortest link): every link turns fully."""
    return scenes.four_bar(a, b, c, g, cogs=([a / 3, 0.0], [b / 2, 0.02], [c / 3, 0.0]),
                           loads=[{"body": "rocker", "moment": -3.0}], near=[g, 10.0])

def random_whitworth(crank: float) -> dict:
    """The bundled slotted lever (RTR) with a crank longer than its pivots' distance
    (0.30 m): the lever turns fully (Whitworth's quick return)."""
    d = raw(ks.example("slotted_lever"))
    d["bodies"][0]["points"]["A"] = [crank, 0.0]
    return d


@st.composite
def turning(draw) -> dict:
    """A random mechanism whose links all turn fully (RRR double crank or RTR
    Whitworth)."""
    if draw(st.booleans()):
        return random_whitworth(draw(st.floats(0.33, 0.6)))
    g = draw(st.floats(0.03, 0.1))
    a, b, c = (draw(st.floats(0.2, 0.45)) for _ in range(3))
    lengths = sorted([a, b, c])
    if g + lengths[2] > lengths[0] + lengths[1] - 0.03:     # keep clear of change points
        b = c = max(a, 0.2)
    return random_double_crank(g, a, b, c)


def check_coarse_rows(d: dict, data) -> None:
    pos = sweep(d)
    fine = ks.solve(at(d, pos))
    stride = data.draw(st.integers(2, max(2, 3 * pos.size // 4)), label="stride")
    offset = data.draw(st.integers(0, stride - 1), label="offset")
    shared = np.arange(offset, pos.size, stride)
    if shared.size < 2:
        shared = np.array([0, pos.size - 1])
    coarse = ks.solve(at(d, pos[shared]))
    n, m = pos.size, shared.size
    for table in TABLES:
        a, b = numbers(coarse, table), numbers(fine, table)
        rows = np.concatenate([shared + n * j for j in range(a.shape[0] // m)])
        if table == "bodies":
            ang = list(getattr(coarse, table).select_dtypes("number").columns).index("angle")
            turn = a[:, ang] - b[rows, ang]
            # the coarse sweep starts its anchor elsewhere: whole turns, the same for
            # every row of a body (measured: 2.8e-14 deg off, the anchor's rounding)
            per_body = turn.reshape(-1, m) / 360.0
            assert 360.0 * np.abs(per_body - np.round(per_body)).max() <= 1e-13
            assert np.all(np.round(per_body) == np.round(per_body[:, :1]))
            a, b = np.delete(a, ang, axis=1), np.delete(b[rows], ang, axis=1)
            rows = np.arange(a.shape[0])
        np.testing.assert_array_equal(a, b[rows], err_msg=table)    # measured 0
    # the driver's flags: a row flagged in the fine sweep stays flagged (a dead point
    # between two fine rows lies between the coarse ones too); a coarse row may add a
    # flag only for a dead point between it and a coarse neighbour (the fine sweep flags
    # a row there) or, at an end, within one coarse spacing beyond the sweep
    fc, ff = coarse.driver, fine.driver
    np.testing.assert_array_equal(fc.undefined_load.to_numpy(),
                                  ff.undefined_load.to_numpy()[shared])
    sc, sf = fc.singular.to_numpy(), ff.singular.to_numpy()
    assert np.all(sc >= sf[shared]), "a fine sweep's singular row lost its flag"
    for k in np.flatnonzero(sc & ~sf[shared]):
        if 0 < k < m - 1:
            assert sf[shared[k - 1]:shared[k + 1] + 1].any(), f"row {shared[k]} flagged"


@each_scene
def test_coarse_rows_are_the_fine_rows(path, data) -> None:
    check_coarse_rows(raw(path), data)


@settings(max_examples=12, deadline=None)
@given(mech=turning(), data=st.data())
def test_coarse_rows_of_fully_turning_links_are_the_fine_rows(mech, data) -> None:
    """Rows up to 270 deg apart on links that turn fully: the nearest value would be
    wrong by whole turns (seen to fail so)."""
    check_coarse_rows(mech, data)


# -- (d) mirror -----------------------------------------------------------------------------

def mirrored(d: dict) -> dict:
    """y -> -y for every point, hint, load and the gravity; every angle negated."""
    m = copy.deepcopy(d)

    def flip(p: list) -> list:
        return [p[0], -p[1]]

    m["gravity"] = flip(m.get("gravity", [0.0, 0.0]))
    m["ground"] = {k: flip(v) for k, v in m["ground"].items()}
    m["near"] = {k: flip(v) for k, v in m.get("near", {}).items()}
    for b in m["bodies"]:
        b["points"] = {k: flip(v) for k, v in b["points"].items()}
        if "cog" in b:
            b["cog"] = flip(b["cog"])
    for j in m["joints"]:
        if "line_angle" in j:
            j["line_angle"] = -j["line_angle"]
    for ld in m.get("loads", []):
        if "force" in ld:
            ld["force"] = flip(ld["force"])
        if "moment" in ld:
            ld["moment"] = -ld["moment"]
    drv = m["driver"]
    if m["joints"][[j["name"] for j in m["joints"]].index(drv["joint"])]["kind"] == "R":
        drv["positions"] = [-p for p in drv["positions"]]
        drv["speed"] = -drv["speed"]
        drv["acceleration"] = -drv.get("acceleration", 0.0)
    return m


@each_scene
def test_the_mirror_image_gives_mirrored_results(path, data) -> None:
    d = a_few_rows(raw(path), data)
    d["driver"]["speed"] = data.draw(st.floats(-50.0, 50.0).filter(lambda w: abs(w) > 0.1))
    d["driver"]["acceleration"] = data.draw(st.floats(-100.0, 100.0))
    sol, mir = ks.solve(d), ks.solve(mirrored(d))
    rot = sol.scene.driver.kind == "R"

    def close(a, b, what):
        scale = max(float(np.abs(a).max()), 1e-300)
        # measured 0 (every sign flip is exact in floating point)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-15 * scale, err_msg=what)

    k, km = sol.kinematics, mir.kinematics
    for c, s in (("x", 1), ("y", -1), ("vx", 1), ("vy", -1), ("ax", 1), ("ay", -1)):
        close(km[c].to_numpy(), s * k[c].to_numpy(), c)
    b, bm = sol.bodies, mir.bodies
    for c in ("omega", "alpha"):
        close(bm[c].to_numpy(), -b[c].to_numpy(), c)
    turns = (bm.angle.to_numpy() + b.angle.to_numpy()) / 360.0
    assert np.abs(turns - np.round(turns)).max() < 3e-16    # measured 7.9e-17 turn
    r, rm = sol.reactions, mir.reactions
    for c, s in (("Fx", 1), ("Fy", -1), ("N", -1), ("M", -1)):
        close(rm[c].to_numpy(), s * r[c].to_numpy(), c)
    q = sol.driver_quantity
    close(mir.driver[q].to_numpy(), (-1 if rot else 1) * sol.driver[q].to_numpy(), q)
    assert mir.driver.singular.tolist() == sol.driver.singular.tolist()


# -- (e) rest -------------------------------------------------------------------------------

@each_scene
def test_speed_to_zero_is_continuous_with_rest(path, data) -> None:
    d = a_few_rows(raw(path), data)
    # a resist load (or one on the working stroke only) has no direction at rest
    # (scene-format: flagged, zero): leave them out
    d["loads"] = [ld for ld in d.get("loads", []) if "resist" not in ld and "when" not in ld]
    acc = data.draw(st.sampled_from([-1.0, 1.0])) * data.draw(st.floats(1.0, 500.0))
    mu = data.draw(st.sampled_from([0.05, 0.2]), label="mu")
    for scene in (d, scenes.with_friction(d, mu)):
        scene["driver"]["acceleration"] = acc
        scene["driver"]["speed"] = 0.0
        rest = ks.solve(scene)
        w = 1e-7
        scene["driver"]["speed"] = w * np.sign(acc)       # from the side the motion starts
        moving = ks.solve(scene)
        undefined = rest.driver.undefined_load.to_numpy()
        # at rest friction has a direction wherever the motion about to start has one
        assert undefined.tolist() == moving.driver.undefined_load.tolist()
        ok = ~undefined
        if rest.self_locking is not None:
            ok &= ~rest.driver.self_locking.to_numpy() & ~moving.driver.self_locking.to_numpy()
        a, b = np.asarray(rest.Me)[ok], np.asarray(moving.Me)[ok]
        scale = max(float(np.abs(a).max(initial=0.0)), 1e-300)
        # measured 6.6e-16 of the largest |Me|, plus the terms in speed^2, which are about
        # w^2 / |acc| of the others: 3.0e-15 on the shaper with friction at acc = -1 (rows 0
        # and 230), growing 4x when w doubles
        np.testing.assert_allclose(a, b, rtol=0, atol=(3e-15 + w * w / abs(acc)) * scale)
        fr, fm = rest.reactions.F.to_numpy(), moving.reactions.F.to_numpy()
        rows = np.tile(ok, fr.size // ok.size)
        np.testing.assert_allclose(fr[rows], fm[rows], rtol=0,      # measured 6.5e-16
                                   atol=3e-15 * max(float(fr[rows].max(initial=0.0)), 1e-300))


# -- (f) mass scale -------------------------------------------------------------------------

@each_scene
def test_masses_times_k_scale_forces_by_k(path, data) -> None:
    d = a_few_rows(raw(path), data)
    mu = data.draw(st.sampled_from([0.0, 0.1]), label="mu")
    if mu:
        d = scenes.with_friction(d, mu)
    k = 10.0 ** data.draw(st.floats(-3.0, 3.0), label="log10 k")
    e = copy.deepcopy(d)
    e["checks"] = {"quiet": ["mass"]}     # up to 1000 x the masses: an extreme scene, meant
    for b in e["bodies"]:
        b["mass"] = k * b.get("mass", 0.0)
        b["inertia"] = k * b.get("inertia", 0.0)
    for ld in e.get("loads", []):
        for key in ("force", "moment", "resist"):
            if key in ld:
                ld[key] = (np.asarray(ld[key]) * k).tolist()
    sol, big = ks.solve(d), ks.solve(e)

    def scaled(a, b, what):
        a, b = np.nan_to_num(a), np.nan_to_num(b)
        # measured 6.4e-16 of the largest value (friction included), 4.5e-15 on the
        # oscillating cylinder's draw (k * mass rounded: a few ulps times its conditioning)
        np.testing.assert_allclose(b, k * a, rtol=0,
                                   atol=1e-14 * k * max(float(np.abs(a).max()), 1e-300),
                                   err_msg=what)

    scaled(np.asarray(sol.Me), np.asarray(big.Me), "Me")
    for c in ("Fx", "Fy", "N", "M"):
        scaled(sol.reactions[c].to_numpy(), big.reactions[c].to_numpy(), c)
    if mu:
        assert big.driver.self_locking.tolist() == sol.driver.self_locking.tolist()
    for c in ("M_red" if sol.scene.driver.kind == "R" else "F_red", ):
        scaled(sol.reduced[c].to_numpy(), big.reduced[c].to_numpy(), c)
