"""Exercises: deterministic variants, answer keys, grading of every answer format."""

from __future__ import annotations

import math

import nbformat
import numpy as np
import pandas as pd
import pytest

import kinetostatics as ks
from kinetostatics import teaching as E
from kinetostatics.model.errors import WorkbenchError

IDS = [f"s{k:03d}" for k in range(50)]


@pytest.fixture(scope="module")
def four_bar():
    ex = E.four_bar_exercise()
    return ex, ex.generate(IDS)


@pytest.fixture(scope="module")
def rotor():
    ex = E.rotor_exercise()
    return ex, ex.generate(IDS)


def _perfect(key: pd.DataFrame) -> pd.DataFrame:
    return key[["student", "question"]].assign(answer=key["expected"])


# ----------------------------------------------------------------- the acceptance test
@pytest.mark.parametrize("which, off, angles", [
    ("four_bar", "Fmax[B]", ["angle[rocker]@30"]),
    ("rotor", "mass[1]", ["angle[1]", "angle[2]"]),
])
@pytest.mark.slow     # fifty variants solved and graded
def test_fifty_variants_graded(which, off, angles, four_bar, rotor):
    ex, s = four_bar if which == "four_bar" else rotor
    assert len(s.variants) == 50 and s.variants["student"].is_unique
    assert len(s.key) == 50 * len(ex.questions)
    # the variants differ
    params = s.variants.drop(columns=["student", "attempt"])
    assert len(params.drop_duplicates()) >= 45
    # a perfect sheet: all pass
    graded, summary = E.grade(_perfect(s.key), s)
    assert graded["passed"].all(), graded[~graded.passed]
    assert summary["score"] == 1.0 and summary["students"] == 50
    assert summary["items"] == 50 * len(ex.questions)
    # one value 5 % off: that item fails, the rest pass
    bad = _perfect(s.key)
    sel = bad["question"] == off
    bad.loc[sel, "answer"] *= 1.05
    graded, summary = E.grade(bad, s)
    assert not graded.loc[graded.question == off, "passed"].any()
    assert graded.loc[graded.question != off, "passed"].all()
    assert summary["failed"] == 50
    for sid in IDS:
        assert summary["per_student"][sid]["failed"] == [off]
    # angles given modulo 360 (plus or minus turns): pass
    turned = _perfect(s.key)
    sel = turned["question"].isin(angles)
    shift = np.resize([360.0, -360.0, 720.0, -1080.0], int(sel.sum()))
    turned.loc[sel, "answer"] = turned.loc[sel, "answer"].to_numpy() + shift
    graded, summary = E.grade(turned, s)
    assert graded["passed"].all()
    # angles are compared as angles: 359.9 vs 0.1 is 0.2 deg apart
    wrap = E.grade({"a": 359.9}, {"a": 0.1}, angle_keys=["a"], student="x")[0]
    assert wrap["passed"].all() and wrap["error"].iloc[0] == pytest.approx(-0.2)


def test_angle_five_percent_off_fails(four_bar):
    _, s = four_bar
    bad = _perfect(s.key)
    sel = bad["question"] == "angle[rocker]@30"
    bad.loc[sel, "answer"] *= 1.05         # about 4 deg: well beyond 0.5 deg
    graded, _ = E.grade(bad, s)
    assert not graded.loc[graded.question == "angle[rocker]@30", "passed"].any()


# ------------------------------------------------------------------------ generation
def test_variant_depends_only_on_seed_and_id():
    a = E.four_bar_exercise(seed=7)
    b = E.four_bar_exercise(seed=7)
    c = E.four_bar_exercise(seed=8)
    assert a.params("ana") == b.params("ana")
    sa = a.generate(["ana", "ion", "maria"]).variants.set_index("student")
    sb = b.generate(["maria", "ana"]).variants.set_index("student")
    pd.testing.assert_series_equal(sa.loc["ana"], sb.loc["ana"])
    assert a.params("ana") != c.params("ana") or a.params("ion") != c.params("ion")
    assert a.answer_key(" ana ") == a.answer_key("ana")


