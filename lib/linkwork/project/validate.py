"""Read and validate the whole config before any job runs.

Three layers: reading the YAML (syntax errors with file and line, duplicate keys refused), the JSON
schema (types, ranges, no unknown keys) and each paper's physical checks (``linkwork.papers.<paper>.checks``:
a linkage must assemble at every crank angle it is asked for, ...).  Every error names the config key
and the offending value.
"""

from __future__ import annotations

import importlib
import math
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..papers import PAPERS
from ..pipeline.errors import ConfigError
from ..pipeline.yamlfile import key_path as _key
from ..pipeline.yamlfile import load_yaml
from ..pipeline.yamlfile import short as _short

_NUMBERLIKE = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")
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
        why = error.schema.get("x-why") if isinstance(error.schema, Mapping) else None
        return f"config key {names}: missing (required in section {key}{f': {why}' if why else ''})"
    if error.validator == "type" and isinstance(value, str) and _NUMBERLIKE.match(value):
        return (
            f"config key {key}: value {value!r} was read as a string, not a number (YAML needs a dot and a signed"
            " exponent, e.g. 1.0e-6)"
        )
    bound = _bound_message(error)
    if bound:
        return f"config key {key}: value {_short(value)} is {bound}"
    return (
        f"config key {key}: value {_short(value)}:"
        f" {error.message if len(error.message) < 200 else error.message[:200] + ' ...'}"
    )


#: Why a bound is set (a schema annotation) and where to move it: a size guard of this machine, or a documented range.
BOUND_KINDS = {
    "x-size-guard": "a size guard for this 2-core, 24 GiB machine: raise it in config/schema.yaml for a larger one",
    "x-range": "the documented range, set in config/schema.yaml: widen it there if your linkage needs it",
}


def _bound_message(error) -> str:
    """'above the largest allowed value X (why); where to move it' for a bound the schema annotates, else ''."""
    if error.validator not in ("maximum", "minimum") or not isinstance(error.schema, Mapping):
        return ""
    side = "above the largest" if error.validator == "maximum" else "below the smallest"
    for kind, where in BOUND_KINDS.items():
        if error.schema.get(kind):
            return f"{side} allowed value {error.validator_value:g} ({error.schema[kind]}); {where}"
    return ""


def validate_schema(config: Mapping[str, Any], schema: Mapping[str, Any]) -> None:
    """Check ``config`` against the JSON schema; raise ConfigError listing every problem."""
    import jsonschema

    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(config), key=lambda e: [str(p) for p in e.absolute_path])
    if errors:
        raise ConfigError("invalid config:\n  " + "\n  ".join(dict.fromkeys(_schema_message(e) for e in errors)))


#: At most this many sweep points in one grid (each job computes points_per_job of them; bounds the work a grid asks
#: for).
SWEEP_POINTS_LIMIT = 2000


def check_sweeps(section: Mapping[str, Any], config: Mapping[str, Any], key: str = "sweeps") -> None:
    """The swept clearance scene and variant exist, a swept clearance fits in the bearing, and no grid is too big."""
    spec = section["clearance"]
    if spec["scene"] not in config["clearance"]["scenes"]:
        raise ConfigError(
            f"config key {key}.clearance.scene: value {spec['scene']!r} is not a scene of clearance.scenes"
        )
    if spec["variant"] not in config["clearance"]["variants"]:
        raise ConfigError(
            f"config key {key}.clearance.variant: value {spec['variant']!r} is not a variant of clearance.variants"
        )
    bearing = config["clearance"]["joints"]["bearing_radius_m"]
    for grid in ("small", "large"):
        too_wide = [c for c in spec[grid]["clearance_m"] if c >= bearing]
        if too_wide:
            raise ConfigError(
                f"config key {key}.clearance.{grid}.clearance_m: value {too_wide[0]!r} is not smaller than "
                f"clearance.joints.bearing_radius_m = {bearing!r} (the journal radius would be <= 0)"
            )
        for sweep in ("clearance", "heald"):
            points = math.prod(len(v) for v in section[sweep][grid].values())
            if points > SWEEP_POINTS_LIMIT:
                raise ConfigError(
                    f"config key {key}.{sweep}.{grid}: {points} grid points exceed the size guard {SWEEP_POINTS_LIMIT} "
                    "(each is a job; raise SWEEP_POINTS_LIMIT in lib/linkwork/project/validate.py for a cluster)"
                )


