"""Test-wide settings.

- Pictures are drawn off-screen (the Agg backend), before any test module imports
  pyplot.
- Hypothesis runs derandomized by default (profile ``repeatable``): the same examples on
  every machine, so CI's verdict does not depend on luck. ``HYPOTHESIS_PROFILE=explore
  python -m pytest`` (a nightly run) searches with fresh random examples, ten times as
  many in every property test, those that set their own count too
  (:func:`_scale_examples`). The quick tier (``-m "not slow"``, where no profile is
  named) runs the same property tests derandomized on a tenth of the examples (profile
  ``quick``, at least five each): every property is still tried, the full suite tries it
  on all of them.
- Two tiers. ``python -m pytest -m "not slow"`` is the everyday line; the full suite is
  ``python -m pytest`` (``-n auto`` in pyproject.toml: a worker more than the cores, the
  quick tier one per core, :func:`pytest_xdist_auto_num_workers`). A test that uses
  one of :data:`SLOW_FIXTURES` is marked ``slow`` here (and ``kernel`` or ``browser``
  where the fixture starts one), so nobody has to remember the mark; the remaining slow
  tests carry ``@pytest.mark.slow`` themselves, or are listed in tests/slow_by_cost.txt:
  a quick test costs at most :data:`QUICK_CPU` of CPU unless it is a keeper
  (:func:`keeper`: a property or invariance test, a command line's smoke test, the
  picture scene, a mutant's killer), which the list may not name.
- Tests that read one fixture's state (the figures drawn for one scene, a class
  generated for a module's tests) run on one xdist worker
  (``--dist loadgroup`` with the groups of :func:`_group`), so each is made once; in
  the quick tier each module's tests run on one worker, so its module fixtures are too.
- The solve path: ``KINETOSTATICS_PATH=fast python -m pytest`` runs the suite on the
  compiled path (numba), ``numpy`` (or unset) on the numpy path. A test of the numpy
  path's own workings takes the fixture ``numpy_path``.
"""

from __future__ import annotations

import gc
import importlib
import os
import pkgutil
import sys
from pathlib import Path

import matplotlib
import pytest
from hypothesis import settings

from tests.prewarm import warm_bytecode
from tests.worker_exit import end_without_teardown

matplotlib.use("Agg")

# The suite's processes (the xdist workers, the CLIs it starts) keep their bytecode even
# where PYTHONDONTWRITEBYTECODE is set (this machine's and CI's environment): else each
# compiles every module again and pytest rewrites every test's asserts again, 13.5 s of
# CPU a process against 7.6 s (measured 2026-11-29; the quick tier starts three).
sys.dont_write_bytecode = False
os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
# jsonschema (under nbformat, which kinetostatics.teaching imports) checks the "iri"
# format with rfc3987_syntax where that is installed (JupyterLab's dependencies bring it),
# which builds 38 lark grammars on import: 1.2 s of CPU in every process of the suite
# (measured 2026-11-29). Nothing here validates that format: the import is declined (an
# ImportError, which jsonschema expects), as where the package is not installed.
sys.modules.setdefault("rfc3987_syntax", None)
# The cyclic collector of the suite's processes (the xdist workers, a serial run) runs
# less often: its youngest generation every 10 000 new containers instead of 700, an
# older one after 50 of the next younger's instead of 10. A worker holds the session's
# shared figures (hundreds of pictures, millions of objects) and every full collection
# walked them all: on the picture tests (test_collisions.py and test_pictures.py, serially)
# 2848 young and 12 full collections took 4.7-5.2 s of CPU, 209 and none 1.6-1.8 s, the
# run's CPU 63.7 s -> 57.6 s, its peak memory the same, 1.78 GB (measured 2026-12-01 at a
# load of 6; side by side on four more files 96.8 s -> 92.1 s; docs/testing.md). Only the
# moment garbage is collected changes.
GC_THRESHOLDS = (10_000, 50, 50)
gc.set_threshold(*GC_THRESHOLDS)