def _four_bar_by_hand(p: dict, phi_deg: np.ndarray) -> dict[str, np.ndarray]:
    """The exercise's four-bar written out from its parameters alone (nothing of the
    workbench): C where the circles about B and D meet (above AD, the sheet's
    assembly), velocities and accelerations by fourth-order central differences in phi
    (h = 3e-3 rad) at constant crank speed, Me from the virtual-power balance
    Me omega_1 + sum (m (g - a_G) . v_G - I_G eps omega) - P |v_E| = 0 (bars of
    7.8 kg/m, centres of mass at mid-length, I_G = m l^2 / 12, E at 0.6 DC)."""
    a, b, c, d = (p[k] for k in "abcd")
    w1 = p["rpm"] * math.pi / 30.0

    def state(phi):
        bx, by = a * np.cos(phi), a * np.sin(phi)
        ex, ey = d - bx, -by
        dist = np.hypot(ex, ey)
        x = (dist * dist + b * b - c * c) / (2 * dist)
        h = np.sqrt(b * b - x * x)
        cx, cy = bx + (x * ex - h * ey) / dist, by + (x * ey + h * ex) / dist
        return np.array([bx / 2, by / 2, (bx + cx) / 2, (by + cy) / 2,
                         d + 0.5 * (cx - d), 0.5 * cy, d + 0.6 * (cx - d), 0.6 * cy,
                         np.arctan2(cy - by, cx - bx), np.arctan2(cy, cx - d)])

    phi, h = np.radians(phi_deg), 3e-3
    f = [state(phi + k * h) for k in (-2, -1, 0, 1, 2)]
    v = (f[0] - 8 * f[1] + 8 * f[3] - f[4]) / (12 * h) * w1
    acc = (-f[0] + 16 * f[1] - 30 * f[2] + 16 * f[3] - f[4]) / (12 * h * h) * w1 * w1
    power = -p["load"] * np.hypot(v[6], v[7])
    for k, length in enumerate((a, b, c)):
        m = 7.8 * length
        power = power - m * (acc[2 * k] * v[2 * k] + (9.81 + acc[2 * k + 1]) * v[2 * k + 1])
        if k:                   # the crank turns at constant speed: no I_G eps
            power = power - m * length**2 / 12 * acc[7 + k] * v[7 + k]
    return {"Me": -power / w1, "angle": np.degrees(f[2][9]), "omega": v[9]}


def test_key_matches_a_four_bar_written_by_hand(four_bar):
    """Every student's key against the four-bar solved by hand from the student's own
    parameters (worst of 50 variants measured: Me@30 1.4e-10 of Me_max, the rocker's
    angle 5.7e-14 deg and speed 1.4e-9 relative, Me_mean 3.6e-11 and Me_max 1.7e-10
    relative: the differences' truncation)."""
    ex, s = four_bar
    for sid in IDS:
        key, hand = ex.answer_key(sid), _four_bar_by_hand(ex.params(sid), np.arange(361.0))
        assert key["Me@30"] == pytest.approx(hand["Me"][30], abs=1e-9 * key["Me_max"])
        assert key["Me_mean"] == pytest.approx(hand["Me"][:-1].mean(), rel=3e-10)
        assert key["Me_max"] == pytest.approx(hand["Me"].max(), rel=1e-9)
        assert key["angle[rocker]@30"] == pytest.approx(hand["angle"][30], abs=1e-12)
        assert key["omega[rocker]@30"] == pytest.approx(hand["omega"][30], rel=1e-8)
    # the reactions asked for are read off the variant's own tables
    sol = ks.solve(ex.scene("s007"))
    key, r = ex.answer_key("s007"), sol.reactions
    assert key["Fmax[B]"] == r.loc[r.joint == "B", "F"].max()
    assert key["F[C]@30"] == r.loc[(r.joint == "C") & (r.position == 30.0), "F"].item()


def test_generate_with_paths_into_a_toml_template():
    s = E.generate(ks.example("four_bar"), {"bodies.crank.mass": (1.0, 2.0, 0.1),
                                            "loads.0.force.1": [-100.0, -200.0, -300.0]},
                   ["a", "b", "c"], seed=3, questions=["Me@45", "F[B]@45", "Me@30.5"])
    assert list(s.variants.columns) == ["student", "bodies.crank.mass", "loads.0.force.1",
                                        "attempt"]
    sc = s.scene("b")
    crank = next(b for b in sc["bodies"] if b["name"] == "crank")
    assert crank["mass"] == s.variants.set_index("student").loc["b", "bodies.crank.mass"]
    # a position between the sweep's rows is solved exactly, not interpolated
    raw = dict(sc, driver={**sc["driver"], "start": 30.5, "stop": 30.5, "count": 1})
    direct = float(ks.solve(raw).Me[0])
    assert s.key.set_index(["student", "question"]).loc[("b", "Me@30.5"), "expected"] == \
        pytest.approx(direct, rel=1e-9)


