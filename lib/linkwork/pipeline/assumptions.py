"""The labelled entries of a paper's config section, whole, as a result: the one home of the reasons, statuses,
ranges and choices that the reports show.  Studies receive values only (``linkwork.configformat.values_only``), so
editing a reason reruns this step and the report that shows it, and nothing else."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any


def _text(values: Any) -> str:
    return "" if values is None else "–".join(f"{float(v):g}" for v in values)


def assumptions(cfg: Mapping[str, Any]):
    """Rule study: every labelled entry of the section ``cfg`` (dims entry): its key path, value, status, reason,
    range or choices and why that range, and the whole entry as JSON (``entry_json``, what the reports look up).
    ``cfg``: the section, or its labelled entries by dotted key path (``configformat.labelled_entries``)."""
    import json

    import numpy as np
    import xarray as xr

    from ..configformat import labelled_entries

    found = labelled_entries(cfg)
    column = lambda f: np.array([f(e) for e in found.values()], dtype=object)  # noqa: E731
    text = {"units": "1"}
    return xr.Dataset(
        {
            "value": (
                "entry", column(lambda e: str(e["value"])), {**text, "long_name": "value (SI; a choice: its name)"},
            ),
            "status": (
                "entry", column(lambda e: str(e["status"])), {**text, "long_name": "sourced, inferred or assumed"},
            ),
            "reason": ("entry", column(lambda e: str(e["reason"])), {**text, "long_name": "why this value"}),
            "range": (
                "entry",
                column(
                    lambda e: (
                        " / ".join(map(str, e.get("choice_labels", e["choices"])))
                        if "choices" in e
                        else _text(e.get("range"))
                    )
                ),
                {**text, "long_name": "plausible range, or the alternatives of a choice ('' if none)"},
            ),
            "range_reason": (
                "entry", column(lambda e: str(e.get("range_reason", ""))),
                {**text, "long_name": "why that range ('' if none)"},
            ),
            "entry_json": (
                "entry", column(lambda e: json.dumps(e, sort_keys=True)),
                {**text, "long_name": "the whole entry as JSON"},
            ),
        },
        coords={"entry": ("entry", np.array(list(found), dtype=object), {**text, "long_name": "config key path"})},
        attrs={"title": "labelled config entries: values, statuses, reasons, ranges"},
    )
