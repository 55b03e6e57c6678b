"""The sheets' interactive cells in a real browser: JupyterLab serves every sheet with a
widget (an Explorer), a headless Chromium (the Debian package, or its old headless shell
where that is installed: tests/_shared_sheets.py; driven by Playwright's Python package;
no browser download) runs all their cells, and the tests check what a student sees:

- on every widget sheet: every widget renders (no "Error displaying widget", no
  model-not-found message), every slider moved by keyboard changes the picture, and
  after each move the sheet shows exactly one picture per explorer, with no JavaScript
  error on the page;
- on the lightest sheet (05; every sheet's widget is the same Explorer), in depth (after a
  dialog came up; its every-slider check made here too): a slider moved by drag changes
  the picture, and after rapid moves the kernel holds the newest values and the picture
  the same number of axes as before (redrawn, never stacked);
- then, on the same run, every check tests/test_notebooks.py makes on a headless run
  (tests/_shared_sheets.py: no error, a picture and a table, no nan, nothing on stderr,
  every figure to the picture standard, every slider's move changes the key numbers
  and leaves no error): the sheet, saved from the browser, gives its outputs, and the
  checks run in its kernel, on the browser's own slider moves (recorded there after
  each: the sliders are not moved again through the Python API). So each widget sheet
  is executed once in the suite, and each slider moved once.

One JupyterLab server (for the session) serves the sheets (copied into a temporary
folder, with the picture audit's cell first, so the checkout's sheets stay without
outputs) to one Chromium page with JupyterLab loaded (for the module's tests, which run
one after another on one xdist worker: tests/conftest.py, SHARED_PER_MODULE): each test
opens its sheet in that page, and closes it and shuts its kernel down after, so the
server, Chromium and the page start once in the suite, not once a sheet or a worker.
The test waits for the page by checking it every POLL ms (Playwright's default, every
animation frame, kept Chromium drawing frames through every wait).
Each sheet's kernel is forked from one process that imported ipykernel, matplotlib,
pandas and kinetostatics once (tests/_kernel_fork.py, the server's kernel spec
``python3``): the same kernel, started without 1.5-1.8 s of imports each (the browser's
11 sheets, setup and call, 155 -> 140 s of CPU, two runs at load 5-10, 2026-12-01).
In CI (``CI=true``) the test must run: a missing Chromium or Playwright fails it;
elsewhere it is skipped with one line saying what to install.

Where the CPU goes (2026-11-30, serial, load 11-14, ``-p tools.cpu_per_test`` and the
processes' own times): of ~170 s for the 11 sheets, the sheets' kernels ~85 s (the
sheet's own pictures, 0.4-2 s each, at any dpi: a 72-dpi PNG costs what a 150-dpi one
does), Chromium ~50-70 s (JupyterLab building each cell's editor and laying the page
out), the server 7 s, this process and Playwright's driver 11 s. Each sheet's setup and
call, before -> after the headless shell and the smaller page: 01 36.7 -> 34.0, 02 22.9
-> 21.0, 03 19.6 -> 18.5, 04 15.7 -> 14.8, 05 12.3 -> 10.4, 06 17.3 -> 16.3, 07 13.3 ->
11.7, 13 11.6 -> 11.2, 14 13.1 -> 10.9, 15 11.4 -> 10.5, 16 8.5 -> 7.6 s (two whole
runs side by side).
"""

from __future__ import annotations

import ast
import contextlib
import json
import os
import re
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import nbformat
import pytest

from tests import _shared_sheets as sheets
from tests._kernel_fork import Forker

ROOT = sheets.ROOT
CHROMIUM = sheets.CHROMIUM
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
SHEETS = ["05_mass_concentration.ipynb"]
# every sheet with an interactive cell (an Explorer's widget)
WIDGET_SHEETS = sheets.WIDGET_SHEETS
RUN_ALL = 600_000      # ms: stops a hung kernel only (a full run took 20-65 s, load 1-17)
RUN_TRY = 240_000      # ms: one "Run All" that has not finished by then is given again once
                       # (under load a Run All given as the kernel connected was seen lost)
