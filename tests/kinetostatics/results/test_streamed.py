"""A sweep too long to hold, solved and written block by block (``solve --out`` over the
memory budget): every file and ``summary.json`` as the one-shot solve writes them, bit
for bit, and the continuous body angles gathered over blocks equal to the whole
sweep's."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import kinetostatics as ks
from kinetostatics.model.scene import load_scene
from kinetostatics.results import streamed
from kinetostatics.results.streamed import StreamedSolve, open_solve
from kinetostatics.results.sweepangles import SweepAngles, degree_angles
from kinetostatics.solver.kinematics import solve_kinematics, with_positions
from kinetostatics.solver.pipeline import Sweep
from kinetostatics.solver.structure import analyse
from tests.helpers import ROOT

SCENES = ROOT / "kinetostatics" / "scenes"
# a streamed solve is the numpy path's (its blocks are solved there): so is the one-shot
# it is compared with, whatever KINETOSTATICS_PATH says
pytestmark = pytest.mark.usefixtures("numpy_path")


def _raw(name: str, count: int) -> dict:
    raw = _scene_raw(name)
    raw["driver"]["count"] = count
    if raw["driver"].get("stop") == 360.0 and raw["driver"].get("start", 0.0) == 0.0:
        raw["driver"]["stop"] = 359.9       # (0 and 360 deg are one crank position)
    return raw


def _bits(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=float).view(np.int64)


def drag_link() -> dict:
    """The bundled four-bar made a drag link (the ground link shortest, Grashof): the
    rocker turns fully, its angle wraps past 180 deg and, sampled coarsely, turns more
    than half a turn between rows (the probes find the whole turns)."""
    raw = tomllib.loads((SCENES / "four_bar.toml").read_text())
    raw["ground"]["D"] = [0.04, 0.0]
    b = {x["name"]: x for x in raw["bodies"]}
    b["coupler"].update(points={"B": [0.0, 0.0], "C": [0.12, 0.0], "P": [0.05, 0.03]},
                        cog=[0.06, 0.01])
    b["rocker"].update(points={"D": [0.0, 0.0], "C": [0.11, 0.0], "E": [0.06, 0.01]},
                       cog=[0.05, 0.0])
    raw["near"] = {"C": [0.08, 0.10]}
    raw["driver"]["stop"] = 359.9
    return raw


def _scene_raw(name: str) -> dict:
    return drag_link() if name == "drag_link" else tomllib.loads(
        (SCENES / f"{name}.toml").read_text())


@pytest.mark.parametrize("name", [*sorted(p.stem for p in SCENES.glob("*.toml")), "drag_link"])
def test_angles_gathered_over_blocks_are_the_whole_sweeps(name: str) -> None:
    """Coarse sweeps (2-40 rows, so that turns between rows are probed) fed in blocks of
    1, 2, 3, 7 and all rows: the angles of degree_angles (body_angles in degrees) over
    the whole sweep, bit for bit."""
    probed = 0
    for count in (2, 3, 4, 6, 17, 40):
        raw = _scene_raw(name)
        raw["driver"]["count"] = count
        scene = load_scene(raw)
        kin = solve_kinematics(scene, analyse(scene))
        pos = scene.driver.positions
        whole = degree_angles(kin)
        for block in (1, 2, 3, 7, count):
            gathered = SweepAngles(scene, kin.structure, pos)
            for start in range(0, count, block):
                rows = slice(start, min(start + block, count))
                gathered.add(rows, solve_kinematics(with_positions(scene, pos[rows]),
                                                    kin.structure))
            probed += bool(gathered.found)
            got = gathered.angles()
            assert sorted(got) == sorted(whole)
            for b, a in whole.items():
                assert np.array_equal(_bits(np.broadcast_to(got[b], a.shape)), _bits(a)), \
                    (count, block, b)
    if name.startswith(("four_bar", "drag_link")) or name == "slider_crank":
        assert probed        # (measured: the coarsest sweeps probe turns between rows)


def _same_output(a: Path, b: Path, fmt: str) -> None:
    names = sorted(p.name for p in b.iterdir())
    assert sorted(p.name for p in a.iterdir()) == names
    for f in names:
        if fmt == "parquet" and f.endswith(".parquet"):
            import pandas as pd
            pd.testing.assert_frame_equal(pd.read_parquet(a / f), pd.read_parquet(b / f),
                                          check_exact=True)
        else:
            assert (a / f).read_bytes() == (b / f).read_bytes(), f


# (one in the quick tier: each solves and writes 40 000 rows twice, 1-1.3 s)
@pytest.mark.parametrize(("name", "block"), [
    pytest.param("four_bar", 15_000, marks=pytest.mark.slow), ("sliding_driver", 9_999),
    pytest.param("drag_link", 12_345, marks=pytest.mark.slow)])
def test_streamed_files_are_the_one_shots(name: str, block: int, tmp_path: Path) -> None:
    """40 000 positions (a sweep the solver solves in blocks) in blocks of ``block``
    rows: every CSV file byte for byte, summary.json too."""
    raw = _raw(name, 40_000)
    s = StreamedSolve(Sweep(raw, budget=False), block=block)
    one = ks.solve(raw)
    assert json.dumps(s.summary()) == json.dumps(one.summary())
    s.write(tmp_path / "streamed")
    one.write(tmp_path / "one")
    _same_output(tmp_path / "streamed", tmp_path / "one", "csv")


@pytest.mark.slow
@pytest.mark.parametrize("name", ["slotted_lever", "scotch_yoke", "four_bar_mm",
                                  "four_bar_motion"])
def test_streamed_files_of_every_kind(name: str, tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    # 34 000 rows streamed in blocks of 20 000: each block spans two of the solver's own
    # blocks of 16 384 rows, the last one short (70 000 in 30 000: 1.4 times the CPU of
    # 50 000 in 20 000, the same roads; 50 000: three blocks, 1.5 times the CPU of these
    # two, measured 2026-11-30)
    raw = _raw(name, 34_000)
    s = StreamedSolve(Sweep(raw, budget=False), block=20_000)
    one = ks.solve(raw)
    assert json.dumps(s.summary()) == json.dumps(one.summary())
    for fmt in ("csv", "parquet"):
        s.write(tmp_path / f"s-{fmt}", fmt)
        one.write(tmp_path / f"o-{fmt}", fmt)
        _same_output(tmp_path / f"s-{fmt}", tmp_path / f"o-{fmt}", fmt)


def test_the_road_is_chosen_by_the_budget(monkeypatch: pytest.MonkeyPatch) -> None:
    raw = _raw("four_bar", 100_000)
    assert isinstance(open_solve(raw), ks.Solution)                 # within the budget
    monkeypatch.setattr(streamed, "budget", lambda: (1e6, "test"))
    assert isinstance(open_solve(raw), StreamedSolve)
    # a sweep the solver does not solve in blocks is not streamed: refused in one line
    raw = _raw("four_bar", 100_000)
    raw["driver"]["start"], raw["driver"]["stop"] = 359.9, 0.0     # decreasing
    monkeypatch.setenv("WORKBENCH_MEMORY", "50M")
    with pytest.raises(ks.WorkbenchError, match="cannot be streamed .its driver positions do "
                       "not increase"):
        open_solve(raw)
    with pytest.raises(ks.WorkbenchError, match="resisting"):
        open_solve(_raw("shaper", 100_000))
    # without --out (ks.solve), the refusal names the streamed road
    with pytest.raises(ks.WorkbenchError, match="solve --out"):
        ks.solve(_raw("four_bar", 100_000))


FULL_DISK = """
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (3_000_000, 3_000_000))
from kinetostatics.results.streamed import StreamedSolve
from kinetostatics.solver.pipeline import Sweep
import json
raw = json.loads(sys.argv[1])
try:
    StreamedSolve(Sweep(raw, budget=False), block=20_000).write(sys.argv[2])
except OSError as exc:
    print(exc)
    sys.exit(3)
"""


@pytest.mark.skipif(not hasattr(os, "fork") or sys.platform == "darwin",
                    reason="RLIMIT_FSIZE as a full disk: Linux")
def test_a_full_disk_leaves_no_streamed_folder(tmp_path: Path) -> None:
    """reactions.csv passes the 3 MB file-size limit halfway: nothing is left."""
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-c", FULL_DISK, json.dumps(_raw("four_bar", 40_000)),
                        str(out)], capture_output=True, text=True, cwd=ROOT, timeout=300,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert r.returncode == 3 and "File too large" in r.stdout, r.stdout + r.stderr
    assert not out.exists()
