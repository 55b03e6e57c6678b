"""The grader's side of a graded notebook's kernel: the nbclient client that keeps the
limits of time and output, and the kernel manager that starts the kernel in its
sandbox (:mod:`~kinetostatics.teaching.sandbox`).

The kernel speaks to the grader through Unix sockets in its scratch folder (Jupyter's
``ipc`` transport: a kernel without network has no TCP ports to offer). The grader
reads no message larger than the output limit (ZeroMQ drops it and the connection with
it: the grader watches its output socket for that and stops the kernel, naming the
limit), counts what the cells print and display, and stops the kernel when the count
passes the limit.
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

#: How long a kernel whose output connection dropped may take to be seen dead before the
#: drop is blamed on a message larger than the output limit (:meth:`GradingClient.
#: _still_alive`; a drop by an oversized message leaves the kernel running).
DEATH_SECONDS = 3.0

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
    args_pipe: tuple[int, int | None] | None = None

    def format_kernel_cmd(self, extra_arguments: list[str] | None = None) -> list[str]:
        """The kernel spec's command, wrapped in bwrap; bwrap's options (the paths it
        binds and covers, the environment) go through a pipe (``--args``), so that the
        sandbox's ``/proc/1/cmdline`` shows none of them, only the kernel's command."""
        argv = super().format_kernel_cmd(extra_arguments)
        cmd = self.sandbox.command(argv, self.scratch, self.uid)
        r, w = self.args_pipe
        self.args_pipe = (r, None)          # the write end is closed here, never again
        end = cmd.index("--")                # bwrap wants its command on its command line
        with os.fdopen(w, "wb") as f:       # a few kB: the pipe holds them unread
            f.write(b"".join(a.encode() + b"\0" for a in cmd[1:end]))
        return [cmd[0], "--args", str(r), *cmd[end:]]

    def close_pipe(self) -> None:
        """Close the grader's end of the arguments' pipe (bwrap has read it)."""
        if self.args_pipe is not None:
            for fd in self.args_pipe:
                if fd is not None:
                    os.close(fd)
            self.args_pipe = None

    def write_connection_file(self, **kwargs) -> None:
        """Write the connection file, readable by the kernel's own user."""
        super().write_connection_file(**kwargs)
        if self.uid is not None:
            os.chown(self.connection_file, self.uid, self.uid)

    async def _async_post_start_kernel(self, **kw) -> None:
        self.process = self.provisioner.process
        self.close_pipe()
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
    km.args_pipe = os.pipe()
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
        self.manager = kw.get("km")             # nbclient forgets it once cleaned up
        self.limits = limits
        self.cell = 0
        self.whole = False
        self.stopped = ""
        self.printed = 0
        self.t0 = time.monotonic()
        self.watch = None               # the output socket's monitor (:meth:`_dropped`)

    def _started(self, cell=None, cell_index=0, **_):
        if self._dropped():             # in the cell before, which keeps the blame
            from nbclient.exceptions import DeadKernelError
            raise DeadKernelError(self.stopped)
        self.cell = int(cell_index)

    def _dropped(self) -> bool:
        """Whether a message larger than the output limit was dropped (ZeroMQ then drops
        the connection of the output socket, which the monitor reports) while the
        kernel lives (its death drops the connection too); then the kernel is stopped
        with the reason. The monitor is set on the first call, once the kernel's client
        has its channels."""
        import zmq
        from zmq.utils.monitor import recv_monitor_message

        if self.stopped:
            return True
        if self.watch is None:
            channel = getattr(getattr(self, "kc", None), "iopub_channel", None)
            sock = getattr(channel, "socket", None)
            if sock is None or not hasattr(self.manager, "sandbox"):
                return False            # (no cap on messages without the sandbox)
            address = f"inproc://ks-output-{id(self)}"
            sock.monitor(address, zmq.EVENT_DISCONNECTED)
            self.watch = zmq.Context.shadow(sock.context.underlying).socket(zmq.PAIR)
            self.watch.connect(address)
            return False
        lost = False
        while self.watch.poll(0):
            lost |= recv_monitor_message(self.watch)["event"] == zmq.EVENT_DISCONNECTED
        if lost and self._still_alive():
            self.stopped = (f"printed a message larger than the output limit "
                            f"({self.limits.output_mb:g} MB): stopped")
            self.kill()
        return bool(self.stopped)

    def _still_alive(self, wait: float = DEATH_SECONDS) -> bool:
        """Whether the kernel still lives ``wait`` seconds after its output connection
        dropped. A kernel that dies drops that connection too, a moment before its
        process can be reaped: on a loaded 2-core machine a kernel that killed its own
        sandbox was seen alive at the drop and its death blamed on the output limit
        (2026-12-01, CI beside two busy loops). A dropped message leaves the kernel
        running, so only a kernel that stays up that long is blamed."""
        end = time.monotonic() + wait
        while self.exit_code() is None:
            if time.monotonic() >= end:
                return True
            time.sleep(0.05)
        return False

    def _unwatch(self) -> None:
        """Close the monitor (before the client's ZeroMQ context ends: an open socket
        would hold its end for minutes)."""
        if self.watch is not None:
            self.watch.close(linger=0)
            self.watch = None

    async def _async_cleanup_kernel(self) -> None:
        self._unwatch()
        await super()._async_cleanup_kernel()

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
        if self._dropped():
            return None
        if self.printed > self.limits.output_mb * (1 << 20) and not self.stopped:
            self.stopped = (f"printed more than {self.limits.output_mb:g} MB (the output "
                            "limit): stopped")
            self.kill()
            return None
        if self.stopped:
            return None
        return super().process_message(msg, cell, cell_index)

    def launch_options(self) -> dict:
        """What the kernel's process needs besides the usual: the read end of the
        sandbox's arguments' pipe, and nbclient's clean-up of a kernel manager it did
        not make (its channels and ZeroMQ contexts: 17 file descriptors a notebook)."""
        pipe = getattr(self.manager, "args_pipe", None)
        return {"pass_fds": (pipe[0],), "cleanup_kc": True} if pipe else {}

    def kill(self) -> None:
        """Kill the kernel's process group at once (bwrap takes its sandbox along)."""
        km = self.km or self.manager
        proc = getattr(km, "process", None) or getattr(
            getattr(km, "provisioner", None), "process", None)
        if proc is not None and proc.poll() is None:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except OSError:
                proc.kill()

    def exit_code(self) -> int | None:
        """The kernel process's exit code once it ended (bwrap: 128 + signal)."""
        proc = getattr(self.manager or self.km, "process", None)
        return None if proc is None else proc.poll()

    def close(self) -> None:
        """Make sure nothing of the kernel is left (and nbclient's exit hook, which
        cannot clean a kernel that never started, is not called at exit)."""
        self.kill()
        self._unwatch()
        if hasattr(self.manager, "close_pipe"):
            self.manager.close_pipe()
        atexit.unregister(self._cleanup_kernel)
