"""Input uncertainty, propagated: which values the compared quantities take over the plausible ranges of the
assumed inputs, per named scenario.

Every config value the paper does not give is a labelled entry ``{value, status, reason}``.  Inputs come in
three kinds:

* an assumed or inferred continuous input carries ``range: [low, high]`` and ``range_reason``;
* a printed value's rounding (the beat-up paper's ``printed_rounding``): an input of kind ``rounding``, which
  the comparison keeps apart from assumptions (a verdict sensitive to the last printed digit);
* a discrete modelling choice carries ``choices: [...]`` (and ``choice_labels``, their names in prose): a
  named **scenario** axis, never a sampled value.  The study runs once per scenario, the cartesian product of
  a paper's choices, nominal choices first.

Per scenario the samples are the nominal point, each continuous input at the two ends of its range with the
others nominal (one at a time), every corner of the box where the inputs are few (``search.corner_limit``)
and a Latin hypercube over all ranges (scipy.stats.qmc, a fixed seed; log-uniform where a range spans more
than a decade).  The samples only start the searches of ``linkwork.pipeline.search``, which find each value's
minimum and maximum over the box and the best consistent assumption set.  A paper's ``uncertainty.results(cfg)``
computes, at one sample, the result Datasets the published numbers are read from; ``evaluate`` reads every
published quantity from them as the comparison would.
"""

from __future__ import annotations

import copy
import itertools
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
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
    choices: tuple = ()  # a discrete choice (a scenario axis): its alternatives (low, high are NaN)
    kind: str = "assumed"  # 'assumed' (a plausible range) or 'rounding' (half a unit of a printed value's last digit)
    labels: tuple = ()  # a choice's names in prose, one per alternative ('gravity on'); the values' text if empty

    @property
    def log(self) -> bool:
        return not self.choices and self.low > 0 and self.high / self.low > 10.0

    def describe(self) -> str:
        """The range as text: 'low-high' or the alternatives."""
        return " / ".join(self.label_of(c) for c in self.choices) if self.choices else f"{self.low:g}–{self.high:g}"

    def label_of(self, choice: Any) -> str:
        """The name in prose of one alternative of a choice."""
        return str(self.labels[self.choices.index(choice)]) if self.labels else str(choice)

    def to_value(self, u: float) -> float:
        """The input's value at unit coordinate ``u`` in [0, 1] of its range (log-uniform for a log range)."""
        import numpy as np

        if u <= 0.0 or u >= 1.0:  # the ends exactly
            return float(self.low if u <= 0.0 else self.high)
        if self.log:
            return float(np.exp(np.log(self.low) + u * (np.log(self.high) - np.log(self.low))))
        return float(self.low + u * (self.high - self.low))

    def to_unit(self, value: float) -> float:
        """The unit coordinate of a value (inverse of ``to_value``)."""
        import numpy as np

        if self.high == self.low:
            return 0.5
        if self.log:
            return float((np.log(value) - np.log(self.low)) / (np.log(self.high) - np.log(self.low)))
        return float((value - self.low) / (self.high - self.low))


#: Attributes of a per-quantity value: NaN for a quantity the paper gives too little to compute.
NOT_REPRODUCIBLE = {"nan_meaning": "the quantity is not reproducible (the paper lacks what it needs)"}


#: Attributes of an input's range end: NaN for a discrete choice.
NO_RANGE = {"nan_meaning": "a discrete choice has no numeric range"}


def labelled_inputs(section: Mapping[str, Any], prefix: str = "") -> Iterator[Input]:
    """Every labelled entry of a section with a range (status assumed or inferred), depth first, in order."""
    for key, value in section.items():
        path = f"{prefix}{key}"
        if isinstance(value, Mapping):
            if "value" in value and (
                "range" in value or "choices" in value
            ):  # a rule passes values and design fields only
                reason = str(value.get("range_reason", value.get("reason", "")))
                if "choices" in value:
                    yield Input(
                        path + ".value", value["value"], float("nan"), float("nan"), reason, tuple(value["choices"]),
                        labels=tuple(value.get("choice_labels", ())),
                    )
                else:
                    low, high = (float(x) for x in value["range"])
                    yield Input(path + ".value", float(value["value"]), low, high, reason)
            else:
                yield from labelled_inputs(value, path + ".")


