"""What the sandbox costs per submission (docs/exercises.md, "The sandbox").

    PYTHONPATH=$PWD python tests/kinetostatics/teaching/bench_sandbox.py [REPEATS]

Not a test: one four-bar student's notebook with the key typed in is run top to
bottom (the picture cell solves and draws the mechanism), in its sandbox and without
one, alternately, REPEATS times each (default 5); and bwrap alone starts ``true`` in
the same sandbox. Prints the medians and the best runs.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import nbformat
import pandas as pd

from kinetostatics import teaching as T
from kinetostatics.teaching.execute import run_notebook
from kinetostatics.teaching.sandbox import sandbox_or_refuse


def main(repeats: int) -> dict:
    root = Path(tempfile.mkdtemp(prefix="ks-bench-"))
    T.generate_class("four_bar", ["s000"], root / "class", seed=1)
    key = pd.read_csv(root / "class" / "key.csv", dtype={"student": str})
    nb = nbformat.read(root / "class" / "students" / "s000.ipynb", as_version=4)
    T.fill_answer_cell(nb, dict(zip(key.question, key.expected, strict=True)))
    sb = sandbox_or_refuse(hide=[root])
    times: dict[str, list[float]] = {"sandbox": [], "none": [], "bwrap_true": []}
    for _ in range(repeats):
        for name, box in (("sandbox", sb), ("none", None)):
            t = time.perf_counter()
            sid, answers = run_notebook(nb, sandbox=box)
            times[name].append(time.perf_counter() - t)
            assert sid == "s000" and len(answers) == len(key)
        with tempfile.TemporaryDirectory() as tmp:
            uid = sb.scratch_owner()
            if uid is not None:
                import os

                os.chown(tmp, uid, uid)
            t = time.perf_counter()
            subprocess.run(sb.command(["true"], tmp, uid), check=True)
            times["bwrap_true"].append(time.perf_counter() - t)
    res = {k: {"median_s": round(statistics.median(v), 3), "best_s": round(min(v), 3)}
           for k, v in times.items()}
    res["repeats"] = repeats
    print(json.dumps(res, indent=1))
    return res


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
