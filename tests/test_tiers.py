"""The tiers' settings (tests/conftest.py): the quick tier (``-m "not slow"``) runs every
property test on a tenth of its examples, at least five; the full suite on all of them;
``HYPOTHESIS_PROFILE=explore`` on ten times as many."""

from __future__ import annotations

import os
from pathlib import Path
from types import SimpleNamespace

import pytest
from hypothesis import settings

from tests import conftest


def _config(markexpr: str) -> SimpleNamespace:
    return SimpleNamespace(getoption=lambda name: {"markexpr": markexpr}[name])


@pytest.mark.parametrize(("markexpr", "quick"), [
    ("not slow", True), ("not slow and not kernel", True), ("kernel and  not   slow", True),
    ("", False), ("slow", False), ("kernel", False)])
def test_the_quick_tier_is_the_run_without_the_slow_tests(markexpr: str, quick: bool) -> None:
    assert conftest._quick_tier(_config(markexpr)) is quick


def test_each_profile_scales_a_property_tests_own_count(monkeypatch) -> None:
    monkeypatch.setattr(conftest, "PROFILE", "quick")
    assert [conftest._examples(n) for n in (400, 100, 40, 12, 3)] == [40, 10, 5, 5, 3]
    monkeypatch.setattr(conftest, "PROFILE", "explore")
    assert conftest._examples(40) == 400


def test_this_run_has_its_tiers_profile(request) -> None:
    """The profile loaded is the one the tier asks for (the count every property test
    without its own inherits)."""
    named = os.environ.get("HYPOTHESIS_PROFILE")
    want = named or ("quick" if conftest._quick_tier(request.config) else "repeatable")
    assert conftest.PROFILE == want
    base = settings.get_profile("repeatable").max_examples
    count = {"quick": base // conftest.QUICK_SHARE, "repeatable": base,
             "explore": conftest.EXPLORE_FACTOR * base}.get(want)
    assert count is None or settings.default.max_examples == count
    if want in ("quick", "repeatable"):
        assert settings.default.derandomize


def test_the_compiled_paths_tests_share_one_worker() -> None:
    """Every entry of COMPILED names a test module that is there, and the test where it
    names one (a test renamed or moved would leave the group silently and compile the
    kernels on a second worker again); their ids fall in the group ``numba``."""
    root = Path(conftest.__file__).resolve().parents[1]
    for entry in conftest.COMPILED:
        module, _, name = entry.partition("::")
        text = (root / module).read_text(encoding="utf-8")
        assert not name or f"def {name}(" in text, entry
        assert conftest._group(f"{entry}{'' if name else 'test_x'}[p]") == "numba", entry
    assert conftest._group("tests/kinetostatics/solver/test_kinematics.py::test_x") is None
    # a test module that sets the compiled path or reads the compiled package is in the
    # group, whole or by the names of its tests that load kernels (a new one must be added)
    for path in sorted((root / "tests").rglob("test_*.py")):
        text = path.read_text(encoding="utf-8")
        module = path.relative_to(root).as_posix()
        if path.name == "test_tiers.py" or not ('use("fast")' in text
                                                 or "kinetostatics.solver.fast" in text):
            continue
        named = any(e.startswith(f"{module}::") and e != f"{module}::"
                    for e in conftest.COMPILED)
        assert named or conftest._group(f"{module}::test_x") == "numba", module


def test_the_kernels_cache_where_the_commands_cache_them(monkeypatch) -> None:
    """numba caches this process's kernels in the loader's folder for this version of
    them (the commands the tests start use the same), and the loader's write of that
    folder into ``NUMBA_CACHE_DIR`` is undone after each test (a command started later
    would take it for the base and cache a folder deeper)."""
    from kinetostatics.solver.fast import loader
    if not loader.installed():
        pytest.skip("numba is not installed")
    import numba
    monkeypatch.setenv("NUMBA_CACHE_DIR", conftest.NUMBA_BASE or "")
    if conftest.NUMBA_BASE is None:
        monkeypatch.delenv("NUMBA_CACHE_DIR")
    assert numba.config.CACHE_DIR == str(loader.cache_folder())
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(loader.cache_folder()))   # as the loader does
    conftest.pytest_runtest_teardown(None)
    assert os.environ.get("NUMBA_CACHE_DIR") == conftest.NUMBA_BASE


