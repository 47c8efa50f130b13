"""Published numbers beside reproduced ones: deviation, tolerance, verdict.

A published-numbers file (``config/published/<paper>.yaml``, already parsed to a
dict) holds

``quantities``
    entries with ``id``, ``quantity`` (text), ``value``, ``unit``, ``where``
    (table, figure, text), ``tolerance`` (``{abs: x}`` or ``{rel: x}``) and a
    ``measure`` saying how to read the value from a result Dataset.
``tables``
    printed tables, expanded cell by cell: ``key`` (the coordinate the first
    column selects), ``columns`` (published column -> result variable),
    ``rows``, a shared ``unit``, ``where`` and ``tolerance``.

An entry may carry ``relation: ge`` or ``le`` for a one-sided claim ("at least").
A measure is ``{variable, reduce, dim}`` with ``reduce`` one of ``max``,
``min``, ``mean``, ``argmax``, ``argmin`` (the coordinate value of the extreme),
``range`` (max - min), ``value`` (a scalar variable) or ``at`` (with
``at: {coord: value}``); an optional ``scale`` converts the result's unit to the
published unit.  A ``measure: null`` marks a number the paper does not give
enough to reproduce (verdict "not reproducible"; say why in ``note``).
A table column is a variable name, or ``{variable, unit, tolerance}`` when the
columns differ in unit or precision.

Published numbers are read here and nowhere else in the library; they never
enter a computation.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

VERDICTS = ("matches", "deviates", "not reproducible")
COLUMNS = [
    "model",
    "id",
    "quantity",
    "where",
    "published",
    "reproduced",
    "unit",
    "deviation",
    "relative_deviation",
    "tolerance",
    "verdict",
]


def evaluate_measure(ds: xr.Dataset, measure: Mapping[str, Any]) -> float:
    """Read one number from a result Dataset as a published-number entry says.

    Returns NaN when the variable or coordinate is missing (not reproducible).
    """
    if measure is None:  # the paper does not give what reproducing this number needs
        return math.nan
    name = measure["variable"]
    if name not in ds:
        return math.nan
    da = ds[name]
    reduce = measure["reduce"]
    dim = measure.get("dim", da.dims[0] if da.dims else None)
    if reduce == "at":
        try:
            value = float(da.sel(measure["at"]))
        except KeyError:
            return math.nan
    elif reduce == "value":
        value = float(da)
    elif reduce in ("max", "min", "mean"):
        value = float(getattr(da, reduce)(dim))
    elif reduce == "range":
        value = float(da.max(dim) - da.min(dim))
    elif reduce in ("argmax", "argmin"):
        index = int(getattr(da, reduce)(dim))
        value = float(da[dim][index])
    else:
        raise ValueError(f"unknown reduce {reduce!r} in measure {dict(measure)}")
    return value * float(measure.get("scale", 1.0))


def tolerance_of(entry: Mapping[str, Any]) -> float:
    """Absolute tolerance of a published entry (relative tolerances scaled by |value|)."""
    tol = entry["tolerance"]
    if "abs" in tol:
        return float(tol["abs"])
    return float(tol["rel"]) * abs(float(entry["value"]))


def verdict(published: float, reproduced: float, tolerance: float, relation: str = "eq") -> str:
    """'matches' within the tolerance, 'deviates' beyond it, 'not reproducible' if NaN.

    relation 'eq' (default) is |reproduced - published| <= tolerance; 'ge' and 'le'
    judge a one-sided claim ("at least", "at most") with the tolerance as slack.
    A hair of floating-point slack (1e-9 of the tolerance) keeps a deviation of
    exactly the tolerance on the matching side.
    """
    if not np.isfinite(reproduced):
        return "not reproducible"
    slack = tolerance * (1 + 1e-9)
    if relation == "ge":
        ok = reproduced >= published - slack
    elif relation == "le":
        ok = reproduced <= published + slack
    elif relation == "eq":
        ok = abs(reproduced - published) <= slack
    else:
        raise ValueError(f"unknown relation {relation!r}")
    return "matches" if ok else "deviates"


def expand_tables(published: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Turn printed tables into one quantity entry per cell."""
    entries = []
    for table in published.get("tables", []):
        key = table["key"]
        names = table["column_names"]
        for row in table["rows"]:
            key_value = row[0]
            for col_name, value in zip(names, row[1:], strict=True):
                column = table["columns"][col_name]
                if isinstance(column, str):  # a variable name; unit and tolerance shared by the table
                    column = {"variable": column}
                entries.append(
                    {
                        "id": f"{table['id']}.{col_name}@{key_value:g}",
                        "quantity": f"{col_name} at {key} = {key_value:g}",
                        "value": value,
                        "unit": column.get("unit", table.get("unit")),
                        "where": table["where"],
                        "tolerance": column.get("tolerance", table.get("tolerance")),
                        "measure": {
                            "variable": column["variable"],
                            "reduce": "at",
                            "at": {table["coordinate"]: key_value},
                        },
                    }
                )
    return entries


