"""Mass concentration (seed 002 s. 2.2, eqs 2.3-2.15) and its error on whole mechanisms."""

from __future__ import annotations

import copy
import tomllib
import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import kinetostatics as ks
from kinetostatics.concentration import (
    ConcentrationError,
    body_concentration,
    concentrate,
    concentration_error_table,
    dynamic_two_point,
    seed_free_parameters,
    static_two_point,
)
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.model.scene import Body, MassModel
from kinetostatics.solver.loads import concentrated_masses

coord = st.floats(-1.0, 1.0)
mass = st.floats(0.1, 50.0)


def conditions(c):
    """Residuals of eqs 2.3, 2.4, 2.5 for a Concentration."""
    d = c.points - np.asarray(c.cog)
    return (c.masses.sum() - c.mass, c.masses @ d[:, 0], c.masses @ d[:, 1],
            c.masses @ np.einsum("ij,ij->i", d, d) - c.inertia)


# --------------------------------------------------------------------------- closed forms

def test_seed_counts():
    assert [seed_free_parameters(n, "static") for n in (1, 2, 3)] == [0, 3, 6]      # eq. 2.7
    assert [seed_free_parameters(n, "dynamic") for n in (1, 2, 3)] == [-1, 2, 5]    # eq. 2.6


@settings(max_examples=100, deadline=None)
@given(m=mass, a=st.floats(0.01, 1.0), b=st.floats(0.01, 1.0), gx=coord, gy=coord,
       ang=st.floats(-3.2, 3.2))
def test_static_two_point_matches_general_solver(m, a, b, gx, gy, ang):
    m1, m2 = static_two_point(m, a, b)                      # eq. 2.11
    assert m1 + m2 == pytest.approx(m, rel=1e-12)
    assert m1 * a - m2 * b == pytest.approx(0.0, abs=1e-12 * m)      # eq. 2.10
    u = np.array([np.cos(ang), np.sin(ang)])
    g = np.array([gx, gy])
    c = concentrate(m, g, [g + a * u, g - b * u], kind="static", unique=True)
    assert c.free == 0 and c.seed_free == 3
    assert np.allclose(c.masses, [m1, m2], rtol=1e-9, atol=1e-12 * m)


@settings(max_examples=100, deadline=None)
@given(m=mass, i_g=st.floats(1e-4, 2.0), a=st.floats(0.02, 1.0), gx=coord, gy=coord,
       ang=st.floats(-3.2, 3.2), side=st.sampled_from([-1.0, 1.0]))
def test_dynamic_two_point_matches_general_solver(m, i_g, a, gx, gy, ang, side):
    a = side * a
    m1, m2, x2 = dynamic_two_point(m, i_g, a)               # eq. 2.14
    # eq. 2.13
    assert m1 + m2 == pytest.approx(m, rel=1e-12)
    assert m1 * a + m2 * x2 == pytest.approx(0.0, abs=1e-9 * m * abs(a))
    assert m1 * a**2 + m2 * x2**2 == pytest.approx(i_g, rel=1e-9)
    u = np.array([np.cos(ang), np.sin(ang)])
    g = np.array([gx, gy])
    c = concentrate(m, g, [g + a * u, g + x2 * u], inertia=i_g, kind="dynamic", unique=True)
    assert c.free == 0 and c.seed_free == 2
    assert np.allclose(c.masses, [m1, m2], rtol=1e-7, atol=1e-9 * m)
    assert abs(c.missing_inertia) <= 1e-7 * i_g


@settings(max_examples=60, deadline=None)
@given(m=mass, i_g=st.floats(1e-4, 2.0), bx=coord, by=coord, cx=coord, cy=coord,
       t=st.floats(0.05, 0.95))
def test_closed_forms_match_the_scene_mass_models(m, i_g, bx, by, cx, cy, t):
    """loads.concentrated_masses (used by the solver) agrees with eqs 2.11 and 2.14."""
    b, c = np.array([bx, by]), np.array([cx, cy])
    L = float(np.hypot(*(c - b)))
    assume(L > 0.05)
    g = b + t * (c - b)
    pts = {"B": tuple(b), "C": tuple(c)}
    body = Body("link", m, i_g, tuple(g), pts, MassModel("static", ("B", "C")))
    (_, mb), (_, mc) = concentrated_masses(body)
    m1, m2 = static_two_point(m, t * L, (1.0 - t) * L)
    assert (mb, mc) == pytest.approx((m1, m2), rel=1e-9)
    sc = body_concentration(body)
    assert sc.missing_inertia == pytest.approx(i_g - m * t * (1 - t) * L**2, rel=1e-9, abs=1e-12)
    body = Body("link", m, i_g, tuple(g), pts, MassModel("dynamic", ("B",)))
    (_, mb), (k, mk) = concentrated_masses(body)
    d1, d2, x2 = dynamic_two_point(m, i_g, t * L)
    assert (mb, mk) == pytest.approx((d1, d2), rel=1e-9)
    assert float(np.hypot(*(np.array(k) - g))) == pytest.approx(abs(x2), rel=1e-9)
    dc = body_concentration(body)
    assert abs(dc.missing_inertia) <= 1e-9 * i_g
    assert max(abs(r) for r in conditions(dc)) <= 1e-9 * (m + i_g)