# The solve path of the suite: numpy unless KINETOSTATICS_PATH says otherwise
# (`KINETOSTATICS_PATH=fast python -m pytest` runs it on the compiled path). Under `auto` a
# worker that once solved 2e4 rows has numba loaded and solves every later call compiled:
# a test's path would hang on which tests ran before it in the same worker. The tests of
# the paths and of the auto rule set theirs (test_fast.py, test_fast_auto.py).
os.environ.setdefault("KINETOSTATICS_PATH", "numpy")

settings.register_profile("repeatable", derandomize=True, print_blob=True)
EXPLORE_FACTOR = 10
settings.register_profile("explore", derandomize=False, print_blob=True,
                          max_examples=EXPLORE_FACTOR * settings.default.max_examples)
#: The quick tier's share of the examples, and the fewest a property test runs there.
QUICK_SHARE, QUICK_FEWEST = 10, 5
settings.register_profile("quick", derandomize=True, print_blob=True,
                          max_examples=settings.default.max_examples // QUICK_SHARE)
PROFILE = os.environ.get("HYPOTHESIS_PROFILE", "repeatable")
settings.load_profile(PROFILE)

#: Fixtures that make a test slow, and why (a test using one is marked ``slow``).
SLOW_FIXTURES = {
    "lecture_figures": "every picture of `solve --plot` for a scene (10-20 s of CPU each)",
    "classes": "a class of 11 generated for every exercise, sealed sheets and PDFs",
    "klass": "a class generated through the command line, with its PDFs",
    "lab": "a JupyterLab server",
    "browser": "headless Chromium",
}
#: Fixtures that start a Jupyter kernel or a browser: the marks they add.
FIXTURE_MARKS = {"lab": ("kernel", "browser"), "browser": ("kernel", "browser"),
                 "klass": ("kernel",), "classes": ("kernel",)}
#: The one picture scene whose command-line figures stay in the quick tier.
QUICK_PICTURE_SCENE = "four_bar"
#: The quick tier's rule: a quick test costs at most this many seconds of CPU (all its
#: phases, as tools/cpu_per_test.py measures them on the 2-core machine) unless it is a
#: keeper (:func:`keeper`); a heavier one is listed in :data:`SLOW_BY_COST` and marked
#: ``slow`` here. ``python tools/cpu_per_test.py RUN.jsonl --over 0.1`` lists the quick
#: tests over the budget that are no keepers (the list's new lines).
QUICK_CPU = 0.1
#: The tests of the quick tier heavier than :data:`QUICK_CPU`, with their measured CPU
#: (``seconds test-id`` a line; an id without ``[...]`` takes every parameter).
SLOW_BY_COST = Path(__file__).with_name("slow_by_cost.txt")
#: The one smoke test of each command line that starts it as ``python -m``.
CLI_SMOKE = ("tests/kinetostatics/test_cli.py::test_solve_writes_contract_csv",
             "tests/balance/test_balance_cli.py::test_text_report_and_bundled_names")
#: Session fixtures whose state is made per scene: tests reading one scene's share a
#: worker (xdist group ``<fixture>-<scene>``), and the tests that use each (the xdist
#: controller sees only test ids; collection checks that the list is whole).
SHARED_PER_SCENE = {"cli_pictures": (
    "tests/kinetostatics/plot/test_cli.py::test_solve_plot_writes_the_pictures",
    "tests/kinetostatics/plot/test_cli.py::test_demo_scene",
    "tests/kinetostatics/plot/test_collisions.py::test_no_collisions_on_any_cli_picture",
    "tests/kinetostatics/plot/test_collisions.py::test_cli_pictures_lecture_size",
    "tests/kinetostatics/plot/test_pictures.py::test_every_new_picture_is_drawn",
    "tests/kinetostatics/plot/test_pictures.py::test_free_body_diagram_draws_the_forces",
    "tests/kinetostatics/plot/test_notation.py::test_every_cli_picture_meets_the_standard")}
_SANDBOX = "tests/kinetostatics/teaching/test_sandbox.py::"
_REPORT_PDF = "tests/balance/test_report_pdf.py::"
#: Module fixtures made once for tests spread among a module's others: the tests that use
#: each run on one worker (xdist group ``<fixture>``; collection checks the list is whole).
SHARED_ONCE = {"hostile": tuple(_SANDBOX + name for name in (
    "test_grading_finishes_and_the_honest_keep_full_marks",
    "test_no_hostile_student_gets_a_key_value", "test_reading_the_key_or_the_seed_fails",
    "test_nothing_outside_the_sandbox_is_written", "test_the_loopback_service_is_not_reached",
    "test_a_limit_hit_is_a_flag_naming_it",
    "test_no_background_process_outlives_its_notebook")),
    "long_sweep_csv": ("tests/kinetostatics/test_tables.py::"
                       "test_long_sweep_written_as_pandas_writes_it",),
    "written": tuple(_REPORT_PDF + name for name in (
        "test_pdf_is_an_a4_document_with_the_html_sections",
        "test_residual_at_rounding_and_micrometres", "test_legends_carry_units",
        "test_pictures_heading_kept_with_its_picture_and_panels_at_full_width"))}


def _import_every_module() -> None:
    """Import every module of both packages.

    Hypothesis draws some examples from the literal constants of the project's modules
    imported so far (its "local constants"), so without this the derandomized examples
    of a test would depend on which modules other tests had imported before it (the
    order of the run, one file or the suite, the xdist worker). With every module
    imported first, every process draws the same examples."""
    for package in ("kinetostatics", "balance"):
        root = importlib.import_module(package)
        for info in pkgutil.walk_packages(root.__path__, f"{package}."):
            if not info.name.endswith("__main__"):
                try:
                    importlib.import_module(info.name)
                except Exception:       # the tests that import it report it
                    continue


#: numba's cache folder as the suite's environment gives it (None: the loader's default),
#: put back after each test (:func:`pytest_runtest_teardown`).
NUMBA_BASE = os.environ.get("NUMBA_CACHE_DIR")


def _settle_numba_cache() -> None:
    """numba's cache folder in this process: the loader's folder for this version of the
    kernels (kinetostatics.solver.fast.loader.cache_folder), before any kernel is made.

    The loader settles the folder when it loads the kernels; here they are made earlier
    (:func:`_import_every_module`, a test module's import), and numba gives a kernel its
    cache folder when it is made: the suite's kernels were cached beside the sources
    (``__pycache__``, unkeyed: stale after a change to a helper they inline), apart from
    the folder of the commands the tests start, which compiled every kernel again (11-12 s
    of CPU each for ``bench --quick`` and a forced ``solve``, measured 2026-11-29)."""
    from kinetostatics.solver.fast import loader
    if not loader.installed():
        return
    folder = loader.cache_folder()
    if folder is not None:
        import numba
        # numba's compiler reads the environment again whenever it changed since numba
        # last read it (config.reload_config), and would put back the folder it names: read
        # now, so that only a later change of NUMBA_CACHE_DIR resets the folder set here
        numba.core.config.reload_config()
        _NUMBA_FOLDER[:] = [str(folder)]
        numba.config.CACHE_DIR = _NUMBA_FOLDER[0]


#: The folder :func:`_settle_numba_cache` gave numba (none yet: empty).
_NUMBA_FOLDER: list[str] = []


def pytest_runtest_setup(item: pytest.Item) -> None:
    """numba's cache folder settled again before each test: a test that changed
    ``NUMBA_CACHE_DIR`` (the loader, a monkeypatch) changes it back after its own
    teardown, and numba's compiler, reading the changed environment, would cache the next
    kernel beside the sources (seen 2026-11-29: an xdist worker where a kernel was
    compiled after such a test)."""
    if _NUMBA_FOLDER and "numba" in sys.modules:
        config = sys.modules["numba"].core.config
        config.reload_config()
        config.CACHE_DIR = _NUMBA_FOLDER[0]


def pytest_runtest_teardown(item: pytest.Item) -> None:
    """``NUMBA_CACHE_DIR`` as it was: the loader writes its keyed folder there when it
    loads the kernels, and a command started by a later test would take that for the
    base and cache one folder deeper (compiling everything again)."""
    if os.environ.get("NUMBA_CACHE_DIR") != NUMBA_BASE:
        if NUMBA_BASE is None:
            os.environ.pop("NUMBA_CACHE_DIR", None)
        else:
            os.environ["NUMBA_CACHE_DIR"] = NUMBA_BASE


def pytest_sessionstart(session: pytest.Session) -> None:
    """Every module imported where tests run (not in an xdist controller, which only
    hands them out, and writes the bytecode the workers read first:
    :func:`~tests.prewarm.warm_bytecode`), the compiled kernels' cache folder settled
    first."""
    config = session.config
    controller = (config.pluginmanager.has_plugin("xdist") and
                  not hasattr(config, "workerinput") and
                  bool(config.getoption("numprocesses")) and
                  config.getoption("dist") != "no")
    if controller:
        warm_bytecode(config)
        return
    _settle_numba_cache()
    if PROFILE in ("repeatable", "quick"):
        _import_every_module()


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config: pytest.Config) -> None:
    """An xdist worker ends without the interpreter's teardown once its exit handlers
    have run (:mod:`tests.worker_exit`): the controller waited seconds for each."""
    if hasattr(config, "workerinput"):
        end_without_teardown()