@dataclass(frozen=True)
class Scenario:
    """One combination of a paper's discrete choices: its name in prose and the values it sets (path -> choice)."""

    label: str
    values: dict = field(default_factory=dict)


def continuous(inputs: Sequence[Input]) -> list[Input]:
    """The inputs that are sampled (those with a range): every input but the choices."""
    return [i for i in inputs if not i.choices]


def scenarios(inputs: Sequence[Input]) -> list[Scenario]:
    """Every combination of the choices among ``inputs``, the nominal one first (each axis nominal first).

    Without choices: one scenario named '' (the paper's single reading)."""
    axes = [i for i in inputs if i.choices]
    ordered = [[i.nominal, *[c for c in i.choices if c != i.nominal]] for i in axes]
    out = []
    for combo in itertools.product(*ordered):
        label = ", ".join(i.label_of(c) for i, c in zip(axes, combo, strict=True))
        out.append(Scenario(label, {i.path: c for i, c in zip(axes, combo, strict=True)}))
    return out


@dataclass(frozen=True)
class Sample:
    """One point of the study: a label, the values of the inputs it moves (path -> value), the scenario."""

    label: str
    values: dict[str, float]
    moved: str = ""  # the input moved alone (one-at-a-time samples), '' otherwise
    scenario: str = ""  # the scenario's name ('' without choices)


def _prefix(scenario: Scenario, first: bool) -> str:
    return "" if first else f"{scenario.label} | "


def samples(inputs: Sequence[Input], lhs_points: int, seed: int, corner_limit: int = 0) -> list[Sample]:
    """Per scenario: nominal, each continuous input at both ends of its range (one at a time), every corner of
    the box if there are at most ``corner_limit`` of them, then ``lhs_points`` Latin-hypercube points (the same
    unit points in every scenario).  The first scenario's labels carry no prefix."""
    import numpy as np

    ranged = continuous(inputs)
    unit = np.empty((0, len(ranged)))
    if lhs_points and ranged:
        from scipy.stats import qmc

        unit = qmc.LatinHypercube(d=len(ranged), seed=seed).random(lhs_points)
    corners = (
        list(itertools.product((0.0, 1.0), repeat=len(ranged))) if ranged and 2 ** len(ranged) <= corner_limit else []
    )
    out = []
    for n, scen in enumerate(scenarios(inputs)):
        pre, fixed = _prefix(scen, n == 0), dict(scen.values)
        out.append(Sample(f"{pre}nominal", dict(fixed), scenario=scen.label))
        for inp in ranged:
            out.append(Sample(f"{pre}{inp.path} low", {**fixed, inp.path: inp.low}, inp.path, scen.label))
            out.append(Sample(f"{pre}{inp.path} high", {**fixed, inp.path: inp.high}, inp.path, scen.label))
        for k, corner in enumerate(corners):
            values = {i.path: i.to_value(u) for i, u in zip(ranged, corner, strict=True)}
            out.append(Sample(f"{pre}corner {k}", {**fixed, **values}, scenario=scen.label))
        for k, row in enumerate(unit):
            values = {i.path: i.to_value(u) for i, u in zip(ranged, row, strict=True)}
            out.append(Sample(f"{pre}lhs {k}", {**fixed, **values}, scenario=scen.label))
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


def batch_dataset(
    cfg: Mapping[str, Any],
    inputs: Sequence[Input],
    chosen: Sequence[Sample],
    published: Mapping[str, Any],
    results: Callable[[Mapping[str, Any]], Sequence[Any]],
):
    """Every published quantity at each sample of a batch (dims sample x quantity)."""
    rows = [evaluate(published, results(apply(cfg, s.values))) for s in chosen]
    return evaluated_dataset(rows, inputs, chosen)


