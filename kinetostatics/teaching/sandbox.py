"""The sandbox a submitted notebook's kernel runs in while it is graded (bubblewrap).

Each notebook gets a kernel of its own, started by ``bwrap`` (bubblewrap, the sandbox
Flatpak uses) in namespaces of its own: no network (a network namespace with nothing
in it: the machine's loopback services cannot be reached), its own process tree (no
``/proc`` of the grader or of anything else), its own IPC and host name, and it dies
with the grader (``--die-with-parent``). It sees, read-only, the Python environment
and the workbench, and, writable, only its scratch folder (its working folder) and a
private ``/tmp``: nothing of the teacher's home, the class folder, the other
submissions or the grades. The kernel speaks to the grader through Unix sockets in
the scratch folder (Jupyter's ``ipc`` transport), not through TCP ports.

Its environment is built from nothing (``--clearenv``): ``PATH``, ``HOME`` (the
scratch folder), ``PYTHONPATH`` (the workbench), the locale, and one thread per
numerical library. The kernel gets no argument, variable, open file or working
folder that leads to the class folder; where the environment or the workbench lies
inside a folder the grader must hide (the class folder, a submission, the grades),
that folder is covered by an empty one.

The limits (:class:`Limits`) are the kernel's resource limits (``prlimit``): address
space, CPU seconds, processes (threads count), file size; the grader adds the wall
time per cell and per notebook and the size of what the cells print. Grading as
root (a container), the kernel runs under a user id of its own (Linux does not count
root's processes), so that the process limit holds.
"""

from __future__ import annotations

import functools
import os
import secrets
import shutil
import signal
import subprocess
import sys
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from ..model.errors import WorkbenchError

__all__ = ["ALLOCATORS", "INSTALL_HINT", "UNSANDBOXED_HINT", "Limits", "Sandbox",
           "SandboxUnavailable", "exit_reason", "find_bwrap", "sandbox_or_refuse"]

UNSANDBOXED_HINT = ("grade with --unsandboxed (the notebooks then run as you, with no "
                    "isolation)")
INSTALL_HINT = ("install bubblewrap (Debian/Ubuntu: apt install bubblewrap; Fedora: dnf "
                f"install bubblewrap), or {UNSANDBOXED_HINT}")


class SandboxUnavailable(WorkbenchError):
    """bubblewrap is missing or cannot start here (the reason and the way out)."""


@dataclass(frozen=True)
class Limits:
    """What one submitted notebook may use while it is graded.

    Parameters
    ----------
    memory_mb : int
        Address space of each process of the kernel, MB (``RLIMIT_AS``; 2048: a
        kernel that has drawn a mechanism inline uses 0.54 GB of address space, of
        which 0.18 GB is touched, with the allocators kept from reserving address
        space ahead, see :data:`ALLOCATORS`).
    cell_seconds : float
        Wall time of one cell, s (the grader interrupts it: ``--timeout``).
    notebook_seconds : float
        Wall time of the whole notebook, s (the grader stops the kernel).
    cpu_seconds : int
        CPU seconds of each process of the kernel (``RLIMIT_CPU``: the kernel is
        killed with ``SIGXCPU`` when it has spent them).
    processes : int
        Processes and threads of the kernel's user at a time (``RLIMIT_NPROC``; the
        kernel itself runs about 10 threads).
    file_mb : int
        Size of any file the notebook writes, MB (``RLIMIT_FSIZE``).
    output_mb : float
        What the cells print and display, in all, MB (the grader stops the kernel).
    """

    memory_mb: int = 2048
    cell_seconds: float = 60.0
    notebook_seconds: float = 600.0
    cpu_seconds: int = 300
    processes: int = 64
    file_mb: int = 64
    output_mb: float = 8.0

    def __post_init__(self):
        for name, low in (("memory_mb", 256), ("cell_seconds", 1), ("notebook_seconds", 1),
                          ("cpu_seconds", 1), ("processes", 16), ("file_mb", 1),
                          ("output_mb", 0.01)):
            v = getattr(self, name)
            if not isinstance(v, int | float) or not v >= low or v != v:
                raise WorkbenchError(f"sandbox limit {name}={v!r}: give a number >= {low}")

    def describe(self) -> str:
        """The limits in one line, as the console and the docs state them."""
        return (f"memory {self.memory_mb} MB per process, {self.cell_seconds:g} s per cell, "
                f"{self.notebook_seconds:g} s per notebook, {self.cpu_seconds} CPU s per "
                f"process, {self.processes} processes and threads, files up to "
                f"{self.file_mb} MB, output up to {self.output_mb:g} MB")

    def prlimit(self) -> list[str]:
        """The ``prlimit`` command that sets the kernel's resource limits."""
        cpu = int(self.cpu_seconds)
        return ["prlimit", f"--as={int(self.memory_mb) << 20}", f"--cpu={cpu}:{cpu + 2}",
                f"--nproc={int(self.processes)}", f"--fsize={int(self.file_mb) << 20}",
                "--core=0"]


def find_bwrap() -> str | None:
    """The ``bwrap`` executable, or None."""
    return shutil.which("bwrap")