RUN_START = 60_000     # ms: a Run All marks every cell queued at once (within 5 s measured)
SAVE_AGAIN = 30         # s: a save not on disk by then is asked again (under 1 s measured)
UPDATE = 300_000       # ms: one slider update (1.5-15 s measured)
POLL = 200             # ms between two checks of a condition the test waits for on the page
                       # (Playwright's default, every animation frame, kept Chromium drawing
                       # frames at 60 Hz through every wait)
# the page's size: a laptop's, not a large screen's (1400 x 1000 before): fewer pixels
# laid out and painted at each change of the page (with the headless shell,
# tests/_shared_sheets.py: sheets 03 and 16 34.3 -> 31.8 and 30.8 -> 28.7 s of CPU, two
# pairs side by side; the whole file 182 -> 167 s, 2026-11-30)
VIEWPORT = {"width": 1000, "height": 700}
CLICK = 60_000         # ms: one click on the page (instant when nothing is in the way)
WIDGET_ERRORS = re.compile(r"Error displaying widget|model not found|Could not find model|"
                           r"Class \S+ not found|Failed to (create|render)|"
                           # (a resource the offline machine cannot fetch is no widget's
                           # error: JupyterLab asks the network for news and fonts)
                           r"Failed to load(?! resource: net::)|No such model",
                           re.IGNORECASE)
INSTALL = ("the browser test needs Chromium and Playwright: apt-get install chromium "
           "(/usr/bin/chromium) and pip install playwright (never `playwright install`)")


# JupyterLab's server, started as ``python -m jupyterlab`` would, with the import of
# rfc3987_syntax declined (as tests/conftest.py declines it in the suite's processes):
# jsonschema, under jupyter_events, builds its 38 lark grammars on import, 1.7 s of the
# server's 3.0 s of CPU to its first answer (1.25 s without; best of three, 2026-11-30)
SERVER = ("import sys; sys.modules['rfc3987_syntax'] = None; "
          "from jupyterlab.labapp import main; sys.exit(main())")
# the page's configuration (the server's labconfig/page_config.json): no build check (the
# page's load had the server run node, `node-version-check.js` and `yarn config`: the
# node processes of a run 1.0-1.1 s of CPU with it, 0.4-0.5 s without: the server's own
# start runs `yarn config` once), and the front end's extensions that no check here uses
# left out (the table of contents, the debugger, the log console, the cell toolbar...,
# with the plugins of the kept ones that need one of them: else those fail to start, an
# error on the page); the notebook, its menus, the completer and the widgets stay.
# JupyterLab's load took 4.0-4.5 s of Chromium's CPU with them, 3.2-3.4 s without
# (two alternating pairs; one sheet's run unchanged within the noise; load 8-10,
# 2026-11-30). MathJax is left out too: no check reads the markdown's formulas (the
# widgets' labels and outputs hold none), and typesetting them as each sheet opened was
# about 1 s of Chromium's CPU per sheet with formulas (sheets 02 and 03: 6.2-6.4 -> 5.2-5.4
# and 5.1-5.5 -> 4.3 s, runs side by side at load 8-10, 2026-12-01).
PAGE_CONFIG = {"buildCheck": False, "buildAvailable": False, "disabledExtensions": {
    name: True for name in [
        *(f"@jupyterlab/{name}-extension" for name in (
            "toc", "debugger", "lsp", "logconsole", "cell-toolbar", "celltags",
            "metadataform", "extensionmanager", "inspector", "terminal", "running",
            "csvviewer", "htmlviewer", "imageviewer", "markdownviewer", "hub", "launcher",
            "help", "settingeditor", "workspaces")),
        "@jupyterlab/mathjax-extension",
        "@jupyterlab/notebook-extension:toc", "@jupyterlab/notebook-extension:language-server",
        "@jupyterlab/notebook-extension:update-raw-mimetype",
        "@jupyterlab/fileeditor-extension:language-server"]}}