def test_closed_form_refusals_and_warning():
    with pytest.raises(ConcentrationError, match="infinity"):
        dynamic_two_point(2.0, 0.01, 0.0)
    with pytest.raises(ConcentrationError, match="distinct"):
        static_two_point(2.0, 0.1, -0.1)
    with pytest.warns(UserWarning, match="bracket"):
        m1, m2 = static_two_point(2.0, -0.1, 0.3)           # both points on one side
    assert m1 + m2 == pytest.approx(2.0) and min(m1, m2) < 0.0
    arr = static_two_point(np.array([1.0, 2.0]), 0.1, 0.3)
    assert np.allclose(arr[0], [0.75, 1.5])


# --------------------------------------------------------------------------- n points

@pytest.mark.filterwarnings("ignore:.*concentrated mass is negative:UserWarning")
@settings(max_examples=100, deadline=None)
@given(m=mass, i_g=st.floats(1e-3, 1.0), g=st.tuples(coord, coord),
       pts=st.lists(st.tuples(coord, coord), min_size=3, max_size=7))
def test_general_static_and_dynamic(m, i_g, g, pts):
    p = np.array(pts)
    spread = np.linalg.svd(p - p.mean(axis=0), compute_uv=False)
    assume(spread.min() > 0.05)                       # points span the plane
    n = len(pts)
    c = concentrate(m, g, p, inertia=i_g, kind="static")
    assert c.free == n - 3 and c.seed_free == 3 * n - 3
    assert max(abs(r) for r in conditions(c)[:3]) <= 1e-9 * m
    # least norm: no move along the null space of the conditions makes the masses smaller
    A = np.vstack([np.ones(n), (p - g).T])
    null = np.linalg.svd(A)[2][3:]
    assert np.allclose(null @ c.masses, 0.0, atol=1e-9 * m)
    # dynamic with n >= 4 points in general position (not all on a circle about G)
    if n >= 4:
        r2 = np.einsum("ij,ij->i", p - g, p - g)
        B = np.vstack([A, r2])
        assume(np.linalg.svd(B, compute_uv=False)[-1] > 1e-3)
        d = concentrate(m, g, p, inertia=i_g, kind="dynamic")
        assert d.free == n - 4 and d.seed_free == 3 * n - 4
        assert max(abs(r) for r in conditions(d)) <= 1e-8 * (m + i_g)
        assert abs(d.missing_inertia) <= 1e-8 * (m + i_g)


def test_unique_request_refuses_underdetermined():
    pts = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
    c = concentrate(2.0, (0.4, 0.3), pts)                     # least-norm: fine
    assert c.free == 1 and not c.unique
    with pytest.raises(ConcentrationError, match="under-determined: 1 of the masses"):
        concentrate(2.0, (0.4, 0.3), pts, unique=True)
    three = concentrate(2.0, (0.4, 0.3), pts[:3], unique=True)
    assert three.unique and np.allclose(three.masses, [0.6, 0.8, 0.6])
    with pytest.warns(UserWarning, match="negative"):
        concentrate(2.0, (1.2, 0.3), pts[:3], unique=True)     # cog outside the triangle


@pytest.mark.parametrize("kwargs,words", [
    (dict(points=[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)], cog=(0.5, 0.2)), "misses the cog"),
    (dict(points=[(0.3, 0.3), (0.3, 0.3)], cog=(0.0, 0.0)), "all the points are at"),
    (dict(points=[(0.3, 0.3)], cog=(0.0, 0.0)), "all the points are at"),
    # dynamic, points on a line through G but not conjugate: a b != I_G / m
    (dict(points=[(-0.1, 0.0), (0.2, 0.0)], cog=(0.0, 0.0), inertia=0.05, kind="dynamic"),
     "not I_G"),
    # dynamic, every point at 0.1 m from G: their inertia is m * 0.01 whatever the masses
    (dict(points=[(0.1, 0.0), (0.0, 0.1), (-0.1, 0.0), (0.0, -0.1)], cog=(0.0, 0.0),
          inertia=0.05, kind="dynamic"), "not I_G"),
    # one point (p_D = -1): only the cog, and only for I_G = 0
    (dict(points=[(0.0, 0.0)], cog=(0.0, 0.0), inertia=0.05, kind="dynamic"), "not I_G"),
    (dict(points=[(0.0, 0.0)], cog=(0.0, 0.0), kind="rigid"), "kind"),
    (dict(points=[(0.0, 0.0)], cog=(0.0, 0.0), mass=0.0), "mass"),
    (dict(points=[], cog=(0.0, 0.0)), "points"),
])
def test_contradictory_requests_are_refused(kwargs, words):
    kw = {"mass": 2.0, **kwargs}
    with pytest.raises(ConcentrationError) as exc:
        concentrate(**kw)
    assert isinstance(exc.value, WorkbenchError)
    assert "\n" not in str(exc.value) and words in str(exc.value)


