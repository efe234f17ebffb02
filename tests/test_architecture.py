"""The package's layers: no import cycles between modules, and each layer imports only the layers
below it (DESIGN.md section 2: specs -> model -> engines -> runner -> results -> reports).

Imports are read from the source: every ``import`` statement, also those inside functions (which
still make one module depend on another) and those under ``if TYPE_CHECKING:`` (a type names a
dependency too); no layer has an exemption.
"""

from __future__ import annotations

import ast
from importlib import resources
from pathlib import Path

import batcert

PACKAGE = Path(str(resources.files(batcert)))

# layer -> layers (package folders or top-level modules) it may import, besides itself
ALLOWED = {
    "units": set(), "errors": set(),
    # the commands' arguments, read and checked once for the command line and the library
    "arguments": {"units", "errors"}, "conventions": set(), "version": set(), "cache": set(),
    # a root finder and a quantile without scipy's large imports (imports nothing)
    "numerics": set(),
    # the one owner of kept results (speed machinery beneath the physics, imports nothing)
    "workspace": set(),
    # the package's top: its version, and the library's functions (imported on first use)
    "__init__": {"version", "api", "errors", "specs"},
    "physics": {"workspace"},
    "methods": {"physics"},
    # (and the error family: an engine that does not exist is a usage problem)
    "engines": {"physics", "workspace", "errors"},
    "results": set(),
    # the spec schemas take their names from the registries of methods/ (metrics, aggregates,
    # impact rules) and from specs/kinds.py (claim checks, league rule kinds)
    "specs": {"units", "errors", "conventions", "physics", "methods"},
    "model": {"units", "errors", "conventions", "physics", "specs", "results"},
    # (and the workspace and a root finder: a ball lot's calibration on its reference bat,
    # runner/lot.py, is kept, and its fallback search is Brent's, as the lab's barrel's is)
    "runner": {"numerics", "units", "errors", "conventions", "physics", "methods", "engines",
               "specs", "model", "results", "version", "workspace"},
    "reports": {"units", "errors", "results", "methods", "cache"},
    "analysis": {"units", "specs", "model", "results", "reports", "version"},
    # (and the workspace and cache: a worker process keeps its results where its parent does)
    "sweeps": {"numerics", "units", "errors", "conventions", "physics", "methods", "engines",
               "specs", "model", "results", "runner", "version", "workspace", "cache"},
    "lab": {"numerics", "units", "errors", "conventions", "physics", "methods", "engines",
            "specs", "model", "runner", "results", "version"},
    "uncertainty": {"units", "errors", "conventions", "physics", "methods", "engines",
                    "specs", "model", "results", "runner", "version"},
    # in play: a batter's swing of a free bat along the barrel, and the batted ball's flight
    "inplay": {"units", "errors", "conventions", "physics", "methods", "engines", "specs", "model",
              "results", "runner", "version"},
    "commands": {"units", "errors", "conventions", "physics", "engines", "specs", "model",
                 "results", "runner", "analysis", "sweeps", "lab", "uncertainty", "inplay",
                 "version"},
    "console": {"units", "reports", "results", "version"},
    # the library: the commands' functions and the cache it keeps, typed results
    "api": {"commands", "physics", "cache", "results", "workspace", "arguments", "errors",
            "specs", "engines"},
    "cli": {"arguments", "api", "version", "__init__", "console", "errors", "commands", "engines",
            "specs", "units", "reports", "runner", "cache", "physics"},
    # the installed command's first lines: Ctrl-C handled before the command line loads
    "launch": {"cli"},
    "__main__": {"cli", "launch"},
}


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def import_graph() -> dict[str, set[str]]:
    """Module -> batcert modules it imports (at any depth in its code)."""
    modules = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        deps: set[str] = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module:
                # "from batcert import workspace" imports the module workspace; "from
                # batcert.x import name" imports batcert.x
                targets = [f"{node.module}.{a.name}" if f"{node.module}.{a.name}" in modules
                           else node.module for a in node.names]
            else:
                continue
            deps |= {t for t in targets if t in modules and t != name}
        graph[name] = deps
    return graph


def _layer(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
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

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_no_import_cycles():
    assert _cycles(import_graph()) == []


def test_each_layer_imports_only_the_layers_below():
    wrong = []
    for module, deps in import_graph().items():
        layer = _layer(module)
        for dep in deps:
            target = _layer(dep)
            if target == layer or target in ALLOWED[layer]:
                continue
            wrong.append(f"{module} -> {dep}")
    assert wrong == []


def test_no_cycles_between_layers():
    """Also no cycle between the packages (layers) as wholes."""
    layers: dict[str, set[str]] = {}
    for module, deps in import_graph().items():
        layers.setdefault(_layer(module), set()).update(
            _layer(d) for d in deps if _layer(d) != _layer(module))
    for layer in list(layers.values()):
        for dep in layer:
            layers.setdefault(dep, set())
    assert _cycles(layers) == []


# "No module over about 400 lines, no function over about 60 without a reason written beside
# it" (issue 25): a function may run longer when a comment beginning "# long" between its
# signature and its body says why
MODULE_LINES = 400
FUNCTION_LINES = 62


def test_modules_and_functions_stay_short():
    too_long = []
    for path in sorted(PACKAGE.rglob("*.py")):
        source = path.read_text(encoding="utf-8")
        lines = source.splitlines()
        name = path.relative_to(PACKAGE.parent)
        if len(lines) > MODULE_LINES:
            too_long.append(f"{name}: {len(lines)} lines")
        for node in ast.walk(ast.parse(source)):
            if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                continue
            length = node.end_lineno - node.lineno + 1
            head = lines[node.lineno - 1:node.body[0].lineno]
            if length > FUNCTION_LINES and not any(s.strip().startswith("# long") for s in head):
                too_long.append(f"{name}:{node.lineno} {node.name}: {length} lines")
    assert too_long == []