def _requirements():
    """Playwright's sync API, or a skip (a failure in CI) naming what to install."""
    missing = not CHROMIUM.exists()
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        missing = True
    if missing:
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(INSTALL + " (CI=true: this test must run)")
        pytest.skip(INSTALL)
    return sync_playwright


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="session")
def lab(tmp_path_factory):
    """One JupyterLab server over a copy of the widget sheets, each with the picture
    audit's cell first (tests/_shared_sheets.py): (base url, token, its folder). It shows
    its application object to the page (``window.jupyterapp``): the tests open and close
    the sheets through its commands."""
    _requirements()
    home = tmp_path_factory.mktemp("lab")
    for name in WIDGET_SHEETS:
        nb = nbformat.read(ROOT / "notebooks" / name, as_version=4)
        nb.cells.insert(0, nbformat.v4.new_code_cell(sheets.AUDIT_HOOK))
        nbformat.write(nb, home / name)
    port, token = _free_port(), "kinetostatics-browser-test"
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    for var, sub in (("JUPYTER_CONFIG_DIR", "config"), ("JUPYTER_RUNTIME_DIR", "runtime"),
                     ("JUPYTERLAB_SETTINGS_DIR", "settings"),
                     ("JUPYTERLAB_WORKSPACES_DIR", "workspaces"), ("IPYTHONDIR", "ipython")):
        env[var] = str(home / ".jupyter" / sub)
    labconfig = home / ".jupyter" / "config" / "labconfig"
    labconfig.mkdir(parents=True)
    (labconfig / "page_config.json").write_text(json.dumps(PAGE_CONFIG))
    # every sheet's kernel forked from one that imported the sheets' libraries once
    # (tests/_kernel_fork.py): its kernel spec first on the server's JUPYTER_PATH
    forker = Forker(home / ".jupyter" / "forker", env=env)
    env["JUPYTER_PATH"] = forker.first_on(env.get("JUPYTER_PATH"))
    log = open(home / "server.log", "w")  # noqa: SIM115 (closed below)
    server = subprocess.Popen(
        [sys.executable, "-c", SERVER, "--no-browser", "--allow-root", f"--port={port}",
         "--ip=127.0.0.1", f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={home}",
         "--LabApp.news_url=", "--LabApp.check_for_updates_class="
         "jupyterlab.NeverCheckForUpdate", "--LabApp.extension_manager=readonly",
         "--LabApp.expose_app_in_browser=True",
         # (the language servers' and the terminals' server extensions: the sheets use
         # neither; 0.6 s of the server's start, measured 2026-11-30)
         '--ServerApp.jpserver_extensions={"jupyter_lsp": False}',
         "--ServerApp.terminals_enabled=False",
         # a kernel shut down (a test's sheet closed, the in-depth test's restart) is
         # stopped at once (SIGTERM), its interpreter not torn down: the test has read
         # everything it checks by then (0.5 s of the kernel's CPU at a graceful exit of a
         # kernel that drew a picture, 0.03 s so; measured 2026-11-30)
         "--KernelManager.shutdown_wait_time=0"],
        cwd=home, env=env, stdout=log, stderr=subprocess.STDOUT)
    base = f"http://127.0.0.1:{port}"
    try:
        for _ in range(600):
            if server.poll() is not None:
                pytest.fail(f"JupyterLab exited: {(home / 'server.log').read_text()[-2000:]}")
            try:
                urllib.request.urlopen(f"{base}/api/status?token={token}", timeout=2)
                break
            except OSError:
                time.sleep(0.5)
        else:
            pytest.fail("JupyterLab did not answer within 300 s")
        yield base, token, home
    finally:
        server.terminate()
        try:
            server.wait(30)
        except subprocess.TimeoutExpired:
            server.kill()
        log.close()
        forker.close()


# Chromium and its page last as long as the module's tests that run one after another,
# not the session: Playwright's sync API marks its event loop as running between its
# calls, and a test of another module run while it lives (on the same xdist worker) finds
# a running loop (the Explorer then schedules its updates instead of computing them)
@pytest.fixture(scope="module")
def browser(lab):
    sync_playwright = _requirements()
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=str(sheets.browser_binary()), headless=True,
                              args=FLAGS)
        yield b
        b.close()


ALL_RAN = """() => {
    const p = [...document.querySelectorAll('.jp-CodeCell .jp-InputPrompt')];
    return p.length > 0 && p.every(e => /\\[\\d+\\]/.test(e.textContent));
}"""
# a cell queued or run: a Run All was taken
STARTED = """() => [...document.querySelectorAll('.jp-CodeCell .jp-InputPrompt')].some(
    e => /\\[(\\*|\\d+)\\]/.test(e.textContent))"""
