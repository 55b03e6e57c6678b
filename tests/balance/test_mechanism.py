"""Static balancing of mechanisms (seed 002 s. 3.4): balance.mechanism and its plots."""

from __future__ import annotations

import copy
import json
import math

import matplotlib.pyplot as plt
import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import balance
import kinetostatics as ks
from balance.errors import BalanceError
from balance.mechanism import (
    balanced_scene,
    centre_of_mass,
    h_vectors,
    harmonic_amplitude,
    shaking_force,
    shaking_tables,
    solve_mechanism_balancing,
)
from balance.mechanism import plot as mp
from kinetostatics.model.errors import WorkbenchError

FOUR_BAR_CW = [{"body": "crank", "about": "A", "radius": 0.06},
               {"body": "rocker", "about": "D", "radius": 0.08}]
CRANK_CW = [{"body": "crank", "about": "A", "radius": 0.10}]
SLIDER_FULL_CW = [{"body": "rod", "about": "B", "radius": 0.10}, *CRANK_CW]


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def raw(name: str, **balancing) -> dict:
    r = copy.deepcopy(ks.load_scene(ks.example(name)).raw)
    if balancing:
        r["balancing"] = balancing
    return r


def uniform(r: dict, n: int = 360) -> dict:
    """The scene swept over a full turn of n uniform positions, endpoint excluded."""
    r = copy.deepcopy(r)
    r["driver"].update(start=0.0, stop=360.0 - 360.0 / n, count=n)
    return r


def drift(res) -> float:
    c = res.centre_of_mass()
    return float(np.hypot(c["x"] - c["x"].mean(), c["y"] - c["y"].mean()).max())


def harmonic_x(tab, k=1) -> float:
    return harmonic_amplitude(tab["Fx"].to_numpy(), k)


# -- four-bar ----------------------------------------------------------------------------

def test_four_bar_full_example_centre_fixed():
    res = solve_mechanism_balancing(raw("four_bar", method="full", counterweights=FOUR_BAR_CW))
    assert res.kind == "four-bar" and "linearly independent" in res.procedure  # coupler cog off BC
    assert drift(res) < 1e-12 * 0.30
    assert res.checks["centre_of_mass_drift_after"] < 1e-12 * 0.30
    assert res.shaking_force_after < 1e-12 * res.shaking_force_before
    d = res.to_dict()
    for cw, spec in zip(d["counterweights"], FOUR_BAR_CW, strict=True):
        assert set(cw) >= {"body", "about", "mass", "position"}
        assert cw["body"] == spec["body"] and cw["mass"] > 0
        about = res.scene.bodies[cw["body"]].points[cw["about"]]
        assert math.dist(cw["position"], about) == pytest.approx(spec["radius"], rel=1e-12)
        assert 0.0 <= cw["angle"] < 360.0
    json.dumps(d)


def on_line_four_bar() -> dict:
    r = raw("four_bar")
    for b in r["bodies"]:
        if b["name"] == "coupler":
            b["cog"] = [0.10, 0.0]
    return r


def test_four_bar_seed_closed_form_339_341():
    r = on_line_four_bar()
    res = solve_mechanism_balancing(r, method="full", counterweights=FOUR_BAR_CW)
    assert res.procedure.startswith("eqs 3.38-3.41")
    m1, m2, m3 = 1.2, 2.0, 1.6
    l1, l2, l3, lad = 0.10, 0.25, 0.20, 0.30
    s1, s2, s3 = 0.05, 0.10, 0.20 - 0.10          # s3 from C, as in fig. 3.18
    mA, mB = m1 * (l1 - s1) / l1, m1 * s1 / l1 + m2 * (l2 - s2) / l2          # eq. 3.38
    mC, mD = m2 * s2 / l2 + m3 * (l3 - s3) / l3, m3 * s3 / l3
    me1, me3 = mB * l1 / 0.06, mC * l3 / 0.08                                 # eq. 3.39
    crank, rocker = res.counterweights
    assert crank.mass == pytest.approx(me1, rel=1e-12)
    assert rocker.mass == pytest.approx(me3, rel=1e-12)
    assert crank.position == pytest.approx((-0.06, 0.0), abs=1e-15)   # on AB's extension
    assert rocker.position == pytest.approx((-0.08, 0.0), abs=1e-15)
    assert res.masses == pytest.approx({"m_A": mA, "m_B": mB, "m_C": mC, "m_D": mD}, rel=1e-12)
    AG = lad * (mD + mC + me3) / (mA + mB + mC + mD + me1 + me3)               # eq. 3.41
    assert res.centre == pytest.approx((AG, 0.0), abs=1e-12)
    assert drift(res) < 1e-12 * lad


