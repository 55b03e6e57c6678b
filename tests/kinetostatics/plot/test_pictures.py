"""The course's pictures: each draws the computed vectors it claims, returns a Figure or
Axes without ``plt.show``, and no two of its labels overlap (nor leave the figure)."""

from __future__ import annotations

import math

import matplotlib as mpl
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import kinetostatics as ks
from kinetostatics import plot as kp
from kinetostatics.cams import optimal_offset, solve_cam
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.model.examples import cam_examples, example
from kinetostatics.plot.cli import cli_figures
from kinetostatics.plot.notation import reading

from .conftest import PICTURE_SCENES, picture_positions

NAMES = ks.examples()


@pytest.fixture(scope="module")
def sols():
    return {n: ks.solve(ks.example(n)) for n in NAMES}


@pytest.fixture(autouse=True)
def _no_show(monkeypatch):
    monkeypatch.setattr(plt, "show", lambda *a, **k: pytest.fail("plt.show called"))
    yield
    plt.close("all")


def cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def clear(fig: Figure) -> None:
    """No two labels of the figure overlap, none is cut by its edge."""
    assert isinstance(fig, Figure)
    hits = kp.overlapping_texts(fig)
    assert not hits, hits


def test_overlap_check_sees_overlaps():
    fig, ax = plt.subplots()
    ax.text(0.5, 0.5, "first label")
    ax.text(0.5, 0.5, "second label")
    assert ("first label", "second label") in kp.overlapping_texts(fig)
    fig2, ax2 = plt.subplots()
    ax2.set_title("x" * 400)
    assert ("x" * 400, "outside the figure") in kp.overlapping_texts(fig2)


def test_declutter_separates_labels():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    texts = [ax.annotate(f"label {k}", (0.5, 0.5), xytext=(3, 3), textcoords="offset points")
             for k in range(4)]
    assert kp.overlapping_texts(fig)
    kp.declutter(ax, texts)
    assert not kp.overlapping_texts(fig)


@pytest.mark.parametrize("name", PICTURE_SCENES)
def test_every_new_picture_is_drawn(name, lecture_figures):
    """Every figure of ``solve --plot`` (overview, Me, polar diagrams, mechanism with
    loads, plans, instantaneous centres, free-body diagrams with their polygons) is a
    Figure. Drawn once per session in the command line's lecture style and shared:
    test_collisions measures the same figures (no overlap, no label on a line, no legend
    on data), the force polygons alone are checked in test_plot."""
    sol, pos, figs = lecture_figures(name)
    unit = "deg" if sol.scene.driver.kind == "R" else "m"
    expect = {"overview", "driver", *(f"polar_{j}" for j in sol.scene.joints)}
    tags = {}
    for p in picture_positions(sol, name):        # (a scene of test_cli.py's at two)
        tag = f"{p:g}{unit}".replace("-", "m").replace(".", "p")
        tags[tag] = f"at φ = {p:g}°" if unit == "deg" else f"at s = {p:g} m"
        expect |= {f"mechanism_{tag}", f"velocity_plan_{tag}", f"acceleration_plan_{tag}",
                   f"instant_centres_{tag}", f"free_body_{tag}_driver",
                   *(f"free_body_{tag}_dyad{d}" for d in range(1, len(sol.kin.dyads) + 1))}
    assert set(figs) == expect
    for stem, fig in figs.items():
        assert isinstance(fig, Figure), stem
        assert fig.axes and all(ax.lines or ax.patches for ax in fig.axes), stem
        for tag, where in tags.items():     # a picture of one position says which
            if f"_{tag}" in stem:
                assert any(where in ax.get_title() for ax in fig.axes), stem
    tag = next(iter(tags))
    # what they draw is the solution's: Me over the sweep, each joint's reaction (on the
    # body its polar diagram names), the mechanism through every point at the position
    # (measured: equal to the last bit)
    me = [ln.get_ydata() for ln in figs["driver"].axes[0].lines]
    assert any(np.array_equal(y, sol.Me) for y in me)
    r = sol.reactions
    for j in sol.scene.joints:
        drawn = [np.column_stack([ln.get_xdata(), ln.get_ydata()]).astype(float)
                 for ln in figs[f"polar_{j}"].axes[0].lines]
        on = [g[["Fx", "Fy"]].to_numpy() for _, g in r[r.joint == j].groupby("on",
                                                                          observed=True)]
        # (a reaction constant over the cycle is drawn as its first row's point)
        assert any(np.array_equal(d, f) or (len(d) == 1 and np.array_equal(d[0], f[0]) and
                                            np.ptp(f, axis=0).max() <= 1e-9 * abs(f).max())
                   for d in drawn for f in on), j
    lines = figs[f"mechanism_{tag}"].axes[0].lines
    verts = np.concatenate([np.column_stack([ln.get_xdata(), ln.get_ydata()]).astype(float)
                            for ln in lines])
    k = sol.kinematics
    points = k.loc[k.position == pos, ["x", "y"]].to_numpy()
    assert len(points) >= len(sol.scene.joints)
    for p in points:
        assert np.hypot(*(verts - p).T).min() <= 1e-12 * sol.scene.size, p