KERNEL_IDLE = """() => {
    const e = document.querySelector('.jp-Notebook-ExecutionIndicator');
    return e !== null && e.getAttribute('data-status') === 'idle';
}"""


DIALOG_TEXT = """() => [...document.querySelectorAll('.jp-Dialog')].map(d =>
    d.innerText.replace(/\\s+/g, ' ').trim())"""
# a dialog that says the kernel died is the sheet's defect (the test fails with its text);
# any other is the loaded machine's (a slow server's "Server Connection Error", the kernel's
# choice asked while the session starts) and is answered: it intercepted every click of a
# Run All once in CI (load of a full suite on two cores), and once a dialog kept the focus
# from the Escape key meant for it (a button is clicked now)
KERNEL_DIED = re.compile(r"kernel .*(died|dead)|restarting", re.IGNORECASE)
# the kernel's choice is accepted (its preselected kernel; Cancel would leave the sheet
# without one); every other dialog is rejected (Cancel, Dismiss)
KERNEL_CHOICE = re.compile(r"select kernel", re.IGNORECASE)


def _clear_dialogs(page) -> list[str]:
    """Answer every open JupyterLab dialog that is not a kernel's death (one coming up
    behind another too); returns their texts (a kernel's death fails the test with the
    dialog's text)."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout
    texts: list[str] = []
    for _ in range(5):
        dialog = page.query_selector(".jp-Dialog")
        if dialog is None:
            break
        text = re.sub(r"\s+", " ", dialog.inner_text()).strip()
        if KERNEL_DIED.search(text):
            pytest.fail(f"JupyterLab said: {text}")
        texts.append(text)
        button = dialog.query_selector(
            ".jp-mod-accept" if KERNEL_CHOICE.search(text) else ".jp-mod-reject")
        try:
            if button is not None:
                button.click(timeout=CLICK)
            else:
                page.keyboard.press("Escape")
            dialog.wait_for_element_state("hidden", timeout=UPDATE)
        except PlaywrightTimeout:
            raise AssertionError(f"a JupyterLab dialog stayed open: {text}") from None
    return texts


def _menu(page, menu: str, item) -> None:
    """Choose ``item`` of the main menu ``menu`` with the notebook in focus; a dialog that
    comes up in the way is dismissed and the choice made again (three tries)."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout
    for attempt in range(3):
        _clear_dialogs(page)
        try:
            page.locator(".jp-Notebook").click(position={"x": 5, "y": 5}, timeout=CLICK)
            page.get_by_role("menuitem", name=menu, exact=True).click(timeout=CLICK)
            page.get_by_role("menuitem", name=item).click(timeout=CLICK)
            return
        except PlaywrightTimeout:
            if attempt == 2:
                raise AssertionError(f"the menu {menu} stayed out of reach; dialogs: "
                                     f"{page.evaluate(DIALOG_TEXT)}") from None
            page.keyboard.press("Escape")        # an open menu, before the dialogs' check


