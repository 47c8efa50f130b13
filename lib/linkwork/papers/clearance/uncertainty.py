"""Input uncertainty of the clearance paper: the assumed joint length, friction thresholds, impact-velocity floor and
film cap, and the initial state of the journals (a scenario).

Each assumed input is moved alone to both ends of its range, in the first start (the initial state is a scenario; the
other starts are judged at the nominal inputs).  A batch is one input's samples in one parameter variant; it reruns only
the scenes the sample's input enters, from the first start's nominal state, each settled and judged as the nominal run
is (the same settling rule from the same start: the state, its judged window, the measure on it and its interval),
without the check reruns: a sample takes the nominal run's numerical error bar.  A sample continues from the nominal
state (the run state at the start of the nominal judged window): its state is the one the nominal state moves to as the
input moves.  Its config holds only those scenes' keys and the samples' moved values come as arguments, so an edit
reruns only the batches whose scenes read the edited key.  The gather step judges the claims for every sample on its own
measures (the moved scenes from the batch, the others from the nominal runs): no sample inherits the nominal outcome.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ...pipeline.uncertainty import Input, apply, labelled_inputs, samples, summary

#: The initial state of the journals as a scenario axis (the labels of ``states.starts``).
START = "states.start"
START_REASON = (
    "the journals' initial state inside the clearance: a nonlinear linkage can settle into different states from"
    " different starts"
)


def inputs(cfg: Mapping[str, Any]) -> list[Input]:
    """The assumed inputs of the clearance section (``assumed``) with their ranges, and the start as a choice."""
    labels = tuple(s["label"] for s in cfg["states"]["starts"])
    start = (
        [
            Input(
                START, labels[0], float("nan"), float("nan"), START_REASON, labels,
                labels=tuple(f"start {x}" for x in labels),
            )
        ]
        if len(labels) > 1
        else []
    )
    return [*labelled_inputs(cfg["assumed"], "assumed."), *start]


def _design(cfg: Mapping[str, Any]):
    """The samples: every one-at-a-time sample in the first start; the other starts (scenarios) at the nominal inputs
    only (their runs are the nominal ones; the inputs are propagated from the first start, a measured cost: each start
    doubles the samples' runs)."""
    settings = cfg["uncertainty"]
    design = samples(inputs(cfg), settings["lhs_points"], settings["seed"])
    first = design[0].scenario
    return [s for s in design if s.scenario == first or not s.moved]


def _moved_values(sample) -> dict[str, Any]:
    """A sample's moved config values, without the start (a scenario, not a config value)."""
    return {k: v for k, v in sample.values.items() if k != START}


def batch_jobs(cfg: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The batches of the whole clearance section ``cfg``: one per parameter variant and moved input (its samples,
    both ends of its range, share one process: its imports, compiled code and nominal runs), with the samples'
    labels and moved values and the compared scenes whose model reads the moved input (a batch's config holds only
    those scenes' keys)."""
    from .adapter import COMPARED, model_keys

    jobs: dict[tuple[str, tuple[str, ...]], dict[str, Any]] = {}
    design = _design(cfg)
    for variant in cfg["variants"]:
        for sample in design[1:]:
            if not sample.moved or sample.scenario != design[0].scenario:
                # a start's nominal point (the nominal runs hold it), or another start's sample (the same batch computes
                # it)
                continue
            moved = tuple(path.removesuffix(".value") for path in _moved_values(sample))
            scenes = [name for name in COMPARED if any(m in model_keys(cfg, variant, name) for m in moved)]
            job = jobs.setdefault((variant, moved), {"variant": variant, "scenes": scenes, "samples": []})
            job["samples"].append({"label": sample.label, "values": _moved_values(sample)})
    return list(jobs.values())


def batch(
    cfg: Mapping[str, Any],
    samples: Sequence[Mapping[str, Any]],
    variant: str,
    nominal: Sequence[Any] = (),
    all_starts: bool = False,
):
    """Rule study: ``batch_at`` from the first start's nominal state (``all_starts``: from every start's; ``nominal``:
    the moved scenes' nominal runs), along a ``start`` dimension."""
    import xarray as xr

    starts = [str(x) for x in nominal[0].start.values][: None if all_starts else 1]
    ds = xr.concat(
        [batch_at(cfg, samples, variant, nominal, k).expand_dims(start=[s]) for k, s in enumerate(starts)], dim="start"
    )
    return ds.assign_coords(
        start=(
            "start", np.array(starts, dtype=object),
            {"units": "1", "long_name": "the start whose nominal state the sample continues"},
        )
    )


def batch_at(
    cfg: Mapping[str, Any],
    samples: Sequence[Mapping[str, Any]],
    variant: str,
    nominal: Sequence[Any] = (),
    start: int = 0,
):
    """The samples (each a label and its moved values) of one variant that move the same scenes: each
    moved scene continued from the nominal run's state (``nominal``: those scenes' nominal runs) with
    the sample's inputs, settled and judged on its state as the nominal run is (``studies.scene`` without check
    reruns).  A scene whose nominal runs never touched (no contact evaluation) is held where the sample moves only
    inputs of the contact and friction effects: they enter only in contact, so its run is the nominal one bit for bit.
    ``start``: which start's nominal state the samples continue from (the first by default)."""
    import xarray as xr

    from .adapter import EFFECT_KEYS
    from .studies import COMPARED, MEASURES, QUANTITIES, scene

    runs = {str(r.attrs["scene"]): r for r in nominal}
    contact_only = set(EFFECT_KEYS["contact"]) | set(EFFECT_KEYS["friction"])
    stats = np.full((len(samples), 1, len(MEASURES), len(QUANTITIES), len(COMPARED), len(SAMPLE_STATISTICS)), np.nan)
    state = np.full((len(samples), 1, len(COMPARED), len(SAMPLE_STATE)), np.nan)
    status = np.full((len(samples), 1, len(COMPARED)), "", dtype=object)
    held = np.zeros((len(samples), 1, len(COMPARED)))
    for i, sample in enumerate(samples):
        local = apply(cfg, sample["values"])
        moved = {path.removesuffix(".value") for path in sample["values"]}
        for k, name in enumerate(COMPARED):
            if name not in cfg.get("scenes", {}):
                continue
            base = runs[name]
            if moved <= contact_only and base.attrs["evaluations_contact"] == 0:
                run, at, held[i, 0, k] = base, start, 1.0
            else:
                run, at = (
                    scene(
                        local, variant, name, first_start_only=True, check=False,
                        memory=base.window_memory.values[start],
                    ),
                    0,
                )
            stats[i, 0, ..., k, :] = np.stack([run[v].values[at] for v in SAMPLE_STATISTICS], axis=-1)
            state[i, 0, k] = [run[v].values[at] for v in SAMPLE_STATE]
            status[i, 0, k] = str(run.state_status.values[at])
    labels = [sample["label"] for sample in samples]
    dims = ("sample", "variant", "measure", "quantity", "scene")
    return xr.Dataset(
        {
            "judged": (
                dims + ("statistic",),
                stats,
                {
                    "units": "SI of the quantity",
                    "long_name": (
                        "the claims' measure on the sample's state and its interval (as the scene run stores them)"
                    ),
                    "nan_meaning": "the sample does not move this scene (or, for an interval, as in the scene run)",
                },
            ),
            "state": (
                ("sample", "variant", "scene", "state_field"),
                state,
                {
                    "units": "1",
                    "long_name": "the sample's state: period (0: not periodic), transient, judged window",
                    "nan_meaning": "the sample does not move this scene",
                },
            ),
            "state_status": (
                ("sample", "variant", "scene"), status,
                {"units": "1", "long_name": "how the sample's state was found ('' where not moved)"},
            ),
            "held": (
                ("sample", "variant", "scene"),
                held,
                {
                    "units": "1",
                    "long_name": (
                        "1 where the scene is the nominal run (it never touched, the sample moves contact inputs only)"
                    ),
                },
            ),
        },
        coords={
            "sample": ("sample", np.array(labels, dtype=object), {"units": "1", "long_name": "sample"}),
            "variant": ("variant", np.array([variant], dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "measure": ("measure", np.array(MEASURES, dtype=object), {"units": "1", "long_name": "deviation measure"}),
            "quantity": (
                "quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"},
            ),
            "scene": ("scene", np.array(COMPARED, dtype=object), {"units": "1", "long_name": "scene"}),
            "statistic": (
                "statistic", np.array(SAMPLE_STATISTICS, dtype=object), {"units": "1", "long_name": "statistic"},
            ),
            "state_field": (
                "state_field", np.array(SAMPLE_STATE, dtype=object), {"units": "1", "long_name": "state field"},
            ),
        },
        attrs={
            "title": f"clearance input uncertainty: variant {variant}, {len(labels)} samples, the moved scenes' states"
        },
    )


#: What a sample keeps of each moved scene's run (the first start).
SAMPLE_STATISTICS = ("judged_mean", "judged_half_width", "judged_standard_error", "judged_dof", "judged_cycles")
SAMPLE_STATE = ("state_period", "state_transient", "window_first", "window_stop")


def sample_judgement(
    nominal: Any, moved: Any | None, ratio: float, confidence: float, start: int = 0
) -> tuple[dict[str, Any], np.ndarray]:
    """The claims at one sample of one variant in the first start: the moved scenes' measures and intervals from the
    sample's own runs (a state the cap cut short: no interval), the others' and every numerical error from the nominal
    claims (``nominal``: one variant; ``start``: which start's).  Returns (``studies.judge``'s verdict, the measures
    (measure, quantity, scene))."""
    from .studies import judge, read, stats_for_judging

    first = nominal.isel(start=start)
    stats = read(
        np.stack(
            [
                first.mean_deviation.values, first.ci_half_width.values, first.standard_error.values,
                first.ci_dof.values, first.judged_cycles.values,
            ],
            axis=-1,
        )
    )
    if moved is not None:
        for k in range(stats.shape[2]):
            x = read(moved.judged.values[:, :, k])
            if np.isfinite(x[..., 0]).all():
                stats[:, :, k] = x
                if str(moved.state_status.values[k]) not in ("periodic", "stationary"):
                    stats[:, :, k, 1:3] = np.inf
    verdict = judge(stats_for_judging(stats, first.numerical_error.values), ratio, confidence)
    return verdict, stats[..., 0]


def oat_orderings(
    design, ins, diffs: np.ndarray, outcomes: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per scenario, continuous input, variant and ordering: the smallest and largest difference over the samples that
    move the input alone and the scenario's nominal one; per claim, whether such a sample decides it (outcome 0 or 1)
    otherwise than the nominal, and whether one leaves it undetermined (-1) where the nominal decides it (``diffs``:
    sample, variant, comparison; ``outcomes``: sample, variant, claim)."""
    from ...pipeline.uncertainty import continuous, scenarios

    scens, ranged = [s.label for s in scenarios(ins)], continuous(ins)
    lo = np.full((len(scens), len(ranged)) + diffs.shape[1:], np.nan)
    hi, changed = np.full_like(lo, np.nan), np.zeros((len(scens), len(ranged)) + outcomes.shape[1:], dtype=int)
    left = np.zeros_like(changed)
    for n, scen in enumerate(scens):
        rows = [i for i, s in enumerate(design) if s.scenario == scen]
        base = next(i for i in rows if not design[i].moved)
        for k, inp in enumerate(ranged):
            idx = [i for i in rows if design[i].moved == inp.path]
            if not idx:  # the input is not propagated in this scenario
                continue
            idx.append(base)
            lo[n, k], hi[n, k] = diffs[idx].min(axis=0), diffs[idx].max(axis=0)
            moved = outcomes[idx[:-1]]
            changed[n, k] = ((moved >= 0) & (moved != outcomes[base])).any(axis=0)
            left[n, k] = ((moved == -1) & (outcomes[base] >= 0)).any(axis=0)
    return lo, hi, changed, left


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], claims: Any, published: Mapping[str, Any]):
    """Rule study: the claims at every sample, each judged on its own measures (moved scenes from the batches, the
    others from the nominal runs in ``claims``; the other starts from the nominal runs), evaluated as the comparison
    reads them, with the ranges; beside them each sample's measures, orderings and decided outcomes (what the
    report tabulates: the range of each claim's measure, not only 0/1)."""
    import xarray as xr

    from ...pipeline.uncertainty import evaluate, evaluated_dataset

    ratio, confidence = cfg["claims"]["close_to_ideal_ratio"], cfg["statistics"]["confidence"]
    moved = {
        (str(label), str(b.variant.values[0])): b.isel(sample=i, variant=0)
        for b in batches
        for i, label in enumerate(b.sample.values)
    }
    variants = [str(v) for v in claims.variant.values]
    starts = [str(x) for x in claims.start.values]
    ins = inputs(cfg)
    design = _design(cfg)
    rows, means, diffs, outcomes = [], [], [], []
    for sample in design:
        holds, sample_means, sample_diffs, sample_out = [], [], [], []
        n = starts.index(str(sample.values.get(START, starts[0])))
        label = sample.label.split(" | ", 1)[-1]  # the sample's label in the first start: its batch's
        for variant in variants:
            nominal = claims.sel(variant=variant)
            if sample.moved:
                batch_run = moved.get((label, variant))
                verdict, m = sample_judgement(
                    nominal, batch_run.isel(start=n) if batch_run is not None else None, ratio, confidence, start=n
                )
                # a sample enters the claim's range only where its margins decide it: an undetermined sample shows
                # neither outcome
                holds.append(np.where(np.array(verdict["outcome"]) >= 0, verdict["point"], np.nan))
                sample_out.append(verdict["outcome"])
                sample_diffs.append([r["difference"] for r in verdict["rows"]])
            else:  # a start at the nominal inputs: the nominal runs' judgement
                at = nominal.isel(start=n)
                # in the first start the nominal is one sample of the range: it enters it only where its margins decide
                # it, as every sample; in another start it is the row's value itself (no range there)
                decided = at.outcome_by_start.values >= 0 if n == 0 else np.ones(at.outcome_by_start.shape, dtype=bool)
                holds.append(np.where(decided, at.holds_by_start.values, np.nan))
                sample_out.append(at.outcome_by_start.values)
                sample_diffs.append(at.comparison_difference.values)
                m = at.mean_deviation.values
            sample_means.append(m)
        judged = xr.Dataset(
            {"holds": (("variant", "claim"), np.array(holds, dtype=float))},
            coords={"variant": variants, "claim": claims.claim.values},
        )
        rows.append(evaluate(published, [judged]))
        means.append(sample_means)
        diffs.append(sample_diffs)
        outcomes.append(sample_out)
    ds = summary([evaluated_dataset(rows, ins, design)], ins)
    for n in range(1, ds.sizes["scenario"]):  # the inputs are not propagated in the other starts: no range there
        for key in ("low", "high", "oat_low", "oat_high"):
            ds[key][n] = np.nan
    lo, hi, changed, left = oat_orderings(design, ins, np.array(diffs), np.array(outcomes, dtype=int))
    ds["sample_mean_deviation"] = (
        ("sample", "variant", "measure", "response", "scene"),
        np.array(means),
        {
            "units": "SI of the quantity",
            "long_name": "the claims' measure on the sample's state (deviation from the ideal curve)",
        },
    )
    ds["sample_comparison_difference"] = (
        ("sample", "variant", "comparison"),
        np.array(diffs),
        {
            "units": "SI of the quantity",
            "long_name": "difference the ordering is about at the sample (> 0: as claimed)",
        },
    )
    ds["sample_claim_outcome"] = (
        ("sample", "variant", "claim"), np.array(outcomes, dtype=int),
        {"units": "1", "long_name": "the claim at the sample: 1 holds, 0 fails, -1 undetermined (within its margins)"},
    )
    oat_dims = ("scenario", "input", "variant")
    ds["oat_comparison_low"] = (
        oat_dims + ("comparison",),
        lo,
        {
            "units": "SI of the quantity",
            "long_name": "smallest difference of the ordering moving this input alone (with the nominal)",
            "nan_meaning": "the input moves no sample in this scenario",
        },
    )
    ds["oat_comparison_high"] = (
        oat_dims + ("comparison",),
        hi,
        {
            "units": "SI of the quantity",
            "long_name": "largest difference of the ordering moving this input alone (with the nominal)",
            "nan_meaning": "the input moves no sample in this scenario",
        },
    )
    ds["oat_claim_changed"] = (
        oat_dims + ("claim",),
        changed,
        {
            "units": "1",
            "long_name": (
                "1 if a sample moving this input decides the claim (holds or fails) otherwise than the scenario's"
                " nominal"
            ),
        },
    )
    ds["oat_claim_left_undetermined"] = (
        oat_dims + ("claim",),
        left,
        {
            "units": "1",
            "long_name": (
                "1 if a sample moving this input leaves undetermined, within its margins, a claim the scenario's"
                " nominal decides"
            ),
        },
    )
    ds["oat_sign_changes"] = (
        (),
        int(np.sum((lo < 0) & (hi > 0))),
        {
            "units": "1",
            "long_name": (
                "(scenario, input, variant, ordering) sets whose difference changes sign over the input's range"
            ),
        },
    )
    ds["oat_orderings"] = (
        (), int(np.sum(np.isfinite(lo))),
        {"units": "1", "long_name": "(scenario, input, variant, ordering) sets propagated"},
    )
    ds = ds.assign_coords(
        variant=("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
        measure=("measure", claims.measure.values, {"units": "1", "long_name": "deviation measure"}),
        response=("response", claims.quantity.values, {"units": "1", "long_name": "compared response"}),
        scene=("scene", claims.scene.values, {"units": "1", "long_name": "scene"}),
        comparison=("comparison", claims.comparison.values, {"units": "1", "long_name": "ordering a claim is made of"}),
        claim=("claim", claims.claim.values, {"units": "1", "long_name": "claim"}),
    )
    ds.attrs["title"] = (
        "Clearance: assumed joint length, friction thresholds, impact-velocity floor and film cap, propagated; the"
        " start as a scenario"
    )
    ds.attrs["sample_rule"] = (
        "a sample's claim value is its own outcome on its measures (every ordering's difference > 0), its moved scenes"
        " settled and judged as the nominal runs are, where the sample's margins (its own intervals, the nominal"
        " numerical errors) decide it; a sample they leave undetermined enters no claim's range (sample_claim_outcome"
        " -1), the first start's nominal sample included; no sample takes the nominal outcome"
    )
    return ds