def test_single_point_static_is_the_cog():
    c = concentrate(3.0, (0.1, 0.2), [(0.1, 0.2)], inertia=0.5, kind="static", unique=True)
    assert c.masses.tolist() == pytest.approx([3.0])
    assert c.seed_free == 0 and c.missing_inertia == pytest.approx(0.5)
    d = concentrate(3.0, (0.1, 0.2), [(0.1, 0.2)], inertia=0.0, kind="dynamic")  # a point mass
    assert d.masses.tolist() == pytest.approx([3.0])


def test_inertia_forces_eq_2_8():
    c = concentrate(2.0, (0.1, 0.0), [(0.0, 0.0), (0.4, 0.0)])
    ax = np.array([[1.0, 2.0], [3.0, 4.0]])
    fx, fy = c.inertia_forces(ax, np.zeros_like(ax))
    assert np.allclose(fx, [[-1.5, -3.0], [-1.5, -2.0]]) and np.allclose(fy, 0.0)
    assert list(c.table().columns) == ["x", "y", "m"]


# --------------------------------------------------------------------------- mechanisms

def _raw(name, **driver):
    with open(ks.example(name), "rb") as fh:
        raw = tomllib.load(fh)
    raw["driver"].update(driver)
    raw["driver"]["count"] = 121
    return raw


SCENES = {
    "four_bar": _raw("four_bar", acceleration=150.0),
    "slider_crank": _raw("slider_crank", acceleration=-800.0),
    "shaper": _raw("shaper", acceleration=40.0),
    "sliding_driver": _raw("sliding_driver"),
}


def _missing_power(raw):
    """Sum over the static-concentrated bodies of the missing couple's power,
    -(I_G - m |GB||GC|) eps omega, from the exact solution's body motions."""
    table = concentration_error_table(raw)
    sc = ks.load_scene(raw)
    sol = ks.solve(raw)
    n = sol.positions.size
    power = np.zeros(n)
    for name, model in table.attrs["static"].items():
        body = sc.bodies[name]
        b, c = (np.array(body.points[p]) for p in model["points"])
        g = np.array(body.cog)
        gb_gc = float(np.dot(b - g, c - g))                # = -|GB||GC| when G is between
        missing = body.inertia + body.mass * gb_gc         # I_G - m |GB||GC|
        assert missing == pytest.approx(body_concentration(
            Body(name, body.mass, body.inertia, body.cog, body.points,
                 MassModel("static", tuple(model["points"])))).missing_inertia, rel=1e-9)
        mo = sol.kin.bodies[name]
        power += -missing * np.broadcast_to(mo.alpha, (n,)) * np.broadcast_to(mo.omega, (n,))
    return table, sol, power


@pytest.mark.parametrize("name", list(SCENES))
def test_error_table_dynamic_exact_static_missing_couple(name):
    raw = SCENES[name]
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)        # the models must be well posed
        table, exact, power = _missing_power(raw)
    assert list(table.columns) == ["model", "quantity", "exact_max", "max_abs", "position",
                                   "max_rel"]
    q = exact.driver_quantity
    assert set(table["quantity"]) == {q} | {f"F[{j}]" for j in exact.scene.joints}
    dyn = table[table.model == "dynamic"]
    assert (dyn["max_rel"] <= 1e-9).all(), dyn
    assert table.attrs["static"], "some body must be concentrated statically"
    # the static Me (Fe) differs by the power of the missing couples over the driver's speed
    raw_static = copy.deepcopy(raw)
    for item in raw_static["bodies"]:
        if item["name"] in table.attrs["static"]:
            item["mass_model"] = table.attrs["static"][item["name"]]
    static = ks.solve(raw_static)
    diff = static.Me - exact.Me
    expected = power / exact.scene.driver.speed
    assert np.allclose(diff, expected, rtol=0.0, atol=1e-9 * np.abs(exact.Me).max())
    row = table[(table.model == "static") & (table.quantity == q)].iloc[0]
    assert row["max_abs"] == pytest.approx(np.abs(expected).max(), rel=1e-6)
    assert row["max_abs"] > 1e-6 * row["exact_max"]        # the error is real


def test_error_table_choice_of_bodies_and_existing_models():
    raw = copy.deepcopy(SCENES["four_bar"])
    raw["bodies"][0]["mass_model"] = {"kind": "static", "points": ["A", "B"]}
    table = concentration_error_table(raw)
    # the coupler's cog (0.125, 0.02) is off BC: exact in the static variant
    assert set(table.attrs["static"]) == {"crank", "rocker"}
    assert table.attrs["dynamic"]["coupler"] == {"kind": "dynamic", "point": "B"}
    # the exact reference ignores the scene's own mass_model
    clean = copy.deepcopy(SCENES["four_bar"])
    me = ks.solve(clean).Me
    row = table[(table.model == "dynamic") & (table.quantity == "Me")].iloc[0]
    assert row["exact_max"] == pytest.approx(np.abs(me).max(), rel=1e-12)
    # the piston of the slider-crank (one joint point, at its cog) stays exact in both
    t2 = concentration_error_table(SCENES["slider_crank"])
    assert "piston" not in t2.attrs["static"] and "piston" not in t2.attrs["dynamic"]
