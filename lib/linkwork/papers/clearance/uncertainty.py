"""Input uncertainty of the clearance paper: the assumed joint length, friction thresholds, impact-velocity floor and
film cap, and the initial state of the journals (a scenario).

Each assumed input is moved alone to both ends of its range, in the first start (the nominal initial state).  A
batch is one parameter variant's samples that move the same scenes (the dry ones or the lubricated ones); it reruns
only those scenes, each settled and judged as the nominal run is (the same settling rule from the same start: the
state, its judged window, the measure on it and its interval), without the check reruns: a sample takes the nominal
run's numerical error bar.  A sample continues from the nominal state (the run state at the start of the nominal
judged window): its state is the one the nominal state moves to as the input moves.  Its config holds only those scenes' keys and the samples' moved values come as
arguments, so an edit reruns only the batches whose scenes read the edited key.  The gather step judges the claims
for every sample on its own measures (the moved scenes from the batch, the others from the nominal runs): no sample
inherits the nominal outcome.  The other starts are scenarios: their claims come from the nominal runs (claims.nc),
at the nominal inputs.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ...pipeline.uncertainty import Input, apply, labelled_inputs, samples, summary

#: The initial state of the journals as a scenario axis (the labels of ``states.starts``).
START = "states.start"
START_REASON = "the journals' initial state inside the clearance: a nonlinear linkage can settle into different states from different starts"


def inputs(cfg: Mapping[str, Any]) -> list[Input]:
    """The assumed inputs of the clearance section (``assumed``) with their ranges, and the start as a choice."""
    labels = tuple(s["label"] for s in cfg["states"]["starts"])
    start = [Input(START, labels[0], float("nan"), float("nan"), START_REASON, labels, labels=tuple(f"start {x}" for x in labels))] if len(labels) > 1 else []
    return [*labelled_inputs(cfg["assumed"], "assumed."), *start]


def _design(cfg: Mapping[str, Any]):
    """The samples: every one-at-a-time sample in the first start; the other starts at the nominal inputs only (their
    runs are the nominal ones)."""
    settings = cfg["uncertainty"]
    design = samples(inputs(cfg), settings["lhs_points"], settings["seed"])
    first = design[0].scenario
    return [s for s in design if s.scenario == first or s.values.keys() <= {START} and not s.moved]


def _moved_values(sample) -> dict[str, Any]:
    """A sample's moved config values, without the start (a scenario, not a config value)."""
    return {k: v for k, v in sample.values.items() if k != START}


