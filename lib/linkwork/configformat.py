"""How values are written in config/config.yaml, and how a rule takes exactly the values it reads.

* A value the paper does not give is a labelled entry ``{value, status, reason}`` with status
  ``sourced``, ``inferred`` or ``assumed``; ``labelled`` returns its value.
* ``pick`` copies chosen key paths (``"linkage"``, ``"numerics.assembly_tol"``) of a section into
  a new nested dict of the same shape, so that a rule's params hold exactly what its study reads
  and a study that reads anything else fails with a KeyError instead of going unnoticed.

Light on purpose (standard library only): the Snakefile imports it.
"""

from __future__ import annotations

import copy
from collections.abc import Iterable, Mapping
from typing import Any


def labelled(entry: Mapping[str, Any]) -> float:
    """The value of a labelled config entry ``{value, status, reason}`` as a float."""
    return float(entry["value"])


def get_path(section: Mapping[str, Any], path: str) -> Any:
    """The value at a dotted key path of a nested mapping (KeyError names the path)."""
    node: Any = section
    for part in path.split("."):
        if not isinstance(node, Mapping) or part not in node:
            raise KeyError(f"config key {path!r} not found (missing {part!r})")
        node = node[part]
    return node


def pick(section: Mapping[str, Any], paths: Iterable[str]) -> dict[str, Any]:
    """A new nested dict holding only the given dotted key paths of ``section`` (deep copies)."""
    out: dict[str, Any] = {}
    for path in paths:
        value = get_path(section, path)
        parts = path.split(".")
        node = out
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        node[parts[-1]] = copy.deepcopy(value)
    return out


def is_labelled(node: Any) -> bool:
    """Whether a config node is a labelled entry ``{value, status, reason, ...}``."""
    return isinstance(node, Mapping) and {"value", "status", "reason"} <= set(node)


#: The label fields the uncertainty design reads (the ranges, and the choices with their names); not the reasons.
DESIGN_FIELDS = ("range", "choices", "choice_labels")


def values_only(section: Mapping[str, Any], keep: Iterable[str] = (), fields: Iterable[str] = ()) -> dict[str, Any]:
    """A copy of ``section`` in which every labelled entry holds only its ``value`` (a study reads values; the
    uncertainty design reads ranges and choices; the reports read reasons), except the label fields named by the
    dotted paths in ``keep`` ('fe.damping_ratio.range' keeps that entry's range) and the label ``fields`` kept on
    every entry (``DESIGN_FIELDS`` for the uncertainty design)."""
    kept = {tuple(p.split(".")) for p in keep}
    everywhere = set(fields)

    def strip(node: Any, path: tuple[str, ...]) -> Any:
        if is_labelled(node):
            return {
                k: copy.deepcopy(v) for k, v in node.items() if k == "value" or k in everywhere or (*path, k) in kept
            }
        if isinstance(node, Mapping):
            return {k: strip(v, (*path, k)) for k, v in node.items()}
        return copy.deepcopy(node)

    return strip(section, ())


def narrow(section: Mapping[str, Any], paths: Iterable[str], fields: Iterable[str] = ()) -> dict[str, Any]:
    """A rule's params: the key ``paths`` of ``section`` (``pick``), every labelled entry reduced to its value, except
    a label field a path names itself ('sixbar.crank_sense.choices') and the label ``fields`` kept everywhere.  So an
    edit of a reason, a range or the choices reruns only the rules that name them."""
    paths = list(paths)
    return values_only(pick(section, paths), keep=paths, fields=fields)


def labelled_entries(section: Mapping[str, Any], prefix: str = "") -> dict[str, dict[str, Any]]:
    """Every labelled entry of a section, whole, by dotted key path (depth first, in order)."""
    out: dict[str, dict[str, Any]] = {}
    for key, node in section.items():
        path = f"{prefix}{key}"
        if is_labelled(node):
            out[path] = copy.deepcopy(dict(node))
        elif isinstance(node, Mapping):
            out.update(labelled_entries(node, path + "."))
    return out