def _under(p: Path, roots: Iterable[Path]) -> bool:
    return any(p == r or r in p.parents for r in roots)


_PROJECT = Path(__file__).resolve().parents[2]
"""The folder that holds the workbench's packages (kinetostatics, balance)."""


def _env_roots() -> list[Path]:
    """What a kernel must read: the Python environment and the workbench."""
    roots = {Path(sys.prefix).resolve(), Path(sys.base_prefix).resolve(),
             Path(sys.executable).resolve().parents[1], _PROJECT}
    out: list[Path] = []
    for r in sorted(roots, key=lambda q: len(q.parts)):
        if not _under(r, out) and r != Path("/"):
            out.append(r)
    return out


ALLOCATORS = {"MALLOC_ARENA_MAX": "2", "ARROW_DEFAULT_MEMORY_POOL": "system"}
"""What keeps a kernel's allocators from reserving address space it never touches
(``RLIMIT_AS`` counts reserved space): glibc's malloc reserves 64 MB per thread
arena, and pyarrow (which pandas loads) its own pool. Measured on a kernel that has
drawn a four-bar inline (15 threads): 2.23 GB of address space with neither, 1.59 GB
with the arena cap, 1.18 GB with the system pool, 0.54 GB with both (0.18 GB touched
in every case). Without them a 2048 MB limit killed the kernel's threads as it
started: a thread that cannot start broke a message off mid-way (the grader read
"Invalid Signature") or aborted the kernel at ``%matplotlib inline``."""

_ETC = ("ld.so.cache", "ld.so.conf", "ld.so.conf.d", "localtime", "fonts", "alternatives",
        "mime.types", "nsswitch.conf", "ssl")


@dataclass(frozen=True)
class Sandbox:
    """One way of running a kernel in bubblewrap: the limits and what to hide.

    Parameters
    ----------
    limits : Limits
        What a notebook may use.
    hide : tuple of paths
        Folders and files covered by an empty one where they lie inside what the
        kernel sees (the class folder, the submissions, the grades).
    bwrap : str
        The ``bwrap`` executable.
    """

    limits: Limits = field(default_factory=Limits)
    hide: tuple[str, ...] = ()
    bwrap: str = "bwrap"

    def command(self, argv: list[str], scratch: str | Path, uid: int | None = None
                ) -> list[str]:
        """``argv`` wrapped in ``bwrap``: run in ``scratch`` (bound at its own path),
        with the limits, under ``uid`` (grading as root: a user id of the kernel's
        own) or the grader's user (in a user namespace of its own)."""
        scratch = str(Path(scratch).resolve())
        roots = _env_roots()
        cmd = [self.bwrap, "--unshare-ipc", "--unshare-pid", "--unshare-net", "--unshare-uts",
               "--unshare-cgroup-try", "--die-with-parent", "--new-session"]
        if uid is None:
            cmd += ["--unshare-user", "--cap-drop", "ALL"]
        cmd += ["--ro-bind", "/usr", "/usr"]
        for d in ("bin", "lib", "lib64", "lib32", "sbin"):
            p = Path("/") / d
            if p.is_symlink():
                cmd += ["--symlink", os.readlink(p), str(p)]
            elif p.is_dir():
                cmd += ["--ro-bind", str(p), str(p)]
        for name in _ETC:
            cmd += ["--ro-bind-try", f"/etc/{name}", f"/etc/{name}"]
        # the private /tmp first: a root that lies under /tmp (a project or an environment
        # there) is bound over it, not covered by it
        cmd += ["--proc", "/proc", "--dev", "/dev", "--perms", "1777", "--tmpfs", "/tmp"]
        made: set[Path] = set()
        for r in roots:
            if not _under(r, [Path("/usr")]):
                # the folders above a bound one, created readable (bwrap makes them 0700)
                for up in reversed(r.parents[:-1]):
                    if up not in made:
                        made.add(up)
                        cmd += ["--perms", "0755", "--dir", str(up)]
                cmd += ["--ro-bind", str(r), str(r)]
        for h in self.hide:
            p = Path(h).resolve()
            if not p.exists():          # nothing to see, and nothing can be made there:
                continue                # what the kernel sees of the roots is read-only
            if _under(p, roots) or any(r in p.parents for r in [Path("/usr")]):
                cmd += (["--tmpfs", str(p)] if p.is_dir()
                        else ["--ro-bind", "/dev/null", str(p)])
        cmd += ["--bind", scratch, scratch, "--chdir", scratch, "--hostname", "sandbox",
                "--clearenv"]
        for k, v in self.environment(scratch, roots).items():
            cmd += ["--setenv", k, v]
        cmd.append("--")
        if uid is not None:                      # root: drop to a user of the kernel's own
            cmd += ["setpriv", f"--reuid={uid}", f"--regid={uid}", "--clear-groups",
                    "--inh-caps=-all", "--bounding-set=-all", "--no-new-privs"]
        return cmd + self.limits.prlimit() + ["--", *argv]

    @staticmethod
    def environment(scratch: str, roots: list[Path]) -> dict[str, str]:
        """The kernel's whole environment."""
        project = str(_PROJECT)
        env = {"PATH": os.pathsep.join([str(Path(sys.executable).parent), "/usr/local/bin",
                                        "/usr/bin", "/bin"]),
               "HOME": scratch, "TMPDIR": "/tmp", "PYTHONPATH": project,
               "MPLBACKEND": "Agg", "MPLCONFIGDIR": str(Path(scratch) / ".matplotlib"),
               "PYTHONDONTWRITEBYTECODE": "1", "LANG": "C.UTF-8", "LC_ALL": "C.UTF-8",
               "PIP_NO_INDEX": "1", "NUMBA_CACHE_DIR": str(Path(scratch) / ".numba"),
               **ALLOCATORS}
        for k in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                  "NUMEXPR_NUM_THREADS", "NUMBA_NUM_THREADS"):
            env[k] = "1"
        return env

    def prepare(self, scratch: str | Path) -> int | None:
        """Make ``scratch`` the kernel's: owned by the kernel's user when grading as
        root (returned, else None), with a copy of the grader's matplotlib font list
        (else every kernel builds it again: 0.3 s). Returns the kernel's user id."""
        uid = self.scratch_owner()
        mpl = Path(scratch) / ".matplotlib"
        mpl.mkdir(exist_ok=True)
        for f in _font_lists():
            shutil.copy(f, mpl / f.name)
        if uid is not None:
            for p in [Path(scratch), mpl, *mpl.iterdir()]:
                os.chown(p, uid, uid)
        return uid

    def scratch_owner(self) -> int | None:
        """The user id a kernel runs under when grading as root (a fresh one, so that
        no other process counts against its process limit), else None."""
        if os.geteuid() != 0:
            return None
        return 1_000_000 + secrets.randbelow(1_000_000_000)

    def probe(self, scratch: str | Path) -> str:
        """``""`` when a process starts in this sandbox here, else bwrap's reason."""
        uid = self.scratch_owner()
        if uid is not None:
            os.chown(scratch, uid, uid)
        try:
            res = subprocess.run(self.command(["true"], scratch, uid), capture_output=True,
                                 text=True, timeout=30, stdin=subprocess.DEVNULL,
                                 env={"PATH": "/usr/bin:/bin"}, cwd=scratch)
        except (OSError, subprocess.SubprocessError) as exc:
            return f"{type(exc).__name__}: {exc}"
        if res.returncode != 0:
            return (res.stderr.strip().splitlines() or [f"exit code {res.returncode}"])[-1]
        return ""


