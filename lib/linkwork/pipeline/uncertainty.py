"""Input uncertainty, propagated: which values the compared quantities take over the plausible ranges of the
assumed inputs.

Every config value the paper does not give is a labelled entry ``{value, status, reason}``; an ``assumed``
or ``inferred`` one also carries ``range: [low, high]`` (or, for a discrete modelling choice,
``choices: [...]``) and ``range_reason``.  A paper may add ranges of
its own (the beat-up paper: the rounding of its printed parameters).  The samples are the nominal point,
each input at the two ends of its range with the others nominal (one at a time), and a Latin hypercube
over all ranges (scipy.stats.qmc, a fixed seed; log-uniform where a range spans more than a decade).
A paper's ``uncertainty.results(cfg)`` computes, at one sample, the result Datasets the published numbers
are read from; ``evaluate`` reads every published quantity from them as the comparison would.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..configformat import get_path


@dataclass(frozen=True)
class Input:
    """An uncertain input: its key path in the paper's section, nominal value, range and why that range."""

    path: str
    nominal: Any
    low: float
    high: float
    reason: str
    choices: tuple = ()  # a discrete choice: its alternatives (low, high are NaN)

    @property
    def log(self) -> bool:
        return not self.choices and self.low > 0 and self.high / self.low > 10.0

    def describe(self) -> str:
        """The range as text: 'low-high' or the alternatives."""
        return " / ".join(map(str, self.choices)) if self.choices else f"{self.low:g}–{self.high:g}"


#: Attributes of a per-quantity value: NaN for a quantity the paper gives too little to compute.
NOT_REPRODUCIBLE = {"nan_meaning": "the quantity is not reproducible (the paper lacks what it needs)"}


#: Attributes of an input's range end: NaN for a discrete choice.
NO_RANGE = {"nan_meaning": "a discrete choice has no numeric range"}


def labelled_inputs(section: Mapping[str, Any], prefix: str = "") -> Iterator[Input]:
    """Every labelled entry of a section with a range (status assumed or inferred), depth first, in order."""
    for key, value in section.items():
        path = f"{prefix}{key}"
        if isinstance(value, Mapping):
            if {"value", "status", "reason"} <= set(value) and ("range" in value or "choices" in value):
                reason = str(value.get("range_reason", value["reason"]))
                if "choices" in value:
                    yield Input(path + ".value", value["value"], float("nan"), float("nan"), reason, tuple(value["choices"]))
                else:
                    low, high = (float(x) for x in value["range"])
                    yield Input(path + ".value", float(value["value"]), low, high, reason)
            else:
                yield from labelled_inputs(value, path + ".")


@dataclass(frozen=True)
class Sample:
    """One point of the study: a label and the values of the inputs it moves (path -> value)."""

    label: str
    values: dict[str, float]
    moved: str = ""  # the input moved alone (one-at-a-time samples), '' otherwise


def samples(inputs: Sequence[Input], lhs_points: int, seed: int) -> list[Sample]:
    """Nominal, each input at both ends of its range (one at a time), then ``lhs_points`` Latin-hypercube points."""
    import numpy as np

    out = [Sample("nominal", {})]
    for inp in inputs:
        if inp.choices:
            out += [Sample(f"{inp.path} {c}", {inp.path: c}, inp.path) for c in inp.choices if c != inp.nominal]
        else:
            out.append(Sample(f"{inp.path} low", {inp.path: inp.low}, inp.path))
            out.append(Sample(f"{inp.path} high", {inp.path: inp.high}, inp.path))
    if lhs_points and inputs:
        from scipy.stats import qmc

        unit = qmc.LatinHypercube(d=len(inputs), seed=seed).random(lhs_points)
        for k, row in enumerate(unit):
            values = {}
            for u, inp in zip(row, inputs, strict=True):
                if inp.choices:
                    values[inp.path] = inp.choices[min(int(u * len(inp.choices)), len(inp.choices) - 1)]
                elif inp.log:
                    values[inp.path] = float(np.exp(np.log(inp.low) + u * (np.log(inp.high) - np.log(inp.low))))
                else:
                    values[inp.path] = inp.low + u * (inp.high - inp.low)
            out.append(Sample(f"lhs {k}", values))
    return out


