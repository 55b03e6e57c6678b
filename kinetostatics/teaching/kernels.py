"""The grader's side of a graded notebook's kernel: the nbclient client that keeps the
limits of time and output, and the kernel manager that starts the kernel in its
sandbox (:mod:`~kinetostatics.teaching.sandbox`).

The kernel speaks to the grader through Unix sockets in its scratch folder (Jupyter's
``ipc`` transport: a kernel without network has no TCP ports to offer). The grader
reads no message larger than the output limit (ZeroMQ drops it), counts what the
cells print and display, and stops the kernel when the count passes the limit.
"""

from __future__ import annotations

import atexit
import math
import os
import signal
import time
from pathlib import Path

from jupyter_client.manager import AsyncKernelManager
from nbclient import NotebookClient

from .sandbox import Limits, Sandbox

__all__ = ["GradingClient", "SandboxedKernelManager", "sandboxed_kernel"]


class SandboxedKernelManager(AsyncKernelManager):
    """A kernel manager whose kernel command runs inside a :class:`Sandbox`.

    Set ``sandbox``, ``scratch`` and ``uid`` (see :func:`sandboxed_kernel`) before the
    kernel starts.
    """

    sandbox: Sandbox | None = None
    scratch: str = ""
    uid: int | None = None
    process = None                          # the bwrap process, once started

    def format_kernel_cmd(self, extra_arguments: list[str] | None = None) -> list[str]:
        """The kernel spec's command, wrapped in bwrap."""
        argv = super().format_kernel_cmd(extra_arguments)
        return self.sandbox.command(argv, self.scratch, self.uid)

    def write_connection_file(self, **kwargs) -> None:
        """Write the connection file, readable by the kernel's own user."""
        super().write_connection_file(**kwargs)
        if self.uid is not None:
            os.chown(self.connection_file, self.uid, self.uid)

    async def _async_post_start_kernel(self, **kw) -> None:
        self.process = self.provisioner.process
        await super()._async_post_start_kernel(**kw)

    post_start_kernel = _async_post_start_kernel

    def client(self, **kwargs):
        """A client that reads no message larger than the output limit."""
        import zmq

        kc = super().client(**kwargs)
        cap = int(self.sandbox.limits.output_mb * (1 << 20)) + (1 << 16)
        kc.context.setsockopt(zmq.MAXMSGSIZE, cap)
        return kc


def sandboxed_kernel(sandbox: Sandbox, scratch: str | Path, uid: int | None,
                     kernel: str = "python3") -> SandboxedKernelManager:
    """A kernel manager for one notebook: its sockets and connection file in
    ``scratch``, its command in ``sandbox`` (under ``uid`` when grading as root)."""
    km = SandboxedKernelManager(kernel_name=kernel, transport="ipc",
                                ip=str(Path(scratch) / "k"))
    km.connection_file = str(Path(scratch) / "kernel.json")
    km.sandbox, km.scratch, km.uid = sandbox, str(scratch), uid
    km.cache_ports = False
    return km


class GradingClient(NotebookClient):
    """An nbclient client that keeps a notebook's limits of time and output.

    ``stopped`` says why the grader stopped the kernel (the output limit), ``""``
    otherwise; ``cell`` is the index of the cell started last; ``whole`` is True when a
    cell's time ran out because the notebook's did.
    """

    def __init__(self, nb, limits: Limits, **kw):
        super().__init__(nb, timeout=max(1, math.ceil(limits.cell_seconds)),
                         allow_errors=False, shutdown_kernel="immediate",
                         on_cell_start=self._started, **kw)
        self.timeout_func = self._cell_timeout
        self.limits = limits
        self.cell = 0
        self.whole = False
        self.stopped = ""
        self.printed = 0
        self.t0 = time.monotonic()

    def _started(self, cell=None, cell_index=0, **_):
        self.cell = int(cell_index)

    def _cell_timeout(self, cell) -> int:
        left = self.limits.notebook_seconds - (time.monotonic() - self.t0)
        self.whole = left < self.limits.cell_seconds
        return max(1, math.ceil(min(self.limits.cell_seconds, left)))

    def process_message(self, msg, cell, cell_index):
        """Count what the cells print and display; stop the kernel past the limit."""
        content = msg.get("content", {})
        size = len(content.get("text", "")) + sum(
            len(v) if isinstance(v, str) else 64 for v in content.get("data", {}).values())
        size += sum(len(x) for x in content.get("traceback", []) if isinstance(x, str))
        self.printed += size
        if self.printed > self.limits.output_mb * (1 << 20) and not self.stopped:
            self.stopped = (f"printed more than {self.limits.output_mb:g} MB (the output "
                            "limit): stopped")
            self.kill()
            return None
        if self.stopped:
            return None
        return super().process_message(msg, cell, cell_index)

    def kill(self) -> None:
        """Kill the kernel's process group at once (bwrap takes its sandbox along)."""
        proc = getattr(self.km, "process", None) or getattr(
            getattr(self.km, "provisioner", None), "process", None)
        if proc is not None and proc.poll() is None:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except OSError:
                proc.kill()

    def exit_code(self) -> int | None:
        """The kernel process's exit code once it ended (bwrap: 128 + signal)."""
        proc = getattr(self.km, "process", None)
        return None if proc is None else proc.poll()

    def close(self) -> None:
        """Make sure nothing of the kernel is left (and nbclient's exit hook, which
        cannot clean a kernel that never started, is not called at exit)."""
        self.kill()
        atexit.unregister(self._cleanup_kernel)
