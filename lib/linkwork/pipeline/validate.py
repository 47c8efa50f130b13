"""Read and validate the whole config before any job runs.

Three layers: reading the YAML (syntax errors with file and line, duplicate keys refused), the JSON
schema (types, ranges, no unknown keys) and each paper's physical checks (``linkwork.papers.<paper>.checks``:
a linkage must assemble at every crank angle it is asked for, ...).  Every error names the config key
and the offending value.
"""

from __future__ import annotations

import importlib
import os
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml

from ..papers import PAPERS
from .errors import ConfigError

_NUMBERLIKE = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")
_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class _UniqueKeyLoader(_Loader):  # type: ignore[misc, valid-type]
    """Safe YAML loader that refuses a key given twice in one mapping."""


def _construct_mapping(loader, node, deep=False):
    seen = {}
    for key_node, _ in node.value:
        key = loader.construct_object(key_node, deep=deep)
        if key in seen:
            mark = key_node.start_mark
            raise ConfigError(f"{mark.name}, line {mark.line + 1}: config key {key!r} is given twice in the same section (first at line {seen[key] + 1})")
        seen[key] = key_node.start_mark.line
    return loader.construct_mapping(node, deep=deep)


_UniqueKeyLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


def load_yaml(path: str | Path) -> Any:
    """Parse a YAML file; syntax errors and duplicate keys become one-line ConfigErrors with file and line."""
    path = Path(path)
    try:
        with open(path, encoding="utf-8") as fh:
            return yaml.load(fh, Loader=_UniqueKeyLoader)  # noqa: S506 (a safe loader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f"{path}, line {mark.line + 1}, column {mark.column + 1}" if mark else str(path)
        raise ConfigError(f"{where}: not valid YAML ({exc.problem or exc.context})") from None
    except OSError as exc:
        raise ConfigError(f"{path}: cannot be read ({exc.strerror})") from None


def _key(path) -> str:
    return ".".join(str(p) for p in path) or "<root>"


def _short(value: Any, limit: int = 80) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 5] + " ...}"


def _schema_message(error) -> str:
    key = _key(error.absolute_path)
    value = error.instance
    if error.validator == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        extra = sorted(set(value) - set(allowed)) if isinstance(value, dict) else []
        names = ", ".join(f"{key}.{e}" if key != "<root>" else e for e in extra)
        return f"config key {names}: unknown key (allowed here: {', '.join(allowed)})"
    if error.validator == "required":
        missing = [r for r in error.validator_value if isinstance(value, dict) and r not in value]
        names = ", ".join(f"{key}.{m}" if key != "<root>" else m for m in missing)
        return f"config key {names}: missing (required in section {key})"
    if error.validator == "type" and isinstance(value, str) and _NUMBERLIKE.match(value):
        return f"config key {key}: value {value!r} was read as a string, not a number (YAML needs a dot and a signed exponent, e.g. 1.0e-6)"
    return f"config key {key}: value {_short(value)}: {error.message if len(error.message) < 200 else error.message[:200] + ' ...'}"


def validate_schema(config: Mapping[str, Any], schema: Mapping[str, Any]) -> None:
    """Check ``config`` against the JSON schema; raise ConfigError listing every problem."""
    import jsonschema

    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(config), key=lambda e: [str(p) for p in e.absolute_path])
    if errors:
        raise ConfigError("invalid config:\n  " + "\n  ".join(dict.fromkeys(_schema_message(e) for e in errors)))


def check_sweeps(section: Mapping[str, Any], config: Mapping[str, Any], key: str = "sweeps") -> None:
    """The swept clearance scene and variant exist."""
    spec = section["clearance"]
    if spec["scene"] not in config["clearance"]["scenes"]:
        raise ConfigError(f"config key {key}.clearance.scene: value {spec['scene']!r} is not a scene of clearance.scenes")
    if spec["variant"] not in config["clearance"]["variants"]:
        raise ConfigError(f"config key {key}.clearance.variant: value {spec['variant']!r} is not a variant of clearance.variants")


def validate_config(config: Mapping[str, Any], schema: Mapping[str, Any]) -> None:
    """Schema first, then the physical checks of every paper section present."""
    validate_schema(config, schema)
    for paper in PAPERS:
        if paper in config:
            importlib.import_module(f"linkwork.papers.{paper}.checks").check(config[paper], paper)
    if "sweeps" in config:
        check_sweeps(config["sweeps"], config)


def merge_overrides(config: dict[str, Any], base: Mapping[str, Any]) -> None:
    """Make ``config`` the file's values ``base`` with the values already in ``config`` (from --config or
    --configfile) laid over them, key by key (in place)."""

    def merged(low: Any, high: Any) -> Any:
        if isinstance(low, Mapping) and isinstance(high, Mapping):
            return {**low, **{k: merged(low.get(k), v) for k, v in high.items()}}
        return high

    overrides = dict(config)
    config.clear()
    config.update(merged(dict(base), overrides))


def validation_key(config: Mapping[str, Any], schema_path: Path, lib: Path) -> str:
    """sha256 of what a validation depends on: the config, the schema file and the validating code."""
    import hashlib
    import json

    from .deps import closure

    digest = hashlib.sha256(json.dumps(config, sort_keys=True, default=str).encode())
    digest.update(Path(schema_path).read_bytes())
    checks = tuple(f"linkwork.papers.{p}.checks" for p in PAPERS)
    for file in closure("linkwork.pipeline.validate", lib, extra=checks):
        digest.update(str(file).encode() + b"\0" + Path(file).read_bytes())
    return digest.hexdigest()


def validate_once(config: Mapping[str, Any], schema_path: Path, lib: Path, stamp: Path) -> None:
    """Validate unless this exact config, schema and validating code passed before (``stamp`` holds the key).

    A passed validation is remembered so that a no-op run stays fast; any change to the three runs it again.
    """
    key = validation_key(config, schema_path, lib)
    if stamp.is_file() and stamp.read_text(encoding="utf-8").strip() == key:
        return
    validate_config(config, load_yaml(schema_path))
    stamp.parent.mkdir(parents=True, exist_ok=True)
    tmp = stamp.with_name(f"{stamp.name}.{os.getpid()}.tmp")
    tmp.write_text(key + "\n", encoding="utf-8")
    os.replace(tmp, stamp)