def test_four_bar_about_other_point():
    """A crank counterweight measured from B (any body point): still balanced."""
    cws = [{"body": "crank", "about": "B", "radius": 0.25}, FOUR_BAR_CW[1]]
    res = solve_mechanism_balancing(raw("four_bar", method="full", counterweights=cws))
    cw = res.counterweights[0]
    assert math.dist(cw.position, (0.10, 0.0)) == pytest.approx(0.25, rel=1e-12)
    assert drift(res) < 1e-12 * 0.30


@st.composite
def four_bars(draw):
    a = draw(st.floats(0.04, 0.10))
    b, c, d = (draw(st.floats(0.18, 0.40)) for _ in range(3))
    assume(a + max(b, c, d) < b + c + d - max(b, c, d) - 0.06)   # Grashof crank, margin
    g1 = draw(st.floats(0.0, 2 * math.pi))                     # local frames at any angle
    g2 = draw(st.floats(0.0, 2 * math.pi))
    cog = st.floats(-0.15, 0.15)
    bodies = [
        {"name": "crank", "mass": draw(st.floats(0.2, 3.0)), "inertia": 0.01,
         "cog": [draw(cog), draw(cog)],
         "points": {"A": [0.0, 0.0], "B": [a * math.cos(g1), a * math.sin(g1)]}},
        {"name": "coupler", "mass": draw(st.floats(0.2, 3.0)), "inertia": 0.02,
         "cog": [draw(cog), draw(cog)],
         "points": {"B": [0.01, -0.02], "C": [0.01 + b * math.cos(g2),
                                               -0.02 + b * math.sin(g2)]}},
        {"name": "rocker", "mass": draw(st.floats(0.2, 3.0)), "inertia": 0.01,
         "cog": [draw(cog), draw(cog)], "points": {"D": [0.0, 0.0], "C": [c, 0.0]}},
    ]
    return {
        "ground": {"A": [0.0, 0.0], "D": [d, 0.0]},
        "driver": {"body": "crank", "joint": "A", "speed": draw(st.floats(5.0, 50.0)),
                   "acceleration": draw(st.floats(-20.0, 20.0)),
                   "start": 0.0, "stop": 360.0, "count": 73},
        "bodies": bodies,
        "joints": [{"name": "A", "kind": "R", "bodies": ["ground", "crank"]},
                   {"name": "B", "kind": "R", "bodies": ["crank", "coupler"]},
                   {"name": "C", "kind": "R", "bodies": ["coupler", "rocker"]},
                   {"name": "D", "kind": "R", "bodies": ["ground", "rocker"]}],
        "near": {"C": [d, 0.5 * c]},
        "balancing": {"method": "full", "counterweights": [
            {"body": "crank", "about": "A", "radius": draw(st.floats(0.02, 0.2))},
            {"body": "rocker", "about": "D", "radius": draw(st.floats(0.02, 0.2))}]},
    }


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(four_bars())
def test_four_bar_random_cogs_off_lines(scene):
    res = solve_mechanism_balancing(scene)
    size = scene["ground"]["D"][0]
    assert drift(res) < 1e-12 * size
    assert res.shaking_force_after <= 1e-9 * max(res.shaking_force_before, 1e-300)


# -- slider-crank ------------------------------------------------------------------------