def check_finite(node: Any, path: tuple = ()) -> None:
    """Every number in the config is finite (YAML's .nan and .inf pass a JSON schema's range checks)."""
    if isinstance(node, Mapping):
        for key, value in node.items():
            check_finite(value, (*path, key))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            check_finite(value, (*path, i))
    elif isinstance(node, float) and not math.isfinite(node):
        raise ConfigError(f"config key {_key(path)}: value {node!r} is not a finite number")


#: A name the user chooses (a scene, a variant, a material, a linkage and its bodies, points, joints and springs, ...)
#: becomes part of file paths and Snakemake wildcards: a letter, then letters, digits or underscores, at most 32
#: characters, and not ending in one piece repeated 20 times (Snakemake takes a wildcard value that does for a cycle of
#: rules and stops the dry run: PeriodicWildcardError, whose detector looks for 20 to 100 repeats at the end).
#: The one pattern of every name; the schema says which keys are names (``additionalProperties`` with a schema).
SAFE_NAME = re.compile(r"(?!.*(.+)\1{19}\Z)[A-Za-z][A-Za-z0-9_]{0,31}")
NAME_RULE = (
    "names become file paths, wildcards and labels: a letter, then letters, digits or _, at most 32 characters,"
    " not ending in one piece repeated 20 times"
)


def _resolve(schema: Mapping[str, Any], node: Mapping[str, Any]) -> Mapping[str, Any]:
    while isinstance(node, Mapping) and "$ref" in node:
        target: Any = schema
        for part in node["$ref"].lstrip("#/").split("/"):
            target = target[part]
        node = target
    return node


def _shown_key(path: tuple, key: Any) -> str:
    """The key path of a name as one line of text: the name as written where it is printable and short, else its repr
    (cut), so that a name holding a newline or a megabyte cannot break the message."""
    text = str(key)
    shown = text if text.isprintable() and len(text) <= 80 else _short(key)
    return f"{_key(path)}.{shown}" if path else shown


def check_names(
    config: Any, schema: Mapping[str, Any], node: Mapping[str, Any] | None = None, path: tuple = ()
) -> None:
    """Every key the schema leaves to the user (``additionalProperties`` with a schema) is a safe name."""
    node = _resolve(schema, schema if node is None else node)
    if not isinstance(node, Mapping):
        return
    if isinstance(config, Mapping):
        named = node.get("properties", {})
        extra = node.get("additionalProperties")
        for key, value in config.items():
            if key in named:
                check_names(value, schema, named[key], (*path, key))
            elif isinstance(extra, Mapping):
                if not isinstance(key, str) or not SAFE_NAME.fullmatch(key):
                    raise ConfigError(
                        f"config key {_shown_key(path, key)}: this name is not allowed ({NAME_RULE})"
                    )
                check_names(value, schema, extra, (*path, key))
    elif isinstance(config, list) and isinstance(node.get("items"), Mapping):
        for i, value in enumerate(config):
            check_names(value, schema, node["items"], (*path, i))


def check_integers(node: Any, schema: Mapping[str, Any], path: tuple = ()) -> None:
    """A count given as a float (``points: 1200.0``) is refused where the schema asks for an integer: the JSON schema
    takes an integral float for an integer, and the code would then count with a float."""
    if isinstance(node, Mapping):
        for key, value in node.items():
            check_integers(value, schema, (*path, key))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            check_integers(value, schema, (*path, i))
    elif isinstance(node, float) and _types(schema, _schema_at(schema, path)) == {"integer"}:
        raise ConfigError(
            f"config key {_key(path)}: value {node!r} is not an integer (a count: write it without the decimal point)"
        )