def _run_all(page, lab, sheet: str) -> None:
    """Run every cell from the Run menu once the kernel is idle, and wait until none is
    pending. A Run All that marks no cell queued within RUN_START was lost (seen under
    load, given as the kernel connected: every cell stayed ``[ ]``) and is given again
    on the page loaded again, up to three times; one that has not finished within
    RUN_TRY is given once more (the kernel's cells then run again, with the same
    values). A dialog in the way is dismissed first (``_clear_dialogs``)."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout
    page.locator(".jp-Notebook .jp-Cell").first.wait_for(timeout=RUN_ALL)
    page.wait_for_function(KERNEL_IDLE, polling=POLL, timeout=RUN_ALL)
    for wait in (RUN_TRY, RUN_ALL):
        for attempt in range(3):
            _menu(page, "Run", re.compile(r"^Run All Cells"))
            try:
                page.wait_for_function(STARTED, polling=POLL, timeout=RUN_START)
                break
            except PlaywrightTimeout:
                if attempt == 2:
                    raise AssertionError("Run All given three times, no cell queued; "
                                         f"dialogs: {page.evaluate(DIALOG_TEXT)}") from None
                # a page that took no Run All kept taking none (seen: three a minute apart,
                # the first sheet of a fresh server at load 12): it is loaded again, the
                # sheet opened again (on the kernel it started)
                _load_app(page, lab)
                _open((page, None), sheet)
                page.wait_for_function(KERNEL_IDLE, polling=POLL, timeout=RUN_ALL)
        try:
            page.wait_for_function(ALL_RAN, polling=POLL, timeout=wait)
            return
        except PlaywrightTimeout:
            if wait == RUN_ALL:
                raise
            page.wait_for_function(KERNEL_IDLE, polling=POLL, timeout=RUN_ALL)


def _run_code(page, code: str) -> str:
    """Append a code cell at the end, run it, and return its text output."""
    cells = page.locator(".jp-Notebook .jp-Cell")
    n = cells.count()
    cells.nth(n - 1).locator(".jp-InputPrompt").click()
    page.keyboard.press("Escape")
    page.keyboard.press("b")                     # a new cell below, in command mode
    new = page.locator(".jp-Notebook .jp-Cell").nth(n)
    new.locator(".cm-content").click()
    page.keyboard.insert_text(code)
    page.keyboard.press("Shift+Enter")
    out = new.locator(".jp-OutputArea-output")
    out.first.wait_for(timeout=UPDATE)
    return out.first.inner_text()


def _image(page):
    return page.locator(".jp-OutputArea-output img.widget-image").last


def _wait_picture(page, before: str) -> str:
    """Wait until the explorer's picture differs from ``before`` and no update is
    computing; returns the picture's source."""
    page.wait_for_function(
        """(before) => {
            const imgs = document.querySelectorAll('.jp-OutputArea-output img.widget-image');
            const img = imgs[imgs.length - 1];
            const html = [...document.querySelectorAll('.widget-html')].map(e => e.textContent);
            return img && img.src !== before && !html.some(t => t.includes('computing'));
        }""", arg=before, polling=POLL, timeout=UPDATE)
    return _image(page).get_attribute("src")


def _wait_settled(page) -> None:
    """Wait until no update is computing and the picture shown is that of the first
    slider's value (the explorer's status line names the values of its picture)."""
    page.wait_for_function(
        """() => {
            const html = [...document.querySelectorAll('.widget-html')].map(e => e.textContent);
            const status = html.find(t => t.includes('values: '));
            const readout = document.querySelector('.widget-slider .widget-readout');
            if (!status || !readout || status.includes('computing')) return false;
            const m = status.match(/values: \\w+ = ([-+0-9.e]+)/);
            return m && Math.abs(parseFloat(m[1]) - parseFloat(readout.textContent)) < 1e-9;
        }""", polling=POLL, timeout=UPDATE)


def _state(page) -> tuple[int, dict]:
    """The explorer's axes count and values, read from the kernel."""
    text = _run_code(page, 'print("STATE", len(explorer.figure.axes), explorer.values)')
    m = re.search(r"STATE (\d+) (\{.*\})", text)
    assert m, text
    return int(m.group(1)), ast.literal_eval(m.group(2))    # a dict of floats we printed


def _page_errors(console: list[str]) -> list[str]:
    """JavaScript errors on the page (uncaught exceptions, widget errors)."""
    return [c for c in console if c.startswith("pageerror") or WIDGET_ERRORS.search(c)
            or (c.startswith("error") and "Uncaught" in c)]


HANDLE_VALUE = """(h) => [parseFloat(h.getAttribute('aria-valuenow')),
                         parseFloat(h.getAttribute('aria-valuemax'))]"""
HANDLE_RANGE = """(h) => ['aria-valuenow', 'aria-valuemin', 'aria-valuemax'].map(
    a => parseFloat(h.getAttribute(a)))"""


APP_READY = "() => window.jupyterapp !== undefined && window.jupyterapp.shell !== undefined"
# the sheet opened, its kernel answering; null returned (the widget: 2-4 s CPU to serialise)
OPEN = """async (path) => { const w = await window.jupyterapp.commands.execute(
    'docmanager:open', {path, factory: 'Notebook'}); await w.sessionContext.ready;
    await w.sessionContext.session?.kernel?.info; return null; }"""