def evaluated_dataset(
    rows: Sequence[Mapping[tuple[str, str], float]], inputs: Sequence[Input], chosen: Sequence[Sample]
):
    """The published quantities already evaluated at each sample (``evaluate``'s rows) as a batch Dataset."""
    import numpy as np
    import xarray as xr

    keys = list(rows[0])
    values = np.array([[row.get(k, np.nan) for k in keys] for row in rows])
    ranged = continuous(inputs)
    inputs_at = np.array([[float(s.values.get(i.path, i.nominal)) for i in ranged] for s in chosen]).reshape(
        len(chosen), len(ranged)
    )
    return xr.Dataset(
        {
            "value": (
                ("sample", "quantity"), values,
                {"units": "unit of the published quantity", "long_name": "our value at the sample", **NOT_REPRODUCIBLE},
            ),
            "input_value": (
                ("sample", "input"), inputs_at,
                {"units": "SI of the input", "long_name": "value of each uncertain continuous input at the sample"},
            ),
        },
        coords={
            "sample": (
                "sample", np.array([s.label for s in chosen], dtype=object), {"units": "1", "long_name": "sample"},
            ),
            "moved": (
                "sample", np.array([s.moved for s in chosen], dtype=object),
                {"units": "1", "long_name": "input moved alone ('' if several)"},
            ),
            "sample_scenario": (
                "sample", np.array([s.scenario for s in chosen], dtype=object),
                {"units": "1", "long_name": "scenario of the sample"},
            ),
            "quantity": (
                "quantity", np.array([f"{m}|{q}" for m, q in keys], dtype=object),
                {"units": "1", "long_name": "model|published quantity id"},
            ),
            "input": (
                "input", np.array([i.path for i in ranged], dtype=object),
                {"units": "1", "long_name": "uncertain input (key path)"},
            ),
        },
    )


def summary(batches_: Sequence[Any], inputs: Sequence[Input]):
    """Gather the batches: per scenario and quantity the nominal value and the range over the scenario's samples,
    and per continuous input the range over its one-at-a-time samples (dims scenario x [input x] quantity)."""
    import numpy as np
    import xarray as xr

    ds = xr.concat(
        batches_, dim="sample", data_vars="all", coords="different", compat="equals", join="exact",
        combine_attrs="override",
    )
    if "sample_scenario" not in ds:
        ds["sample_scenario"] = ("sample", np.full(ds.sizes["sample"], "", dtype=object))
    values, moved, labels = ds.value.values, list(ds.moved.values), [str(x) for x in ds.sample.values]
    of = [str(x) for x in ds.sample_scenario.values]
    scens = scenarios(inputs)
    ranged = continuous(inputs)
    shape = (len(scens), ds.sizes["quantity"])
    nominal, low, high = np.full(shape, np.nan), np.full(shape, np.nan), np.full(shape, np.nan)
    oat_low = np.full((len(scens), len(ranged), ds.sizes["quantity"]), np.nan)
    oat_high = np.full_like(oat_low, np.nan)
    for n, scen in enumerate(scens):
        rows = [i for i, o in enumerate(of) if o == scen.label]
        if not rows:
            continue
        nominal[n] = values[labels.index(f"{_prefix(scen, n == 0)}nominal")]
        low[n], high[n] = _nan_extremes(values[rows])
        for k, inp in enumerate(ranged):
            moved_rows = [i for i in rows if moved[i] == inp.path]
            if moved_rows:
                oat_low[n, k], oat_high[n, k] = _nan_extremes(np.vstack([values[moved_rows], nominal[n][None]]))
    axes = [i for i in inputs if i.choices]
    unit = "unit of the published quantity"
    out = xr.Dataset(
        {
            "nominal": (
                ("scenario", "quantity"), nominal,
                {"units": unit, "long_name": "our value at the nominal inputs of the scenario", **NOT_REPRODUCIBLE},
            ),
            "low": (
                ("scenario", "quantity"), low,
                {"units": unit, "long_name": "smallest value over the assumed inputs' box", **NOT_REPRODUCIBLE},
            ),
            "high": (
                ("scenario", "quantity"), high,
                {"units": unit, "long_name": "largest value over the assumed inputs' box", **NOT_REPRODUCIBLE},
            ),
            "oat_low": (
                ("scenario", "input", "quantity"), oat_low,
                {"units": unit, "long_name": "smallest value moving this input alone", **NOT_REPRODUCIBLE},
            ),
            "oat_high": (
                ("scenario", "input", "quantity"), oat_high,
                {"units": unit, "long_name": "largest value moving this input alone", **NOT_REPRODUCIBLE},
            ),
            "input_low": (
                "input", [i.low for i in ranged],
                {"units": "SI of the input", "long_name": "lower end of the input's range"},
            ),
            "input_high": (
                "input", [i.high for i in ranged],
                {"units": "SI of the input", "long_name": "upper end of the input's range"},
            ),
            "input_nominal": (
                "input", np.array([str(i.nominal) for i in ranged], dtype=object),
                {"units": "SI of the input", "long_name": "nominal value"},
            ),
            "input_range": (
                "input", np.array([i.describe() for i in ranged], dtype=object),
                {"units": "SI of the input", "long_name": "range"},
            ),
            "input_reason": (
                "input", np.array([i.reason for i in ranged], dtype=object),
                {"units": "1", "long_name": "why this range"},
            ),
            "input_kind": (
                "input", np.array([i.kind for i in ranged], dtype=object),
                {"units": "1", "long_name": "assumed (a plausible range) or rounding (the last printed digit)"},
            ),
            "scenario_choice": (
                ("scenario", "choice"),
                np.array([[s.values[a.path] for a in axes] for s in scens], dtype=object)
                .astype(str)
                .reshape(len(scens), len(axes))
                .astype(object),
                {"units": "1", "long_name": "the value each choice takes in the scenario"},
            ),
            "choice_reason": (
                "choice", np.array([a.reason for a in axes], dtype=object),
                {"units": "1", "long_name": "why the choice is open"},
            ),
            "samples": (
                (),
                ds.sizes["sample"],
                {
                    "units": "1",
                    "long_name": "samples evaluated (nominal, one at a time, corners, Latin hypercube; every scenario)",
                },
            ),
            "value": ds.value,
            "input_value": ds.input_value,
        },
        coords={
            "quantity": ds.quantity,
            "input": (
                "input", np.array([i.path for i in ranged], dtype=object),
                {"units": "1", "long_name": "uncertain input (key path)"},
            ),
            "scenario": (
                "scenario", np.array([s.label for s in scens], dtype=object),
                {"units": "1", "long_name": "named scenario (discrete choices), nominal first"},
            ),
            "choice": (
                "choice", np.array([a.path for a in axes], dtype=object),
                {"units": "1", "long_name": "discrete choice (key path)"},
            ),
            "sample": ds.sample,
            "moved": ds.moved,
            "sample_scenario": ds.sample_scenario,
        },
    )
    out.attrs["interval_method"] = "samples only (nominal, one at a time, corners, Latin hypercube)"
    return out