def check_states(node: Any, path: tuple = ()) -> None:
    """Every state-finding block (``chunk_cycles``, ``min_cycles``, ``max_cycles``, ...: ``engines.states.settle``)
    can decide within its cap: the shortest judged window and a chunk fit in ``max_cycles``, and so do the whole
    periods a periodic state is recognised by."""
    if isinstance(node, Mapping):
        if {"chunk_cycles", "min_cycles", "max_cycles"} <= set(node):
            cap = node["max_cycles"]
            for name in ("chunk_cycles", "min_cycles"):
                if node[name] > cap:
                    raise ConfigError(
                        f"config key {_key((*path, name))}: value {node[name]!r} is above {_key((*path, 'max_cycles'))}"
                        f" = {cap!r}"
                    )
            if "max_period" in node and "periods" in node and node["max_period"] * node["periods"] > cap:
                raise ConfigError(
                    f"config key {_key((*path, 'periods'))}: {node['periods']!r} whole periods of up to"
                    f" {_key((*path, 'max_period'))} = {node['max_period']!r} cycles do not fit in"
                    f" {_key((*path, 'max_cycles'))} = {cap!r}"
                )
        for key, value in node.items():
            check_states(value, (*path, key))
    elif isinstance(node, list):
        for i, value in enumerate(node):
            check_states(value, (*path, i))


def check_labelled(node: Any, path: tuple = ()) -> None:
    """Every labelled entry is one value of its own range or choices: a range with its low end below its high end
    holding the value, a choice's value among its choices, one name in prose per choice."""
    if not isinstance(node, Mapping):
        return
    if {"value", "status", "reason"} <= set(node):
        where = f"config key {_key(path)}"
        if "choices" in node:
            if node["value"] not in node["choices"]:
                raise ConfigError(
                    f"{where}.value: {_short(node['value'])} is not one of its choices {_short(node['choices'])}"
                )
            if "choice_labels" in node and len(node["choice_labels"]) != len(node["choices"]):
                raise ConfigError(
                    f"{where}.choice_labels: {len(node['choice_labels'])} names for {len(node['choices'])} choices"
                )
        if "range" in node and isinstance(node["value"], (int, float)):
            low, high = node["range"]
            if not low < high:
                raise ConfigError(
                    f"{where}.range: {_short(node['range'])} is not a range (the low end must be below the high end)"
                )
            if not low <= node["value"] <= high:
                raise ConfigError(
                    f"{where}.value: {_short(node['value'])} lies outside its own range {_short(node['range'])}"
                )
        return
    for key, value in node.items():
        check_labelled(value, (*path, key))


def validate_config(config: Mapping[str, Any], schema: Mapping[str, Any], memo: Memo | None = None) -> None:
    """Safe names and finite numbers first, then the schema, then the physical checks of every paper section
    (their messages name the physics), then every labelled entry against its own range or choices.

    ``memo``: where the physical checks (a paper section's, the linkages') remember that they passed, each by its own
    inputs; without it every check runs."""
    check_names(config, schema)
    check_finite(config)
    validate_schema(config, schema)
    check_integers(config, schema)
    check_states(config)
    for paper in PAPERS:
        if paper in config:
            module = f"linkwork.papers.{paper}.checks"
            section = config[paper]
            _physics(memo, paper, section, module, lambda: importlib.import_module(module).check(section, paper))
    check_labelled(config)
    if "sweeps" in config:
        check_sweeps(config["sweeps"], config)
    linkages = config.get("linkages") or {}
    _physics(memo, "linkages", linkages, "linkwork.engines.multibody.describe", lambda: check_linkages(linkages))


@dataclass(frozen=True)
class Memo:
    """Where the physical checks remember a pass: ``folder`` holds one stamp per check (its key), ``lib`` the package
    whose code the keys read."""

    folder: Path
    lib: Path


def _physics(memo: Memo | None, name: str, section: Any, module: str, check: Callable[[], None]) -> None:
    """Run ``check`` (the physical check ``name`` of ``section``, coded in ``module``) unless it passed before on the
    same section and the same code: the checks that follow a linkage through its turn take about a second, and an edit
    of another paper's keys or code cannot change their outcome."""
    if memo is None:
        check()
        return
    import hashlib
    import json

    from ..pipeline.deps import closure

    digest = hashlib.sha256(json.dumps(_typed(section)).encode())
    for file in closure(module, memo.lib):
        digest.update(str(file).encode() + b"\0" + Path(file).read_bytes())
    key, stamp = digest.hexdigest(), memo.folder / name
    if stamp.is_file() and stamp.read_text(encoding="utf-8").strip() == key:
        return
    check()
    _write_stamp(stamp, key)


