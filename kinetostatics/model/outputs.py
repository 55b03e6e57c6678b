"""Outputs written whole or not at all: a run's files staged under temporary names in the
target folder and renamed into place once every one of them is complete.

A run writes into a *staging folder* inside its target folder (``.staging-<pid>-<n>``,
on the same file system, so that a rename is atomic). When the run ends well, the old
files of the same run kind that the new run did not write are removed (a CSV run after
a Parquet run leaves no Parquet tables of the earlier run beside it), the earlier
``summary.json`` goes first and the new one comes last, and each new file is renamed
into place. When the run fails (an error, a full disk, an interrupt), the staging folder
is removed: the earlier results stay as they were, untouched, and a folder the run
created is removed again. A run killed outright leaves only its hidden staging folder,
which the next run into that folder removes.

A run that fails where an earlier run of its kind left results gets a note beside them,
``FAILED.txt``, saying which run failed, why, and that the other files are older; the
earlier ``summary.json`` (the file that says "a run is here", which a script reads as
current) is removed, the earlier tables are not touched; the next run that ends well
removes the note.

Used by every writer of the workbench: :meth:`kinetostatics.Solution.write`, the ``cam``
and ``motion`` outputs, the balancing report, the grades files (docs/limits.md).
"""

from __future__ import annotations

import contextlib
import fnmatch
import itertools
import os
import shutil
import sys
from collections.abc import Iterable, Iterator
from datetime import UTC, datetime
from pathlib import Path

STAGING = ".staging-"       # prefix of the staging folders (hidden)
PARTIAL = ".partial-"       # prefix of a single file being written
FAILED = "FAILED.txt"       # the note left beside earlier results by a failed run
LAST = ("summary.json",)    # the files that say "a run is here": removed first, put last
_serial = itertools.count()


class StagedFolder:
    """The staging side of one run into ``target`` (see :func:`staged_folder`).

    Attributes
    ----------
    target : Path
        The folder the run's files end up in.
    kind : tuple of str
        Glob patterns of the files of this run kind (``"*.csv"``, ``"summary.json"``):
        earlier files matching them that the run does not write again are removed when it
        ends well.
    """

    def __init__(self, target: str | Path, kind: Iterable[str] = ()):
        self.target = Path(target)
        self.kind = tuple(kind)
        self._stage: Path | None = None
        self._created = False

    @property
    def path(self) -> Path:
        """The staging folder (created on first use, with the target folder if need be):
        write every file of the run here, under its final name."""
        if self._stage is None:
            if not self.target.exists():
                self.target.mkdir(parents=True)
                self._created = True
            elif not self.target.is_dir():
                raise FileExistsError(17, "exists and is not a folder", str(self.target))
            _remove_stale(self.target)
            stage = self.target / f"{STAGING}{os.getpid()}-{next(_serial)}"
            stage.mkdir()
            self._stage = stage
        return self._stage

    def file(self, name: str) -> Path:
        """Where to write the run's file ``name`` (inside the staging folder)."""
        return self.path / name

    def earlier(self) -> list[Path]:
        """The files of this run kind in the target folder now (an earlier run's)."""
        if not self.target.is_dir():
            return []
        return sorted(p for p in self.target.iterdir()
                      if p.is_file() and any(fnmatch.fnmatch(p.name, k) for k in self.kind))

    def commit(self) -> list[Path]:
        """Put the staged files in place; return their final paths (in name order, the
        files of ``LAST`` at the end)."""
        if self._stage is None:
            return []
        new = sorted((p for p in self._stage.iterdir()),
                     key=lambda p: (p.name in LAST, p.name))
        names = {p.name for p in new}
        old = self.earlier()
        for p in sorted(old, key=lambda p: p.name not in LAST):   # summary.json first
            if p.name not in names or p.name in LAST:
                p.unlink(missing_ok=True)
        (self.target / FAILED).unlink(missing_ok=True)
        out = []
        for p in new:
            dest = self.target / p.name
            if dest.is_dir() and not p.is_dir():
                raise IsADirectoryError(21, "a folder is in the way of a result file",
                                        str(dest))
            os.replace(p, dest)
            out.append(dest)
        self._stage.rmdir()
        self._stage = None
        return out

    def abandon(self) -> None:
        """Remove the staging folder (and the target folder, when this run created it and
        nothing else is in it)."""
        if self._stage is not None:
            shutil.rmtree(self._stage, ignore_errors=True)
            self._stage = None
        if self._created:
            with contextlib.suppress(OSError):
                self.target.rmdir()
            self._created = False


