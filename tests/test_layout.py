"""The house rules of the layout: no import cycle, small modules, one home per definition."""

from __future__ import annotations

import ast
import bisect
import functools
from pathlib import Path

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


@functools.cache
def _parse(source: str) -> ast.Module:
    """The syntax tree of a module's source, parsed once for every rule (read, never
    changed; each rule parsing the 49k lines again cost 1-2 s of CPU per test)."""
    return ast.parse(source)


@functools.cache
def _walk(source: str) -> tuple[ast.AST, ...]:
    """Every node of a module's tree (:func:`_parse`), walked once for the three rules
    that look at every node (each walking it again: about 0.5 s more CPU for this module,
    7.2 s against 6.6-6.8 s, measured 2026-11-29)."""
    return tuple(ast.walk(_parse(source)))


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
    out: list[tuple[str, str | None, int]] = []
    for mod, taken, line in _raw_imports(name, path, path.read_text()):
        if taken is not None and f"{mod}.{taken}" in modules:      # ``from pkg import module``
            out.append((f"{mod}.{taken}", None, line))
        else:
            out.append((mod, taken, line))
    return out


@functools.cache
def _raw_imports(name: str, path: Path, source: str) -> tuple[tuple[str, str | None, int], ...]:
    """The imports of a module's source as written (relative ones made absolute), walked
    once for every rule (each rule walking the 49k lines again cost 0.3 s of CPU)."""
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
                out.extend((mod, a.name, child.lineno) for a in child.names)
            visit(child)

    visit(_parse(source))
    return tuple(out)


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


def test_every_module_is_small() -> None:
    """No module over MAX_LINES lines (one test for the ~210 modules, each named in the
    message: a test each cost 1.5 s of CPU in pytest's and pytest-xdist's bookkeeping)."""
    long = {name: lines for name, path in _modules().items()
            if (lines := path.read_text().count("\n")) > MAX_LINES and name not in LONG_MODULES}
    assert not long, [f"{name} has {lines} lines (more than {MAX_LINES}): split it by job"
                      for name, lines in long.items()]


def test_no_private_name_crosses_a_package() -> None:
    """No module imports a ``_private`` module or name of another package (share it by
    making it public, once)."""
    assert _private_crossings(_modules()) == []


def _plant(root: Path, files: dict[str, str]) -> dict[str, Path]:
    """Write ``files`` below ``root``; every folder without an ``__init__.py`` gets an
    empty one (a package)."""
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    for rel in files:
        for folder in Path(rel).parents[:-1]:
            init = root / folder / "__init__.py"
            if not init.exists():
                init.write_text("")
    return _modules(root, ("pkg",))


def test_a_cycle_through_a_package_init_is_found(tmp_path: Path) -> None:
    """The cycle this test once missed: ``results`` imports ``solver.kinematics``, which
    runs ``solver/__init__``, which imports ``pipeline``, which imports ``results``."""
    modules = _plant(tmp_path, {
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
        "pkg/solver/_arith.py": "def full(): pass\n",
        "pkg/solver/closure.py": "from . import _arith\nfrom ._arith import full\n",
        "pkg/motion/scene.py": "from ..solver import _arith\n",
        "pkg/motion/loads.py": "from ..solver.closure import _hidden\n",
    })
    bad = _private_crossings(modules)
    assert len(bad) == 2, bad              # inside solver/ it is the package's own business
    assert any("motion/scene.py:1: pkg.solver._arith" in b for b in bad), bad
    assert any("motion/loads.py:1: pkg.solver.closure._hidden" in b for b in bad), bad


# -- the floors: subpackages and top-level modules ---------------------------------------

def _unit(name: str) -> str:
    """The floor a module belongs to: its package's subpackage or top-level module
    (``kinetostatics.solver.pipeline`` -> ``kinetostatics.solver``; ``balance.__main__``;
    the package roots ``kinetostatics`` and ``balance`` are floors of their own)."""
    return ".".join(name.split(".")[:2])


def _unit_graph(modules: dict[str, Path]) -> tuple[dict[str, set[str]], dict]:
    """Floor -> the floors its modules import at run time (at module level or inside
    functions, every package ``__init__`` on the way counted), and one example import
    per edge."""
    graph: dict[str, set[str]] = {}
    example: dict[tuple[str, str], str] = {}
    for name, path in modules.items():
        u = _unit(name)
        graph.setdefault(u, set())
        for m in _imports(name, path, modules):
            v = _unit(m)
            if v != u:
                graph[u].add(v)
                example.setdefault((u, v), f"{name} imports {m}")
    return graph, example


