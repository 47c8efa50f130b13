"""The library's imports form no circle: every module's imports (module-level and inside functions, relative ones
resolved) read with ast, and the graph's strongly connected components must be single modules."""

from __future__ import annotations

import ast
from pathlib import Path

LIB = Path(__file__).resolve().parents[1] / "lib"


def _modules() -> dict[str, Path]:
    out = {}
    for path in LIB.rglob("*.py"):
        parts = path.relative_to(LIB).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


def _targets(name: str, path: Path, node: ast.AST, modules: dict[str, Path]) -> list[str]:
    """The library modules one import statement of module ``name`` reaches (a name imported from a package counts as
    its submodule where there is one)."""
    if isinstance(node, ast.Import):
        wanted = [a.name for a in node.names]
    else:
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        base = package.split(".")[: len(package.split(".")) - node.level + 1] if node.level else []
        module = ".".join([*base, *([node.module] if node.module else [])])
        wanted = [f"{module}.{a.name}" if f"{module}.{a.name}" in modules else module for a in node.names]
    found = []
    for target in wanted:
        while target and target not in modules and "." in target:
            target = target.rpartition(".")[0]
        if (
            target in modules and target != name and not name.startswith(target + ".")
        ):  # a package's own __init__ is not a circle
            found.append(target)
    return found


def import_graph() -> dict[str, set[str]]:
    modules = _modules()
    graph = {}
    for name, path in modules.items():
        graph[name] = {t for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
                       if isinstance(node, (ast.Import, ast.ImportFrom)) for t in _targets(name, path, node, modules)}
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm, iterative)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        out.append(sorted(component))
            elif child not in index:
                index[child] = low[child] = counter[0]
                counter[0] += 1
                stack.append(child)
                on.add(child)
                work.append((child, iter(sorted(graph[child]))))
            elif child in on:
                low[node] = min(low[node], index[child])
    return out


def test_the_circle_finder_finds_a_circle():
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert circles({"a": {"b"}, "b": set()}) == []


def test_the_graph_sees_imports_inside_functions():
    graph = import_graph()
    assert "linkwork.project.published" in graph["linkwork.project.validate"]  # imported inside validate_once


def test_no_import_circle_in_the_library():
    assert circles(import_graph()) == []


#: The library's layers, lowest first: a module imports only from its own layer or the ones below it.
LAYERS = (
    ("linkwork", "linkwork.units", "linkwork.configformat", "linkwork.compilecache"), ("linkwork.engines",),
    ("linkwork.pipeline",), ("linkwork.papers",), ("linkwork.project",),
)


def _layer(module: str) -> int:
    """The index of the deepest layer prefix that names ``module``."""
    best = -1
    for i, prefixes in enumerate(LAYERS):
        if (
            any(module == p or module.startswith(p + ".") for p in prefixes if p != "linkwork")
            or module == "linkwork"
            and i == 0
        ):
            best = i
    return best


def test_every_import_points_downward():
    """Engines know no pipeline, the toolkit (pipeline) knows no paper, papers know not the project layer that knows
    them all (validation, the README's findings); the package registry linkwork.papers is read from above only."""
    upward = [(m, t) for m, targets in import_graph().items() for t in targets
              if _layer(t) > _layer(m) and not (m.startswith("linkwork.papers.") and t == "linkwork.papers")]
    assert upward == []


def test_the_layer_check_sees_an_upward_import():
    assert (
        _layer("linkwork.pipeline.compare") == 2
        and _layer("linkwork.papers.heald.studies") == 3
        and _layer("linkwork.units") == 0
    )
    assert _layer("linkwork.project.validate") > _layer("linkwork.papers.heald")