# the default style (no lecture_style: what a script calling the pictures gets), on one
# scene of each driver kind; the command line's style is measured on every scene
@pytest.mark.slow
@pytest.mark.parametrize("name", ["four_bar", "sliding_driver"])
def test_every_new_picture_is_clear_in_the_default_style(name, sols):
    sol = sols[name]
    pos = float(sol.positions[len(sol.positions) // 7])
    for stem, fig in cli_figures(sol, [pos]).items():
        assert isinstance(fig, Figure), stem
        clear(fig)
        plt.close(fig)


def _arrows(ax: Axes, color: str) -> list[tuple[np.ndarray, np.ndarray]]:
    """(tail, tip) of the annotation arrows of one colour."""
    rgba = mpl.colors.to_rgba(color)
    return [(np.asarray(t.xyann, float), np.asarray(t.xy, float)) for t in ax.texts
            if t.arrow_patch is not None and
            np.allclose(t.arrow_patch.get_edgecolor()[:3], rgba[:3])]


def test_four_bar_acceleration_plan_closes_from_both_sides(sols):
    """a_C = a_B + a_CB^n + a_CB^t (from b) and a_C = a_D + a_CD^n + a_CD^t (from pi):
    both tangential components end at the computed a_C."""
    sol = sols["four_bar"]
    i = 40
    ax = kp.acceleration_plan(sol, row=i)
    k = sol.kinematics
    c = k[(k.body == "rocker") & (k.point == "C")].iloc[i]
    b = k[(k.body == "crank") & (k.point == "B")].iloc[i]
    a_c = np.array([c.ax, c.ay])
    scale = float(np.hypot(*a_c))
    near = 1e-15 * scale            # measured: the sides close to 2.1e-16 relative
    tangential = _arrows(ax, "tab:cyan")
    ends_at_c = [tail for tail, tip in tangential if np.hypot(*(tip - a_c)) <= near]
    normal = _arrows(ax, "tab:olive")
    starts = [n_tail for t in ends_at_c for n_tail, n_tip in normal
              if np.hypot(*(n_tip - t)) <= near]
    # one side starts at b, the other at the pole
    assert len(ends_at_c) == 2 and len(starts) == 2
    assert any(np.hypot(*(s - (b.ax, b.ay))) <= near for s in starts)
    assert any(np.hypot(*s) <= near for s in starts)
    clear(ax.figure)


def test_slotted_lever_plan_closes_through_coriolis(sols):
    """a_A(block) = a_A3(lever) + 2 omega x v_rel + a_rel: the Coriolis arrow starts at
    the lever's coincident point, the relative one ends at the block's a_A."""
    sol = sols["slotted_lever"]
    i = 50
    ax = kp.acceleration_plan(sol, row=i)
    k = sol.kinematics
    a = k[(k.body == "block") & (k.point == "A")].iloc[i]
    a_a = np.array([a.ax, a.ay])
    cor = _arrows(ax, "tab:pink")
    rel = _arrows(ax, "tab:gray")
    assert len(cor) == 1
    assert any(np.hypot(*(tail - cor[0][1])) <= 1e-12 * np.hypot(*a_a) and
               np.hypot(*(tip - a_a)) <= 1e-12 * np.hypot(*a_a) for tail, tip in rel)
    m = sol.kin.bodies["lever"].take(i)
    blk = sol.kin.bodies["block"].take(i)
    x, y = blk.point(sol.scene.bodies["block"].local("A"))
    v_rel = np.array(blk.vel_at(x, y)) - np.array(m.vel_at(x, y))
    expect = 2.0 * float(m.omega) * np.array([-v_rel[1], v_rel[0]])     # 2 omega x v_rel
    np.testing.assert_allclose(cor[0][1] - cor[0][0], expect, rtol=0,
                               atol=1e-12 * np.hypot(*a_a))
    # the velocity plan: the slider's tip is the computed velocity
    vp = kp.velocity_plan(sol, row=i)
    tips = [t.xy for t in vp.texts if t.get_text() == "a"]
    np.testing.assert_allclose(tips[0], (a.vx, a.vy), rtol=0, atol=1e-12 * np.hypot(a.vx, a.vy))


def test_slider_crank_plans(sols):
    sol = sols["slider_crank"]
    k = sol.kinematics
    i = 25
    c = k[(k.body == "piston") & (k.point == "C")].iloc[i]
    ax = kp.velocity_plan(sol, row=i)
    tips = [t.xy for t in ax.texts if "c" in t.get_text().split(" = ")]
    np.testing.assert_allclose(tips[0], (c.vx, c.vy), rtol=0, atol=1e-12 * abs(c.vx))
    ax = kp.acceleration_plan(sol, row=i)
    tips = [t.xy for t in ax.texts if "c" in t.get_text().split(" = ")]
    np.testing.assert_allclose(tips[0], (c.ax, c.ay), rtol=0, atol=1e-12 * abs(c.ax))


@pytest.mark.parametrize("name", NAMES)
def test_free_body_forces_balance_each_body(name, sols):
    """On each body of a dyad (and the driver) the forces and couples balance."""
    sol = sols[name]
    n = sol.positions.size
    for i in (0, n // 3, 2 * n // 3):
        for d in range(len(sol.kin.dyads) + 1):
            fs = kp.free_body_forces(sol, d, row=i)
            scale = max(np.hypot(f["fx"], f["fy"]) for f in fs)
            size = max(np.hypot(f["x"], f["y"]) for f in fs) + 1.0
            for b in {f["body"] for f in fs}:
                on = [f for f in fs if f["body"] == b]
                F = np.sum([[f["fx"], f["fy"]] for f in on], axis=0)
                M = sum(f["x"] * f["fy"] - f["y"] * f["fx"] + f["m"] for f in on)
                # measured: 1e-14 relative at most
                assert np.hypot(*F) <= 1e-11 * scale, (name, i, d, b, F)
                assert abs(M) <= 1e-11 * scale * size, (name, i, d, b, M)


@pytest.mark.parametrize("name", ["four_bar"])
def test_free_body_diagram_draws_the_forces(name, lecture_figures):
    """The dyad's free-body diagram of ``solve --plot`` (:func:`kp.dyad_free_body`, read
    from the figures drawn once for the quick tier's picture scene: drawing it again
    cost 1.3 s of CPU) draws every force it claims."""
    sol, pos, figs = lecture_figures(name)
    fig = figs[f"free_body_{pos:g}deg_dyad1".replace(".", "p")]
    assert len(fig.axes) == 2
    fbd, poly = fig.axes
    assert poly.get_xlabel() == "Fx [N]" and fbd.get_xlabel() == "x [m]"
    fs = kp.free_body_forces(sol, 1, pos)
    arrows = [t for t in fbd.texts if t.arrow_patch is not None and not t.get_text()]
    drawn = [np.subtract(t.xy, t.xyann) for t in arrows]
    drawn = [v for v in drawn if np.hypot(*v) > 0]
    # every force (the inner joint once) is an arrow parallel to it
    expect = [np.array([f["fx"], f["fy"]]) for f in fs if f["kind"] != "inner"
              and np.hypot(f["fx"], f["fy"]) > 0]
    for e in expect:
        assert any(abs(cross(e / np.hypot(*e), v / np.hypot(*v))) < 1e-9 and
                   np.dot(e, v) > 0 for v in drawn), e
    labels = " ".join(t.get_text() for t in fbd.texts)
    assert "$F_{\\mathrm{B}}$" in labels and "crank→coupler" in labels


# (the quick tier draws the four-bar's, its one picture scene; the others in the full suite)
@pytest.mark.parametrize("name", ["four_bar", pytest.param("slider_crank", marks=pytest.mark.slow),
                                  pytest.param("shaper", marks=pytest.mark.slow)])
def test_instant_centres_picture(name, sols):
    """The picture of the centres draws (their values: test_centres.py)."""
    sol = sols[name]
    tab = kp.instant_centres(sol, row=33)
    ax = kp.plot_instant_centres(sol, row=33)
    shown = {t.get_text() for t in ax.texts} | {t.get_text() for t in ax.get_legend().get_texts()}
    assert all(any(n in s for s in shown) for n in tab.name), (name, shown)
    clear(ax.figure)


def test_polar_numbers(sols):
    sol = sols["four_bar"]
    ax = kp.plot_polar(sol, "B")
    nums = [t for t in ax.texts if t.get_text().isdigit()]
    assert [t.get_text() for t in nums] == [str(k) for k in range(12)]
    fx, fy = sol.reaction("B")
    for k, t in enumerate(nums):        # number k at 30 k deg
        j = int(np.argmin(np.abs(sol.positions - 30.0 * k)))
        np.testing.assert_allclose(t.xy, (fx[j], fy[j]), rtol=0, atol=1e-12)
    assert not [t for t in kp.plot_polar(sol).texts if t.get_text().isdigit()]


def test_collinear_forces_drawn_side_by_side(sols):
    """Nearly collinear forces (the shaper's RTR dyad, the yoke's weight on its guide):
    overlapping arrows moved sideways, the offset named; a scale bar in N; the polygon
    still closes (the closing error in the title)."""
    for name, dyad, pos in (("shaper", 1, 51), ("scotch_yoke", 1, 117)):
        ax = kp.force_polygon(sols[name], dyad, pos)
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert any(s.startswith("side-by-side offset") and s.endswith("N (drawing only)")
                   for s in labels), labels
        assert any(t.get_text().endswith(" N") and t.get_text()[0].isdigit()
                   for t in ax.texts)                                       # the scale bar
        err = float(ax.get_title().rsplit("|ΣF| = ", 1)[1].split()[0])
        assert err <= 1e-12 * max(abs(v) for v in ax.get_xlim() + ax.get_ylim())
        assert not ax.child_axes                                            # no inset
        clear(ax.figure)
    ax = kp.force_polygon(sols["four_bar"], 1, 51)                         # a wide one
    assert not any(t.get_text().startswith("side-by-side")
                   for t in ax.get_legend().get_texts())


def test_projector_style():
    base = plt.rcParams["font.size"]
    with kp.projector():
        fig, _ = plt.subplots()
        assert fig.dpi == 150 and plt.rcParams["font.size"] > base
    assert plt.rcParams["font.size"] == base
    with kp.projector(**{"font.size": 20}):
        assert plt.rcParams["font.size"] == 20
    style = kp.projector()              # one call: on for every later figure
    assert plt.figure().dpi == 150
    style.restore()
    assert plt.rcParams["font.size"] == base and plt.figure().dpi != 150


@pytest.mark.slow
def test_projector_pictures_stay_clear(sols):
    with kp.projector():
        clear(kp.overview(sols["four_bar"]))
        clear(kp.dyad_free_body(sols["slider_crank"], 1, 40))


# ------------------------------------------------------------------------------ flywheel
@pytest.fixture(scope="module")
def cycle():
    return kp.reduced_cycle(ks.example("four_bar_motion"))


def test_reduced_cycle(cycle):
    assert list(cycle.columns) == ["phi", "I_r", "dI_r", "M_loads", "M_motor", "M", "delta_E"]
    assert cycle.phi.iloc[0] == 0.0 and cycle.phi.iloc[-1] == 360.0
    # the default motor does the loads' cycle work: Delta E closes (trapezoid rule)
    assert abs(cycle.delta_E.iloc[-1]) <= 1e-12 * np.ptp(cycle.delta_E)
    # dI_r is the derivative of I_r (central differences at 1 deg: measured 1.1e-3 of
    # the range of I_r, the h^2 error of the difference)
    phi = np.deg2rad(cycle.phi.to_numpy())
    num = np.gradient(cycle.I_r.to_numpy(), phi)
    assert np.max(np.abs(num[1:-1] - cycle.dI_r.to_numpy()[1:-1])) <= 3e-3 * np.ptp(cycle.I_r)
    with pytest.raises(WorkbenchError, match="crank"):
        kp.reduced_cycle(ks.example("sliding_driver"))


def test_wittenbauer_tangents_give_delta(cycle):
    """From (-J, -E0), omega^2 = 2 (E0 + Delta E) / (J + I_r) reaches exactly
    omega_m^2 (1 +- delta/2)^2 at the touching points (eq. 4.20)."""
    wm, delta = 31.45, 0.02
    w = kp.wittenbauer_flywheel(cycle.I_r, cycle.delta_E, wm, delta)
    assert w["J"] > 0
    omega = np.sqrt(2.0 * (w["E0"] + cycle.delta_E) / (w["J"] + cycle.I_r))
    np.testing.assert_allclose(omega.max(), wm * (1 + delta / 2), rtol=1e-12)
    np.testing.assert_allclose(omega.min(), wm * (1 - delta / 2), rtol=1e-12)
    ax = kp.plot_wittenbauer(cycle, wm, delta)
    assert f"J = {reading(w['J'])}" in ax.get_title()
    clear(ax.figure)
    fig = kp.plot_flywheel_curves(cycle)
    assert [a.get_ylabel() for a in fig.axes] == ["$I_r$ [kg m²]", "reduced moment [N m]",
                                                  "ΔE [J]"]
    clear(fig)
    with pytest.raises(WorkbenchError):
        kp.wittenbauer_flywheel(cycle.I_r, cycle.delta_E, wm, 0.0)


# ---------------------------------------------------------------------------------- cams
@pytest.fixture(scope="module")
def cams():
    return {n: solve_cam(example(n)) for n in cam_examples()}


def test_cam_shocks_against_closed_forms(cams):
    res = cams["translating_roller"]
    law, w, h = res.scene.law, res.scene.speed, res.scene.law.stroke
    rise, ret = law.segments[0].angle, law.segments[2].angle
    shocks = kp.cam_shocks(law, w)
    assert all(s["kind"] == "soft" for s in shocks)
    got = {round(s["angle"], 6): s["da"] for s in shocks}
    a_rise = 4.0 * h * w**2 / rise**2                # constant acceleration: 4 h w^2 / b^2
    a_ret = math.pi**2 * h * w**2 / (2.0 * ret**2)   # cosine: pi^2 h w^2 / (2 b^2)
    deg = math.degrees
    expect = {0.0: a_rise, round(deg(rise / 2), 6): -2 * a_rise, round(deg(rise), 6): a_rise,
              round(deg(rise + law.segments[1].angle), 6): -a_ret,
              round(deg(rise + law.segments[1].angle + ret), 6): -a_ret}
    assert set(got) == set(expect)
    for k, v in expect.items():
        assert abs(got[k] - v) <= 1e-6 * abs(v), (k, got[k], v)       # measured 1e-8


@pytest.mark.parametrize("name", cam_examples())
def test_cam_pictures(name, cams):
    res = cams[name]
    fig = kp.plot_cam_motion(res)
    assert len(fig.axes) == 3 and fig.axes[-1].get_xlabel() == "cam angle φ [deg]"
    clear(fig)
    for angle in (0.0, 60.0, 200.0):
        ax = kp.draw_cam(res, angle)
        clear(ax.figure)
        # the roller touches the drawn profile: its centre is one roller radius from it
        prof = next(ln for ln in ax.lines if ln.get_label() == "cam profile").get_xydata()
        centre = next(ln for ln in ax.lines if ln.get_marker() == "o").get_xydata()[0]
        rr = res.scene.follower.roller_radius
        gap = float(np.min(np.hypot(*(prof - centre).T)))
        assert abs(gap - rr) <= 2e-3 * res.scene.follower.base_radius, (angle, gap, rr)
        plt.close("all")


def test_cam_diagram(cams):
    res = cams["translating_roller"]
    ax = kp.plot_cam_diagram(res)
    clear(ax.figure)
    tau = math.radians(res.summary["transmission_angle_admissible"])
    e, r0 = optimal_offset(res.scene.law, tau)
    smallest = next(ln for ln in ax.lines if ln.get_label().startswith("smallest cam"))
    np.testing.assert_allclose(smallest.get_xydata()[0], (e, -math.sqrt(r0**2 - e**2)),
                               rtol=0, atol=1e-12)
    # the tangents touch the curve and keep it above
    m = res.motion
    for ln in ax.lines:
        if ln.get_label().startswith("tangent"):
            (x0, y0), (x1, y1) = ln.get_xydata()
            k = (y1 - y0) / (x1 - x0)
            above = m.s - (y0 + k * (m.ds - x0))
            assert above.min() >= -1e-12 and above.min() <= 1e-12
            np.testing.assert_allclose(abs(k), math.tan(tau), rtol=1e-12)
    with pytest.raises(WorkbenchError, match="translating"):
        kp.plot_cam_diagram(cams["oscillating_roller"])


def test_transmission_picture_matches_the_summary(sols):
    """One definition, min(tau, 180 - tau): the curve's minimum is the summary's."""
    for name in ("four_bar", "slider_crank"):
        sol = sols[name]
        ax = kp.plot_transmission(sol)
        low = min(float(np.min(ln.get_ydata())) for ln in ax.lines if len(ln.get_ydata()) > 2)
        assert abs(low - sol.summary()["transmission_angle_min"]) <= 1e-12
        assert "min(τ, 180° − τ)" in ax.get_ylabel()
        clear(ax.figure)