def pytest_addoption(parser: pytest.Parser, pluginmanager: pytest.PytestPluginManager) -> None:
    """Without pytest-xdist (``-p no:xdist``, or not installed) the configuration's
    ``-n auto --dist loadgroup`` are taken and ignored: the run is serial."""
    if not pluginmanager.has_plugin("xdist"):
        group = parser.getgroup("xdist (not loaded)")
        # (a lowercase short option: pytest-xdist declares its own -n the same way)
        group._addoption("-n", "--numprocesses", dest="numprocesses", default=None,
                        help="ignored: pytest-xdist is not loaded")
        group.addoption("--dist", dest="dist", default="no",
                        help="ignored: pytest-xdist is not loaded")


def _quick_tier(config: pytest.Config) -> bool:
    """The run deselects the slow tests (``-m "not slow"``, alone or with more)."""
    return "not slow" in " ".join((config.getoption("markexpr") or "").split())


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_auto_num_workers(config: pytest.Config) -> int | None:
    """``-n auto``: the full suite on one worker more than the processors it may use, the
    quick tier on as many (``PYTEST_XDIST_AUTO_NUM_WORKERS`` still decides where set).

    The full suite's workers wait on processes they start (Jupyter kernels, Chromium,
    the CLIs, process pools): with two workers on the 2-core machine a fifth of its
    processor time went unused (1016 s of CPU in 645 s), and a third worker took up the
    slack: 535 s of pytest against 589 s on a fresh clone with an empty cache (measured
    2026-11-30, f190c15); a fourth took 550 s against the three's 529 s (727a8be, the same
    day, quiet: the waits are filled, a worker more only adds its start and its share of
    the compiles and fixtures). The quick tier's tests seldom wait, and each worker's start
    costs some 8 s of CPU (every module imported): there a worker more only adds load."""
    if os.environ.get("PYTEST_XDIST_AUTO_NUM_WORKERS"):
        return None
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return (usable or 1) + (0 if _quick_tier(config) else 1)