@functools.lru_cache(maxsize=1)
def _font_lists() -> tuple[Path, ...]:
    """matplotlib's font lists of the grader's cache (none when it has no cache)."""
    try:
        import matplotlib

        return tuple(Path(matplotlib.get_cachedir()).glob("fontlist-*.json"))
    except (ImportError, OSError, RuntimeError):     # pragma: no cover - no matplotlib
        return ()


@functools.lru_cache(maxsize=8)
def _probe(sandbox: Sandbox) -> str:
    import tempfile

    with tempfile.TemporaryDirectory(prefix="ks-probe-") as tmp:
        return sandbox.probe(tmp)


def sandbox_or_refuse(limits: Limits | None = None, hide: Iterable[str | Path] = ()
                      ) -> Sandbox:
    """The sandbox the notebooks of a class run in, once bubblewrap was seen starting.

    Raises
    ------
    SandboxUnavailable
        bwrap is missing or cannot start (namespaces disabled, another OS): one line
        saying how to install it and naming ``--unsandboxed``.
    """
    if not sys.platform.startswith("linux"):
        raise SandboxUnavailable(f"the grading sandbox (bubblewrap) needs Linux, this is "
                                 f"{sys.platform}: grade on Linux, or {UNSANDBOXED_HINT}")
    exe = find_bwrap()
    if exe is None:
        raise SandboxUnavailable(f"notebooks are graded in a sandbox and bwrap was not "
                                 f"found: {INSTALL_HINT}")
    sb = Sandbox(limits or Limits(), tuple(sorted({str(Path(h).resolve()) for h in hide})),
                 exe)
    why = _probe(sb)
    if why:
        raise SandboxUnavailable(f"bwrap cannot start a sandbox here ({why}): make user "
                                 f"namespaces available, or {UNSANDBOXED_HINT}")
    return sb


_SIGNALS = {signal.SIGKILL: "killed (SIGKILL)", signal.SIGSEGV: "crashed (SIGSEGV)"}


def exit_reason(code: int | None, limits: Limits) -> str:
    """Why a sandboxed kernel ended, from bwrap's exit code (128 + signal when the
    kernel was killed)."""
    if code is None:
        return "still running"
    sig = -code if code < 0 else (code - 128 if code > 128 else 0)
    if sig == signal.SIGXCPU:
        return f"killed: CPU time limit of {limits.cpu_seconds} s hit"
    if sig == signal.SIGXFSZ:
        return f"killed: file size limit of {limits.file_mb} MB hit"
    if sig:
        try:
            name = signal.Signals(sig).name
        except ValueError:
            name = f"signal {sig}"
        return _SIGNALS.get(sig, f"killed by {name}")
    return f"exited with code {code}"
