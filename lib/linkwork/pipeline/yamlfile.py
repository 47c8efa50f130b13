"""Reading YAML as the project does: a safe loader that refuses a key given twice, a key that is a list or a mapping,
a number YAML 1.1 reads unlike YAML 1.2 (0720 as octal, 5:00 in base 60), a file that is not UTF-8 and one that
expands through its aliases beyond a size bound; every refusal a one-line ConfigError with file and line.  Used for
the config, its schema and the published-numbers files (``validate``, ``published``).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import yaml

from .errors import ConfigError

_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class _UniqueKeyLoader(_Loader):  # type: ignore[misc, valid-type]
    """Safe YAML loader that refuses a key given twice in one mapping."""


def _construct_mapping(loader, node, deep=False):
    seen = {}
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=deep)
        mark = key_node.start_mark
        if not isinstance(key_node, yaml.ScalarNode):
            kind = "list" if isinstance(key_node, yaml.SequenceNode) else "mapping"
            raise ConfigError(
                f"{mark.name}, line {mark.line + 1}, column {mark.column + 1}: a config key is a {kind}, not a name"
            )
        if key in seen:
            raise ConfigError(
                f"{mark.name}, line {mark.line + 1}: config key {key!r} is given twice in the same section (first at"
                f" line {seen[key] + 1})"
            )
        seen[key] = key_node.start_mark.line
    return loader.construct_mapping(node, deep=deep)


_UniqueKeyLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


#: A YAML file expands to at most this many entries (mappings, lists and scalars, aliases expanded): a bound on the
#: time and memory a file of a few lines can ask for (an alias bomb); config/config.yaml holds a few thousand.
YAML_ENTRIES_LIMIT = 1_000_000
#: Scalars YAML 1.1 (PyYAML) reads as numbers that YAML 1.2 and a reader do not: a leading zero (octal, 0720 -> 464),
#: base 60 (5:00 -> 300) and binary (0b101 -> 5).
_YAML11_NUMBER = re.compile(r"^[-+]?(0[0-7_]+|0b[01_]+|[0-9][0-9_]*(:[0-5]?[0-9])+(\.[0-9_]*)?)$")
_NUMBER_TAGS = ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float")


def _expanded_size(node, memo: dict) -> int:
    """Entries of a YAML node with every alias expanded, counted without expanding (shared nodes memoised)."""
    key = id(node)
    if key not in memo:
        memo[key] = 1  # a recursive alias counts once
        if isinstance(node, yaml.MappingNode):
            memo[key] = 1 + sum(_expanded_size(k, memo) + _expanded_size(v, memo) for k, v in node.value)
        elif isinstance(node, yaml.SequenceNode):
            memo[key] = 1 + sum(_expanded_size(v, memo) for v in node.value)
    return memo[key]


def _yaml11_surprise(node, path: tuple = (), seen: set | None = None) -> tuple[tuple, Any] | None:
    """The first scalar (its key path and node) that YAML 1.1 reads as a number where YAML 1.2 would not."""
    seen = set() if seen is None else seen
    if id(node) in seen:
        return None
    seen.add(id(node))
    if isinstance(node, yaml.ScalarNode):
        return (
            (path, node) if node.tag in _NUMBER_TAGS and not node.style and _YAML11_NUMBER.match(node.value) else None
        )
    children = (
        [(k.value if isinstance(k, yaml.ScalarNode) else "?", v) for k, v in node.value]
        if isinstance(node, yaml.MappingNode)
        else list(enumerate(node.value)) if isinstance(node, yaml.SequenceNode) else []
    )
    for name, child in children:
        found = _yaml11_surprise(child, (*path, name), seen)
        if found:
            return found
    return None


def load_yaml(path: str | Path) -> Any:
    """Parse a YAML file; syntax errors, duplicate keys, numbers YAML 1.1 reads unlike YAML 1.2 (0720 as octal, 5:00 in
    base 60) and a file expanding to more than ``YAML_ENTRIES_LIMIT`` entries become one-line ConfigErrors with file
    and line."""
    path = Path(path)
    try:
        with open(path, encoding="utf-8") as fh:
            loader = _UniqueKeyLoader(fh)
            try:
                node = loader.get_single_node()
                if node is None:
                    return None
                size = _expanded_size(node, {})
                if size > YAML_ENTRIES_LIMIT:
                    raise ConfigError(
                        f"{path}: expands to {size:.3g} entries (aliases expanded), more than the size guard"
                        f" {YAML_ENTRIES_LIMIT} (raise YAML_ENTRIES_LIMIT in lib/linkwork/pipeline/yamlfile.py for a"
                        " larger file)"
                    )
                surprise = _yaml11_surprise(node)
                if surprise:
                    where, scalar = surprise
                    read = loader.construct_object(scalar)
                    raise ConfigError(
                        f"{path}, line {scalar.start_mark.line + 1}: config key {key_path(where)}: value {scalar.value}"
                        f" would be read as {read!r} (YAML 1.1: a leading zero is octal, a colon base 60, 0b binary);"
                        " write the number plainly, or quote it for text"
                    )
                return loader.construct_document(node)
            finally:
                loader.dispose()
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f"{path}, line {mark.line + 1}, column {mark.column + 1}" if mark else str(path)
        raise ConfigError(f"{where}: not valid YAML ({exc.problem or exc.context})") from None
    except UnicodeDecodeError as exc:
        raise ConfigError(
            f"{path}: not UTF-8 text (byte {exc.object[exc.start]:#04x} at offset {exc.start}); save the file as UTF-8"
        ) from None
    except OSError as exc:
        raise ConfigError(f"{path}: cannot be read ({exc.strerror})") from None


def key_path(path) -> str:
    """A config key path as text (``clearance.scenes.dry_1``; ``<root>`` for none)."""
    return ".".join(str(p) for p in path) or "<root>"


def short(value: Any, limit: int = 80) -> str:
    """A value's repr, cut to ``limit`` characters."""
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 5] + " ...}"