# every document of the main area closed, its changes dropped (the test read what it
# saved; a clean document closes without asking)
CLOSE_ALL = """() => { for (const w of [...window.jupyterapp.shell.widgets('main')]) {
    if (w.context) { w.context.model.dirty = false; } w.close(); } }"""
NO_SHEET = "() => document.querySelectorAll('.jp-Notebook, .jp-Dialog').length === 0"


def _load_app(page, lab) -> None:
    """JupyterLab loaded in ``page`` on a fresh workspace (no sheet open)."""
    base, token, _ = lab
    page.goto(f"{base}/lab?token={token}&reset", timeout=RUN_ALL)
    page.wait_for_function(APP_READY, polling=POLL, timeout=RUN_ALL)
    page.evaluate("() => window.jupyterapp.restored")      # (a promise: awaited)


@pytest.fixture(scope="module")
def jupyterlab(lab, browser):
    """One page with JupyterLab loaded: (page, its console messages).
    Each test opens its sheet in it (``_open``); the fixture ``app`` closes it after."""
    page = browser.new_page(viewport=VIEWPORT)
    console: list[str] = []
    page.on("console", lambda m: console.append(f"{m.type}: {m.text}"))
    page.on("pageerror", lambda e: console.append(f"pageerror: {e}"))
    _load_app(page, lab)
    yield page, console
    page.close()


def _shut_kernels(lab) -> None:
    """Every session of the server ended, its kernel shut down (the server answers when
    the kernel is gone)."""
    base, token, _ = lab
    with urllib.request.urlopen(f"{base}/api/sessions?token={token}", timeout=60) as r:
        sessions = json.load(r)
    for session in sessions:
        urllib.request.urlopen(urllib.request.Request(
            f"{base}/api/sessions/{session['id']}?token={token}", method="DELETE"),
            timeout=UPDATE / 1000).close()


@pytest.fixture
def app(jupyterlab, lab):
    """The session's JupyterLab page for one test; after it, every sheet closed and every
    kernel shut down, so the next test finds the page as loaded (a page that does not
    close its sheets, or shows a dialog, is loaded again)."""
    page, console = jupyterlab
    console.clear()
    yield page, console
    try:
        page.evaluate(CLOSE_ALL)
        page.wait_for_function(NO_SHEET, polling=POLL, timeout=CLICK)
    except Exception:                   # noqa: BLE001 (any state: the page is loaded again)
        _load_app(page, lab)
    _shut_kernels(lab)


def _open(app, sheet: str):
    """``sheet`` opened in the session's JupyterLab page (``app``), its kernel started:
    (page, console)."""
    page, console = app
    page.evaluate(OPEN, sheet)
    page.locator(".jp-Notebook .jp-Cell").first.wait_for(timeout=RUN_ALL)
    return page, console


def _move_every_slider(page, sheet: str, console: list[str], run) -> None:
    """Every slider of the (run) sheet moved once by keyboard: the picture changes, the
    sheet still shows exactly one picture per explorer, no JavaScript error; the kernel's
    state recorded (``run``: the kernel's client, sheets.MOVES_RECORD) before the first
    move and after each (the headless checks hold every move to the API's standard)."""
    page.locator(".widget-slider").first.wait_for(timeout=UPDATE)
    pictures = page.locator(".jp-OutputArea-output img.widget-image")
    explorers = pictures.count()
    assert explorers >= 1, sheet
    handles = page.locator(".widget-slider .noUi-handle")
    assert handles.count() >= 1, sheet
    run(sheets.MOVES_RECORD)
    for k in range(handles.count()):
        handle = handles.nth(k)
        handle.scroll_into_view_if_needed()
        before = [pictures.nth(j).get_attribute("src") for j in range(explorers)]
        value, top = handle.evaluate(HANDLE_VALUE)
        handle.focus()
        page.keyboard.press("ArrowLeft" if value >= top else "ArrowRight")
        page.wait_for_function(
            """(before) => {
                const imgs = [...document.querySelectorAll(
                    '.jp-OutputArea-output img.widget-image')];
                const html = [...document.querySelectorAll('.widget-html')]
                    .map(e => e.textContent);
                return imgs.length === before.length &&
                       imgs.some((img, j) => img.src !== before[j]) &&
                       !html.some(t => t.includes('computing'));
            }""", arg=before, polling=POLL, timeout=UPDATE)
        assert pictures.count() == explorers, (sheet, k, "pictures stacked")
        run(sheets.MOVES_RECORD)
        errors = _page_errors(console)
        assert not errors, (sheet, k, errors)
    text = page.locator(".jp-Notebook").inner_text()
    assert not WIDGET_ERRORS.findall(text), sheet