class _Item:
    """A collected test as :func:`conftest._in_order_of_cost` reads it."""

    def __init__(self, nodeid: str, marks: tuple[str, ...] = (),
                 fixtures: tuple[str, ...] = ()) -> None:
        self.nodeid, self.marks, self.fixturenames = nodeid, marks, fixtures

    def get_closest_marker(self, name: str) -> str | None:
        return name if name in self.marks else None


def test_the_costliest_units_go_out_first() -> None:
    """The compiled group first (its longest test first), then the browser's group, the
    kernels', the slow ones and the quick tier's in the collection's order:
    pytest-xdist hands the units out in the order of their first test."""
    fast = "tests/kinetostatics/solver/test_fast.py::"
    items = [_Item("tests/a.py::test_quick"), _Item("tests/b.py::test_slow", ("slow",)),
             _Item(fast + "test_small"), _Item("tests/a.py::test_quick_too"),
             _Item("tests/test_browser.py::test_sheet[01]", ("slow", "kernel", "browser")),
             _Item("tests/test_mutants.py::test_every_mutant_is_killed_by_a_quick_test"),
             _Item("tests/c.py::test_kernel", ("slow", "kernel")),
             _Item("tests/test_browser.py::test_sheet[02]", ("slow", "kernel", "browser")),
             _Item("tests/kinetostatics/test_cli.py::test_bench_quick", ("slow",))]
    order = [i.nodeid.split("::")[1] for i in conftest._in_order_of_cost(items, False)]
    # (the browser's tests one unit: one JupyterLab server, Chromium and page for them)
    assert order == ["test_bench_quick", "test_small", "test_sheet[01]", "test_sheet[02]",
                     "test_every_mutant_is_killed_by_a_quick_test", "test_kernel",
                     "test_slow", "test_quick", "test_quick_too"]
    # the quick tier hands out modules, ranked by the tests it keeps: the module whose
    # slow test is deselected counts as quick; the picture scene's figures (a slow
    # fixture kept in the quick tier) go first, then the larger modules
    items = [_Item("tests/a.py::test_1"), _Item("tests/b.py::test_1"),
             _Item("tests/b.py::test_2"), _Item("tests/a.py::test_slow", ("slow",)),
             _Item("tests/p.py::test_pictures", (), ("lecture_figures",))]
    order = [i.nodeid for i in conftest._in_order_of_cost(items, True)]
    assert order == ["tests/p.py::test_pictures", "tests/b.py::test_1", "tests/b.py::test_2",
                     "tests/a.py::test_slow", "tests/a.py::test_1"]


def test_the_longest_tests_are_there() -> None:
    """Every entry of LONGEST names a test that is there, or the start of its name (a
    renamed one would lose its early start silently)."""
    root = Path(conftest.__file__).resolve().parents[1]
    for entry in conftest.LONGEST:
        module, _, name = entry.partition("::")
        assert f"def {name.split('[')[0]}" in (root / module).read_text(encoding="utf-8"), entry


def _decorated(root: Path, entry: str) -> str:
    """The decorators and ``def`` line of the test an id names (``module::name[...]``)."""
    module, _, name = entry.partition("::")
    lines = (root / module).read_text(encoding="utf-8").splitlines()
    start = next(i for i, line in enumerate(lines)
                 if line.startswith(f"def {name.split('[')[0]}("))
    first = start
    while first and (lines[first - 1].startswith(("@", " ", ")", "]"))):
        first -= 1
    return "\n".join(lines[first:start + 1])