def _write_stamp(stamp: Path, key: str) -> None:
    """``key`` into the file ``stamp``, atomically."""
    stamp.parent.mkdir(parents=True, exist_ok=True)
    tmp = stamp.with_name(f"{stamp.name}.{os.getpid()}.tmp")
    tmp.write_text(key + "\n", encoding="utf-8")
    os.replace(tmp, stamp)


def check_linkages(linkages: Mapping[str, Any]) -> None:
    """Every linkage of ``linkages`` assembles and runs through its driven turn (``describe.errors``: one line per
    problem, naming its key)."""
    from ..engines.multibody.describe import errors

    problems = [
        line for name, scene in linkages.items() for line in errors(scene["linkage"], f"linkages.{name}.linkage")
    ]
    if problems:
        raise ConfigError("invalid config:\n  " + "\n  ".join(problems))


def _branches(schema: Mapping[str, Any], node: Any) -> list[Mapping[str, Any]]:
    """``node`` resolved and the subschemas it combines (``allOf``, ``anyOf``, ``oneOf``, resolved in turn), depth
    first: where the keys of a value governed by ``node`` may be described."""
    node = _resolve(schema, node)
    if not isinstance(node, Mapping):
        return []
    out = [node]
    for word in ("allOf", "anyOf", "oneOf"):
        for sub in node.get(word, []):
            out += _branches(schema, sub)
    return out


def _child(schema: Mapping[str, Any], node: Any, part: Any) -> Mapping[str, Any] | None:
    """The schema node of the value at ``part`` (a key, or an index for a list) of a value governed by ``node``: its
    ``items``, else the property of that name in any branch, else the first ``additionalProperties`` schema (a name
    the user chooses, e.g. a linkage, a joint); None where the schema says nothing."""
    branches = _branches(schema, node)
    if isinstance(part, int):
        found = [b["items"] for b in branches if isinstance(b.get("items"), Mapping)]
    else:
        found = [b["properties"][part] for b in branches if part in b.get("properties", {})]
        found = found or [
            b["additionalProperties"] for b in branches if isinstance(b.get("additionalProperties"), Mapping)
        ]
    return _resolve(schema, found[0]) if found else None


def _schema_at(schema: Mapping[str, Any], path: tuple) -> Mapping[str, Any] | None:
    """The schema node that governs the config value at ``path`` (None where the schema says nothing), through
    ``$ref``, ``additionalProperties`` (names the user chooses) and ``allOf``/``anyOf``/``oneOf``."""
    node: Any = schema
    for part in path:
        node = _child(schema, node, part)
        if node is None:
            return None
    return _resolve(schema, node)


def _types(schema: Mapping[str, Any], node: Mapping[str, Any] | None) -> set[str]:
    """The JSON types ``node`` names, in any of its branches (``_branches``)."""
    out: set[str] = set()
    for branch in _branches(schema, node):
        kind = branch.get("type", [])
        out |= {kind} if isinstance(kind, str) else set(kind)
    return out


def _from_text(text: str, types: set[str]) -> Any:
    """A command-line string read as the number or boolean the schema asks for (YAML 1.2's forms); else unchanged."""
    word = text.strip()
    if "boolean" in types and word.lower() in ("true", "false"):
        return word.lower() == "true"
    if types & {"number", "integer"}:
        try:
            return int(word)
        except ValueError:
            pass
        try:
            return float(word)
        except ValueError:
            pass
    return text


