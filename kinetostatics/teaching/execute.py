"""Running a submitted notebook in a fresh kernel, in a sandbox, to read its answers.

A copy of the notebook runs top to bottom in a fresh ``python3`` kernel (nbclient),
from an empty scratch folder, with a time limit per cell; the submitted file is never
changed. The kernel runs in bubblewrap (:mod:`~kinetostatics.teaching.sandbox`): no
network, no view of the grader, the class folder or the other submissions, limits on
memory, time, processes, files and output. After the last cell the kernel's
``student_id`` and ``answers`` are read, so computed answers count as computed.

Without a sandbox (``sandbox=None``: the teacher's explicit ``--unsandboxed``) the
kernel runs as the teacher, with the whole machine in reach.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any

from ..model.errors import WorkbenchError
from .sandbox import Limits, Sandbox, exit_reason

__all__ = ["NotebookRunError", "SubmissionError", "cell_name", "run_notebook"]

_MARK = "KS-ANSWERS "
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
    """The failing cell of ``run`` (``nb`` with the answers' reader after its last),
    named in ``nb``'s numbering."""
    for k, cell in enumerate(run.cells, start=1):
        for out in cell.get("outputs", []):
            if out.get("output_type") == "error":
                return f"{cell_name(nb, k)} raised {out.get('ename')}: {out.get('evalue')}"
    return "a cell raised an error"


KERNEL_STARTS = 3      # a kernel that dies before it answers is started again, twice


def _execute(client, env: dict[str, str]) -> None:
    """Run ``client()``'s notebook; a kernel that dies before it replies to its first
    request (no cell has run: the machine's hiccup, not the notebook's fault; seen now
    and then in this project's tests, two kernels starting at a time on a 2-core
    machine, which graded the notebook as broken) is started again, up to
    ``KERNEL_STARTS`` times in all."""
    for attempt in range(1, KERNEL_STARTS + 1):
        try:
            # the kernel's own output streams (its start-up chatter) are not the teacher's
            # business, nor is the grader's terminal the kernel's: what the cells print
            # comes back through the notebook's outputs
            c = client()
            c.execute(env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                      stderr=subprocess.DEVNULL, **c.launch_options())
            return
        except RuntimeError as exc:
            if "before replying to kernel_info" not in str(exc) or attempt == KERNEL_STARTS:
                raise


class NotebookRunError(SubmissionError):
    """The notebook did not run to its end: a cell raised, ran too long, the kernel
    died or hit a limit of its sandbox (its saved answers may still be read)."""


def _run_in(run, tmp: str, timeout: float, kernel: str, sandbox: Sandbox | None,
            made: list) -> None:
    """Execute ``run`` in a kernel started in ``tmp``; ``made`` receives the clients
    (the last one knows why it stopped a kernel)."""
    from .kernels import GradingClient, sandboxed_kernel

    if sandbox is None:
        limits = Limits(cell_seconds=max(1.0, float(timeout)), notebook_seconds=1e9)
        env = _env()
    else:
        limits = sandbox.limits
        uid = sandbox.prepare(tmp)
        env = {"PATH": "/usr/bin:/bin"}        # bwrap's own; the kernel's is built anew

    def client():
        km = None if sandbox is None else sandboxed_kernel(sandbox, tmp, uid, kernel)
        made.append(GradingClient(run, limits, km=km, kernel_name=kernel,
                                  resources={"metadata": {"path": tmp}}))
        return made[-1]
    try:
        _execute(client, env)
    finally:
        for c in made:
            c.close()


def _stopped(made: list, nb, dead: bool = False) -> str:
    """Why the run stopped (a cell's or the notebook's time, the output limit, the
    kernel's death and its cause), naming the cell in ``nb``'s numbering."""
    c = made[-1] if made else None
    k = c.cell + 1 if c is not None else 0      # run.cells[k - 1] is the student's cell k
    where = cell_name(nb, k) if 0 < k <= len(nb.cells) else "a cell"
    if c is None:
        return "the kernel died while running the notebook"
    if c.stopped:
        return f"{where} {c.stopped}"
    if not dead:
        if c.whole:
            return (f"the notebook ran longer than {c.limits.notebook_seconds:g} s (the "
                    f"limit per notebook), in {where}")
        return f"{where} ran longer than {c.limits.cell_seconds:g} s"
    code = c.exit_code()
    why = "" if code is None else f": {exit_reason(code, c.limits)}"
    return f"the kernel died in {where}{why}"


def run_notebook(nb, timeout: float = 60.0, kernel: str = "python3",
                 sandbox: Sandbox | None = None) -> tuple[str | None, dict[str, Any]]:
    """Run a notebook in a fresh kernel and read its ``student_id`` and ``answers``.

    Parameters
    ----------
    nb : nbformat.NotebookNode
        The submitted notebook (not changed).
    timeout : float
        Seconds allowed per cell (rounded up to whole seconds) without a sandbox; in a
        sandbox its limits' ``cell_seconds`` rule.
    kernel : str
        Kernel name.
    sandbox : Sandbox, optional
        The sandbox the kernel runs in (:func:`sandbox_or_refuse`); None runs the
        kernel as the grader's user, with no isolation.

    Returns
    -------
    student_id : str or None
        The kernel's ``student_id`` after the run.
    answers : dict
        The kernel's ``answers`` after the run (numbers as floats, text kept).

    Raises
    ------
    SubmissionError
        A cell raised (which one and what), a cell or the notebook ran longer than
        allowed, the kernel died or hit a limit (which), or the notebook leaves no
        ``answers`` dict.
    """
    import copy
    import tempfile

    import nbformat
    from nbclient.exceptions import CellExecutionError, CellTimeoutError, DeadKernelError

    run = copy.deepcopy(nb)
    for cell in run.cells:
        cell.pop("id", None)
    run.cells.append(nbformat.v4.new_code_cell(_READER))
    run.metadata["kernelspec"] = {"name": kernel, "display_name": kernel,
                                  "language": "python"}
    with tempfile.TemporaryDirectory(prefix="ks-grade-", ignore_cleanup_errors=True) as tmp:
        made: list = []
        try:
            _run_in(run, tmp, timeout, kernel, sandbox, made)
        except CellTimeoutError:
            raise NotebookRunError(_stopped(made, nb)) from None
        except DeadKernelError:
            raise NotebookRunError(_stopped(made, nb, dead=True)) from None
        except CellExecutionError:
            raise NotebookRunError(_failed_cell(run, nb)) from None
        except ValueError as exc:
            if "Invalid Signature" not in str(exc):
                raise
            raise NotebookRunError(_broken_message(made, nb)) from None
    return _answers_read(run)


def _broken_message(made: list, nb) -> str:
    """Why a kernel's message arrived broken (signed wrongly): the kernel could not
    finish sending it, most often because a thread of its own could not start within
    the sandbox's memory limit."""
    c = made[-1] if made else None
    k = c.cell + 1 if c is not None else 0
    where = cell_name(nb, k) if 0 < k <= len(nb.cells) else "a cell"
    limit = f" of {c.limits.memory_mb} MB" if c is not None else ""
    return (f"the kernel broke off a message in {where} (it could not start a thread: "
            f"most often the memory limit{limit} was hit)")


def _answers_read(run) -> tuple[str | None, dict[str, Any]]:
    text = "".join(o.get("text", "") for o in run.cells[-1].get("outputs", [])
                   if o.get("output_type") == "stream")
    line = next((ln for ln in text.splitlines() if ln.startswith(_MARK)), None)
    if line is None:
        raise SubmissionError("the notebook's answers could not be read after the run")
    try:
        got = json.loads(line[len(_MARK):])
        answers = got["answers"]
        sid = got["student_id"]
    except (ValueError, TypeError, KeyError):
        raise SubmissionError("the notebook's answers could not be read after the "
                              "run") from None
    if not isinstance(answers, dict):
        raise SubmissionError("after the run there is no dict named 'answers'")
    return (None if sid is None else str(sid)), answers