def test_the_slow_by_cost_list_names_tests_there_and_no_keepers() -> None:
    """Every line of tests/slow_by_cost.txt names a test that is there (by its module and
    function; the conftest stops a whole run whose list names a parameter that is not),
    over the quick tier's budget, and none that must stay quick: no property test (a
    ``given`` among its decorators), invariance test, command-line smoke test or mutant
    killer."""
    root = Path(conftest.__file__).resolve().parents[1]
    listed = conftest.slow_by_cost()
    killers = conftest.mutant_killers()
    assert len(listed) > 100 and len(killers) >= 6
    for entry, cpu in listed.items():
        assert cpu >= conftest.QUICK_CPU, entry
        assert "invariance" not in entry.split("::")[0], entry
        assert entry.split("[")[0] not in conftest.CLI_SMOKE, entry
        assert not any(k.startswith(entry) for k in killers), entry
        assert "given(" not in _decorated(root, entry), entry


def test_the_named_keepers_stay_quick() -> None:
    """The command lines' smoke tests and the mutants' killers are there, carry no
    ``slow`` mark and use no slow fixture (tools/mutants.py --killers runs them in the
    quick tier: a killer marked slow would kill nothing)."""
    root = Path(conftest.__file__).resolve().parents[1]
    for entry in (*conftest.CLI_SMOKE, *conftest.mutant_killers()):
        text = _decorated(root, entry)
        assert "mark.slow" not in text, entry
        assert not any(f"{name}" in text.split("def ", 1)[1]
                       for name in conftest.SLOW_FIXTURES), entry
        module = (root / entry.split("::")[0]).read_text(encoding="utf-8")
        assert "pytestmark = pytest.mark.slow" not in module, entry


class _Marked(_Item):
    """A collected test that takes marks, and the function it runs."""

    def __init__(self, nodeid: str, obj=None) -> None:
        super().__init__(nodeid)
        self.obj, self.marks = obj, ()

    def add_marker(self, mark) -> None:
        self.marks += (mark.name,)


def _run_config(args: list[str], keyword: str = "") -> SimpleNamespace:
    root = Path(conftest.__file__).resolve().parents[1]
    options = {"keyword": keyword}
    return SimpleNamespace(getoption=options.__getitem__, args=args, rootpath=root,
                           getini=lambda name: ["tests"])


def test_the_listed_tests_are_marked_slow_and_a_listed_keeper_stops_the_run(
        monkeypatch) -> None:
    listed = {"tests/a.py::test_heavy": 0.4, "tests/a.py::test_param[2]": 0.3}
    monkeypatch.setattr(conftest, "slow_by_cost", lambda: listed)
    items = [_Marked("tests/a.py::test_heavy[1]"), _Marked("tests/a.py::test_param[1]"),
             _Marked("tests/a.py::test_param[2]"), _Marked(conftest.CLI_SMOKE[0])]
    conftest._mark_by_cost(_run_config(["tests/a.py"]), items)
    assert [i.marks for i in items] == [("slow",), (), ("slow",), ("quick_keeper",)]
    # a run of the whole suite: every entry must name a test
    with pytest.raises(pytest.UsageError, match="not there"):
        conftest._mark_by_cost(_run_config([]), items[:2])
    conftest._mark_by_cost(_run_config([], keyword="heavy"), items[:2])
    # an entry parametrized by ../shared's cases (absent from a fresh clone) is stale
    # only when its test function is gone
    listed["tests/a.py::test_param[shared-x]"] = 0.2
    conftest._mark_by_cost(_run_config([]), items)
    listed["tests/a.py::test_gone[shared-x]"] = 0.2
    with pytest.raises(pytest.UsageError, match="test_gone"):
        conftest._mark_by_cost(_run_config([]), items)

    def prop() -> None:
        pass
    prop.is_hypothesis_test = True
    listed["tests/a.py::test_prop"] = 0.2
    with pytest.raises(pytest.UsageError, match="property"):
        conftest._mark_by_cost(_run_config(["tests/a.py"]),
                               [_Marked("tests/a.py::test_prop", prop)])