def test_balance_questions():
    key = E.answer_key(
        "[static_test]\ndisk_mass = 5.0\ncomparison_mass = 0.05\ncomparison_radius = 0.10\n"
        "alpha = 25.0\ncorrection_radius = 0.08\n", ["correction_mass", "eccentricity"])
    assert key["correction_mass"] == pytest.approx(0.134032, abs=1e-6)
    import balance
    res = balance.solve(balance.example_path("resonance_example"))["resonance_test"][0]
    k2 = E.answer_key(balance.example_path("resonance_example"),
                      ["res_mass[1]", "res_angle[1]", "res_mirror[1]",
                       "resonance_test.0.A"])
    assert k2["res_angle[1]"] == res["angle"] and k2["resonance_test.0.A"] == res["A"]


@pytest.mark.parametrize("bad, msg", [
    ("Me", "position"), ("F[Z]@30", "no joint"), ("foo[1]@30", "unknown mechanism"),
    ("Me@400", "outside the sweep"), ("Me@@3", "quantity"), ("x[crank]@30", "body.point"),
])
def test_bad_questions(bad, msg):
    with pytest.raises(WorkbenchError, match=msg):
        E.answer_key(ks.example("four_bar"), [bad])


def test_bad_ranges():
    with pytest.raises(WorkbenchError, match="no item named"):
        E.generate(ks.example("four_bar"), {"bodies.cranc.mass": (1, 2)}, ["a"],
                   questions=["Me@30"])
    with pytest.raises(WorkbenchError, match="high"):
        E.generate(ks.example("four_bar"), {"bodies.crank.mass": (2, 1)}, ["a"],
                   questions=["Me@30"])
    with pytest.raises(WorkbenchError, match="no valid variant"):
        E.generate(ks.example("four_bar"), {"ground.D.0": (2.0, 3.0)}, ["a"],
                   questions=["Me@30"], max_tries=3)
    with pytest.raises(WorkbenchError, match="duplicate"):
        E.four_bar_exercise().generate(["a", "a"])


# -------------------------------------------------------------------- answer formats
def test_dict_csv_and_wide_forms(tmp_path, rotor):
    ex, s = rotor
    key = ex.answer_key("s003")
    # one student's dict, with decimal commas and degree signs
    ans = {q: f"{v:.9f}".replace(".", ",") for q, v in key.items()}
    ans["angle[1]"] = f"{key['angle[1]'] - 360:.6f}°"
    graded, summary = E.grade(ans, ex, student="s003")
    assert summary["score"] == 1.0, graded
    # a wide CSV for the class, one answer missing, one not a number
    form = s.answer_form()
    wide = s.key.pivot(index="student", columns="question", values="expected").reset_index()
    wide = wide[form.columns]
    wide.loc[0, "mass[2]"] = np.nan
    wide["mass[1]"] = wide["mass[1]"].astype(object)
    wide.loc[1, "mass[1]"] = "zero point one"
    path = tmp_path / "answers.csv"
    wide.to_csv(path, index=False)
    graded, summary = E.grade(path, s)
    st = graded.set_index(["student", "question"])["status"]
    assert st[("s000", "mass[2]")] == "missing"
    assert st[("s001", "mass[1]")] == "not a number"
    assert summary["missing"] == 1 and summary["failed"] == 1
    assert summary["passed"] == summary["items"] - 2
    # long CSV, a student not in the class, a question not asked
    long = _perfect(s.key)
    long = pd.concat([long, pd.DataFrame([{"student": "zz", "question": "mass[1]",
                                           "answer": 1.0},
                                          {"student": "s000", "question": "foo",
                                           "answer": 2.0}])])
    long.to_csv(tmp_path / "long.csv", index=False)
    graded, summary = E.grade(tmp_path / "long.csv", s)
    assert summary["unknown_students"] == ["zz"] and summary["unknown_questions"] == ["foo"]
    assert graded["passed"].all()
    # the written set
    files = s.to_csv(tmp_path / "set")
    assert sorted(p.name for p in files) == ["answers.csv", "key.csv", "variants.csv"]
    table = E.class_table(graded)
    assert list(table.columns) == ["student", "passed", "total", "score %", "failed"]