def test_slider_crank_full_342_345():
    res = solve_mechanism_balancing(raw("slider_crank", method="full",
                                        counterweights=SLIDER_FULL_CW))
    m1, m2, m3, l1, l2, s1, s2 = 6.0, 4.0, 3.0, 0.150, 0.350, 0.04, 0.12
    mC = m3 + m2 * s2 / l2                                      # eq. 3.42
    me2 = mC * l2 / 0.10                                        # eq. 3.45
    me1 = (mC * l2 / 0.10 + m1 * s1 / l1 + m2 + m3) * l1 / 0.10
    rod, crank = res.counterweights
    assert (rod.body, crank.body) == ("rod", "crank")
    assert rod.mass == pytest.approx(me2, rel=1e-12)
    assert crank.mass == pytest.approx(me1, rel=1e-12)
    assert drift(res) < 1e-12 * l2
    assert res.centre == pytest.approx((0.0, 0.0), abs=1e-12)     # at A
    assert res.shaking_force_after < 1e-12 * res.shaking_force_before


def test_first_harmonic_vanishes_and_partial_fraction():
    sc = uniform(raw("slider_crank"))
    w = sc["driver"]["speed"]
    mC, r = 3.0 + 4.0 * 0.12 / 0.35, 0.150
    first = solve_mechanism_balancing(sc, method="first-harmonic", counterweights=CRANK_CW)
    before = harmonic_x(first.before)
    assert before > 1e3
    assert harmonic_x(first.after) < 1e-12 * before                     # FFT, 360 positions
    # the unbalance moves across the line (s. 3.4.2): first harmonic of Fy = m_C r w^2
    assert harmonic_amplitude(first.after["Fy"].to_numpy()) == pytest.approx(mC * r * w * w,
                                                                             rel=1e-9)
    assert first.A1 == 1.0
    assert first.counterweights[0].mass == pytest.approx(
        (1.6 + 4.0 * 0.23 / 0.35 + mC) * r / 0.10, rel=1e-12)          # (3.51 corrected)
    # the higher harmonics are untouched
    assert harmonic_x(first.after, 2) == pytest.approx(harmonic_x(first.before, 2), rel=1e-9)
    for f in (0.0, 0.5, 2.0 / 3.0):
        part = solve_mechanism_balancing(sc, method="partial", counterweights=CRANK_CW,
                                         fraction=f)
        assert harmonic_x(part.after) == pytest.approx((1.0 - f) * mC * r * w * w, rel=1e-9)
        assert harmonic_amplitude(part.after["Fy"].to_numpy()) == pytest.approx(
            f * mC * r * w * w, rel=1e-9, abs=1e-9 * before)
    part0 = solve_mechanism_balancing(sc, method="partial", counterweights=CRANK_CW)
    mB = 6.0 * 0.04 / 0.15 + 4.0 * 0.23 / 0.35
    assert part0.counterweights[0].mass == pytest.approx(mB * r / 0.10, rel=1e-12)   # 3.47


def test_counter_rotating_pair_contract_and_harmonics():
    sc = uniform(raw("slider_crank"))
    res = solve_mechanism_balancing(sc, method="counter-rotating", counterweights=CRANK_CW,
                                    pair_radius=0.08)
    d = balance.solve(dict(sc, balancing={"method": "counter-rotating",
                                          "counterweights": CRANK_CW,
                                          "pair_radius": 0.08}))["balancing"]
    assert {"counterweights", "counter_rotating", "shaking_force_before",
            "shaking_force_after"} <= set(d)
    assert set(d["counter_rotating"]) >= {"mass", "radius"}
    mC = 3.0 + 4.0 * 0.12 / 0.35
    assert d["counter_rotating"]["mass"] == pytest.approx(mC * 0.150 * 1.0 / (2 * 0.08),
                                                          rel=1e-12)      # eq. 3.53
    assert d["counter_rotating"]["radius"] == 0.08
    assert 0.0 <= d["counter_rotating"]["co_angle"] < 360.0
    before = harmonic_x(res.before)
    for c in ("Fx", "Fy"):      # the first harmonic vanishes in both directions
        assert harmonic_amplitude(res.after[c].to_numpy()) < 1e-12 * before
    assert d["shaking_force_after"] < d["shaking_force_before"]
    json.dumps(d)