def apply(cfg: Mapping[str, Any], values: Mapping[str, float]) -> dict[str, Any]:
    """A deep copy of ``cfg`` with the values at the given key paths replaced (the paths must exist)."""
    out = copy.deepcopy(dict(cfg))
    for path, value in values.items():
        get_path(out, path)  # KeyError names a path the config lacks
        *parents, last = path.split(".")
        node = out
        for part in parents:
            node = node[part]
        node[last] = value
    return out


def batches(count: int, size: int) -> list[range]:
    """Sample indices split into consecutive batches of at most ``size`` (one Snakemake job each)."""
    return [range(start, min(start + size, count)) for start in range(0, count, size)]


def evaluate(published: Mapping[str, Any], datasets: Sequence[Any]) -> dict[tuple[str, str], float]:
    """Every published quantity (and table cell) read from result Datasets: (model, id) -> value."""
    import xarray as xr

    from .compare import VARIANT_DIMS, evaluate_measure, expand_tables

    ds = xr.merge(datasets, combine_attrs="drop")
    dim = next((d for d in VARIANT_DIMS if d in ds.dims), None)
    variants = [str(v) for v in ds[dim].values] if dim else [""]
    out = {}
    for variant in variants:
        part = ds.sel({dim: variant}) if dim else ds
        for entry in [*published.get("quantities", []), *expand_tables(published)]:
            out[(variant, entry["id"])] = evaluate_measure(part, entry["measure"])
    return out


def batch_dataset(cfg: Mapping[str, Any], inputs: Sequence[Input], chosen: Sequence[Sample], published: Mapping[str, Any],
                  results: Callable[[Mapping[str, Any]], Sequence[Any]]):
    """Every published quantity at each sample of a batch (dims sample x quantity)."""
    rows = [evaluate(published, results(apply(cfg, s.values))) for s in chosen]
    return evaluated_dataset(rows, inputs, chosen)


def evaluated_dataset(rows: Sequence[Mapping[tuple[str, str], float]], inputs: Sequence[Input], chosen: Sequence[Sample]):
    """The published quantities already evaluated at each sample (``evaluate``'s rows) as a batch Dataset."""
    import numpy as np
    import xarray as xr

    keys = list(rows[0])
    values = np.array([[row.get(k, np.nan) for k in keys] for row in rows])
    inputs_at = np.array([[_numeric(s.values.get(i.path, i.nominal), i) for i in inputs] for s in chosen]).reshape(len(chosen), len(inputs))
    return xr.Dataset(
        {
            "value": (("sample", "quantity"), values, {"units": "unit of the published quantity", "long_name": "our value at the sample", **NOT_REPRODUCIBLE}),
            "input_value": (("sample", "input"), inputs_at, {"units": "SI of the input", "long_name": "value of each uncertain input at the sample (a choice: its index)"}),
        },
        coords={
            "sample": ("sample", np.array([s.label for s in chosen], dtype=object), {"units": "1", "long_name": "sample"}),
            "moved": ("sample", np.array([s.moved for s in chosen], dtype=object), {"units": "1", "long_name": "input moved alone ('' if several)"}),
            "quantity": ("quantity", np.array([f"{m}|{q}" for m, q in keys], dtype=object), {"units": "1", "long_name": "model|published quantity id"}),
            "input": ("input", np.array([i.path for i in inputs], dtype=object), {"units": "1", "long_name": "uncertain input (key path)"}),
        },
    )


