"""Jupyter kernels forked from one process that imported the sheets' libraries once.

Every sheet the suite runs (tests/test_browser.py in JupyterLab, tests/test_notebooks.py
with nbclient) starts a fresh ``python3`` kernel, which imports ipykernel, matplotlib,
pandas and kinetostatics before the sheet's first picture: 1.5-1.8 s of the kernel's CPU,
the same in each. Here a *forker* process imports them once; the kernel spec
:func:`kernel_spec` writes runs a small *launcher* in place of ``python -m
ipykernel_launcher``, which asks the forker for a kernel: the forker forks, and the child
takes the launcher's environment, folder, standard streams and arguments and runs
ipykernel's ``IPKernelApp`` as ``ipykernel_launcher`` would. The kernel is the same
code, with the same modules, started in a fresh process; each sheet still runs every cell
(its imports find the modules loaded). The launcher stands for the kernel towards
Jupyter: it forwards the signals it gets (an interrupt, a shutdown's SIGTERM) to the
kernel and exits with its status; killed, its connection closes and the forker kills
the kernel.

Usage: ``python tests/_kernel_fork.py serve SOCKET`` (the forker, the fixture's child:
:class:`Forker`); ``python -S tests/_kernel_fork.py launch SOCKET -f CONNECTION_FILE``
(the kernel spec's command, stdlib only: started in 0.03 s).
"""

from __future__ import annotations

import array
import contextlib
import json
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

# what a sheet's kernel imports before its first picture (each sheet's first cell, the
# audit's hook, ipykernel itself); imported once by the forker
# (not ipywidgets nor matplotlib's inline backend: each ties itself to the kernel's shell
# when imported under one, registering the widgets' comm target and the inline figures'
# display; imported before the kernel, they would not)
PRELOAD = ("ipykernel.kernelapp", "ipykernel.ipkernel", "ipykernel.zmqshell",
           "IPython.core.pylabtools", "matplotlib.pyplot", "numpy", "pandas",
           "IPython.display", "kinetostatics", "kinetostatics.plot",
           "kinetostatics.plot.audit", "kinetostatics.notebook", "balance", "balance.plot")
# the forker's sockets, closed in each kernel
_OPEN: list[socket.socket] = []


# ---- the launcher (the kernel spec's command; the standard library only) ----------------

def _launch(path: str, argv: list[str]) -> int:
    """Ask the forker at ``path`` for a kernel with ``argv``; stand for it until it ends
    (its exit status returned)."""
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    conn.connect(path)
    request = json.dumps({"argv": argv, "cwd": os.getcwd(), "env": dict(os.environ)}).encode()
    fds = [sys.stdin.fileno(), sys.stdout.fileno(), sys.stderr.fileno()]
    conn.sendmsg([len(request).to_bytes(8, "big") + request],
                 [(socket.SOL_SOCKET, socket.SCM_RIGHTS, array.array("i", fds))])
    reader = conn.makefile("r")
    pid = int(reader.readline())

    def forward(signum, _frame) -> None:
        try:
            os.kill(pid, signum)
        except ProcessLookupError:
            pass

    for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT):
        signal.signal(signum, forward)
    line = ""
    while not line:
        try:
            line = reader.readline() or "1"        # (the forker gone: a failure)
        except InterruptedError:
            continue
    return int(line)


# ---- the forker ---------------------------------------------------------------------------

def _pythonpath(env) -> list[str]:
    return [os.path.abspath(p) for p in env.get("PYTHONPATH", "").split(os.pathsep) if p]


