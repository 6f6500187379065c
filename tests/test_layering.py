"""Imports point down: the package's import graph has no cycle, and follows the model's data flow.

The graph is read from the source (the AST of every module of fastrest/), not from a running
interpreter, so it holds every import: at the top of a module and inside functions, relative and
absolute, and ``importlib.import_module("...")`` with a literal name. An edge goes to the module
named (``from .tables import error`` -> ``fastrest.tables.error``; ``from .tables import Table`` ->
``fastrest.tables``); the parent packages that Python imports along the way are not edges (every
module would otherwise import its own package).
"""
import ast
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1] / "fastrest"

# The data flow (docs/architecture.md): material -> critical values -> loading law -> energy ->
# unloading -> limits -> solver -> curves, tables, SI impact, forward map, force law -> the APIs on
# top. A module may import its own layer or lower ones, never a higher one. Modules not listed
# are top-level APIs (jit, models, rough, export, figures, cli, the package itself).
LAYERS = [
    ("plumbing", ["fastrest._version", "fastrest._deprecation", "fastrest._doc", "fastrest._jit",
                  "fastrest._validation", "fastrest._threads", "fastrest._provenance", "fastrest.fastpath", "fastrest.interpolation"]),
    ("material and critical values", ["fastrest.critical", "fastrest.materials"]),
    ("loading laws", ["fastrest.loading", "fastrest.loading.*"]),
    ("loading law, validated", ["fastrest.contact"]),
    ("energy", ["fastrest.energy"]),
    ("unloading", ["fastrest.unloading", "fastrest.unloading.*"]),
    ("limits", ["fastrest.limits"]),
    ("solver", ["fastrest.direct"]),
    ("curves, tables, impact, force", ["fastrest.cells", "fastrest._placement", "fastrest.curve_data",
                                       "fastrest.curve", "fastrest.scene", "fastrest.tables", "fastrest.tables.*",
                                       "fastrest.repeated", "fastrest.impact", "fastrest.forward", "fastrest.law_cells",
                                       "fastrest.force_law"]),
]
TOP = len(LAYERS)


def _module_name(path):
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _resolve(base, level, package):
    """The absolute module of a relative import ``level`` dots up from ``package``."""
    if not level:
        return base
    up = package.split(".")[:len(package.split(".")) - level + 1]
    return ".".join(up + ([base] if base else []))


def import_graph():
    """{module: {imported fastrest module: first line}} over every module of the package."""
    files = {_module_name(p): p for p in sorted(ROOT.rglob("*.py"))}
    graph = {}
    for mod, path in files.items():
        package = mod if path.name == "__init__.py" else mod.rpartition(".")[0]
        edges = {}

        def add(target, line):
            if target == "fastrest" or target.startswith("fastrest."):
                # the longest prefix that is a module: fastrest.tables.Table -> fastrest.tables
                while target not in files and "." in target:
                    target = target.rpartition(".")[0]
                if target != mod:
                    edges.setdefault(target, line)

        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                for a in node.names:
                    add(a.name, node.lineno)
            elif isinstance(node, ast.ImportFrom):
                base = _resolve(node.module or "", node.level, package)
                for a in node.names:
                    add(f"{base}.{a.name}" if f"{base}.{a.name}" in files else base, node.lineno)
            elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                  and node.func.attr == "import_module" and node.args
                  and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
                name = node.args[0].value
                anchor = node.args[1] if len(node.args) > 1 else None
                if name.startswith(".") and anchor is not None:
                    level = len(name) - len(name.lstrip("."))
                    add(_resolve(name.lstrip("."), level, package), node.lineno)
                else:
                    add(name, node.lineno)
        graph[mod] = edges
    return graph


def find_cycle(graph):
    """One import cycle as a list of modules (first == last), or None."""
    colour, stack = {}, []

    def visit(m):
        colour[m] = 1
        stack.append(m)
        for t in sorted(graph.get(m, ())):
            if colour.get(t) == 1:
                return stack[stack.index(t):] + [t]
            if t not in colour:
                found = visit(t)
                if found:
                    return found
        stack.pop()
        colour[m] = 2
        return None

    for m in sorted(graph):
        if m not in colour:
            found = visit(m)
            if found:
                return found
    return None


def layer(mod):
    for rank, (_, members) in enumerate(LAYERS):
        for pattern in members:
            if mod == pattern or (pattern.endswith(".*") and mod.startswith(pattern[:-1])):
                return rank
    return TOP


@pytest.fixture(scope="module")
def graph():
    return import_graph()


def test_the_graph_sees_every_kind_of_import(graph):
    """Sanity of the reader: function-local, relative, absolute and importlib imports are edges."""
    assert "fastrest.tables.error" in graph["fastrest.tables.store"]        # from . import error
    assert "fastrest.unloading" in graph["fastrest.limits"]                  # from . import unloading as _u
    assert "fastrest.contact" in graph["fastrest.energy"]                   # from .contact import ...
    assert "fastrest.force_law" in graph["fastrest.impact"]                 # inside a method
    assert "fastrest.tables._rectilinear" in graph["fastrest.tables.table"]
    g = {"a": {"b": 1}, "b": {"c": 1}, "c": {"a": 1}}
    assert find_cycle(g) == ["a", "b", "c", "a"]


def test_no_import_cycle(graph):
    cycle = find_cycle(graph)
    if cycle:
        where = [f"{a} imports {b} (line {graph[a][b]})" for a, b in zip(cycle, cycle[1:])]
        pytest.fail("import cycle: " + " -> ".join(cycle) + "\n  " + "\n  ".join(where))


def test_imports_follow_the_data_flow(graph):
    """No module imports one of a higher layer, even inside a function."""
    up = [f"{a} ({LAYERS[layer(a)][0]}) imports {b} ({LAYERS[layer(b)][0] if layer(b) < TOP else 'top-level API'}), "
          f"line {line}"
          for a, edges in sorted(graph.items()) for b, line in sorted(edges.items()) if layer(b) > layer(a)]
    assert not up, "imports pointing up:\n  " + "\n  ".join(up)


def test_every_layered_module_exists(graph):
    for _, members in LAYERS:
        for pattern in members:
            name = pattern[:-2] if pattern.endswith(".*") else pattern
            assert name in graph, f"{name} is listed in LAYERS but is not a module of fastrest"
