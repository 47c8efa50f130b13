"""Which lib modules a script or report really depends on: the closure of its imports.

Snakemake does not see what a script imports, so each rule declares the lib files in the import
closure of its script (and of the study module it runs) as inputs; editing a module then reruns
exactly the rules that can execute it.  Imports are read statically, nothing is imported: every
``import`` / ``from ... import`` statement at the start of a line, at any indentation (lazy imports inside functions
count), absolute ``linkwork...`` ones, relative ones inside the package, and sibling modules of the entry file (a
report's ``_common``).  A module's parent packages count too (their ``__init__`` runs on import); a package whose names
import every subpackage it finds says so (``_DISCOVERS``).  The scan is a line match, not a parse, because it runs on
every Snakemake invocation: a docstring line that reads like an import statement can only add a dependency, never hide
one.  Standard library only.
"""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

_IMPORT = re.compile(
    r"^[ \t]*(?:from[ \t]+(\.*[\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n#]+)|import[ \t]+([^\n#]+))", re.M
)

PACKAGE = "linkwork"
#: A package's __init__ that holds ``linkwork-deps: NAME ... import every subpackage`` imports every subpackage it finds
#: when one of those names is read (``linkwork.papers``: PAPERS, CITATIONS): a module importing such a name has every
#: subpackage's __init__ in its closure.
_DISCOVERS = re.compile(r"linkwork-deps:((?:\s+[A-Za-z_]\w*)+)\s+import every subpackage")


@lru_cache(maxsize=None)
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
def _statements(file: Path) -> tuple[tuple[int, str, tuple[str, ...]], ...]:
    """(relative level, module, imported names) of every import statement in a file (read once)."""
    found = []
    for src, names, plain in _IMPORT.findall(file.read_text(encoding="utf-8")):
        if plain:
            found += [(0, part.split(" as ")[0].strip(), ()) for part in plain.split(",") if part.strip()]
            continue
        level = len(src) - len(src.lstrip("."))
        items = tuple(n.split(" as ")[0].strip() for n in names.strip("()").replace("\\", " ").split(",") if n.strip())
        found.append((level, src[level:], items))
    return tuple(found)


def _imported_names(file: Path, name: str | None) -> list[str]:
    """Module names a file imports (absolute, and relative ones resolved when ``name`` is known)."""
    found: list[str] = []
    for level, module, items in _statements(file):
        if level:
            if name is None:
                continue
            package = _package_of(name, file).split(".")
            base = ".".join(package[: len(package) - (level - 1)])
            base = f"{base}.{module}" if module else base
        else:
            base = module
        if base:
            found.append(base)
        found += [f"{base}.{item}" for item in items if item != "*"]  # from package import submodule
    return found


@lru_cache(maxsize=None)
def _discovering(package: str, lib: Path) -> frozenset[str]:
    """The names of ``package`` whose reading imports every subpackage (its __init__'s ``linkwork-deps`` line)."""
    file = module_file(package, lib) if package else None
    if file is None or file.name != "__init__.py":
        return frozenset()
    found = _DISCOVERS.search(file.read_text(encoding="utf-8"))
    return frozenset(found.group(1).split()) if found else frozenset()


@lru_cache(maxsize=None)
def closure(entry: str | Path, lib: str | Path, extra: tuple[str | Path, ...] = ()) -> list[Path]:
    """Every file in the import closure of ``entry``: lib modules, sibling helpers and the entry itself.

    ``entry`` is a file path (a script or report) or a module name (``linkwork.papers.x.studies``);
    ``extra`` are more entries whose closures are joined in.
    """
    lib = Path(lib)
    seen: dict[Path, None] = {}  # insertion-ordered set
    todo: list[tuple[Path, str | None, Path | None]] = []
    for item in (entry, *extra):
        item_str = str(item)
        if item_str.startswith(PACKAGE + ".") or item_str == PACKAGE:
            if module_file(item_str, lib) is None:
                raise ValueError(f"module {item_str} not found under {lib}")
            parts = item_str.split(".")
            for k in range(1, len(parts) + 1):  # importing a module runs its parent packages first
                todo.append((module_file(".".join(parts[:k]), lib), ".".join(parts[:k]), None))
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
            package, _, attribute = imported.rpartition(".")
            if attribute in _discovering(package, lib):  # a name whose reading imports every subpackage
                for sub in sorted(module_file(package, lib).parent.glob("*/__init__.py")):
                    todo.append((sub, f"{package}.{sub.parent.name}", None))
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