def summary(batches_: Sequence[Any], inputs: Sequence[Input]):
    """Gather the batches: per quantity the nominal value, the range over all samples, and per input the
    range over its one-at-a-time samples."""
    import numpy as np
    import xarray as xr

    ds = xr.concat(batches_, dim="sample", data_vars="all", coords="different", compat="equals", join="exact", combine_attrs="override")
    values = ds.value.values
    nominal = values[list(ds.sample.values).index("nominal")]
    oat_low = np.full((len(inputs), ds.sizes["quantity"]), np.nan)
    oat_high = np.full_like(oat_low, np.nan)
    moved = list(ds.moved.values)
    for k, inp in enumerate(inputs):
        rows = [i for i, m in enumerate(moved) if m == inp.path]
        if rows:
            oat_low[k] = np.nanmin(np.vstack([values[rows], nominal[None]]), axis=0)
            oat_high[k] = np.nanmax(np.vstack([values[rows], nominal[None]]), axis=0)
    with np.errstate(invalid="ignore"):
        low, high = np.nanmin(values, axis=0), np.nanmax(values, axis=0)
    out = xr.Dataset(
        {
            "nominal": ("quantity", nominal, {"units": "unit of the published quantity", "long_name": "our value at the nominal inputs", **NOT_REPRODUCIBLE}),
            "low": ("quantity", low, {"units": "unit of the published quantity", "long_name": "smallest value over every sample", **NOT_REPRODUCIBLE}),
            "high": ("quantity", high, {"units": "unit of the published quantity", "long_name": "largest value over every sample", **NOT_REPRODUCIBLE}),
            "oat_low": (("input", "quantity"), oat_low, {"units": "unit of the published quantity", "long_name": "smallest value moving this input alone", **NOT_REPRODUCIBLE}),
            "oat_high": (("input", "quantity"), oat_high, {"units": "unit of the published quantity", "long_name": "largest value moving this input alone", **NOT_REPRODUCIBLE}),
            "input_low": ("input", [i.low for i in inputs], {"units": "SI of the input", "long_name": "lower end of the input's range (NaN for a choice)", **NO_RANGE}),
            "input_high": ("input", [i.high for i in inputs], {"units": "SI of the input", "long_name": "upper end of the input's range (NaN for a choice)", **NO_RANGE}),
            "input_nominal": ("input", np.array([str(i.nominal) for i in inputs], dtype=object), {"units": "SI of the input", "long_name": "nominal value"}),
            "input_range": ("input", np.array([i.describe() for i in inputs], dtype=object), {"units": "SI of the input", "long_name": "range or alternatives"}),
            "input_reason": ("input", np.array([i.reason for i in inputs], dtype=object), {"units": "1", "long_name": "why this range"}),
            "samples": ((), ds.sizes["sample"], {"units": "1", "long_name": "samples evaluated (nominal, one at a time, Latin hypercube)"}),
            "value": ds.value,
            "input_value": ds.input_value,
        },
        coords={"quantity": ds.quantity, "input": ("input", np.array([i.path for i in inputs], dtype=object), {"units": "1", "long_name": "uncertain input (key path)"}),
                "sample": ds.sample, "moved": ds.moved},
    )
    return out


def _numeric(value: Any, inp: Input) -> float:
    return float(inp.choices.index(value)) if inp.choices else float(value)


def sample_count(inputs: Sequence[Input], lhs_points: int) -> int:
    """How many samples ``samples`` makes: nominal, two per input (the alternatives of a choice), the Latin hypercube."""
    one_at_a_time = sum(len(i.choices) - 1 if i.choices else 2 for i in inputs)
    return 1 + one_at_a_time + (lhs_points if inputs else 0)


def run_batch(cfg: Mapping[str, Any], published: Mapping[str, Any], index: int, inputs: Sequence[Input],
              results: Callable[[Mapping[str, Any]], Sequence[Any]]):
    """One batch of a paper's study (its settings in ``cfg['uncertainty']``: lhs_points, batch_size, seed)."""
    settings = cfg["uncertainty"]
    every = samples(inputs, settings["lhs_points"], settings["seed"])
    chosen = [every[i] for i in batches(len(every), settings["batch_size"])[index]]
    ds = batch_dataset(cfg, inputs, chosen, published, results)
    ds.attrs["title"] = f"input uncertainty, batch {index}"
    return ds


def gathered(inputs: Sequence[Input], batch_datasets: Sequence[Any], title: str):
    """Every batch of a paper's study in one Dataset, with the ranges."""
    ds = summary(batch_datasets, inputs)
    ds.attrs["title"] = title
    return ds
