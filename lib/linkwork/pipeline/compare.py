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
enough to reproduce (verdict "not printed"; say why in ``note``).
A table column is a variable name, or ``{variable, unit, tolerance}`` when the
columns differ in unit or precision.

Verdict classes (``classify``) name their cause: the paper's own numbers, an input it does not print, its model, or our
numerics.  With the acceptance region A of a published value (value +- tolerance, or one-sided for ``ge``/``le``), our
value N at the nominal inputs of a scenario, our numerical error bar e and the range [low, high] of our value over the
box of the continuous inputs (``linkwork.pipeline.search``):

The paper's own numbers decide

``reproduced``                        [low - e, high + e] lies inside A;
``differs``                           [low - e, high + e] lies outside A (the table says by how much);
``reproduced at the printed digits``  N lies in A, and only the rounding of printed values (their last digit) moves it
                                      out;
``differs at the printed digits``     N lies outside A, and only the rounding of printed values moves it in;

An input the paper does not print decides (the row's 'decided by' names it)

``decided by an unprinted input``     the verdict changes within the assumed inputs' ranges, and the row matches in a
                                      consistent set (one point of the box under which as many of the paper's rows
                                      match at once as under the best such point);
``only where other rows fail``        the row matches somewhere in the box, but only where other rows of the paper
                                      fail: no consistent set includes it;
``not printed``                       N is undefined: the paper does not print what the number needs;

The model decides

``decided by the paper's model``      the paper's own model leaves the row open whatever the inputs (the caller names
                                      the cause, e.g. a contact law's memory of its first impact: ``model_decides``);
``no counterpart in this model``      N is undefined because this model variant has no such quantity
                                      (``absent="model"``), not because the paper omits an input;

Our numerics decide

``undetermined by our numerics``      [N - e, N + e] is partly inside A and partly outside.

The class is the classifier's own: no step after ``classify`` changes it.
A modelling choice is a named scenario (one block of rows each), never a range.

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

#: Every class, most favourable first; each names its cause (``CAUSE``).
VERDICTS = (
    "reproduced", "reproduced at the printed digits", "decided by an unprinted input", "only where other rows fail",
    "decided by the paper's model", "undetermined by our numerics", "differs at the printed digits", "differs",
    "no counterpart in this model", "not printed",
)
#: What decides each class: the paper's numbers, an input it does not print, a model, or our numerics.
CAUSE = {
    "reproduced": "the paper's numbers",
    "reproduced at the printed digits": "the paper's numbers",
    "differs at the printed digits": "the paper's numbers",
    "differs": "the paper's numbers",
    "decided by an unprinted input": "an input the paper does not print",
    "only where other rows fail": "an input the paper does not print",
    "not printed": "an input the paper does not print",
    "decided by the paper's model": "the paper's model",
    "no counterpart in this model": "our model",
    "undetermined by our numerics": "our numerics",
}
#: Each class in a few plain words, for legends and the index: the one verdict-to-word map.
VERDICT_MEANING = {
    "reproduced": (
        "within the tolerance over the whole range of the assumed inputs judged (where 'decided by' names a limit,"
        " within it), with our error bar"
    ),
    "reproduced at the printed digits": (
        "within the tolerance at the printed values; the last printed digit of an input moves it out"
    ),
    "decided by an unprinted input": (
        "an input the paper does not print decides: within the tolerance for some of its values, outside for others"
    ),
    "only where other rows fail": (
        "within the tolerance only for unprinted inputs under which other rows of the paper fail"
    ),
    "decided by the paper's model": "the paper's own model leaves it open whatever the inputs (the row says why)",
    "undetermined by our numerics": "our own numerical error bar straddles the tolerance",
    "differs at the printed digits": (
        "outside the tolerance at the printed values; only the last printed digit moves it in"
    ),
    "differs": (
        "outside the tolerance over the whole range of the assumed inputs judged (where 'decided by' names a limit,"
        " within it), with our error bar"
    ),
    "no counterpart in this model": "this model variant has no such quantity",
    "not printed": "the paper does not print what reproducing it needs",
}
#: One colour per class, for tables and the index's matrix.
VERDICT_COLOURS = {  # distinct hues, light enough for black text in a table cell
    "reproduced": "#66bd63",
    "reproduced at the printed digits": "#c2e699",
    "decided by an unprinted input": "#74add1",
    "only where other rows fail": "#b2a3d9",
    "decided by the paper's model": "#f1b6da",
    "undetermined by our numerics": "#fee08b",
    "differs at the printed digits": "#fdae61",
    "differs": "#e8684a",
    "no counterpart in this model": "#a6a6a6",
    "not printed": "#dedede",
}
HALF_DIGIT = "half a unit of the last printed digit"
COLUMNS = [
    "model", "scenario", "id", "role", "quantity", "where", "published", "relation", "unit", "tolerance",
    "tolerance_source", "reproduced", "deviation", "relative_deviation", "numerical_error", "numerical_source",
    "input_low", "input_high", "input_source", "decided_by", "in_consistent_set", "told", "verdict",
]
#: What a row's ``told`` column may hold: what the classifier was told beyond the row's numbers (';'-joined), so that
#: its class can be recomputed from the row alone (``reclassify``).
TOLD = ("rounding only", "model decides", "absent from the model")


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
    elif reduce == "max_over_min":
        value = float(da.max(dim) / da.min(dim))
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


def acceptance(published: float, tolerance: float, relation: str = "eq") -> tuple[float, float]:
    """The interval of values that reproduce a published one (one-sided for 'ge' and 'le')."""
    slack = tolerance * (1 + 1e-9) + 1e-12 * abs(published)
    if relation == "ge":
        return published - slack, math.inf
    if relation == "le":
        return -math.inf, published + slack
    if relation == "eq":
        return published - slack, published + slack
    raise ValueError(f"unknown relation {relation!r}")


def _inside(lo: float, hi: float, region: tuple[float, float]) -> bool:
    return region[0] <= lo and hi <= region[1]


def _outside(lo: float, hi: float, region: tuple[float, float]) -> bool:
    return hi < region[0] or lo > region[1]


def classify(published: float, tolerance: float, relation: str, nominal: float, error: float, low: float, high: float,
             rounding_only: bool = False, consistent: bool | None = None, model_decides: bool = False,
             absent: str = "paper") -> str:
    """The verdict class of one comparison (see the module docstring); NaN ``error`` counts as 0.

    ``rounding_only``: only the rounding of printed values moves the row across its boundary; ``consistent``:
    whether the row matches in a maximal consistent assumption set (None: not searched, taken as yes);
    ``model_decides``: the paper's model leaves the row open whatever the inputs (the caller names why);
    ``absent``: why an undefined value is undefined, 'paper' (not printed) or 'model' (no counterpart)."""
    if not np.isfinite(nominal):
        return "no counterpart in this model" if absent == "model" else "not printed"
    if model_decides:
        return "decided by the paper's model"
    region = acceptance(published, tolerance, relation)
    e = 0.0 if not np.isfinite(error) else abs(error)
    if not _inside(nominal - e, nominal + e, region) and not _outside(nominal - e, nominal + e, region):
        return "undetermined by our numerics"
    lo = min(nominal, low if np.isfinite(low) else nominal) - e
    hi = max(nominal, high if np.isfinite(high) else nominal) + e
    if _inside(lo, hi, region):
        return "reproduced"
    if _outside(lo, hi, region):
        return "differs"
    if rounding_only:
        inside = _inside(nominal - e, nominal + e, region)
        return "reproduced at the printed digits" if inside else "differs at the printed digits"
    return "only where other rows fail" if consistent is False else "decided by an unprinted input"


def crossing_inputs(
    region: tuple[float, float], nominal: float, error: float, oat: Mapping[str, tuple[float, float]]
) -> list[str]:
    """The inputs (key paths) that, moved alone within their ranges, change the verdict."""
    e = abs(error) if np.isfinite(error) else 0.0
    base_inside = _inside(nominal - e, nominal + e, region)

    def changes(lo: float, hi: float) -> bool:  # moving this input alone reaches the other side of the boundary
        return not _inside(lo - e, hi + e, region) if base_inside else not _outside(lo - e, hi + e, region)

    return [name for name, (lo, hi) in oat.items() if np.isfinite(lo) and changes(lo, hi)]


def decided_by(
    region: tuple[float, float], nominal: float, error: float, oat: Mapping[str, tuple[float, float]]
) -> str:
    """Which inputs, moved alone within their ranges, change the verdict (else the one that moves our value most)."""
    crossing = [input_name(name) for name in crossing_inputs(region, nominal, error, oat)]
    if crossing:
        return ", ".join(crossing)
    spans = {input_name(name): hi - lo for name, (lo, hi) in oat.items() if np.isfinite(lo) and hi > lo}
    return f"jointly (largest alone: {max(spans, key=spans.get)})" if spans else "jointly"


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
                        "role": "table cell",
                        "tolerance_source": table.get("tolerance_source", HALF_DIGIT),
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


def compare(
    published: Mapping[str, Any],
    ds: xr.Dataset,
    model: str = "",
    errors: Mapping[str, tuple[float, str]] | None = None,
    uncertainty: xr.Dataset | None = None,
    causes: Mapping[str, Any] | None = None,
) -> pd.DataFrame:
    """The comparison table for one result Dataset (one model variant), one block of rows per scenario.

    ``causes`` tells the classifier what the values cannot: ``{"model_decides": {id: why}}`` names rows the paper's
    model leaves open whatever the inputs ('decided by' says why), ``{"absent": why}`` that an undefined value has no
    counterpart in this model variant (else it is taken as not printed by the paper).

    ``errors``: published id -> (our numerical error bar in the published unit, where it comes from), or -> {scenario
    index: (error bar, source)} where each scenario has its own; an id missing here has no estimate (NaN; it cannot
    make a verdict 'undetermined').  ``uncertainty``: the
    gathered input-uncertainty study (linkwork.pipeline.uncertainty.summary, searched) or None (no assumed
    input).  The first scenario's values are read from ``ds``; another scenario's from the study's nominal
    point of that scenario (with its own numerical error bars where ``errors`` gives them, else the first scenario's).
    """
    scenario_labels = (
        [str(x) for x in uncertainty.scenario.values]
        if uncertainty is not None and "scenario" in uncertainty.dims
        else [""]
    )
    rows = [
        row
        for n, label in enumerate(scenario_labels)
        for row in _scenario_rows(published, ds, model, errors or {}, uncertainty, n, label, causes or {})
    ]
    return pd.DataFrame(rows, columns=COLUMNS)


def _study_at(uncertainty: xr.Dataset | None, n: int, key: str) -> dict[str, Any] | None:
    """What the uncertainty study holds for one quantity key ('model|id') in scenario ``n`` (None if nothing)."""
    if uncertainty is None or "input" not in uncertainty.dims or uncertainty.sizes["input"] == 0:
        return None
    keys = [str(q) for q in uncertainty.quantity.values]
    if key not in keys:
        return None
    q = keys.index(key)
    inputs = [str(i) for i in uncertainty.input.values]
    kinds = (
        [str(k) for k in uncertainty.input_kind.values] if "input_kind" in uncertainty else ["assumed"] * len(inputs)
    )
    consistent = float(uncertainty.in_consistent_set.values[n, q]) if "in_consistent_set" in uncertainty else math.nan
    return {
        "nominal": float(uncertainty.nominal.values[n, q]),
        "low": float(uncertainty.low.values[n, q]),
        "high": float(uncertainty.high.values[n, q]),
        "oat": {
            name: (float(uncertainty.oat_low.values[n, k, q]), float(uncertainty.oat_high.values[n, k, q]))
            for k, name in enumerate(inputs)
        },
        "rounding": {name for name, kind in zip(inputs, kinds, strict=True) if kind == "rounding"},
        "consistent": None if not np.isfinite(consistent) else bool(consistent),
        "source": (
            f"{_scenario_samples(uncertainty, n)} samples over {len(inputs)} inputs"
            + (", then bounded searches" if "low_at" in uncertainty else "")
        ),
    }


def _scenario_samples(uncertainty: xr.Dataset, n: int) -> int:
    """How many samples the uncertainty study evaluated in scenario ``n`` (all of them where it names no scenarios)."""
    if "sample_scenario" not in uncertainty or "scenario" not in uncertainty.dims:
        return int(uncertainty.samples)
    return int(
        (np.asarray(uncertainty.sample_scenario.values).astype(str) == str(uncertainty.scenario.values[n])).sum()
    )


def _scenario_rows(published: Mapping[str, Any], ds: xr.Dataset, model: str, errors: Mapping[str, tuple[float, str]],
                   uncertainty: xr.Dataset | None, n: int, scenario: str,
                   causes: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The comparison rows of one model variant in scenario ``n`` (named ``scenario``)."""
    rows = []
    for entry in [*published.get("quantities", []), *expand_tables(published)]:
        value = float(entry["value"])
        study = _study_at(uncertainty, n, f"{model}|{entry['id']}")
        reproduced = evaluate_measure(ds, entry["measure"]) if n == 0 or study is None else study["nominal"]
        tol = tolerance_of(entry)
        relation = entry.get("relation", "eq")
        given = errors.get(entry["id"], (math.nan, "no estimate"))
        if isinstance(given, Mapping):  # per scenario index: the scenario's own error bar, else the first scenario's
            error, error_source = given.get(n, given.get(0, (math.nan, "no estimate")))
            own = n in given
        else:
            (error, error_source), own = given, n == 0
        if not own:
            error_source = f"{error_source} (the first scenario's)"
        low = high = reproduced
        source, decider, consistent, rounding_only = "no assumed input enters this number", "", None, False
        if study is not None:
            low, high, source, consistent = study["low"], study["high"], study["source"], study["consistent"]
            region = acceptance(value, tol, relation)
            crossing = crossing_inputs(region, reproduced, error, study["oat"])
            rounding_only = (
                bool(study["rounding"])
                and set(study["oat"]) <= study["rounding"]
                or bool(crossing)
                and set(crossing) <= study["rounding"]
            )
        elif entry["measure"] is None:
            source = "not reproducible: nothing to propagate"
        model_decides = (causes.get("model_decides") or {}).get(entry["id"])
        absent = "model" if causes.get("absent") else "paper"
        verdict_class = classify(value, tol, relation, reproduced, error, low, high, rounding_only, consistent,
                                 model_decides=bool(model_decides), absent=absent)
        told = [name for name, flag in zip(TOLD, (rounding_only, bool(model_decides), absent == "model")) if flag]
        if verdict_class in ("decided by an unprinted input", "only where other rows fail",
                             "reproduced at the printed digits", "differs at the printed digits"):
            decider = decided_by(acceptance(value, tol, relation), reproduced, error, study["oat"])
        elif verdict_class == "decided by the paper's model":
            decider = str(model_decides)
        elif verdict_class == "no counterpart in this model":
            source = str(causes["absent"])
        deviation = reproduced - value
        rows.append(
            {
                "model": model,
                "scenario": scenario,
                "id": entry["id"],
                "role": entry.get("role", "headline"),
                "quantity": entry["quantity"],
                "where": entry["where"],
                "published": value,
                "relation": relation,
                "unit": entry["unit"],
                "tolerance": tol,
                "tolerance_source": entry.get("tolerance_source", HALF_DIGIT),
                "reproduced": reproduced,
                "deviation": deviation,
                "relative_deviation": deviation / value if value != 0 else math.nan,
                "numerical_error": error,
                "numerical_source": error_source,
                "input_low": low,
                "input_high": high,
                "input_source": source,
                "decided_by": decider,
                "in_consistent_set": np.nan if consistent is None else float(consistent),
                "told": "; ".join(told),
                "verdict": verdict_class,
            }
        )
    return rows


def reclassify(row: Mapping[str, Any]) -> str:
    """The class ``classify`` gives a comparison row from the row alone (its numbers and what it was told): a test
    that every row's final class is the classifier's own, with no relabelling after it."""
    told = {x.strip() for x in str(row.get("told") or "").split(";") if x.strip()}
    consistent = row.get("in_consistent_set")
    consistent = None if consistent is None or not np.isfinite(float(consistent)) else bool(consistent)
    return classify(
        float(row["published"]), float(row["tolerance"]), str(row["relation"]), float(row["reproduced"]),
        float(row["numerical_error"]), float(row["input_low"]), float(row["input_high"]),
        rounding_only="rounding only" in told, consistent=consistent, model_decides="model decides" in told,
        absent="model" if "absent from the model" in told else "paper",
    )


def verdict_counts(table: pd.DataFrame) -> dict[str, int]:
    """How many rows of each verdict (all three keys always present)."""
    counts = table["verdict"].value_counts()
    return {v: int(counts.get(v, 0)) for v in VERDICTS}


#: Dimensions along which a result holds several model variants, one comparison block each.
VARIANT_DIMS = ("form", "model", "variant")


def compare_datasets(
    published: Mapping[str, Any],
    datasets: list[xr.Dataset],
    errors: Mapping[str, Mapping[str, tuple[float, str]]] | None = None,
    uncertainty: xr.Dataset | None = None,
    causes: Mapping[str, Mapping[str, Any]] | None = None,
) -> pd.DataFrame:
    """The comparison table over the merged result Datasets, one block per model variant.

    ``errors``: model variant -> published id -> (numerical error bar, source); ``causes``: model variant -> what
    the classifier is told beyond the values; see ``compare``.
    """
    ds = xr.merge(datasets, combine_attrs="drop")
    dim = next((d for d in VARIANT_DIMS if d in ds.dims), None)
    variants = [str(v) for v in ds[dim].values] if dim else [""]
    errors = errors or {}
    return pd.concat(
        [
            compare(published, ds.sel({dim: v}) if dim else ds, model=v, errors=errors.get(v), uncertainty=uncertainty,
                    causes=(causes or {}).get(v))
            for v in variants
        ],
        ignore_index=True,
    )


ROLES = ("headline", "table cell")


def counts_dataset(table: pd.DataFrame) -> xr.Dataset:
    """Verdict counts per model, scenario, role (headline claims apart from table cells) and class."""
    models = list(dict.fromkeys(table["model"]))
    scen_of = scenario_of(table)
    scens = list(dict.fromkeys(scen_of))
    counts = np.array(
        [
            [
                [
                    [
                        int(((table.model == m) & (scen_of == s) & (table.role == r) & (table.verdict == v)).sum())
                        for v in VERDICTS
                    ]
                    for r in ROLES
                ]
                for s in scens
            ]
            for m in models
        ]
    )
    return xr.Dataset(
        {
            "verdict_count": (
                ("count_model", "count_scenario", "role", "verdict"), counts,
                {"units": "1", "long_name": "comparison rows per model, scenario, role and verdict class"},
            )
        },
        coords={
            "count_model": (
                "count_model", np.array(models, dtype=object),
                {"units": "1", "long_name": "model variant of the comparison block"},
            ),
            "count_scenario": (
                "count_scenario", np.array(scens, dtype=object),
                {"units": "1", "long_name": "named scenario ('' : the paper's single reading)"},
            ),
            "role": (
                "role", np.array(ROLES, dtype=object),
                {"units": "1", "long_name": "headline claim or table cell (a trivial check)"},
            ),
            "verdict": ("verdict", np.array(VERDICTS, dtype=object), {"units": "1", "long_name": "verdict class"}),
        },
    )


def scenario_of(table: pd.DataFrame) -> pd.Series:
    """Each row's scenario as text ('' where it has none; a column empty in every row reads back from CSV as NaN)."""
    if "scenario" not in table:
        return pd.Series([""] * len(table), index=table.index, dtype=object)
    return table["scenario"].astype(object).where(table["scenario"].notna(), "").astype(str)


def nominal_rows(table: pd.DataFrame) -> pd.DataFrame:
    """The rows of the first scenario (the nominal choices) of a comparison table; all rows if it has none."""
    if "scenario" not in table or not len(table):
        return table
    scen = scenario_of(table)
    return table[scen == scen.iloc[0]]


def scenario_changes(table: pd.DataFrame) -> pd.DataFrame:
    """Per published id (and model), the rows whose verdict differs between the named scenarios: a DataFrame of the
    non-nominal scenarios' rows where the verdict is not the nominal scenario's."""
    if "scenario" not in table or not len(table):
        return table.iloc[0:0]
    first = nominal_rows(table).set_index(["model", "id"]).verdict
    scen = scenario_of(table)
    rest = table[scen != scen.iloc[0]]
    keys = list(zip(rest.model, rest.id, strict=True))
    return rest[[first.get(k) is not None and first.get(k) != v for k, v in zip(keys, rest.verdict, strict=True)]]


def input_name(path: str) -> str:
    """The short name of an uncertain input's key path ('parameters.M_P.value' -> 'M_P')."""
    return path.removesuffix(".value").rsplit(".", 1)[-1]


def findings_attrs(title: str, defensible: str, paper_model: str) -> dict[str, str]:
    """The attributes every paper's findings carry: which model is defensible and which is the paper's own (the
    answer is rendered from the paper's statements, ``linkwork.pipeline.statements``)."""
    return {"title": title, "defensible_model": defensible, "paper_model": paper_model}


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