def pytest_configure(config: pytest.Config) -> None:
    """The xdist_group mark, and the profile ``quick`` for the quick tier (before the
    test modules are imported: their own settings inherit its count)."""
    global PROFILE
    config.addinivalue_line("markers", "xdist_group(name): run on one xdist worker")
    config.addinivalue_line("markers", "quick_keeper(reason): stays in the quick tier "
                            "whatever it costs (tests/conftest.py, keeper)")
    if "HYPOTHESIS_PROFILE" not in os.environ and _quick_tier(config):
        PROFILE = "quick"
        settings.load_profile(PROFILE)


def _examples(own: int) -> int:
    """A property test's own count of examples under the loaded profile."""
    if PROFILE == "explore":
        return EXPLORE_FACTOR * own
    return max(own // QUICK_SHARE, min(own, QUICK_FEWEST))


def _scale_examples(items: list[pytest.Item]) -> None:
    """Profiles ``explore`` and ``quick``: ten times, or a tenth of (at least five), the
    examples of every property test that sets its own count (hypothesis reads a test's
    settings when it runs; the others inherit the profile's default)."""
    done = set()                        # (a parametrized test's items share one function)
    for item in items:
        test = getattr(getattr(item, "obj", None), "__func__", getattr(item, "obj", None))
        own = getattr(test, "_hypothesis_internal_use_settings", None)
        if own is None or id(test) in done:
            continue
        done.add(id(test))
        if own.max_examples != settings.default.max_examples:
            test._hypothesis_internal_use_settings = settings(
                own, max_examples=_examples(own.max_examples))


def mutant_killers() -> tuple[str, ...]:
    """The quick tests named to kill the mutants of tools/mutants.py (``--killers``)."""
    from tools.mutants import MUTANTS
    return tuple(name for m in MUTANTS for name in m.killers)


def keeper(item: pytest.Item, killers: tuple[str, ...] = ()) -> str | None:
    """Why a test stays in the quick tier whatever it costs (a property test, an
    invariance test, a command line's smoke test, a mutant's killer, the picture scene's
    figures), else None."""
    base = item.nodeid.split("[")[0]
    if getattr(getattr(item, "obj", None), "is_hypothesis_test", False):
        return "property"
    if "invariance" in base.split("::")[0].rsplit("/", 1)[-1]:
        return "invariance"
    if base in CLI_SMOKE:
        return "command-line smoke test"
    if item.nodeid in killers:
        return "mutant killer"
    scene = getattr(item, "callspec", None)
    if ("lecture_figures" in getattr(item, "fixturenames", ()) and scene is not None
            and scene.params.get("name") == QUICK_PICTURE_SCENE):
        return "picture scene"
    return None


def slow_by_cost() -> dict[str, float]:
    """:data:`SLOW_BY_COST`: test id (or a test's id without parameters) to CPU seconds."""
    entries = {}
    for line in SLOW_BY_COST.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            cpu, nodeid = line.split(maxsplit=1)
            entries[nodeid.strip()] = float(cpu)
    return entries


def _mark_by_cost(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark ``slow`` the tests of :data:`SLOW_BY_COST` and ``quick_keeper`` the keepers
    (:func:`keeper`); a keeper listed, or (in a run of the whole suite) an entry that names
    no test, stops the run."""
    listed, killers, found = slow_by_cost(), mutant_killers(), set()
    for item in items:
        reason = keeper(item, killers)
        if reason:
            item.add_marker(pytest.mark.quick_keeper(reason))
        entry = next((e for e in (item.nodeid, item.nodeid.split("[")[0]) if e in listed),
                     None)
        if entry is None:
            continue
        found.add(entry)
        if reason:
            raise pytest.UsageError(f"{item.nodeid} is in {SLOW_BY_COST.name} but stays "
                                    f"in the quick tier ({reason}): make it cheaper")
        item.add_marker(pytest.mark.slow)
    root = config.rootpath
    whole = not config.getoption("keyword") and {
        (root / a).resolve() for a in config.args or ["."]} <= {
        (root / t).resolve() for t in [".", *config.getini("testpaths")]}
    # an entry of a test parametrized by data outside the repository (../shared's cases,
    # absent from a fresh clone) is stale only when its test function is gone
    functions = {item.nodeid.split("[")[0] for item in items}
    stale = sorted(e for e in listed.keys() - found
                   if e.split("[")[0] not in functions or "[shared-" not in e)
    if whole and stale:
        raise pytest.UsageError(f"{SLOW_BY_COST.name} names tests that are not there: "
                                f"{stale}")


@pytest.hookimpl(tryfirst=True)      # before xdist's, which reads the xdist_group marks
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark ``slow`` (and ``kernel``/``browser``) every test that uses a slow fixture,
    and group the tests that share a per-scene session fixture."""
    if PROFILE in ("explore", "quick"):
        _scale_examples(items)
    _mark_by_cost(config, items)
    for item in items:
        used = set(getattr(item, "fixturenames", ()))
        scene = getattr(item, "callspec", None)
        scene = scene.params.get("name") if scene is not None else None
        for name in used & SLOW_FIXTURES.keys():
            if name == "lecture_figures" and scene == QUICK_PICTURE_SCENE:
                continue
            item.add_marker(pytest.mark.slow)
            for mark in FIXTURE_MARKS.get(name, ()):
                item.add_marker(getattr(pytest.mark, mark))
        for table, suffix in ((SHARED_PER_SCENE, f"-{scene}"), (SHARED_ONCE, "")):
            for name in used.intersection(table):
                if item.nodeid.split("[")[0] not in table[name]:
                    raise pytest.UsageError(f"{item.nodeid} uses {name}: add it to "
                                            "SHARED_PER_SCENE or SHARED_ONCE in "
                                            "tests/conftest.py")
                item.add_marker(pytest.mark.xdist_group(name + suffix))
    # the longest work first, so the workers start on the long units and the short ones
    # fill in at the end, instead of one worker finishing a run of long tests alone
    items[:] = _in_order_of_cost(items, _quick_tier(config))


#: Single tests measured among the longest (30-170 s each at a load of 5 on 2 cores,
#: 2026-11-29), started with the browser's
LONGEST = ("tests/kinetostatics/test_cli.py::test_bench_quick",
           "tests/test_mutants.py::test_every_mutant_is_killed_by_a_quick_test",
           "tests/kinetostatics/solver/test_fast.py::test_the_examples_agree",
           "tests/kinetostatics/solver/test_fast.py::test_random_geometry_agrees",
           "tests/kinetostatics/solver/test_fast.py::test_the_environment_variable_forces",
           "tests/test_fuzz_scenes.py::test_mutated_scenes_through_the_api[four_bar_motion]",
           "tests/test_fuzz_scenes.py::test_a_sample_through_the_command_line",
           "tests/test_fuzz_scenes.py::test_resource_bombs_end_in_one_line",
           "tests/kinetostatics/design/test_bench_design.py::test_bench_design_row")


def _cost_rank(item: pytest.Item) -> int:
    """0 for the browser's tests and :data:`LONGEST`, 1 for the other kernels', 2 for the
    other slow tests and those of a slow fixture (the quick tier's picture scene), 3 for
    the quick tier."""
    if item.get_closest_marker("browser") or item.nodeid.startswith(LONGEST):
        return 0
    if item.get_closest_marker("kernel"):
        return 1
    slow = item.get_closest_marker("slow") or SLOW_FIXTURES.keys() & set(
        getattr(item, "fixturenames", ()))
    return 2 if slow else 3


def _in_order_of_cost(items: list[pytest.Item], by_module: bool) -> list[pytest.Item]:
    """The tests in the order their xdist work units (:func:`_scope`) should be handed
    out: the units of the costliest rank (:func:`_cost_rank` of their costliest test)
    first, among those the largest first, the collection's order otherwise (stable
    sorts); inside a unit its costliest tests first.

    pytest-xdist's ``loadgroup`` queues the units in the order of their first test
    (:func:`pytest_xdist_make_scheduler` turns its own reordering, by size alone, off): by
    size alone the groups of shared fixtures went first and the browser's single tests
    (20-35 s each) after them, the last of them the run's tail on one worker while the
    other had run out of work."""
    units: dict[str, list[pytest.Item]] = {}
    for item in items:
        units.setdefault(_scope(item.nodeid, by_module), []).append(item)

    def cost(unit: list[pytest.Item]) -> tuple[int, int]:
        # the quick tier ranks a unit by its quick tests (the slow ones are deselected
        # after this hook)
        kept = [i for i in unit if not i.get_closest_marker("slow")] if by_module else unit
        kept = kept or unit
        return min(map(_cost_rank, kept)), -len(kept)

    ranked = sorted(units.values(), key=cost)
    return [item for unit in ranked for item in sorted(unit, key=_cost_rank)]


#: Test modules whose tests share a costly module fixture or cache (a class generated; the
#: browser test's JupyterLab server, Chromium and page with JupyterLab loaded; the layout
#: rules' syntax trees of every module; a design run; the exercises' generated classes):
#: each runs on one xdist worker, so the fixture is made once. (Spread over two workers,
#: the browser's eleven tests started a second server, Chromium and JupyterLab page: 10 s
#: of CPU, measured 2026-11-29; on one worker they take some 250 s of CPU while the other
#: worker runs the compiled group, handed out first. Spread over three workers,
#: test_layout parsed and walked every module on each, test_design ran its design on two,
#: test_exercises generated its classes on each: the three modules under ``-n 3``, 27.2 and
#: 28.1 s of CPU spread, 15.1 and 17.0 s so; test_layout 8.3 -> 3.3 s, test_design 11.8
#: -> 6.5 s, test_exercises 7.2 -> 5.4 s, measured 2026-11-30. test_notebooks forks its
#: sheets' kernels from one process that imports their libraries, ~2 s, once a worker:
#: tests/_kernel_fork.py, 2026-12-01.)
SHARED_PER_MODULE = ("tests/kinetostatics/teaching/test_classroom.py",
                     "tests/kinetostatics/teaching/test_class_record.py",
                     "tests/test_browser.py",
                     "tests/test_notebooks.py",
                     "tests/test_layout.py",
                     "tests/kinetostatics/design/test_design.py",
                     "tests/kinetostatics/teaching/test_exercises.py")


#: Tests that run the compiled kernels (numba), in the test's process or in a command it
#: starts: all on one xdist worker (group ``numba``). The project ships no cache, so a
#: fresh clone compiles each kernel on its first call (test_fast.py's kernels: 101 s of
#: CPU on a fresh cache against 7 s on a warm one, measured serially 2026-11-29); spread
#: over two workers, both compiled the same kernels at once. On one worker the first call
#: compiles a kernel and writes numba's cache, every later call (and command) loads it.
COMPILED = ("tests/kinetostatics/solver/test_fast.py::",
            "tests/kinetostatics/solver/test_many_fast.py::",
            "tests/kinetostatics/solver/test_many_guided.py::",
            "tests/kinetostatics/solver/test_many_geometry.py::",
            "tests/kinetostatics/solver/test_many_rounds.py::",
            "tests/kinetostatics/solver/test_fast_short.py::",
            "tests/kinetostatics/solver/test_fast_long.py::",
            "tests/kinetostatics/solver/test_fast_auto.py::",
            "tests/kinetostatics/solver/test_fast_rowcost.py::",
            "tests/kinetostatics/solver/test_fast_guided.py::",
            "tests/kinetostatics/solver/test_fast_guided_trig.py::",
            "tests/kinetostatics/solver/test_fast_guided_still.py::",
            "tests/kinetostatics/solver/test_fast_stats.py::",
            "tests/kinetostatics/solver/test_fast_trig.py::",
            "tests/kinetostatics/results/test_fast_tables_turn.py::",
            "tests/kinetostatics/solver/test_fast_cache_names.py::",
            "tests/kinetostatics/solver/test_fast_kept_ground.py::",
            "tests/kinetostatics/solver/test_screen.py::",
            "tests/kinetostatics/solver/test_screen_probe.py::",
            "tests/kinetostatics/solver/test_screen_chain.py::",
            "tests/kinetostatics/solver/test_screen_bound.py::",
            "tests/kinetostatics/results/test_fastpass.py::",
            "tests/kinetostatics/design/test_stacked.py::"
            "test_auto_judges_on_the_stack_even_with_the_compiled_path_loaded",
            "tests/kinetostatics/design/test_bench_design.py::test_bench_design_row",
            "tests/kinetostatics/test_cli.py::test_bench_quick",
            "tests/kinetostatics/test_cli.py::test_bench_tables_quick")


def _group(nodeid: str) -> str | None:
    """The xdist group of a test id: ``<fixture>-<scene>`` for the tests of
    :data:`SHARED_PER_SCENE`, ``<fixture>`` for those of :data:`SHARED_ONCE`, the module
    for those of :data:`SHARED_PER_MODULE`, ``numba`` for :data:`COMPILED`, else None."""
    base, _, param = nodeid.partition("[")
    module = base.split("::")[0]
    if base.startswith(COMPILED):
        return "numba"
    if module in SHARED_PER_MODULE:
        return module
    for name, tests in SHARED_PER_SCENE.items():
        if base in tests:
            return f"{name}-{param.rstrip(']')}"
    for name, tests in SHARED_ONCE.items():
        if base in tests:
            return name
    return None


def _scope(nodeid: str, by_module: bool) -> str:
    """The xdist work unit of a test id: its :func:`_group`, else its module (the quick
    tier, ``by_module``) or itself."""
    return _group(nodeid) or (nodeid.split("::")[0] if by_module else nodeid)


@pytest.hookimpl(optionalhook=True)     # (a hook of pytest-xdist: unknown without it)
def pytest_xdist_make_scheduler(config: pytest.Config, log):
    """``--dist loadgroup`` that also groups by :func:`_group` (pytest-xdist's own
    grouping renames the test ids, which pytest 9.2 no longer lets it do: its groups are
    then silently ignored, pytest-xdist issue 1386), and in the quick tier by module."""
    if config.getoption("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling
    # the quick tier hands out whole modules: a module fixture is then made once, not on
    # each worker (measured: 5 s less CPU in all); the full suite spreads its long tests
    by_module = _quick_tier(config)
    # the units go out in the order of their first test (:func:`_in_order_of_cost`), not
    # by their number of tests
    config.option.loadscopereorder = False

    class SharedFixtureScheduling(LoadGroupScheduling):
        def _split_scope(self, nodeid: str) -> str:
            if "@" in nodeid:
                return super()._split_scope(nodeid)
            return _scope(nodeid, by_module)

    return SharedFixtureScheduling(config, log)


@pytest.fixture
def numpy_path():
    """The numpy solve path for one test, whatever ``KINETOSTATICS_PATH`` says (a test of
    the numpy path's own workings: what it lets go, its blocks, its traps)."""
    from kinetostatics.solver.fast import use
    use("numpy")
    yield
    use(None)


@pytest.fixture
def fast():
    """The compiled solve path for one test, put back after (skipped where its kernels
    do not load: no numba, no writable cache folder)."""
    from kinetostatics.solver.fast import loader, use
    if loader.kernels() is None:
        pytest.skip("the compiled kernels do not load here")
    use("fast")
    yield
    use(None)