def _saved_outputs(page, home: Path, sheet: str) -> list:
    """Save the sheet from the browser (Ctrl+S) and return the outputs of its cells
    (the audit's first cell aside), once the saved file holds every cell of the sheet,
    each run (a file saved before the Run All ended has a cell without a count; the one
    empty cell Shift+Enter leaves at the end is never run)."""
    _clear_dialogs(page)
    cells = sum(c.cell_type == "code" for c in nbformat.read(ROOT / "notebooks" / sheet,
                                                            as_version=4).cells)
    start = time.monotonic()
    asked = -SAVE_AGAIN
    while True:
        if time.monotonic() - asked >= SAVE_AGAIN:      # (a key press lost under load)
            asked = time.monotonic()
            page.locator(".jp-Notebook").click(position={"x": 5, "y": 5}, timeout=CLICK)
            page.keyboard.press("Control+s")
        time.sleep(0.5)
        try:
            code = [c for c in nbformat.read(home / sheet, as_version=4).cells
                    if c.cell_type == "code"]
        except ValueError:              # nbformat.reader.NotJSONError among them
            # Jupyter's "atomic" save writes the file in place (a backup aside): read
            # while the server writes, it is empty or cut short (seen once at load 7)
            code = []
        if len(code) > cells and all(c.execution_count is not None
                                     for c in code if c.source.strip()):
            return [o for c in code[1:] for o in c.outputs]
        if time.monotonic() - start > UPDATE / 1000:
            raise AssertionError(f"{sheet}: the saved sheet has {len(code)} code cells "
                                 f"(the sheet {cells} and the audit's), or some not run; "
                                 f"dialogs: {page.evaluate(DIALOG_TEXT)}")


@contextlib.contextmanager
def _kernel(lab, sheet: str):
    """A client of the sheet's kernel of its own (the page's cells stay as they are):
    ``run(code)`` runs the code there and returns what it printed; a cell that raises
    fails the test with its traceback."""
    from jupyter_client.blocking import BlockingKernelClient
    base, token, home = lab
    with urllib.request.urlopen(f"{base}/api/sessions?token={token}", timeout=60) as r:
        kernels = [s["kernel"]["id"] for s in json.load(r) if s["path"] == sheet]
    assert len(kernels) == 1, (sheet, kernels)
    client = BlockingKernelClient()
    client.load_connection_file(str(home / ".jupyter" / "runtime" / f"kernel-{kernels[0]}.json"))
    client.start_channels()

    def run(code: str) -> str:
        said: list[str] = []
        reply = client.execute_interactive(
            code, timeout=sheets.CELL_TIMEOUT, allow_stdin=False,
            output_hook=lambda m: said.append(m["content"]["text"])
            if m["msg_type"] == "stream" else None)["content"]
        assert reply["status"] == "ok", "\n".join(
            [f"{sheet}: {reply.get('ename')}: {reply.get('evalue')}", code,
             *reply.get("traceback", [])])
        return "".join(said)

    try:
        client.wait_for_ready(timeout=UPDATE / 1000)
        yield run
    finally:
        client.stop_channels()


def _headless_checks(page, lab, sheet: str, run) -> None:
    """The checks of tests/test_notebooks.py on the browser's run of the sheet (which
    then skips the sheet): its outputs as saved, the browser's slider moves (recorded in
    the kernel by ``run``, the kernel's client, with sheets.MOVES_RECORD) held to what
    the headless run's moves through the API are, the sheet's own checks, every figure
    to the picture standard."""
    outputs = _saved_outputs(page, lab[2], sheet)
    for code in sheets.checks_after(sheet, browser=True):
        run(code)
    sheets.check_run(sheet, outputs, sheets.audits_of(run(sheets.AUDIT_REPORT)))


