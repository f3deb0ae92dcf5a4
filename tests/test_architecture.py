"""The package's layers: no import cycles, and no module imports a layer above its own.

Parsed with ``ast``, so imports inside functions count (only ``if TYPE_CHECKING:`` blocks are
left out: they never run). The layer order is the one of ``docs/architecture.md``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "cosserat"

# lowest first; a module may import from its own layer and the layers before it
LAYERS = [
    [
        "cosserat.errors",
        "cosserat.config",
        "cosserat._version",
        "cosserat._jit_cache",
        "cosserat._atomic",
        "cosserat._text",
        "cosserat._moved",
        "cosserat._stencil",
    ],
    ["cosserat.viz"],
    ["cosserat.model"],
    ["cosserat.numerics"],
    ["cosserat.results"],
    ["cosserat.routes"],
    ["cosserat.analysis"],
    ["cosserat.studies", "cosserat.calibration", "cosserat.dem"],
    ["cosserat.paper"],
    ["cosserat.cli"],
    ["cosserat", "cosserat.__main__", "cosserat.cell"],
]


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def imports_of(path: Path, modules: set[str]) -> set[str]:
    """Package modules imported by ``path`` anywhere (module level or in a function)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    tree = ast.parse(path.read_text())
    skip: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and _is_type_checking(node):
            skip.update(id(n) for child in node.body for n in ast.walk(child))
    found: set[str] = set()
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        targets: list[str] = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            # ``from pkg import submodule`` depends on the submodule, not on pkg's contents
            targets = [
                f"{mod}.{a.name}" if f"{mod}.{a.name}" in modules else mod for a in node.names
            ]
        for t in targets:
            # the longest package module that the target names
            while t and t not in modules:
                t = t.rpartition(".")[0]
            if t and t != name:
                found.add(t)
    return found


def graph() -> dict[str, set[str]]:
    files = {module_name(p): p for p in PACKAGE.rglob("*.py")}
    modules = set(files)
    return {name: imports_of(path, modules) for name, path in files.items()}


def layer_of(module: str) -> int:
    best, index = "", -1
    for i, prefixes in enumerate(LAYERS):
        for prefix in prefixes:
            hit = module == prefix or module.startswith(prefix + ".")
            if hit and len(prefix) > len(best):
                best, index = prefix, i
    return index


def cycles(g: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in g[v]:
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

    for v in sorted(g):
        if v not in index:
            visit(v)
    return out


def test_the_graph_is_read():
    g = graph()
    assert "cosserat.routes.numerical" in g
    assert "cosserat.numerics.cosserat" in g["cosserat.routes.numerical"]
    assert "cosserat.config" in g["cosserat.routes.numerical"]


def test_no_import_cycles():
    assert cycles(graph()) == []


def test_every_module_has_a_layer():
    assert [m for m in graph() if layer_of(m) < 0] == []


def test_no_module_imports_a_layer_above_its_own():
    g = graph()
    upward = sorted(
        f"{m} (layer {layer_of(m)}) imports {t} (layer {layer_of(t)})"
        for m, targets in g.items()
        for t in targets
        if layer_of(t) > layer_of(m)
    )
    assert upward == []


def test_the_cycle_finder_finds_cycles():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


@pytest.mark.parametrize("module", ["cosserat.viz.plotting"])
def test_viz_is_a_leaf(module):
    """The drawing primitives import nothing of the package at run time."""
    assert graph()[module] == set()