@pytest.mark.parametrize("offset, angle", [(0.0, 30.0), (0.05, 0.0), (-0.04, 110.0)])
def test_inclined_and_offset_lines(offset, angle):
    """The first harmonic along the slider's line vanishes for any line direction and for
    an offset slider-crank (A1 and its phase from the Fourier series)."""
    sc = uniform(raw("slider_crank"))
    t = math.radians(angle)
    sc["ground"]["O"] = [-offset * math.sin(t), offset * math.cos(t)]
    sc["near"] = {"C": [0.5 * math.cos(t), 0.5 * math.sin(t)]}
    for j in sc["joints"]:
        if j["kind"] == "T":
            j["line_angle"] = angle
    u = np.array([math.cos(t), math.sin(t)])
    for method in ("first-harmonic", "counter-rotating", "full"):
        cws = SLIDER_FULL_CW if method == "full" else CRANK_CW
        res = solve_mechanism_balancing(sc, method=method, counterweights=cws)
        fa = res.after[["Fx", "Fy"]].to_numpy() @ u
        fb = res.before[["Fx", "Fy"]].to_numpy() @ u
        assert harmonic_amplitude(fa) < 1e-11 * harmonic_amplitude(fb)
        assert res.checks["first_harmonic_after"] < 1e-11 * res.checks["first_harmonic_before"]
    if offset:
        fh = solve_mechanism_balancing(sc, method="first-harmonic", counterweights=CRANK_CW)
        assert fh.A1 != pytest.approx(1.0, abs=1e-6) and "offset" in fh.procedure


# -- tables: centre of mass, h vectors, shaking force against kinetostatics ---------------

@pytest.mark.parametrize("name, cws", [("four_bar", FOUR_BAR_CW),
                                       ("slider_crank", SLIDER_FULL_CW)])