# the sheets of the in-depth test have their every slider moved there (each sheet is run
# once in the browser)
@pytest.mark.slow
@pytest.mark.browser
@pytest.mark.parametrize("sheet", [s for s in WIDGET_SHEETS if s not in SHEETS],
                         ids=[s[:2] for s in WIDGET_SHEETS if s not in SHEETS])
def test_every_slider_of_every_widget_sheet(lab, app, sheet):
    """Every slider of the sheet moved once (by keyboard): the picture changes, the
    sheet still shows exactly one picture per explorer, no JavaScript error; then the
    headless checks on the same run (``_headless_checks``)."""
    page, console = _open(app, sheet)
    _run_all(page, lab, sheet)
    with _kernel(lab, sheet) as run:
        _move_every_slider(page, sheet, console, run)
        _headless_checks(page, lab, sheet, run)


@pytest.mark.slow
@pytest.mark.browser
@pytest.mark.parametrize("sheet", SHEETS, ids=[s[:2] for s in SHEETS])
def test_sheet_in_a_real_browser(lab, app, sheet):
    """The sheet run after a dialog came up (a kernel restart asked), then: every widget
    renders, every slider moved by keyboard changes the picture (as in
    ``test_every_slider_of_every_widget_sheet``), a slider moved by drag too, and after
    rapid moves the kernel holds the newest values, the picture its axes; then the
    headless checks on the same run (``_headless_checks``)."""
    page, console = _open(app, sheet)
    page.locator(".jp-Notebook .jp-Cell").first.wait_for(timeout=RUN_ALL)
    page.wait_for_function(KERNEL_IDLE, polling=POLL, timeout=RUN_ALL)
    # a dialog in the way of Run All is dismissed (one intercepted every click in CI)
    _menu(page, "Kernel", re.compile(r"^Restart Kernel…"))
    page.locator(".jp-Dialog").first.wait_for(timeout=UPDATE)
    _run_all(page, lab, sheet)
    assert page.locator(".jp-Dialog").count() == 0

    # every widget renders
    page.locator(".widget-slider").first.wait_for(timeout=UPDATE)
    text = page.locator(".jp-Notebook").inner_text()
    bad = WIDGET_ERRORS.findall(text) + [c for c in console if WIDGET_ERRORS.search(c)]
    assert not bad, f"{sheet}: {bad}"
    assert page.locator(".jp-OutputArea-output img.widget-image").count() == 1
    with _kernel(lab, sheet) as run:
        _move_every_slider(page, sheet, console, run)
        _rapid_moves(page, sheet, console)
        _headless_checks(page, lab, sheet, run)


def _rapid_moves(page, sheet: str, console: list[str]) -> None:
    """A slider moved by drag changes the picture; after rapid moves the kernel holds
    the newest values and the picture the same number of axes as before."""
    axes, values = _state(page)
    picture = _image(page).get_attribute("src")

    # a slider moved by drag (toward its farther end) changes the picture
    handle = page.locator(".widget-slider .noUi-handle").first
    handle.scroll_into_view_if_needed()         # (the cell _state ran is at the end)
    value, low, top = handle.evaluate(HANDLE_RANGE)
    box = handle.bounding_box()
    dx = 60 if top - value >= value - low else -60
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] / 2 + dx, box["y"] + box["height"] / 2, steps=5)
    page.mouse.up()
    picture = _wait_picture(page, picture)

    # rapid moves (away from the end the drag went to): the newest value computed, the
    # same number of axes
    handle.focus()
    back = "ArrowLeft" if dx > 0 else "ArrowRight"
    for _ in range(4):
        page.keyboard.press(back)
    if handle.evaluate(HANDLE_RANGE)[0] == value:   # the drag went 4 steps: once more, so
        page.keyboard.press(back)                   # the newest values are new ones
    _wait_settled(page)
    new_axes, new_values = _state(page)
    assert new_axes == axes, f"{sheet}: {new_axes} axes after rapid moves, {axes} before"
    assert new_values != values
    shown = float(page.locator(".widget-slider .widget-readout").first.inner_text())
    first = next(iter(new_values))
    assert new_values[first] == pytest.approx(shown), (new_values, shown)
    text = page.locator(".jp-Notebook").inner_text()
    bad = WIDGET_ERRORS.findall(text) + [c for c in console if WIDGET_ERRORS.search(c)]
    assert not bad, f"{sheet}: {bad}"
