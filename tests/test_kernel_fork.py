"""The kernels forked for the sheets' tests (tests/_kernel_fork.py) are those Jupyter
would start: the kernel's own folder, environment, sys.path and matplotlib backend; a
kernel whose launcher is killed (a shutdown at once) is gone with it."""

from __future__ import annotations

import json
import os
import time

import pytest

from tests import _shared_sheets as sheets
from tests._kernel_fork import Forker

# what the kernel reports of itself
REPORT = """
import json, os, sys
import matplotlib
print(json.dumps({"cwd": os.getcwd(), "path": sys.path, "mark": os.environ.get("FORK_MARK"),
                  "backend": matplotlib.get_backend(), "pid": os.getpid(),
                  "parent": get_ipython().kernel.parent.parent_handle,
                  "jpy_parent": os.environ.get("JPY_PARENT_PID")}))
"""


def _report(km) -> dict:
    client = km.client()
    client.start_channels()
    try:
        client.wait_for_ready(timeout=120)
        said: list[str] = []
        reply = client.execute_interactive(
            REPORT, timeout=120, output_hook=lambda m: said.append(m["content"]["text"])
            if m["msg_type"] == "stream" else None)
        assert reply["content"]["status"] == "ok", reply["content"]
        return json.loads("".join(said))
    finally:
        client.stop_channels()


@pytest.mark.slow
@pytest.mark.kernel
def test_a_forked_kernel_is_the_one_jupyter_starts(tmp_path, monkeypatch):
    """A kernel started through the forker's kernel spec, from a folder of its own with a
    variable in its environment, has that folder, that variable, the sys.path of a kernel
    started by ``python -m ipykernel_launcher`` (its PYTHONPATH first, the folder not in
    it), matplotlib's inline backend, the server's pid to watch; killed (its launcher),
    it is gone."""
    import psutil
    from jupyter_client.manager import KernelManager
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    env["PYTHONPATH"] = str(sheets.ROOT)
    forker = Forker(tmp_path / "forker", env=env)
    try:
        monkeypatch.setenv("JUPYTER_PATH", forker.jupyter_path)
        monkeypatch.setenv("FORK_MARK", "the kernel's own")
        monkeypatch.setenv("PYTHONPATH", str(sheets.ROOT))
        monkeypatch.delenv("MPLBACKEND", raising=False)
        folder = tmp_path / "sheets"
        folder.mkdir()
        km = KernelManager(kernel_name="python3")
        assert forker.jupyter_path in km.kernel_spec.resource_dir
        km.start_kernel(cwd=str(folder))
        try:
            seen = _report(km)
        finally:
            km.shutdown_kernel(now=True)            # the launcher killed
        for _ in range(100):                        # (the kernel killed by the forker)
            if not psutil.pid_exists(seen["pid"]):
                break
            time.sleep(0.1)
        gone = not psutil.pid_exists(seen["pid"])
    finally:
        forker.close()
    assert seen["cwd"] == str(folder) and seen["mark"] == "the kernel's own"
    assert seen["path"][0] == str(sheets.ROOT) and str(folder) not in seen["path"]
    assert seen["backend"] == "module://matplotlib_inline.backend_inline"
    assert seen["parent"] == int(seen["jpy_parent"]) == os.getpid()
    assert gone, "the kernel outlived its launcher"
