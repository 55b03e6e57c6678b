"""The house rules of the layout: no import cycle, small modules, one home per definition."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("kinetostatics", "balance")
MAX_LINES = 600
# modules allowed over MAX_LINES, with the reason (none today)
LONG_MODULES: dict[str, str] = {}


def _modules(root: Path = ROOT, packages: tuple[str, ...] = PACKAGES) -> dict[str, Path]:
    """Every module of ``packages`` below ``root``, by dotted name (a package by its
    ``__init__``)."""
    out = {}
    for pkg in packages:
        for path in sorted((root / pkg).rglob("*.py")):
            parts = list(path.relative_to(root).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            out[".".join(parts)] = path
    return out


def _type_checking(node: ast.AST) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


def _ancestors(name: str) -> list[str]:
    """``a.b.c`` -> ``[a, a.b]``: the packages whose ``__init__`` runs before it."""
    parts = name.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts))]


def _package(name: str, modules: dict[str, Path]) -> str:
    """The package a module lives in (a package's ``__init__`` lives in the package)."""
    return name if modules[name].name == "__init__.py" else name.rpartition(".")[0]


def _import_statements(name: str, path: Path, modules: dict[str, Path]):
    """Each run-time import of ``name`` (module level or inside functions; ``if
    TYPE_CHECKING:`` blocks left out) as (module imported, name taken from it or None,
    line)."""
    is_pkg = path.name == "__init__.py"
    base = name.split(".") if is_pkg else name.split(".")[:-1]
    out: list[tuple[str, str | None, int]] = []

    def visit(node: ast.AST) -> None:
        for child in ast.iter_child_nodes(node):
            if _type_checking(child):
                continue
            if isinstance(child, ast.Import):
                out.extend((a.name, None, child.lineno) for a in child.names)
            elif isinstance(child, ast.ImportFrom):
                if child.level:
                    head = base[: len(base) - (child.level - 1)]
                    mod = ".".join(head + ([child.module] if child.module else []))
                else:
                    mod = child.module or ""
                for a in child.names:
                    sub = f"{mod}.{a.name}"
                    if sub in modules:          # ``from pkg import module``
                        out.append((sub, None, child.lineno))
                    else:
                        out.append((mod, a.name, child.lineno))
            visit(child)

    visit(ast.parse(path.read_text()))
    return out


def _imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """Modules of the packages whose code runs when ``name`` runs its imports: each module
    imported and every package ``__init__`` above it (``import a.b.c`` runs ``a`` and
    ``a.b`` first), less ``name``'s own packages, which are running already."""
    found: set[str] = set()
    for mod, _, _ in _import_statements(name, path, modules):
        found.update(m for m in (*_ancestors(mod), mod) if m in modules)
    found.difference_update({name, *_ancestors(name)})
    return found


def _private_crossings(modules: dict[str, Path]) -> list[str]:
    """Imports of a private module or name (a leading underscore) from another package."""
    bad = []
    for name, path in modules.items():
        here = _package(name, modules)
        for mod, taken, line in _import_statements(name, path, modules):
            if mod not in modules:
                continue                       # outside the packages (pymunk, numpy, ...)
            private_module = any(p.startswith("_") and not p.startswith("__")
                                 for p in mod.split("."))
            private_name = taken is not None and taken.startswith("_") \
                and not taken.startswith("__")
            if (private_module or private_name) and _package(mod, modules) != here:
                what = f"{mod}.{taken}" if private_name else mod
                bad.append(f"{path.relative_to(path.parents[len(name.split('.')) - 1])}"
                           f":{line}: {what}")
    return bad


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def strong(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in graph:
        if v not in index:
            strong(v)
    return out


def test_no_import_cycle() -> None:
    modules = _modules()
    graph = {name: _imports(name, path, modules) for name, path in modules.items()}
    assert _cycles(graph) == []


def test_cycle_finder_finds_a_cycle() -> None:
    """The checker itself: a -> b -> c -> a is a cycle, d -> a is not part of it."""
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _cycles(graph) == [["a", "b", "c"]]


@pytest.mark.parametrize("name", sorted(_modules()))
def test_module_is_small(name: str) -> None:
    lines = _modules()[name].read_text().count("\n")
    assert lines <= MAX_LINES or name in LONG_MODULES, (
        f"{name} has {lines} lines (more than {MAX_LINES}): split it by job")


def test_no_private_name_crosses_a_package() -> None:
    """No module imports a ``_private`` module or name of another package (share it by
    making it public, once)."""
    assert _private_crossings(_modules()) == []


def _plant(root: Path, files: dict[str, str]) -> dict[str, Path]:
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    return _modules(root, ("pkg",))


def test_a_cycle_through_a_package_init_is_found(tmp_path: Path) -> None:
    """The cycle this test once missed: ``results`` imports ``solver.kinematics``, which
    runs ``solver/__init__``, which imports ``pipeline``, which imports ``results``."""
    modules = _plant(tmp_path, {
        "pkg/__init__.py": "",
        "pkg/results.py": "from .solver.kinematics import K\n",
        "pkg/solver/__init__.py": "from .pipeline import solve\n",
        "pkg/solver/kinematics.py": "K = 1\n",
        "pkg/solver/pipeline.py": "from ..results import R\n",
    })
    graph = {name: _imports(name, path, modules) for name, path in modules.items()}
    assert _cycles(graph) == [["pkg.results", "pkg.solver", "pkg.solver.pipeline"]]
    # a module importing its own package's siblings is no cycle
    assert "pkg.solver" not in graph["pkg.solver.pipeline"]


def test_a_private_import_across_packages_is_found(tmp_path: Path) -> None:
    modules = _plant(tmp_path, {
        "pkg/__init__.py": "",
        "pkg/solver/__init__.py": "",
        "pkg/solver/_arith.py": "def full(): pass\n",
        "pkg/solver/closure.py": "from . import _arith\nfrom ._arith import full\n",
        "pkg/motion/__init__.py": "",
        "pkg/motion/scene.py": "from ..solver import _arith\n",
        "pkg/motion/loads.py": "from ..solver.closure import _hidden\n",
    })
    bad = _private_crossings(modules)
    assert len(bad) == 2, bad              # inside solver/ it is the package's own business
    assert any("motion/scene.py:1: pkg.solver._arith" in b for b in bad), bad
    assert any("motion/loads.py:1: pkg.solver.closure._hidden" in b for b in bad), bad