def _reach(graph: dict[str, set[str]], start: str) -> set[str]:
    seen: set[str] = set()
    todo = [start]
    while todo:
        for w in graph.get(todo.pop(), ()):
            if w not in seen:
                seen.add(w)
                todo.append(w)
    return seen


def test_no_two_floors_import_each_other() -> None:
    """Among the subpackages and top-level modules of both packages (kinetostatics.model,
    .solver, .results, .teaching, ...; balance.field, balance.__main__, ...) no import
    points back up: no two import each other, directly or through others, lazily or
    not."""
    graph, example = _unit_graph(_modules())
    cycles = _cycles(graph)
    assert cycles == [], [(c, [example[a, b] for a in c for b in c if (a, b) in example])
                          for c in cycles]


def test_the_solver_stands_below_the_results() -> None:
    """The solver gives arrays; the results (Solution, tables, writers) wrap them."""
    graph, example = _unit_graph(_modules())
    assert "kinetostatics.results" not in _reach(graph, "kinetostatics.solver"), \
        [e for (a, b), e in example.items() if a == "kinetostatics.solver"]
    assert "kinetostatics.solver" in graph["kinetostatics.results"]


def test_balance_never_reaches_teaching() -> None:
    """kinetostatics.teaching is the top floor: it may use balance; nothing in balance
    reaches it, even lazily (the balancing command line included)."""
    graph, _ = _unit_graph(_modules())
    for u in graph:
        if u.split(".")[0] == "balance":
            assert "kinetostatics.teaching" not in _reach(graph, u), u


def test_a_floor_cycle_through_a_lazy_import_is_found(tmp_path: Path) -> None:
    """The checker itself: a lazy import inside a function counts."""
    modules = _plant(tmp_path, {
        "pkg/cli.py": "def main():\n    from .teaching import grade\n",
        "pkg/teaching/__init__.py": "from .grading import grade\n",
        "pkg/teaching/grading.py": "from ..cli import main\ndef grade(): pass\n",
    })
    graph, _ = _unit_graph(modules)
    assert _cycles(graph) == [["pkg.cli", "pkg.teaching"]]


# The floors from the lowest up: a floor imports only floors below it (lazily or not). A
# new subpackage or top-level module takes its place here.
FLOORS = (
    "kinetostatics.model", "kinetostatics.common", "kinetostatics", "kinetostatics.solver",
    "kinetostatics.results", "kinetostatics.transmission", "kinetostatics.motion",
    "kinetostatics.cams", "kinetostatics.plot", "kinetostatics.notebook",
    "kinetostatics.concentration", "kinetostatics.design", "kinetostatics.simulation",
    "kinetostatics.bench",
    "balance.errors", "balance.common", "balance.uncertainty", "balance.rotor", "balance.model",
    "balance.resonance", "balance.field", "balance.machine", "balance.mechanism",
    "balance.plot", "balance.api", "balance.report", "balance", "balance.__main__",
    "kinetostatics.teaching", "kinetostatics.cli", "kinetostatics.__main__",
)


def test_the_floors_stand_in_their_order() -> None:
    """Every floor has its place in FLOORS, and every import goes down it: the solver
    below the results, the results below the pictures, balance below the teaching and
    the balancing command line below kinetostatics' (it shares only kinetostatics.common)."""
    graph, example = _unit_graph(_modules())
    assert set(graph) <= set(FLOORS), sorted(set(graph) - set(FLOORS))
    place = {f: i for i, f in enumerate(FLOORS)}
    up = [example[u, v] for u in graph for v in graph[u] if place[v] > place[u]]
    assert up == []


MAX_TOP_MODULES = 8


def test_few_top_level_modules() -> None:
    """kinetostatics/ holds subpackages; at most eight modules of its own."""
    top = sorted(p.name for p in (ROOT / "kinetostatics").glob("*.py"))
    assert len(top) <= MAX_TOP_MODULES, top


# -- functions ------------------------------------------------------------------------

MAX_FUNCTION_LINES = 80          # lines of code: docstring, blank lines and comments aside
# functions still over it, with the reason (none: the last three, in plot/, were split)
LONG_FUNCTIONS: set[str] = set()


def _code_lines(source: str, node: ast.AST) -> int:
    """Lines of code of a function: lines holding a token other than a comment, its
    docstring left out (nested functions count as its own lines)."""
    doc = None
    body = node.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
            and isinstance(body[0].value.value, str):
        doc = (body[0].lineno, body[0].end_lineno)
    lines = _token_lines(source)

    def between(first: int, last: int) -> int:
        return bisect.bisect_right(lines, last) - bisect.bisect_left(lines, first)
    return between(node.lineno, node.end_lineno) - (between(*doc) if doc else 0)