def batch_jobs(cfg: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The batches of the whole clearance section ``cfg``: one per parameter variant and sample (but the nominal
    ones), with the sample's label and moved values and the compared scenes whose model reads a moved input (a
    batch's config holds only those scenes' keys)."""
    from .adapter import model_keys
    from .studies import COMPARED

    jobs = []
    design = _design(cfg)
    for variant in cfg["variants"]:
        for sample in design[1:]:
            if not sample.moved:
                continue  # another start's nominal point: the nominal runs hold it
            moved = [path.removesuffix(".value") for path in _moved_values(sample)]
            scenes = [name for name in COMPARED if any(m in model_keys(cfg, variant, name) for m in moved)]
            jobs.append({"variant": variant, "scenes": scenes, "samples": [{"label": sample.label, "values": _moved_values(sample)}]})
    return jobs


def batch(cfg: Mapping[str, Any], samples: Sequence[Mapping[str, Any]], variant: str, nominal: Sequence[Any] = ()):
    """Rule study: the samples (each a label and its moved values) of one variant that move the same scenes: each
    moved scene continued from the nominal run's state (first start; ``nominal``: those scenes' nominal runs) with
    the sample's inputs, settled and judged on its state as the nominal run is (``studies.scene`` without check
    reruns).  A scene whose nominal runs never touched (no contact evaluation) is held where the sample moves only
    inputs of the contact and friction effects: they enter only in contact, so its run is the nominal one bit for bit."""
    import xarray as xr

    from .adapter import EFFECT_KEYS
    from .studies import COMPARED, QUANTITIES, scene

    runs = {str(r.attrs["scene"]): r for r in nominal}
    contact_only = set(EFFECT_KEYS["contact"]) | set(EFFECT_KEYS["friction"])
    stats = np.full((len(samples), 1, 2, len(QUANTITIES), len(COMPARED), len(SAMPLE_STATISTICS)), np.nan)
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
                run, held[i, 0, k] = base, 1.0
            else:
                run = scene(local, variant, name, first_start_only=True, check=False, memory=base.window_memory.values[0])
            stats[i, 0, ..., k, :] = np.stack([run[v].values[0] for v in SAMPLE_STATISTICS], axis=-1)
            state[i, 0, k] = [run[v].values[0] for v in SAMPLE_STATE]
            status[i, 0, k] = str(run.state_status.values[0])
    labels = [sample["label"] for sample in samples]
    dims = ("sample", "variant", "measure", "quantity", "scene")
    return xr.Dataset(
        {
            "judged": (dims + ("statistic",), stats, {"units": "SI of the quantity", "long_name": "the claims' measure on the sample's state and its interval (as the scene run stores them)",
                                                       "nan_meaning": "the sample does not move this scene (or, for an interval, as in the scene run)"}),
            "state": (("sample", "variant", "scene", "state_field"), state, {"units": "1", "long_name": "the sample's state: period (0: not periodic), transient, judged window",
                                                                             "nan_meaning": "the sample does not move this scene"}),
            "state_status": (("sample", "variant", "scene"), status, {"units": "1", "long_name": "how the sample's state was found ('' where not moved)"}),
            "held": (("sample", "variant", "scene"), held, {"units": "1", "long_name": "1 where the scene is the nominal run (it never touched, the sample moves contact inputs only)"}),
        },
        coords={
            "sample": ("sample", np.array(labels, dtype=object), {"units": "1", "long_name": "sample"}),
            "variant": ("variant", np.array([variant], dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "measure": ("measure", np.array(["rms", "peak"], dtype=object), {"units": "1", "long_name": "deviation measure"}),
            "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
            "scene": ("scene", np.array(COMPARED, dtype=object), {"units": "1", "long_name": "scene"}),
            "statistic": ("statistic", np.array(SAMPLE_STATISTICS, dtype=object), {"units": "1", "long_name": "statistic"}),
            "state_field": ("state_field", np.array(SAMPLE_STATE, dtype=object), {"units": "1", "long_name": "state field"}),
        },
        attrs={"title": f"clearance input uncertainty: variant {variant}, {len(labels)} samples, the moved scenes' states"},
    )


#: What a sample keeps of each moved scene's run (the first start).
SAMPLE_STATISTICS = ("judged_mean", "judged_half_width", "judged_standard_error", "judged_dof", "judged_cycles")
SAMPLE_STATE = ("state_period", "state_transient", "window_first", "window_stop")


def sample_judgement(nominal: Any, moved: Any | None, ratio: float, confidence: float) -> tuple[dict[str, Any], np.ndarray]:
    """The claims at one sample of one variant in the first start: the moved scenes' measures and intervals from the
    sample's own runs (a state the cap cut short: no interval), the others' and every numerical error from the
    nominal claims (``nominal``: one variant).  Returns (``studies.judge``'s verdict, the measures (measure,
    quantity, scene))."""
    from .studies import judge, read, stats_for_judging

    first = nominal.isel(start=0)
    stats = read(np.stack([first.mean_deviation.values, first.ci_half_width.values, first.standard_error.values, first.ci_dof.values, first.judged_cycles.values], axis=-1))
    if moved is not None:
        for k in range(stats.shape[2]):
            x = read(moved.judged.values[:, :, k])
            if np.isfinite(x[..., 0]).all():
                stats[:, :, k] = x
                if str(moved.state_status.values[k]) not in ("periodic", "stationary"):
                    stats[:, :, k, 1:3] = np.inf
    verdict = judge(stats_for_judging(stats, first.numerical_error.values), ratio, confidence)
    return verdict, stats[..., 0]


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], claims: Any, published: Mapping[str, Any]):
    """Rule study: the claims at every sample, each judged on its own measures (moved scenes from the batches, the
    others from the nominal runs in ``claims``; the other starts from the nominal runs), evaluated as the comparison
    reads them, with the ranges; beside them each sample's measures, orderings and decided outcomes (what the
    report tabulates: the range of each claim's measure, not only 0/1)."""
    import xarray as xr

    from ...pipeline.uncertainty import evaluate, evaluated_dataset

    ratio, confidence = cfg["claims"]["close_to_ideal_ratio"], cfg["statistics"]["confidence"]
    moved = {(str(label), str(b.variant.values[0])): b.isel(sample=i, variant=0) for b in batches for i, label in enumerate(b.sample.values)}
    variants = [str(v) for v in claims.variant.values]
    starts = [str(x) for x in claims.start.values]
    ins = inputs(cfg)
    design = _design(cfg)
    first = design[0].scenario
    rows, means, diffs, outcomes = [], [], [], []
    for sample in design:
        holds, sample_means, sample_diffs, sample_out = [], [], [], []
        for variant in variants:
            nominal = claims.sel(variant=variant)
            if sample.scenario == first:
                verdict, m = sample_judgement(nominal, moved.get((sample.label, variant)), ratio, confidence)
                holds.append(verdict["point"])
                sample_out.append(verdict["outcome"])
                sample_diffs.append([r["difference"] for r in verdict["rows"]])
            else:  # another start at the nominal inputs: the nominal runs' judgement
                k = starts.index(str(sample.values[START]))
                at = nominal.isel(start=k)
                holds.append(at.holds_by_start.values)
                sample_out.append(at.outcome_by_start.values)
                sample_diffs.append(at.comparison_difference.values)
                m = at.mean_deviation.values
            sample_means.append(m)
        judged = xr.Dataset({"holds": (("variant", "claim"), np.array(holds, dtype=float))}, coords={"variant": variants, "claim": claims.claim.values})
        rows.append(evaluate(published, [judged]))
        means.append(sample_means)
        diffs.append(sample_diffs)
        outcomes.append(sample_out)
    ds = summary([evaluated_dataset(rows, ins, design)], ins)
    ds["sample_mean_deviation"] = (("sample", "variant", "measure", "response", "scene"), np.array(means),
                                   {"units": "SI of the quantity", "long_name": "the claims' measure on the sample's state (deviation from the ideal curve)"})
    ds["sample_comparison_difference"] = (("sample", "variant", "comparison"), np.array(diffs),
                                          {"units": "SI of the quantity", "long_name": "difference the ordering is about at the sample (> 0: as claimed)"})
    ds["sample_claim_outcome"] = (("sample", "variant", "claim"), np.array(outcomes, dtype=int),
                                  {"units": "1", "long_name": "the claim at the sample: 1 holds, 0 fails, -1 undetermined (within its margins)"})
    ds = ds.assign_coords(variant=("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
                          measure=("measure", claims.measure.values, {"units": "1", "long_name": "deviation measure"}),
                          response=("response", claims.quantity.values, {"units": "1", "long_name": "compared response"}),
                          scene=("scene", claims.scene.values, {"units": "1", "long_name": "scene"}),
                          comparison=("comparison", claims.comparison.values, {"units": "1", "long_name": "ordering a claim is made of"}),
                          claim=("claim", claims.claim.values, {"units": "1", "long_name": "claim"}))
    ds.attrs["title"] = "Clearance: assumed joint length, friction thresholds, impact-velocity floor and film cap, propagated; the start as a scenario"
    ds.attrs["sample_rule"] = ("a sample's claim value is its own outcome on its measures (every ordering's difference > 0), its moved scenes settled and "
                               "judged as the nominal runs are; sample_claim_outcome adds the margins (the sample's own intervals, the nominal numerical "
                               "errors); no sample takes the nominal outcome")
    return ds


def contact_law(cfg: Mapping[str, Any], variant: str, law: str, nominal: Sequence[Any] = ()):
    """Rule study: the compared scenes with contact under another elastic law (``law``, e.g. the conformal one), each
    continued from its nominal state (first start) and judged on its own state as an input-uncertainty sample is
    (``batch`` with the law as the moved value; a scene whose nominal runs never touched is held: the law acts only
    in contact).  The sensitivity of the verdicts to the contact law."""
    return batch(cfg, [{"label": f"elastic law {law}", "values": {"joints.elastic_law": law}}], variant, nominal=nominal)


def law_judgement(nominal: Any, law_run: Any, ratio: float, confidence: float) -> dict[str, Any]:
    """The claims of one variant under the other contact law (``law_run``: ``contact_law``'s result), the nominal
    numerical errors kept: ``studies.judge``'s verdict."""
    verdict, _ = sample_judgement(nominal, law_run.isel(sample=0, variant=0), ratio, confidence)
    return verdict