def compare(published: Mapping[str, Any], ds: xr.Dataset, model: str = "") -> pd.DataFrame:
    """The comparison table for one result Dataset (one model variant)."""
    rows = []
    for entry in [*published.get("quantities", []), *expand_tables(published)]:
        value = float(entry["value"])
        reproduced = evaluate_measure(ds, entry["measure"])
        tol = tolerance_of(entry)
        deviation = reproduced - value
        rows.append(
            {
                "model": model,
                "id": entry["id"],
                "quantity": entry["quantity"],
                "where": entry["where"],
                "published": value,
                "reproduced": reproduced,
                "unit": entry["unit"],
                "deviation": deviation,
                "relative_deviation": deviation / value if value != 0 else math.nan,
                "tolerance": tol,
                "verdict": verdict(value, reproduced, tol, entry.get("relation", "eq")),
            }
        )
    return pd.DataFrame(rows, columns=COLUMNS)


def verdict_counts(table: pd.DataFrame) -> dict[str, int]:
    """How many rows of each verdict (all three keys always present)."""
    counts = table["verdict"].value_counts()
    return {v: int(counts.get(v, 0)) for v in VERDICTS}


#: Dimensions along which a result holds several model variants, one comparison block each.
VARIANT_DIMS = ("form", "model", "variant")


def compare_datasets(published: Mapping[str, Any], datasets: list[xr.Dataset]) -> pd.DataFrame:
    """The comparison table over the merged result Datasets, one block per model variant."""
    ds = xr.merge(datasets, combine_attrs="drop")
    dim = next((d for d in VARIANT_DIMS if d in ds.dims), None)
    variants = [str(v) for v in ds[dim].values] if dim else [""]
    return pd.concat([compare(published, ds.sel({dim: v}) if dim else ds, model=v) for v in variants], ignore_index=True)


def counts_dataset(table: pd.DataFrame, rows: pd.Series | None = None) -> xr.Dataset:
    """Verdict counts per model (dims count_model x verdict), optionally of a subset of rows."""
    part = table if rows is None else table[rows]
    models = list(dict.fromkeys(table["model"]))
    counts = np.array([[verdict_counts(part[part.model == m])[v] for v in VERDICTS] for m in models])
    return xr.Dataset(
        {"verdict_count": (("count_model", "verdict"), counts, {"units": "1", "long_name": "comparison rows per verdict"})},
        coords={"count_model": ("count_model", np.array(models, dtype=object), {"units": "1", "long_name": "model variant of the comparison block"}),
                "verdict": ("verdict", np.array(VERDICTS, dtype=object), {"units": "1", "long_name": "verdict"})},
    )


def scalar(value: float, unit: str, long_name: str) -> tuple:
    """A scalar data variable with units for a findings Dataset."""
    return ((), float(value), {"units": unit, "long_name": long_name})


def where_true(x, ok, fmt: str = ".3g") -> str:
    """Text naming the sub-ranges of a sweep ``x`` where ``ok`` holds ('all of a-b', 'none of a-b', 'a-b, c-d')."""
    x, ok = np.asarray(x, dtype=float), np.asarray(ok, dtype=bool)
    span = f"{x.min():{fmt}}–{x.max():{fmt}}"
    if ok.all():
        return f"all of {span}"
    if not ok.any():
        return f"none of {span}"
    parts, start = [], None
    for i, flag in enumerate(ok):
        if flag and start is None:
            start = i
        if (not flag or i == ok.size - 1) and start is not None:
            end = i if flag else i - 1
            parts.append(f"{x[start]:{fmt}}–{x[end]:{fmt}}")
            start = None
    return ", ".join(parts)