def test_filled_notebooks(tmp_path, four_bar):
    ex, _ = four_bar
    key = ex.answer_key("s010")
    # a notebook whose answer cell holds literal numbers
    p1 = E.write_answer_notebook(tmp_path / "s010.ipynb", "s010", key)
    graded, summary = E.grade(p1, ex)
    assert summary["score"] == 1.0 and graded["student"].eq("s010").all()
    # an executed notebook: the answers computed in the cell, the values in its output
    nb = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("student_id = 's011'\nanswers = {'Me@30': sol.Me[30]}")
    cell.metadata["nbgrader"] = {"grade_id": "answers", "solution": True, "grade": False,
                                 "locked": False, "schema_version": 3, "task": False}
    k11 = ex.answer_key("s011")
    bundle = E.record(k11, "s011")._repr_mimebundle_()
    cell.outputs = [nbformat.v4.new_output("execute_result", data=bundle, execution_count=1)]
    nb.cells.append(cell)
    p2 = tmp_path / "run.ipynb"
    nbformat.write(nb, str(p2))
    graded, summary = E.grade([p1, p2], ex)
    assert summary["students"] == 2 and summary["score"] == 1.0
    # computed but not run: a clear message
    cell.outputs = []
    nbformat.write(nb, str(p2))
    with pytest.raises(WorkbenchError, match="run the notebook"):
        E.grade(p2, ex)
    # one variable per question, named by var_name
    src = "student_id = 's012'\n" + "\n".join(
        f"{E.var_name(q)} = {v!r}" for q, v in ex.answer_key("s012").items())
    cell = nbformat.v4.new_code_cell(src)
    cell.metadata["tags"] = ["answers"]
    nb = nbformat.v4.new_notebook(cells=[cell])
    nbformat.write(nb, str(tmp_path / "vars.ipynb"))
    assert E.grade(tmp_path / "vars.ipynb", ex)[1]["score"] == 1.0
    # a notebook without an answer cell
    nbformat.write(nbformat.v4.new_notebook(), str(tmp_path / "empty.ipynb"))
    with pytest.raises(WorkbenchError, match="no answer cell"):
        E.read_answers(tmp_path / "empty.ipynb")


def test_tolerances_and_overrides():
    key = {"F": 100.0, "phi": 10.0}
    g, _ = E.grade({"F": 100.9, "phi": 370.4}, key, angle_keys=["phi"], student="a")
    assert g["passed"].all()
    g, _ = E.grade({"F": 100.9, "phi": 370.4}, key, angle_keys=["phi"], student="a",
                   rtol=0.005, angle_atol=0.1)
    assert not g["passed"].any()
    g, _ = E.grade({"F": 0.004}, {"F": 0.0}, student="a", atol=0.01)
    assert g["passed"].all()
    assert E.var_name("x[coupler.P]@30") == "x_coupler_P_30"
    assert math.isnan(E.to_float(None)) and E.to_float("12,5") == 12.5
    with pytest.raises(WorkbenchError, match="one student"):
        E.grade({"a": {"F": 1.0}, "b": {"F": 1.0}}, key)


def test_first_draws_solved_together_give_the_same_variants(monkeypatch) -> None:
    """Exercise.prepare solves the class's first draws with solve_many (stacked where
    the scenes allow it); every variant, redraws included, is the one drawn alone."""
    from kinetostatics.results import solving
    from kinetostatics.solver import many
    from kinetostatics.teaching import keys

    calls, alone = [], []
    real, solo = solving.solved_outcomes, many._alone
    monkeypatch.setattr(solving, "solved_outcomes",
                        lambda items, **kw: calls.append(len(items)) or real(items, **kw))
    monkeypatch.setattr(many, "_alone", lambda sc: alone.append(len(calls)) or solo(sc))
    ids = IDS[:12]
    mine = E.Exercise(ks.example("four_bar"), {"bodies.crank.mass": (1.0, 2.0, 0.1),
                                               "bodies.rocker.points.C.0": (0.19, 0.21)},
                      ["Me@45", "F[B]@45", "Me_max"], seed=3, name="mine")
    for ex in (mine, E.slider_crank_exercise(seed=4), E.rotor_exercise(seed=5)):
        drawn = [ex._variant(s) for s in ids]
        again = type(ex)(**{f: getattr(ex, f) for f in ("template", "ranges", "questions",
                                                        "seed", "check", "name", "data")})
        got = again.key(ids)
        pd.testing.assert_frame_equal(got, ex.key(ids), check_exact=True)
        for s, a in zip(ids, drawn, strict=True):
            b = again._variant(s)
            assert (a["attempt"], a["params"], a["scene"], a["rows"]) == \
                (b["attempt"], b["params"], b["scene"], b["rows"])
    assert calls[0] == 12 and 1 not in alone    # the first class: one stacked solve
    assert keys.key_rows_many([], ["Me@45"]) == []
