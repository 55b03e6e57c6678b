"""A class that cheats (issue 35): every submitted notebook runs in a bubblewrap sandbox.

One class is generated; each hostile student hands in their own notebook with one
attack cell after the answers cell (so that a stolen key would fill the answers), and
the whole class is graded once, from the command line, two notebooks at a time, with
small limits. Each test then reads that run for one attack: it must fail, the grading
must finish, the grades files and the class folder must not change, and the honest
students keep 100 %. The fast tests check the refusal without bwrap and the command.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import socket
import subprocess
import sys
import threading
from pathlib import Path

import nbformat
import pandas as pd
import pytest

from kinetostatics import teaching as T
from kinetostatics.cli import main
from kinetostatics.model.errors import WorkbenchError
from kinetostatics.teaching import classroom
from kinetostatics.teaching import sandbox as S

IDS = ["honest", "honest2", "proc", "walker", "cmdline", "seed", "writer", "net", "forker",
       "hog", "printer", "looper", "daemon", "parricide"]
SEED = 20261128
SLEEP = "6173"           # the background process's sleep, to find it afterwards
# the grader's limit per cell: the looper (and, on a loaded machine, the printer) runs
# this long (40 s before: their 80 s of CPU were most of the class's 85 s at a load of 9;
# the twelve other notebooks took 7 s each there, two at a time, cells and kernel start;
# at 12 s the forker's 48 processes were not all started at a load of 12, and its flag
# read "ran longer than 12 s" instead of BlockingIOError)
CELL_SECONDS = 20

STEAL = '''
import csv, glob, os
def _steal(path):
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["student"] == student_id:
                answers[row["question"]] = float(row["expected"])
'''

ATTACKS = {
    # up the process tree: each ancestor's working folder, then every open key.csv
    "proc": STEAL + """
pid = os.getppid()
while pid > 1:
    try:
        cwd = os.readlink(f"/proc/{pid}/cwd")
        for k in glob.glob(cwd + "/key.csv") + glob.glob(cwd + "/*/key.csv"):
            _steal(k)
        pid = int(open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[1])
    except (OSError, ValueError):
        break
for pid in [p for p in os.listdir("/proc") if p.isdigit()]:
    try:
        for fd in os.listdir(f"/proc/{pid}/fd"):
            if os.readlink(f"/proc/{pid}/fd/{fd}").endswith("key.csv"):
                _steal(f"/proc/{pid}/fd/{fd}")
    except OSError:
        pass