def _nan_extremes(values):
    """Column-wise min and max ignoring NaN (NaN where a column holds only NaN: a quantity not reproducible)."""
    import warnings

    import numpy as np

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nanmin(values, axis=0), np.nanmax(values, axis=0)


def sample_count(inputs: Sequence[Input], lhs_points: int, corner_limit: int = 0) -> int:
    """How many samples ``samples`` makes: per scenario nominal, two per continuous input, the corners, the Latin
    hypercube."""
    ranged = continuous(inputs)
    corners = 2 ** len(ranged) if ranged and 2 ** len(ranged) <= corner_limit else 0
    per_scenario = 1 + 2 * len(ranged) + corners + (lhs_points if ranged else 0)
    return per_scenario * len(scenarios(inputs))


def design(inputs: Sequence[Input], settings: Mapping[str, Any]) -> list[Sample]:
    """The whole sample design of a paper's study (its ``uncertainty`` settings)."""
    corner_limit = settings.get("search", {}).get("corner_limit", 0)
    return samples(inputs, settings["lhs_points"], settings["seed"], corner_limit)


def run_batch(cfg: Mapping[str, Any], published: Mapping[str, Any], index: int, inputs: Sequence[Input],
              results: Callable[[Mapping[str, Any]], Sequence[Any]]):
    """One batch of a paper's study (its settings in ``cfg['uncertainty']``: lhs_points, batch_size, seed, search)."""
    settings = cfg["uncertainty"]
    every = design(inputs, settings)
    chosen = [every[i] for i in batches(len(every), settings["batch_size"])[index]]
    ds = batch_dataset(cfg, inputs, chosen, published, results)
    ds.attrs["title"] = f"input uncertainty, batch {index}"
    return ds


def gathered(
    inputs: Sequence[Input],
    batch_datasets: Sequence[Any],
    title: str,
    search: Callable[..., Any] | None = None,
    workers: int = 1,
):
    """Every batch of a paper's study in one Dataset, with the ranges; ``search`` (a Dataset -> Dataset step of
    ``linkwork.pipeline.search``, run in ``workers`` processes) replaces the samples' ranges by the box's extremes and
    adds the consistent sets."""
    ds = summary(batch_datasets, inputs)
    if search is not None:
        ds = search(ds, workers)
    ds.attrs["title"] = title
    return ds