@contextlib.contextmanager
def staged_folder(target: str | Path, kind: Iterable[str] = ()) -> Iterator[StagedFolder]:
    """Write a run's files into ``target`` whole or not at all.

    Parameters
    ----------
    target : str or Path
        The output folder (created when needed; removed again if the run fails and it
        was created for it).
    kind : iterable of str
        Glob patterns of the files of this run kind in ``target``: those of an earlier run
        not written again are removed when this one ends well.

    Yields
    ------
    StagedFolder
        Write each file to ``stage.file(name)``. On a normal exit the files are renamed
        into place; on an exception the staging folder is removed and the earlier files
        stay untouched.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> out = Path(tempfile.mkdtemp()) / "run"
    >>> with staged_folder(out, ("*.csv", "summary.json")) as stage:
    ...     _ = stage.file("motion.csv").write_text("phi,s")
    ...     _ = stage.file("summary.json").write_text("{}")
    >>> sorted(p.name for p in out.iterdir())
    ['motion.csv', 'summary.json']
    """
    stage = StagedFolder(target, kind)
    try:
        yield stage
        stage.commit()
    except OSError as exc:
        stage.abandon()
        raise _told(exc, stage.target, "its earlier files are kept as they were") from exc
    except BaseException:
        stage.abandon()
        raise


@contextlib.contextmanager
def failure_noted(target: str | Path | None, kind: Iterable[str], what: str = "run",
                  ) -> Iterator[None]:
    """Note a failed run beside the earlier results it leaves in ``target``.

    When the body raises and ``target`` holds files of this run ``kind``, ``FAILED.txt``
    is written beside them: the run, the time, the error, and that the other files are
    from an earlier run; the earlier ``summary.json`` is removed, so that no summary there
    looks current. Nothing is written when there is no earlier result (a new folder is
    not created for the note). A run that ends well removes the note
    (:meth:`StagedFolder.commit`). ``target`` None: nothing to do.
    """
    try:
        yield
    except BaseException as exc:
        if target is not None:
            _note_failure(StagedFolder(target, kind), what, exc)
        raise


def _note_failure(stage: StagedFolder, what: str, exc: BaseException) -> None:
    earlier = [p for p in stage.earlier() if p.name != FAILED]
    if not earlier:
        return
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M:%S UTC")
    old = datetime.fromtimestamp(max(p.stat().st_mtime for p in earlier), UTC)
    reason = " ".join(str(exc).split()) or type(exc).__name__
    summaries = [p for p in earlier if p.name in LAST]
    text = (f"The {what} of {when} into this folder failed: {reason}\n"
            f"The other files here are from an earlier run (last written "
            f"{old:%Y-%m-%d %H:%M:%S UTC}), not from the run that failed"
            + (f"; its {', '.join(p.name for p in summaries)} was removed" if summaries else "")
            + ".\n")
    with contextlib.suppress(OSError):          # a full disk: the error is told anyway
        with atomic_file(stage.target / FAILED) as tmp:
            tmp.write_text(text, encoding="utf-8")
        for p in summaries:
            p.unlink(missing_ok=True)


@contextlib.contextmanager
def atomic_file(path: str | Path) -> Iterator[Path]:
    """Write one file whole or not at all: yields a temporary path beside ``path``
    (``.partial-<pid>-<n>-<name>``), renamed to ``path`` when the body ends well and
    removed when it fails (an earlier ``path`` then stays untouched). The parent folder
    is created when needed (and removed again on failure if it was created)."""
    path = Path(path)
    parent = path.parent
    created = []
    if parent.is_dir():
        _remove_stale(parent)
    else:
        for p in (parent, *parent.parents):
            if p.exists():
                break
            created.append(p)
        parent.mkdir(parents=True)
    tmp = parent / f"{PARTIAL}{os.getpid()}-{next(_serial)}-{path.name}"
    try:
        yield tmp
        if not tmp.exists():
            raise FileNotFoundError(2, "the file was not written", str(path))
        os.replace(tmp, path)
    except BaseException as exc:
        tmp.unlink(missing_ok=True)
        for p in created:
            with contextlib.suppress(OSError):
                p.rmdir()
        if isinstance(exc, OSError):
            raise _told(exc, path, "it was not changed") from exc
        raise


def _told(exc: OSError, target: Path, kept: str) -> OSError:
    """``exc`` with a message that names the output and says what became of it (a write
    that fails on a full disk names no file)."""
    if exc.filename is not None and not isinstance(exc, FileNotFoundError):
        return exc
    reason = exc.strerror or str(exc)
    return type(exc)(exc.errno, f"{reason} while writing {target} ({kept})")


def _remove_stale(folder: Path) -> None:
    """Remove the staging folders and partial files of runs that are gone (a run killed
    outright leaves them)."""
    for p in folder.iterdir():
        for prefix in (STAGING, PARTIAL):
            if p.name.startswith(prefix):
                pid = p.name[len(prefix):].split("-")[0]
                if pid.isdigit() and not _alive(int(pid)):
                    if p.is_dir():
                        shutil.rmtree(p, ignore_errors=True)
                    else:
                        p.unlink(missing_ok=True)


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    if sys.platform == "win32":
        return True                     # no cheap check: leave it
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True
    return True
