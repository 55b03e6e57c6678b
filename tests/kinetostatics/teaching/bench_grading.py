"""Wall time of grading a class with executed notebooks: 1 and 2 processes, and a dask
LocalCluster of 2 workers (docs/exercises.md, "Big classes").

    PYTHONPATH=$PWD python tests/kinetostatics/teaching/bench_grading.py N [OUT.json]

Not a test (it runs for many minutes): each of the N submissions is a student's own
notebook with the key typed in, run top to bottom in its own kernel (the picture cell
solves and draws the mechanism).
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from pathlib import Path

import nbformat
import pandas as pd

from kinetostatics import teaching as T


def main(n: int, out: str | None) -> None:
    root = Path(tempfile.mkdtemp(prefix="ks-bench-"))
    ids = [f"s{k:03d}" for k in range(n)]
    t = time.perf_counter()
    T.generate_class("four_bar", ids, root / "class", jobs=2)
    res = {"students": n, "cores": os.cpu_count(),
           "generate_jobs2_s": round(time.perf_counter() - t, 1)}
    key = pd.read_csv(root / "class" / "key.csv", dtype={"student": str})
    subs = root / "subs"
    subs.mkdir()
    for sid in ids:
        g = key[key.student == sid]
        nb = nbformat.read(root / "class" / "students" / f"{sid}.ipynb", as_version=4)
        T.fill_answer_cell(nb, dict(zip(g.question, g.expected, strict=True)))
        nbformat.write(nb, str(subs / f"{sid}.ipynb"))

    def record(name, **kw):
        t0 = time.perf_counter()
        rep = T.grade_class(root / "class", [subs], timeout=120, **kw)
        dt = time.perf_counter() - t0
        assert not rep.broken and (rep.scores["score %"] == 100.0).all(), rep.broken[:3]
        res[name] = round(dt, 1)
        print(name, res[name], "s", flush=True)
        if out:
            Path(out).write_text(json.dumps(res, indent=1))

    record("grade_jobs2_s", jobs=2)
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        record("grade_dask2_s", executor=client.get_executor())
    record("grade_jobs1_s", jobs=1)
    print(json.dumps(res))


if __name__ == "__main__":
    main(int(sys.argv[1]), sys.argv[2] if len(sys.argv) > 2 else None)