""",
    # every file named key.csv anywhere, and the class folder's path guessed right
    "walker": STEAL + '''
for root, dirs, files in os.walk("/"):
    # everything but the system's and the Python packages' own trees
    dirs[:] = [x for x in dirs if os.path.join(root, x) not in ("/proc", "/sys", "/usr")
               and x not in ("site-packages", "lib")]
    if "key.csv" in files:
        _steal(os.path.join(root, "key.csv"))
try:
    _steal(CLASS + "/key.csv")
except OSError:
    pass
''',
    # the class folder from the grader's command line
    "cmdline": STEAL + '''
for pid in [p for p in os.listdir("/proc") if p.isdigit()]:
    try:
        argv = open(f"/proc/{pid}/cmdline").read().split("\\0")
    except OSError:
        continue
    for a in argv:
        if os.path.isfile(os.path.join(a, "key.csv")):
            _steal(os.path.join(a, "key.csv"))
for k, v in os.environ.items():
    if os.path.isfile(os.path.join(v, "key.csv")):
        _steal(os.path.join(v, "key.csv"))
''',
    # the seed in teacher.json, and the key computed from it
    "seed": '''
import json
try:
    seed = json.load(open(CLASS + "/teacher.json"))["seed"]
    from kinetostatics import teaching as _T
    k = _T.exercise("slider_crank", seed).key([student_id])
    answers.update(dict(zip(k.question, k.expected)))
except OSError:
    pass
''',
    # the class folder, another student's notebook, the grades
    "writer": '''
for path in [CLASS + "/key.csv", CLASS + "/planted.txt", HONEST, GRADES]:
    try:
        with open(path, "a") as f:
            f.write("100,100,100\\n")
    except OSError:
        pass
''',
    # a service on the machine's loopback
    "net": '''
import socket
for host in ("127.0.0.1", "localhost", "::1"):
    try:
        socket.create_connection((host, PORT), timeout=2).sendall(b"key please")
    except OSError:
        pass
''',
    "forker": "import os\nwhile True:\n    os.fork()\n",
    "hog": "x = bytearray(50 * 10**9)\n",
    "printer": "for _ in range(10**7):\n    print('x' * 100)\n",
    "looper": "while True:\n    pass\n",
    "daemon": f'''
import subprocess
subprocess.Popen(["sleep", "{SLEEP}"], start_new_session=True,
                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
''',
    "parricide": '''
import os, signal
try:
    os.kill(os.getppid(), signal.SIGKILL)
except OSError:
    pass
for pid in [p for p in os.listdir("/proc") if p.isdigit()]:
    try:
        os.kill(int(pid), signal.SIGKILL)        # everything in reach, itself last
    except OSError:
        pass
''',
}


def _run(argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def _digest(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def _sleepers() -> list[str]:
    out = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            argv = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if argv[:2] == [b"sleep", SLEEP.encode()]:
            out.append(pid)
    return out


class _Listener:
    """A loopback service the test opens: it records whoever connects."""

    def __init__(self):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.sock.settimeout(0.5)
        self.port = self.sock.getsockname()[1]
        self.connected: list = []
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self):
        while not self.stop.is_set():
            try:
                conn, addr = self.sock.accept()
            except OSError:
                continue
            self.connected.append(addr)
            conn.close()

    def close(self):
        self.stop.set()
        self.thread.join(5)
        self.sock.close()


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    """The class graded once: the console, the grades, the folders before and after."""
    if S.find_bwrap() is None and os.environ.get("CI") != "true":
        pytest.skip("bubblewrap (bwrap) is not installed: apt-get install bubblewrap")
    root = tmp_path_factory.mktemp("hostile")
    d = root / "class"
    # the handouts are not read here: written without their picture (the class took
    # 4.7-5.3 s of CPU with them, 0.3-0.5 s without, at a load of 10, measured
    # 2026-11-30); test_classroom.py and test_class_record.py check the pictured handouts
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(classroom, "picture_figure", lambda exercise, variant: None)
        T.generate_class("slider_crank", IDS, d, seed=SEED)
    key = pd.read_csv(d / "key.csv", dtype={"student": str})
    subs = root / "subs"
    subs.mkdir()
    grades = root / "out" / "grades.csv"
    grades.parent.mkdir()
    grades.write_text("the grades of last week\n", encoding="utf-8")
    listener = _Listener()
    consts = (f"CLASS = {str(d)!r}\nHONEST = {str(subs / 'honest.ipynb')!r}\n"
              f"GRADES = {str(grades)!r}\nPORT = {listener.port}\n")
    for sid in IDS:
        nb = nbformat.read(d / "students" / f"{sid}.ipynb", as_version=4)
        if sid.startswith("honest"):
            k = key[key.student == sid]
            T.fill_answer_cell(nb, dict(zip(k.question, k.expected, strict=True)))
        else:
            # the attack is the cell under test: its notebook without the picture (the
            # honest two draw theirs; a kernel that draws is measured in
            # test_a_kernel_that_draws_stays_well_inside_the_memory_limit): the kernel's
            # CPU 1.25-1.33 s -> 0.6-0.75 s, 2.5 s less wall a notebook at a load of 4
            nb.cells = [c for c in nb.cells if c.get("id") != "picture"]
            at = next(i for i, c in enumerate(nb.cells)
                      if "answers" in c.get("metadata", {}).get("tags", []))
            nb.cells.insert(at + 1, nbformat.v4.new_code_cell(consts + ATTACKS[sid]))
        nbformat.write(nb, str(subs / f"{sid}.ipynb"))
    before = {"class": _digest(d), "subs": _digest(subs), "out": _digest(grades.parent)}
    # graded as a teacher types it: from the class folder, its path on the command line
    res = subprocess.run([sys.executable, "-m", "kinetostatics", "exercises", "grade", d,
                          subs, "--out", grades, "--jobs", "2", "--timeout", str(CELL_SECONDS),
                          "--notebook-seconds", "120", "--memory-mb", "1536",
                          "--output-mb", "1", "--processes", "48"], cwd=d,
                         capture_output=True, text=True, timeout=1200)
    code, out, err = res.returncode, res.stdout, res.stderr
    listener.close()
    summary = pd.read_csv(grades.with_name("grades_students.csv"), dtype={"student": str},
                          keep_default_na=False).set_index("student")
    return {"code": code, "out": out, "err": err, "summary": summary, "key": key,
            "before": before, "dir": d, "subs": subs, "grades": grades,
            "connected": listener.connected}


def _score(hostile, sid) -> float:
    return float(hostile["summary"].loc[sid, "score %"])


# ----------------------------------------------------------------- the whole run
@pytest.mark.slow
def test_grading_finishes_and_the_honest_keep_full_marks(hostile):
    assert hostile["code"] == 0, hostile["err"]
    assert hostile["summary"].index.tolist() == IDS
    assert _score(hostile, "honest") == 100.0 and _score(hostile, "honest2") == 100.0
    assert "sandbox: bubblewrap" in hostile["out"]
    assert set(hostile["summary"]["sandbox"]) == {"bubblewrap"}


@pytest.mark.slow
def test_no_hostile_student_gets_a_key_value(hostile):
    s = hostile["summary"]
    for sid in IDS[2:]:
        assert _score(hostile, sid) == 0.0, (sid, s.loc[sid].to_dict())


@pytest.mark.slow
@pytest.mark.parametrize("sid", ["proc", "walker", "cmdline", "seed"])
def test_reading_the_key_or_the_seed_fails(hostile, sid):
    # the attack ran to its end, found nothing and left the answers empty
    assert _score(hostile, sid) == 0.0
    assert int(hostile["summary"].loc[sid, "passed"]) == 0
    assert "did not run" not in hostile["summary"].loc[sid, "flags"]


@pytest.mark.slow
def test_nothing_outside_the_sandbox_is_written(hostile):
    d, subs, grades = hostile["dir"], hostile["subs"], hostile["grades"]
    assert _digest(d) == hostile["before"]["class"]
    assert not (d / "planted.txt").exists()
    assert _digest(subs) == hostile["before"]["subs"]
    # the grades file is the grader's own: written once, by the grader
    text = grades.read_text(encoding="utf-8")
    assert "100,100,100" not in text and text.startswith("student,question")


@pytest.mark.slow
def test_the_loopback_service_is_not_reached(hostile):
    assert hostile["connected"] == []


@pytest.mark.slow
@pytest.mark.parametrize("sid, says", [
    ("forker", "raised BlockingIOError"),
    ("hog", "raised MemoryError"),
    # the printer is stopped by the output limit, or (seen on a loaded 2-core machine,
    # its output flooding the client) by the cell's time limit first: stopped either way
    ("printer", ("printed more than 1 MB (the output limit): stopped",
                 f"ran longer than {CELL_SECONDS} s")),
    ("looper", f"ran longer than {CELL_SECONDS} s"),
    ("parricide", "the kernel died"),
])
def test_a_limit_hit_is_a_flag_naming_it(hostile, sid, says):
    flags = hostile["summary"].loc[sid, "flags"]
    says = (says,) if isinstance(says, str) else says
    assert flags.startswith("did not run: ") and any(s in flags for s in says), flags
    assert f"!! FLAG {sid}: did not run" in hostile["out"]


@pytest.mark.slow
def test_no_background_process_outlives_its_notebook(hostile):
    assert _sleepers() == []


@pytest.mark.slow
@pytest.mark.parametrize("src, limits, says", [
    ("while True:\n    pass", {"cpu_seconds": 2, "cell_seconds": 60},
     "the kernel died in cell 2 ('while True:'): killed: CPU time limit of 2 s hit"),
    ("open('big', 'wb').write(b'x' * (3 << 20))", {"file_mb": 1},
     "raised OSError: [Errno 27] File too large"),
    ("import time\ntime.sleep(30)", {"notebook_seconds": 3},
     "the notebook ran longer than 3 s (the limit per notebook), in cell 2 ('import time')"),
    # one message over the limit: ZeroMQ drops it with the connection (the grader read
    # "the notebook's answers could not be read" before it watched for that)
    ("print('x' * (3 << 20))", {"output_mb": 1},
     "cell 2 (\"print('x' * (3 << 20))\") printed a message larger than the output limit "
     "(1 MB): stopped"),
])
def test_the_other_limits_name_themselves(src, limits, says):
    if S.find_bwrap() is None and os.environ.get("CI") != "true":
        pytest.skip("bubblewrap (bwrap) is not installed: apt-get install bubblewrap")
    from kinetostatics.teaching.execute import NotebookRunError, run_notebook

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in
                                         ("x = 1", src, "answers = {'a': 1.0}")])
    with pytest.raises(NotebookRunError) as got:
        run_notebook(nb, sandbox=S.sandbox_or_refuse(S.Limits(**limits)))
    assert says in str(got.value)


@pytest.mark.slow
def test_the_sandbox_shows_no_path_and_leaves_no_descriptor():
    """bwrap's options (its binds and covers) reach it through a pipe: the sandbox's
    process list shows only the kernel's command; and a class of hundreds run in one
    process leaves no file descriptor behind per notebook (17 did, before)."""
    if S.find_bwrap() is None and os.environ.get("CI") != "true":
        pytest.skip("bubblewrap (bwrap) is not installed: apt-get install bubblewrap")
    from kinetostatics.teaching.execute import run_notebook

    src = ("import os\nanswers = {'ps': ' | '.join(open(f'/proc/{p}/cmdline').read() for p in "
           "os.listdir('/proc') if p.isdigit())}")
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(src)])
    sb = S.sandbox_or_refuse(hide=["/tmp"])
    fds = []
    for _ in range(3):
        _, answers = run_notebook(nb, sandbox=sb)
        fds.append(len(os.listdir("/proc/self/fd")))
    assert "--ro-bind" not in answers["ps"] and "--setenv" not in answers["ps"]
    assert "ipykernel_launcher" in answers["ps"]
    assert fds[0] == fds[-1], fds


@pytest.mark.slow
def test_a_kernel_that_draws_stays_well_inside_the_memory_limit():
    """The address-space limit counts reserved space: with the allocators capped
    (S.ALLOCATORS) a kernel that drew a mechanism inline uses 0.54 GB of the 2048 MB
    (measured; 2.23 GB without the caps, which killed the kernel's threads: the
    grader read "Invalid Signature" and honest sheets were graded "did not run")."""
    if S.find_bwrap() is None and os.environ.get("CI") != "true":
        pytest.skip("bubblewrap (bwrap) is not installed: apt-get install bubblewrap")
    from kinetostatics.teaching.execute import run_notebook

    cells = ["%matplotlib inline\nimport kinetostatics as ks\n"
             "from kinetostatics.plot import draw_mechanism\n"
             "draw_mechanism(ks.solve(ks.example('four_bar')), 30);",
             "peak = [ln for ln in open('/proc/self/status') if ln.startswith('VmPeak')][0]\n"
             "answers = {'peak_mb': int(peak.split()[1]) / 1024}"]
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    _, answers = run_notebook(nb, sandbox=S.sandbox_or_refuse())
    assert answers["peak_mb"] < 0.45 * S.Limits().memory_mb, answers   # 530 MB measured


def test_a_broken_message_names_the_cell_and_the_memory_limit(monkeypatch):
    """A kernel that cannot start a thread breaks a message off: the grader's reason
    says so, with the cell and the limit, not "ValueError: Invalid Signature"."""
    from kinetostatics.teaching import execute as E
    from kinetostatics.teaching.kernels import GradingClient

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = [0] * 10**8")])

    def broken(run, tmp, timeout, kernel, sandbox, made):
        c = GradingClient(run, S.Limits(memory_mb=700))
        c.cell = 0
        made.append(c)
        raise ValueError("Invalid Signature: b'00ff'")

    monkeypatch.setattr(E, "_run_in", broken)
    with pytest.raises(E.NotebookRunError) as got:
        E.run_notebook(nb)
    assert "cell 1 ('x = [0] * 10**8')" in str(got.value), got.value
    assert "memory limit of 700 MB" in str(got.value) and "Signature" not in str(got.value)


# ------------------------------------------------------------------ fast checks
def test_a_project_under_tmp_is_bound_over_the_private_tmp(tmp_path, monkeypatch):
    """The private /tmp is mounted before the Python environment and the project are
    bound: a clone under /tmp (a CI checkout) was covered by it, and every kernel died
    before it answered (measured: 19 sandbox tests failed on a clone in /tmp)."""
    monkeypatch.setattr(S, "_PROJECT", Path("/tmp/some-clone"))
    cmd = S.Sandbox().command(["true"], tmp_path)
    tmpfs = next(i for i in range(len(cmd) - 1) if cmd[i:i + 2] == ["--tmpfs", "/tmp"])
    binds = [i for i in range(len(cmd) - 2) if cmd[i] == "--ro-bind"
             and cmd[i + 1] == "/tmp/some-clone"]
    assert binds and all(tmpfs < i for i in binds), cmd


def test_without_bwrap_grading_refuses_in_one_line(tmp_path, monkeypatch):
    d = tmp_path / "class"
    T.generate_class("slider_crank", ["ana"], d, seed=SEED)
    monkeypatch.setattr(S, "find_bwrap", lambda: None)
    code, out, err = _run(["exercises", "grade", d, d / "students"])
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "bwrap was not found" in lines[0]
    assert "apt install bubblewrap" in lines[0] and "--unsandboxed" in lines[0]
    # read as saved, nothing runs: no sandbox needed
    code, out, err = _run(["exercises", "grade", d, d / "students", "--no-execute"])
    assert code == 0 and "WARNING" not in out


def test_the_sandbox_hides_what_lies_inside_what_it_shows(tmp_path):
    project = Path(T.__file__).resolve().parents[2]
    inside = project / "tests"
    sb = S.Sandbox(S.Limits(), (str(inside), str(tmp_path)), "bwrap")
    cmd = sb.command(["python"], tmp_path / "scratch", None)
    i = cmd.index(str(inside))
    assert cmd[i - 1] == "--tmpfs"                  # covered by an empty folder
    assert cmd.count(str(tmp_path)) == 0            # /tmp is the sandbox's own anyway
    for flag in ("--unshare-net", "--unshare-pid", "--unshare-ipc", "--die-with-parent",
                 "--clearenv", "--unshare-user"):
        assert flag in cmd
    env = {cmd[i + 1]: cmd[i + 2] for i, a in enumerate(cmd) if a == "--setenv"}
    assert env["HOME"] == str((tmp_path / "scratch").resolve())
    assert set(env) >= {"PATH", "PYTHONPATH", "MPLBACKEND"} and "PWD" not in env


def test_limits_are_checked_and_stated():
    with pytest.raises(WorkbenchError, match="memory_mb=10"):
        S.Limits(memory_mb=10)
    text = S.Limits().describe()
    for part in ("2048 MB", "60 s per cell", "600 s per notebook", "64 processes",
                 "output up to 8 MB"):
        assert part in text
    assert S.exit_reason(128 + 24, S.Limits()) == "killed: CPU time limit of 300 s hit"
