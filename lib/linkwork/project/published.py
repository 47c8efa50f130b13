"""Validate the published-numbers files (``config/published/<paper>.yaml``) like the config, before any job.

Three layers, as for the config: reading (syntax errors and duplicate keys with file and line, ``yamlfile.load_yaml``),
the JSON schema ``config/published.schema.yaml`` (types, tolerances >= 0, relations, measures, no unknown keys), then
what a schema cannot say: every number finite, the ``paper`` field naming its file, ids unique (a table's cells
included, as ``compare.expand_tables`` names them), a table row with one value per column and every column described,
and each measure naming a variable the paper's study writes (``linkwork.papers.<paper>.checks.RESULT_VARIABLES``).
Every problem is one line naming the file and the entry.
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..pipeline.errors import ConfigError


def _where(path: Path, parts) -> str:
    return f"{path}, " + ".".join(str(p) for p in parts) if parts else str(path)


def schema_problems(data: Any, schema: Mapping[str, Any], path: Path) -> list[str]:
    """One line per schema error of one file (``path`` names it)."""
    import jsonschema

    from ..pipeline.yamlfile import short as _short

    errors = sorted(
        jsonschema.Draft202012Validator(schema).iter_errors(data), key=lambda e: [str(p) for p in e.absolute_path]
    )
    out = []
    for e in errors:
        while e.validator == "oneOf" and e.context:  # the measure or column alternatives: the closest one's reason
            e = max(
                e.context, key=lambda c: (len(c.absolute_path), c.validator != "type")
            )  # deepest, not "not of type null"
        if e.validator == "additionalProperties" and isinstance(e.instance, Mapping):
            extra = sorted(set(e.instance) - set(e.schema.get("properties", {})))
            out.append(
                f"{_where(path, [*e.absolute_path, extra[0] if extra else '?'])}: unknown key (allowed here:"
                f" {', '.join(sorted(e.schema.get('properties', {})))})"
            )
        elif e.validator == "required" and isinstance(e.instance, Mapping):
            missing = [r for r in e.validator_value if r not in e.instance]
            out.append(f"{_where(path, [*e.absolute_path, missing[0] if missing else '?'])}: missing")
        else:
            message = e.message if len(e.message) < 160 else e.message[:160] + " ..."
            out.append(f"{_where(path, e.absolute_path)}: value {_short(e.instance)}: {message}")
    return list(dict.fromkeys(out))


def _shown(path: Path) -> Path:
    """``path`` relative to the working directory (the project's root under Snakemake) where it lies below it."""
    try:
        return path.resolve().relative_to(Path.cwd().resolve())
    except ValueError:
        return path


def _non_finite(node: Any, parts: tuple = ()) -> list[tuple]:
    if isinstance(node, Mapping):
        return [p for k, v in node.items() for p in _non_finite(v, (*parts, k))]
    if isinstance(node, list):
        return [p for i, v in enumerate(node) for p in _non_finite(v, (*parts, i))]
    return [parts] if isinstance(node, float) and not math.isfinite(node) else []


def rule_problems(paper: str, data: Mapping[str, Any], path: Path, variables: frozenset[str]) -> list[str]:
    """The rules beyond the schema (see the module's docstring), for a file that passed the schema."""
    out = [f"{_where(path, p)}: value is not a finite number" for p in _non_finite(data)]
    if data["paper"] != paper:
        out.append(f"{_where(path, ['paper'])}: value {data['paper']!r} is not the file's paper {paper!r}")
    seen: dict[str, str] = {}
    named = [
        (f"quantities.{i}", e["id"], e["measure"] and e["measure"]["variable"])
        for i, e in enumerate(data["quantities"])
    ]
    for t, table in enumerate(data.get("tables", [])):
        where = f"tables.{t}"
        missing = [c for c in table["column_names"] if c not in table["columns"]]
        if missing:
            out.append(f"{_where(path, [where, 'columns'])}: column {missing[0]!r} of column_names is not described")
            continue
        for r, row in enumerate(table["rows"]):
            if len(row) != len(table["column_names"]) + 1:
                out.append(
                    f"{_where(path, [where, 'rows', r])}: {len(row)} values; a row holds the key and one per column "
                    f"({len(table['column_names']) + 1})"
                )
                continue
            for name in table["column_names"]:
                column = table["columns"][name]
                named.append(
                    (
                        f"{where}.rows.{r}", f"{table['id']}.{name}@{row[0]:g}",
                        column if isinstance(column, str) else column["variable"],
                    )
                )
                if "tolerance" not in table and (isinstance(column, str) or "tolerance" not in column):
                    out.append(
                        f"{_where(path, [where, 'columns', name])}: no tolerance (give the table's or the column's)"
                    )
    for where, id_, variable in named:
        if id_ in seen:
            out.append(f"{path}, {where}: id {id_!r} is given twice (first at {seen[id_]})")
        seen.setdefault(id_, where)
        if variable is not None and variable not in variables:
            out.append(
                f"{path}, {where} ({id_}): measure variable {variable!r} is not one the {paper} comparison reads"
                f" (known: {', '.join(sorted(variables))}; a variable its study writes is added in RESULT_VARIABLES of"
                f" linkwork.papers.{paper}.checks)"
            )
    return list(dict.fromkeys(out))


def result_variables(paper: str) -> frozenset[str]:
    """The result variables a published file's measures may name (``linkwork.papers.<paper>.checks``)."""
    return importlib.import_module(f"linkwork.papers.{paper}.checks").RESULT_VARIABLES


def check_published(folder: Path, schema_path: Path, papers) -> None:
    """Every paper's published file in ``folder`` checked; one ConfigError listing every problem of every file."""
    from ..pipeline.yamlfile import load_yaml

    schema = load_yaml(schema_path)
    problems = []
    for paper in papers:
        path = _shown(Path(folder) / f"{paper}.yaml")
        if not path.is_file():
            problems.append(f"{path}: missing (the {paper} paper's published numbers)")
            continue
        try:
            data = load_yaml(path)
        except ConfigError as exc:
            problems.append(str(exc))
            continue
        found = schema_problems(data, schema, path)
        problems += found or rule_problems(paper, data, path, result_variables(paper))
    if problems:
        raise ConfigError("invalid published numbers:\n  " + "\n  ".join(problems))
