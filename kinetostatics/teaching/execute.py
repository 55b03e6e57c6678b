"""Running a submitted notebook in a clean kernel, without network, to read its answers.

A copy of the notebook runs top to bottom in a fresh ``python3`` kernel (nbclient),
from an empty temporary folder, with a time limit per cell; the submitted file is
never changed. Before the student's first cell a guard cell switches the network off
(Python sockets may connect only to this machine: a guard against accidental
downloads, not a sandbox against a hostile student). After the last cell the kernel's
``student_id`` and ``answers`` are read, so computed answers count as computed.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import tempfile
from pathlib import Path
from typing import Any

from ..model.errors import WorkbenchError

__all__ = ["NotebookRunError", "SubmissionError", "cell_name", "run_notebook"]

_MARK = "KS-ANSWERS "
_GUARD = '''import socket as _ks_socket

def _ks_no_network(*_a, **_k):
    raise OSError("the network is switched off while the notebook is graded")

def _ks_guard(orig):
    def connect(self, address, *rest):
        if self.family in (_ks_socket.AF_INET, _ks_socket.AF_INET6) and \\
                str(address[0]) not in ("127.0.0.1", "::1", "localhost"):
            _ks_no_network()
        return orig(self, address, *rest)
    return connect

_ks_socket.socket.connect = _ks_guard(_ks_socket.socket.connect)
_ks_socket.socket.connect_ex = _ks_guard(_ks_socket.socket.connect_ex)
_ks_getaddrinfo = _ks_socket.getaddrinfo
_ks_socket.getaddrinfo = lambda host, *a, **k: (
    _ks_getaddrinfo(host, *a, **k) if host in (None, "localhost", "127.0.0.1", "::1")
    else _ks_no_network())
del _ks_guard'''
_READER = '''import json as _ks_json

def _ks_value(v):
    if v is None or isinstance(v, (str, bool)):
        return v
    try:
        return float(v)
    except (TypeError, ValueError):
        return repr(v)

_ks_ans = globals().get("answers")
print("KS-ANSWERS " + _ks_json.dumps({
    "student_id": None if globals().get("student_id") is None else str(student_id),
    "answers": ({str(k): _ks_value(v) for k, v in _ks_ans.items()}
                if isinstance(_ks_ans, dict) else None)}))'''


class SubmissionError(WorkbenchError):
    """A submission that cannot be read or run (the reason says why)."""


def _env() -> dict[str, str]:
    root = str(Path(__file__).resolve().parents[2])
    env = dict(os.environ)
    env["MPLBACKEND"] = "Agg"
    env["PYTHONPATH"] = os.pathsep.join([root, *filter(None, [env.get("PYTHONPATH")])])
    for k in ("http_proxy", "https_proxy", "HTTP_PROXY", "HTTPS_PROXY"):
        env[k] = "http://127.0.0.1:9"            # nothing listens there: pip fails fast
    env["PIP_NO_INDEX"] = "1"
    return env


def _first_line(cell) -> str:
    src = cell.get("source", "")
    src = "".join(src) if isinstance(src, list) else str(src)
    line = next((ln.strip() for ln in src.splitlines() if ln.strip()), "")
    return line if len(line) <= 60 else line[:57] + "..."


def cell_name(nb, k: int) -> str:
    """``cell k ("its first line")``: a cell as a teacher finds it (every cell counted
    from 1, as the notebook shows them top to bottom)."""
    return f"cell {k} ({_first_line(nb.cells[k - 1])!r})" if 0 < k <= len(nb.cells) \
        else f"cell {k}"


def _failed_cell(run, nb) -> str:
    """The failing cell of ``run`` (``nb`` with a guard cell before its first), named
    in ``nb``'s numbering."""
    for k, cell in enumerate(run.cells):
        for out in cell.get("outputs", []):
            if out.get("output_type") == "error":
                return f"{cell_name(nb, k)} raised {out.get('ename')}: {out.get('evalue')}"
    return "a cell raised an error"


KERNEL_STARTS = 3      # a kernel that dies before it answers is started again, twice


def _execute(client) -> None:
    """Run ``client()``'s notebook; a kernel that dies before it replies to its first
    request (no cell has run: the machine's hiccup, not the notebook's fault; seen now
    and then in this project's tests, two kernels starting at a time on a 2-core
    machine, which graded the notebook as broken) is started again, up to
    ``KERNEL_STARTS`` times in all."""
    for attempt in range(1, KERNEL_STARTS + 1):
        try:
            # the kernel's own stderr (its start-up chatter) is not the teacher's business;
            # what the cells print comes back through the notebook's outputs
            client().execute(env=_env(), stderr=subprocess.DEVNULL)
            return
        except RuntimeError as exc:
            if "before replying to kernel_info" not in str(exc) or attempt == KERNEL_STARTS:
                raise


class NotebookRunError(SubmissionError):
    """The notebook did not run to its end: a cell raised, ran too long, or the kernel
    died (its saved answers may still be read)."""


def run_notebook(nb, timeout: float = 60.0, kernel: str = "python3"
                 ) -> tuple[str | None, dict[str, Any]]:
    """Run a notebook in a clean kernel and read its ``student_id`` and ``answers``.

    Parameters
    ----------
    nb : nbformat.NotebookNode
        The submitted notebook (not changed).
    timeout : float
        Seconds allowed per cell (rounded up to whole seconds).
    kernel : str
        Kernel name.

    Returns
    -------
    student_id : str or None
        The kernel's ``student_id`` after the run.
    answers : dict
        The kernel's ``answers`` after the run (numbers as floats, text kept).

    Raises
    ------
    SubmissionError
        A cell raised (which one and what), a cell ran longer than ``timeout``, the
        kernel died, or the notebook leaves no ``answers`` dict.
    """
    import copy

    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError, CellTimeoutError, DeadKernelError

    run = copy.deepcopy(nb)
    for cell in run.cells:
        cell.pop("id", None)
    run.cells.insert(0, nbformat.v4.new_code_cell(_GUARD))
    run.cells.append(nbformat.v4.new_code_cell(_READER))
    run.metadata["kernelspec"] = {"name": kernel, "display_name": kernel,
                                  "language": "python"}
    started = [0]

    def on_start(cell=None, cell_index=0, **_):
        started[0] = int(cell_index)

    orig = [*nb.cells]
    with tempfile.TemporaryDirectory(prefix="ks-grade-") as tmp:
        try:
            _execute(lambda: NotebookClient(
                run, timeout=max(1, math.ceil(timeout)), kernel_name=kernel,
                allow_errors=False, resources={"metadata": {"path": tmp}},
                on_cell_start=on_start))
        except CellTimeoutError:
            # run.cells[k] is the student's cell k (the guard cell is run.cells[0])
            k = started[0]
            where = cell_name(nb, k) if 0 < k <= len(orig) else "a cell"
            raise NotebookRunError(f"{where} ran longer than {timeout:g} s") from None
        except DeadKernelError:
            raise NotebookRunError("the kernel died while running the notebook") from None
        except CellExecutionError:
            raise NotebookRunError(_failed_cell(run, nb)) from None
    text = "".join(o.get("text", "") for o in run.cells[-1].get("outputs", [])
                   if o.get("output_type") == "stream")
    line = next((ln for ln in text.splitlines() if ln.startswith(_MARK)), None)
    if line is None:
        raise SubmissionError("the notebook's answers could not be read after the run")
    got = json.loads(line[len(_MARK):])
    if got["answers"] is None:
        raise SubmissionError("after the run there is no dict named 'answers'")
    return got["student_id"], got["answers"]