@functools.lru_cache(maxsize=8)
def _token_lines(source: str) -> tuple[int, ...]:
    """The lines of ``source`` holding a token other than a comment, in order (tokenized
    once per file, not once per function: 12 s of CPU before; counted by bisection, not
    by a pass over the file's lines per function: 0.6 s of CPU before)."""
    import io
    import tokenize

    skip = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT,
            tokenize.DEDENT, tokenize.ENDMARKER}
    lines: set[int] = set()
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type not in skip:
            lines.update(range(tok.start[0], tok.end[0] + 1))
    return tuple(sorted(lines))


def _long_functions(root: Path = ROOT, packages: tuple[str, ...] = PACKAGES,
                    limit: int = MAX_FUNCTION_LINES) -> dict[str, int]:
    out = {}
    for path in _modules(root, packages).values():
        source = path.read_text()
        for node in _walk(source):
            # (a function of fewer lines than the limit, blank and comment lines counted,
            # has fewer lines of code: its file is not tokenized, 2.0 -> 0.3 s of CPU)
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef) and \
                    node.end_lineno - node.lineno + 1 >= limit:
                n = _code_lines(source, node)
                if n >= limit:
                    out[f"{path.relative_to(root).as_posix()}:{node.name}"] = n
    return out


def test_no_long_function() -> None:
    long = _long_functions()
    assert set(long) <= LONG_FUNCTIONS, {k: v for k, v in long.items()
                                         if k not in LONG_FUNCTIONS}


def test_the_function_counter_counts_code_only(tmp_path: Path) -> None:
    body = "\n".join(f"    x{i} = {i}  # a comment" for i in range(78))
    _plant(tmp_path, {"pkg/m.py": f'def f():\n    """Doc\n\n    more doc."""\n\n    # note\n'
                                  f"{body}\n\n\ndef g():\n{body}\n    return x0\n"})
    # f: its def and 78 lines (79: under the limit); g: 80
    assert _long_functions(tmp_path, ("pkg",)) == {"pkg/m.py:g": 80}


# -- private state ----------------------------------------------------------------------

# writes of another object's private attributes still there, with the owner
PRIVATE_WRITES: set[str] = set()


def _private_writes(root: Path = ROOT, packages: tuple[str, ...] = PACKAGES) -> list[str]:
    """Assignments to ``obj._name`` (or ``obj.__dict__["_name"]``, ``setattr(obj,
    "_name", ...)``) where obj is not ``self`` or ``cls``: private state written from
    outside its class."""
    bad = []
    for path in _modules(root, packages).values():
        rel = path.relative_to(root).as_posix()
        for node in _walk(path.read_text()):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                    and node.func.id == "setattr" and len(node.args) >= 2 \
                    and isinstance(node.args[1], ast.Constant):
                targets = [(node.args[0], str(node.args[1].value))]
            elif isinstance(node, ast.Assign | ast.AugAssign | ast.AnnAssign):
                targets = []
                for t in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                    for sub in ast.walk(t):
                        if isinstance(sub, ast.Attribute):
                            targets.append((sub.value, sub.attr))
                        elif isinstance(sub, ast.Subscript) and \
                                isinstance(sub.value, ast.Attribute) and \
                                sub.value.attr == "__dict__" and \
                                isinstance(sub.slice, ast.Constant):
                            targets.append((sub.value.value, str(sub.slice.value)))
            else:
                continue
            for owner, attr in targets:
                if attr.startswith("_") and not attr.startswith("__") and \
                        ast.unparse(owner) not in ("self", "cls"):
                    bad.append(f"{rel}:{node.lineno}: {ast.unparse(owner)}.{attr}")
    return bad


def test_no_private_state_written_from_outside() -> None:
    bad = [b for b in _private_writes() if b.split(":")[0] not in PRIVATE_WRITES]
    assert bad == []


def test_the_private_write_finder_finds_them(tmp_path: Path) -> None:
    _plant(tmp_path, {"pkg/m.py": "def f(model, ax):\n    model._loads = []\n"
                                  "    ax.__dict__['_cache'] = 1\n    setattr(ax, '_x', 2)\n"
                                  "    model.loads = []\n",
                      "pkg/c.py": "class C:\n    def f(self):\n        self._x = 1\n"})
    assert [b.split(": ")[1] for b in _private_writes(tmp_path, ("pkg",))] == \
        ["model._loads", "ax._cache", "ax._x"]