def _child(conn: socket.socket, request: dict, fds: list[int]) -> None:
    """In the forked child: become the kernel ``ipykernel_launcher`` would start."""
    for k, fd in enumerate(fds):
        os.dup2(fd, k)
        os.close(fd)
    conn.close()
    signal.signal(signal.SIGCHLD, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    for other in _OPEN:
        other.close()
    # sys.path as ``python -m ipykernel_launcher`` has it in the kernel's environment (the
    # launcher takes the folder out): the kernel's PYTHONPATH, then the interpreter's own
    own = _pythonpath(os.environ)
    os.environ.clear()
    os.environ.update(request["env"])
    os.chdir(request["cwd"])
    sys.path[:] = [*_pythonpath(os.environ), *(p for p in sys.path if p not in own)]
    import matplotlib
    # (matplotlib read MPLBACKEND when the forker imported it: the kernel's own, now;
    # ipykernel sets its inline backend there when none is set)
    if not os.environ.get("MPLBACKEND"):
        os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
    matplotlib.rcParams["backend"] = os.environ["MPLBACKEND"]
    # (ipykernel read JPY_PARENT_PID, the server's pid it watches, when the forker
    # imported it: the kernel's own given here)
    argv = [*request["argv"],
            f"--IPKernelApp.parent_handle={int(os.environ.get('JPY_PARENT_PID') or 0)}"]
    sys.argv = [sys.argv[0], *argv]
    from ipykernel.kernelapp import IPKernelApp
    try:
        IPKernelApp.launch_instance(argv=argv)
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else 1
    except BaseException:                               # noqa: BLE001 (the kernel's end)
        import traceback
        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


def _fork_one(conn: socket.socket) -> int:
    """One launcher's request: the kernel forked, the launcher told its pid."""
    head, fds, _flags, _addr = socket.recv_fds(conn, 8 + 65536, 3)
    size = int.from_bytes(head[:8], "big")
    data = head[8:]
    while len(data) < size:
        data += conn.recv(size - len(data))
    request = json.loads(data)
    pid = os.fork()
    if pid == 0:
        _child(conn, request, fds)
    for fd in fds:
        os.close(fd)
    conn.sendall(f"{pid}\n".encode())
    return pid


def _serve(path: str) -> None:
    """The forker: the modules imported, then one kernel forked per connection, in one
    thread (no thread but the one forking): a kernel that ends is reaped and its status
    sent to its launcher; a launcher's connection that closes (the launcher killed) has
    its kernel killed."""
    sys.modules.setdefault("rfc3987_syntax", None)      # (as the suite's processes do)
    import importlib
    import selectors
    for name in PRELOAD:
        importlib.import_module(name)
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    server.bind(path)
    server.listen(16)
    _OPEN.append(server)
    sel = selectors.DefaultSelector()
    sel.register(server, selectors.EVENT_READ)
    kernels: dict[int, socket.socket] = {}          # pid -> its launcher's connection
    parent = os.getppid()
    ending = []
    signal.signal(signal.SIGTERM, lambda *_: ending.append(True))
    print("ready", flush=True)
    # (its parent gone: the forker ends, and its kernels, which watch it, with it)
    while os.getppid() == parent and not ending:
        for key, _ in sel.select(timeout=0.2):
            if key.fileobj is server:
                conn, _ = server.accept()
                pid = _fork_one(conn)
                kernels[pid] = conn
                _OPEN.append(conn)
                sel.register(conn, selectors.EVENT_READ, pid)
            else:                                   # the launcher gone: its kernel too
                with contextlib.suppress(OSError):
                    if key.fileobj.recv(1):
                        continue
                with contextlib.suppress(ProcessLookupError):
                    os.kill(key.data, signal.SIGKILL)
                sel.unregister(key.fileobj)
        while kernels:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                break
            if pid == 0:
                break
            conn = kernels.pop(pid, None)
            if conn is not None:
                with contextlib.suppress(OSError, KeyError, ValueError):
                    sel.unregister(conn)
                with contextlib.suppress(OSError):
                    conn.sendall(f"{os.waitstatus_to_exitcode(status)}\n".encode())
                conn.close()
                _OPEN.remove(conn)
    # ended (SIGTERM): the kernels left killed and reaped here, so that their processor
    # time reaches the forker's parent with the forker's (tools/cpu_per_test.py)
    for pid in kernels:
        with contextlib.suppress(ProcessLookupError):
            os.kill(pid, signal.SIGKILL)
    for pid in kernels:
        with contextlib.suppress(ChildProcessError):
            os.waitpid(pid, 0)


class Forker:
    """The forker as a child of this process, and the kernel spec that asks it for
    kernels (:meth:`first_on`: its folder first on a ``JUPYTER_PATH``)."""

    def __init__(self, folder: Path, env: dict[str, str] | None = None) -> None:
        self.folder = folder
        folder.mkdir(parents=True, exist_ok=True)
        self.socket = str(folder / "forker.sock")
        self.process = subprocess.Popen(
            [sys.executable, __file__, "serve", self.socket], stdout=subprocess.PIPE,
            env=env, cwd=folder, text=True)
        if self.process.stdout.readline().strip() != "ready":
            raise RuntimeError("the kernel forker did not start")
        spec = folder / "kernels" / "python3"
        spec.mkdir(parents=True, exist_ok=True)
        (spec / "kernel.json").write_text(json.dumps({
            "argv": [sys.executable, "-S", __file__, "launch", self.socket,
                     "-f", "{connection_file}"],
            "display_name": "Python 3 (ipykernel)", "language": "python",
            "interrupt_mode": "signal", "metadata": {"debugger": False}}))

    @property
    def jupyter_path(self) -> str:
        """The folder to put first on ``JUPYTER_PATH`` (its kernels/python3)."""
        return str(self.folder)

    def first_on(self, path: str | None) -> str:
        """A ``JUPYTER_PATH`` (``path``, None or empty: unset) with this forker's kernel
        spec first."""
        return os.pathsep.join(filter(None, [self.jupyter_path, path]))

    def close(self) -> None:
        """The forker ended, its kernels killed."""
        self.process.terminate()
        try:
            self.process.wait(30)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()


if __name__ == "__main__":
    # (run as a script: its folder, tests/, is no place to import from; tests/kinetostatics
    # would stand for the package)
    if sys.path and os.path.abspath(sys.path[0]) == os.path.dirname(os.path.abspath(__file__)):
        del sys.path[0]
    if sys.argv[1] == "serve":
        _serve(sys.argv[2])
    else:
        sys.exit(_launch(sys.argv[2], sys.argv[3:]))