def test_tables_agree_with_kinetostatics_frame(name, cws):
    """Before and after: the shaking force and moment equal the force and moment that
    kinetostatics finds on the frame, without loads and gravity (an independent path)."""
    res = solve_mechanism_balancing(raw(name, method="full", counterweights=cws))

    def bare(r):
        r = copy.deepcopy(r)
        r.pop("loads", None)
        r.pop("balancing", None)
        r["gravity"] = [0.0, 0.0]
        return r

    tabs = shaking_tables(res)
    for tab, scene in ((tabs["before"], bare(res.scene.raw)), (tabs["after"],
                                                                bare(balanced_scene(res)))):
        frame = ks.solve(scene).frame
        scale = res.shaking_force_before
        for c in ("Fx", "Fy"):
            np.testing.assert_allclose(tab[c], frame[c], rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(tab["M"], frame["M"], rtol=0,
                                   atol=1e-12 * max(tab["M"].abs().max(), 1.0))
    assert list(tabs["before"].columns) == ["position", "Fx", "Fy", "F", "M"]


def test_centre_of_mass_and_h_vectors_337():
    sol = ks.solve(ks.example("four_bar"))
    com = centre_of_mass(sol)
    assert com["mass"].iloc[0] == pytest.approx(4.8)
    h = h_vectors(sol)
    total = h.groupby("position", sort=False)[["hx", "hy"]].sum()
    np.testing.assert_allclose(total["hx"].to_numpy(), com["x"].to_numpy(), atol=1e-15)  # A = 0
    np.testing.assert_allclose(total["hy"].to_numpy(), com["y"].to_numpy(), atol=1e-15)
    for _, g in h.groupby("body"):                         # constant length (s. 3.4)
        assert np.ptp(g["h"].to_numpy()) < 1e-15
    # the shaking force is -m a_G of the whole mechanism
    f = shaking_force(sol)
    np.testing.assert_allclose(f["Fx"], -4.8 * com["ax"], atol=1e-10)


# -- errors ------------------------------------------------------------------------------

@pytest.mark.parametrize("name, balancing, match", [
    ("four_bar", {"method": "full", "counterweights": [
        {"body": "cranck", "about": "A", "radius": 0.06}, FOUR_BAR_CW[1]]}, "unknown body"),
    ("four_bar", {"method": "partial", "counterweights": CRANK_CW}, "slider-crank"),
    ("four_bar", {"method": "full", "counterweights": [
        {"body": "crank", "about": "A", "radius": 0.0}, FOUR_BAR_CW[1]]}, "positive"),
    ("four_bar", {"method": "full", "counterweights": [
        {"body": "crank", "about": "A", "radius": -0.1}, FOUR_BAR_CW[1]]}, "positive"),
    ("four_bar", {"method": "full", "counterweights": FOUR_BAR_CW[:1]}, "missing"),
    ("four_bar", {"method": "full", "counterweights": [
        *FOUR_BAR_CW, {"body": "coupler", "about": "B", "radius": 0.1}]}, "coupler"),
    ("four_bar", {"method": "full", "counterweights": [
        {"body": "crank", "about": "Q", "radius": 0.06}, FOUR_BAR_CW[1]]}, "no point"),
    ("four_bar", {"method": "ful", "counterweights": FOUR_BAR_CW}, "did you mean 'full'"),
    ("four_bar", {"method": "full", "counterweights": FOUR_BAR_CW, "fraction": 0.5},
     "partial"),
    ("slider_crank", {"method": "full", "counterweights": CRANK_CW}, "rod"),
    ("slider_crank", {"method": "partial", "counterweights": CRANK_CW, "fraction": 1.5},
     r"\[0, 1\]"),
    ("slotted_lever", {"method": "full", "counterweights": CRANK_CW}, "neither"),
    ("sliding_driver", {"method": "full", "counterweights": CRANK_CW}, "crank driver"),
])
def test_bad_input_one_line(name, balancing, match):
    with pytest.raises(WorkbenchError, match=match) as exc:
        solve_mechanism_balancing(raw(name, **balancing))
    assert "\n" not in str(exc.value)
    with pytest.raises(ValueError):
        balance.solve(raw(name, **balancing))


def test_massless_mechanism_refused():
    r = raw("four_bar", method="full", counterweights=FOUR_BAR_CW)
    for b in r["bodies"]:
        b["mass"] = 0.0
    with pytest.raises(BalanceError, match="no mass"):
        solve_mechanism_balancing(r)


def test_no_balancing_table():
    with pytest.raises(BalanceError, match="no \\[balancing\\]"):
        solve_mechanism_balancing(raw("four_bar"))


def test_balance_solve_contract_keys():
    out = balance.solve(raw("four_bar", method="full", counterweights=FOUR_BAR_CW))
    d = out["balancing"]
    assert {"counterweights", "shaking_force_before", "shaking_force_after"} <= set(d)
    assert [c["body"] for c in d["counterweights"]] == ["crank", "rocker"]
    assert all(set(c) >= {"body", "about", "mass", "position"} for c in d["counterweights"])
    assert d["shaking_force_after"] < 1e-9 * d["shaking_force_before"]
    json.dumps(out)


# -- plots -------------------------------------------------------------------------------

def labelled(ax: Axes) -> None:
    assert isinstance(ax, Axes) and isinstance(ax.figure, Figure)
    assert ax.get_xlabel() and ax.get_ylabel() and ax.get_title()
    assert "(" in ax.get_xlabel() and "(" in ax.get_ylabel()


@pytest.mark.slow     # every picture of a balancing (1.5 s)
def test_plots(tmp_path):
    res = solve_mechanism_balancing(raw("slider_crank", method="counter-rotating",
                                        counterweights=CRANK_CW))
    ax = mp.plot_shaking_hodograph(res)
    labelled(ax)
    assert ax.get_aspect() == 1.0
    labelled(mp.plot_centre_of_mass(res))
    labelled(mp.plot_counterweights(res, position=60.0))
    fig = mp.plot_shaking_force(res)
    assert isinstance(fig, Figure)
    for a in fig.axes:
        assert a.get_ylabel()
    assert "(deg)" in fig.axes[-1].get_xlabel()
    fig = mp.overview(solve_mechanism_balancing(raw("four_bar", method="full",
                                                    counterweights=FOUR_BAR_CW)))
    fig.savefig(tmp_path / "overview.png", dpi=60)
    assert (tmp_path / "overview.png").stat().st_size > 1000
