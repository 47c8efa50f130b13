"""Which lib modules a script or report really depends on: the closure of its imports.

Snakemake does not see what a script imports, so each rule declares the lib files in the import
closure of its script (and of the study module it runs) as inputs; editing a module then reruns
exactly the rules that can execute it.  Imports are read statically with ``ast`` (nothing is
imported): absolute ``linkwork...`` imports, relative imports inside the package, imports inside
functions (lazy imports count), and sibling modules of the entry file (a report's ``_common``).
A module's parent packages count too (their ``__init__`` runs on import).  Standard library only.
"""

from __future__ import annotations

import ast
from functools import lru_cache
from pathlib import Path

PACKAGE = "linkwork"


def module_file(name: str, lib: Path) -> Path | None:
    """The file of module ``name`` under ``lib`` (a package's __init__.py), or None if not ours."""
    parts = name.split(".")
    if parts[0] != PACKAGE:
        return None
    base = lib.joinpath(*parts)
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    return None


def _package_of(name: str, file: Path) -> str:
    return name if file.name == "__init__.py" else name.rpartition(".")[0]


@lru_cache(maxsize=None)
def _imported_names(file: Path, name: str | None) -> tuple[str, ...]:
    """Module names a file imports (absolute, and relative ones resolved when ``name`` is known)."""
    tree = ast.parse(file.read_text(encoding="utf-8"), filename=str(file))
    found: list[str] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                if name is None:
                    continue
                package = _package_of(name, file).split(".")
                base = ".".join(package[: len(package) - (node.level - 1)])
                base = f"{base}.{node.module}" if node.module else base
            else:
                base = node.module or ""
            found.append(base)
            found += [f"{base}.{alias.name}" for alias in node.names]  # from package import submodule
    return tuple(found)


def closure(entry: str | Path, lib: str | Path, extra: tuple[str | Path, ...] = ()) -> list[Path]:
    """Every file in the import closure of ``entry``: lib modules, sibling helpers and the entry itself.

    ``entry`` is a file path (a script or report) or a module name (``linkwork.papers.x.studies``);
    ``extra`` are more entries whose closures are joined in.
    """
    lib = Path(lib)
    seen: dict[Path, None] = {}
    todo: list[tuple[Path, str | None, Path | None]] = []
    for item in (entry, *extra):
        item_str = str(item)
        if item_str.startswith(PACKAGE + ".") or item_str == PACKAGE:
            file = module_file(item_str, lib)
            if file is None:
                raise ValueError(f"module {item_str} not found under {lib}")
            todo.append((file, item_str, None))
        else:
            todo.append((Path(item), None, Path(item).parent))
    done: set[Path] = set()
    while todo:
        file, name, sibling_dir = todo.pop()
        if file in done:
            continue
        done.add(file)
        seen[file] = None
        for imported in _imported_names(file, name):
            parts = imported.split(".")
            for k in range(1, len(parts) + 1):  # the module and its parent packages
                target = module_file(".".join(parts[:k]), lib)
                if target is not None and target not in done:
                    todo.append((target, ".".join(parts[:k]), None))
            if sibling_dir is not None and parts[0] != PACKAGE and (sibling_dir / f"{parts[0]}.py").is_file():
                todo.append((sibling_dir / f"{parts[0]}.py", None, sibling_dir))
    return sorted(seen)


def relative(files: list[Path], root: str | Path) -> list[str]:
    """Paths relative to the project root, as Snakemake inputs."""
    root = Path(root).resolve()
    return [str(f.resolve().relative_to(root)) for f in files]