def _private_imports(modules: dict[str, Path]) -> list[str]:
    """Imports of a ``_private`` module or name from any other module."""
    bad = []
    for name, path in modules.items():
        for mod, taken, line in _import_statements(name, path, modules):
            if mod not in modules or mod == name:
                continue
            private_module = any(p.startswith("_") and not p.startswith("__")
                                 for p in mod.split("."))
            private_name = taken is not None and taken.startswith("_") \
                and not taken.startswith("__")
            if private_module or private_name:
                bad.append(f"{name}:{line}: {mod}.{taken or ''}")
    return bad


# private imports still there, each with the owner who makes the name public
PRIVATE_IMPORTS: set[str] = set()


def test_no_private_name_crosses_a_module() -> None:
    """Stricter than across packages: no module imports another module's private name
    (inside the solver too; a name two modules share is public)."""
    bad = [b for b in _private_imports(_modules()) if b.split(":")[0] not in PRIVATE_IMPORTS]
    assert bad == []


def test_the_private_import_finder_sees_siblings(tmp_path: Path) -> None:
    modules = _plant(tmp_path, {"pkg/a.py": "_x = 1\ny = 2\n",
                                "pkg/b.py": "from .a import _x, y\n"})
    assert _private_imports(modules) == ["pkg.b:1: pkg.a._x"]


# -- radians inside ----------------------------------------------------------------------

# Radians inside, degrees at the edge. The edge: the scene readers (model/ of both packages,
# and the cam and motion kinds' readers, cams/scene.py, cams/units.py (the cam's units
# stage, which judges typed numbers) and motion/scene.py, until they move into model/),
# the writers (results/, balance/report/) and the one home of angles for people,
# kinetostatics/common/angles.py (messages, picture labels, table columns, a person's
# degree arguments). Elsewhere at most ten conversions remain (counted in code, strings
# and comments aside: degrees/radians/deg2rad/rad2deg calls and 180/pi products), each
# with a comment "degrees kept (k/10)" saying why. 127 in 46 files on 3ad9062; 10 on
# a695774, 6 once the continuity worked in radians (its turns along the driver's radians,
# its angles radians; the tables' degrees written in results/sweepangles.py).
DEGREE_EDGE = ("kinetostatics/model/", "balance/model/", "kinetostatics/cams/scene.py",
               "kinetostatics/cams/units.py", "kinetostatics/motion/scene.py",
               "kinetostatics/results/", "balance/report/", "kinetostatics/common/angles.py")
MAX_DEGREE_CONVERSIONS = 6


def _degree_conversions(root: Path = ROOT, floors: tuple[str, ...] = PACKAGES
                        ) -> list[str]:
    names = {"degrees", "radians", "deg2rad", "rad2deg"}
    out = []
    for floor in floors:
        for path in sorted((root / floor).rglob("*.py")):
            for node in _walk(path.read_text()):
                if isinstance(node, ast.Call):
                    f = node.func
                    called = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", None)
                    if called in names:
                        out.append(f"{path.relative_to(root).as_posix()}:{node.lineno}")
                elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult | ast.Div):
                    text = ast.unparse(node)
                    inner = [ast.unparse(x) for x in (node.left, node.right)
                             if isinstance(x, ast.BinOp)]
                    if "180" in text and "pi" in text and \
                            not any("180" in s and "pi" in s for s in inner):
                        out.append(f"{path.relative_to(root).as_posix()}:{node.lineno}")
    return out


def test_few_degree_conversions_inside() -> None:
    found = [f for f in _degree_conversions() if not f.startswith(DEGREE_EDGE)]
    assert len(found) <= MAX_DEGREE_CONVERSIONS, found
    lines = {f: (ROOT / f.split(":")[0]).read_text().splitlines() for f in found}
    for f in found:         # each one says why (on its line or in the comment above it)
        path, line = f.split(":")
        around = lines[f][max(0, int(line) - 4):int(line)]
        assert any("degrees kept" in x for x in around), f


def test_the_degree_counter_counts(tmp_path: Path) -> None:
    _plant(tmp_path, {"pkg/m.py": "import math\nimport numpy as np\nx = math.degrees(1.0)\n"
                                  "y = np.deg2rad(2.0) * 3\nz = 2.0 * 180.0 / math.pi\n"
                                  "w = 'math.radians(1)'  # math.radians(2)\n"})
    assert len(_degree_conversions(tmp_path, ("pkg",))) == 3