def coerce_overrides(config: dict[str, Any], overrides: Mapping[str, Any], schema: Mapping[str, Any]) -> None:
    """Read the strings of ``--config`` (``overrides``; Snakemake reads nested values and ``false`` as text) as the
    numbers and booleans the schema asks for at their keys, in ``config`` (in place).  A string the schema does not
    want as text and that is no number stays text: the schema check then names its key."""

    def walk(node: Any, target: Any, path: tuple) -> None:
        items = node.items() if isinstance(node, Mapping) else enumerate(node) if isinstance(node, list) else []
        for key, value in items:
            here = (*path, key)
            if isinstance(value, str):
                types = _types(schema, _schema_at(schema, here))
                if types and "string" not in types:
                    target[key] = _from_text(value, types)
            else:
                walk(value, target[key], here)

    walk(overrides, config, ())


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


def validation_key(config: Mapping[str, Any], schema_path: Path, lib: Path, published: Path | None = None) -> str:
    """sha256 of what a validation depends on: the config, the schema file, the validating code and (``published``: the
    folder of the published-numbers files) those files with their schema."""
    import hashlib
    import json

    from ..pipeline.deps import closure

    digest = hashlib.sha256(json.dumps(_typed(config)).encode())  # in file order: keys may not be comparable
    digest.update(Path(schema_path).read_bytes())
    checks = tuple(f"linkwork.papers.{p}.checks" for p in PAPERS)
    for file in closure("linkwork.project.validate", lib, extra=(*checks, "linkwork.project.published")):
        digest.update(str(file).encode() + b"\0" + Path(file).read_bytes())
    if published is not None:
        for file in [published_schema(published), *(Path(published) / f"{p}.yaml" for p in PAPERS)]:
            digest.update(str(file).encode() + b"\0" + (file.read_bytes() if file.is_file() else b"missing"))
    return digest.hexdigest()


def _typed(node: Any) -> Any:
    """``node`` as JSON that keeps what YAML read: every mapping as its (key, value) pairs and every value that JSON
    does not hold (a date, a key that is no string) with its type, so that a quoted and an unquoted date differ."""
    if isinstance(node, Mapping):
        return {"map": [[_typed(k), _typed(v)] for k, v in node.items()]}
    if isinstance(node, list):
        return [_typed(v) for v in node]
    if node is None or isinstance(node, (str, bool, int, float)):
        return node
    return {"type": type(node).__name__, "repr": repr(node)}


def published_schema(published: Path) -> Path:
    """The schema of the published-numbers files in the folder ``published`` (config/published.schema.yaml)."""
    return Path(published).parent / "published.schema.yaml"


def validate_once(
    config: Mapping[str, Any], schema_path: Path, lib: Path, stamp: Path, published: Path | None = None
) -> None:
    """Validate unless this exact config, schema and validating code passed before (``stamp`` holds the key);
    ``published``: the folder of the papers' published-numbers files, validated too (``linkwork.project.published``).

    A passed validation is remembered so that a no-op run stays fast; any change to what it read runs it again, and
    then each physical check only if its own section or code changed (their stamps in the folder ``<stamp>.d``).
    """
    key = validation_key(config, schema_path, lib, published)
    if stamp.is_file() and stamp.read_text(encoding="utf-8").strip() == key:
        return
    validate_config(config, load_yaml(schema_path), Memo(stamp.with_name(f"{stamp.name}.d"), Path(lib)))
    if published is not None:
        from .published import check_published

        check_published(published, published_schema(published), list(PAPERS))
    _write_stamp(stamp, key)


def main(argv: list[str] | None = None) -> int:
    """``python -m linkwork.project.validate FILE ...``: read each YAML file as the workflow does (syntax errors, keys
    given twice, YAML 1.1 numbers, with file and line).  Snakemake reads a ``--configfile`` before the workflow runs and
    reports its syntax errors without file or line; this names them."""
    import sys

    files = sys.argv[1:] if argv is None else argv
    if not files:
        print("usage: python -m linkwork.project.validate FILE ...", file=sys.stderr)
        return 2
    failed = 0
    for name in files:
        try:
            load_yaml(name)
            print(f"{name}: reads as YAML")
        except ConfigError as exc:
            print(f"linkwork: {exc}", file=sys.stderr)
            failed = 1
    return failed


if __name__ == "__main__":
    raise SystemExit(main())
