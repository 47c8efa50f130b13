"""Input uncertainty of the clearance paper: the assumed joint length, friction thresholds and film cap.

Each input is moved alone to both ends of its range.  A batch is one parameter variant's samples that move
the same scenes (the dry ones or the lubricated ones); it reruns only those scenes (the pipeline's tolerance)
and keeps their deviation from the ideal curve (RMS and peak per recorded cycle).  Its config holds only
those scenes' keys and the samples' moved values come as arguments, so an edit reruns only the batches whose
scenes read the edited key; samples that move the same scenes share one process (and its compiled scenes).  The gather step judges the claims for every sample, taking the nominal runs' deviations for
every other scene, so an edit of a claim's threshold reruns no scene.  The joint length and the film cap e0 enter the lubricated scenes, the friction thresholds v0 and v1 every
scene with clearance (the lubricated ones name friction for their dry contact).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ...pipeline.uncertainty import Input, apply, labelled_inputs, samples, summary


def inputs(cfg: Mapping[str, Any]) -> list[Input]:
    """The assumed inputs of the clearance section (``assumed``) with their ranges."""
    return list(labelled_inputs(cfg["assumed"], "assumed."))


def _design(cfg: Mapping[str, Any]):
    settings = cfg["uncertainty"]
    return samples(inputs(cfg), settings["lhs_points"], settings["seed"])


def batch_jobs(cfg: Mapping[str, Any]) -> list[dict[str, Any]]:
    """The batches of the whole clearance section ``cfg``: per parameter variant, the samples (but the nominal
    one) grouped by the compared scenes whose model reads a moved input; each with its samples' labels and
    moved values and those scenes.  A batch's config holds only those scenes' keys."""
    from .adapter import model_keys
    from .studies import COMPARED

    groups: dict[tuple[str, tuple[str, ...]], list[dict[str, Any]]] = {}
    for variant in cfg["variants"]:
        for sample in _design(cfg)[1:]:
            moved = [path.removesuffix(".value") for path in sample.values]
            scenes = tuple(name for name in COMPARED if any(m in model_keys(cfg, variant, name) for m in moved))
            groups.setdefault((variant, scenes), []).append({"label": sample.label, "values": dict(sample.values)})
    return [{"variant": variant, "scenes": list(scenes), "samples": members} for (variant, scenes), members in groups.items()]


def batch(cfg: Mapping[str, Any], samples: Sequence[Mapping[str, Any]], variant: str):
    """Rule study: the samples (each a label and its moved values) of one variant that move the same scenes:
    each moved scene settled and recorded over ``statistics.uncertainty_record_cycles`` cycles (a short record:
    its own confidence interval decides there), its per-cycle RMS and peak deviation from the ideal curve
    (``cfg['scenes']`` holds exactly the moved scenes; the gather step takes the nominal runs for the others)."""
    import xarray as xr

    from .studies import COMPARED, QUANTITIES, recorded, scene

    cycles = cfg["statistics"]["uncertainty_record_cycles"]
    values = np.full((len(samples), 1, 2, len(QUANTITIES), len(COMPARED), cycles), np.nan)
    settled = np.ones((len(samples), 1, len(COMPARED)))
    for i, sample in enumerate(samples):
        local = apply(cfg, sample["values"])
        for k, name in enumerate(COMPARED):
            if name in cfg.get("scenes", {}):
                run = scene(local, variant, name, "pipeline", record=cycles)
                part = recorded(run)[..., -cycles:]
                values[i, 0, ..., k, :] = part
                settled[i, 0, k] = run.attrs["settled"]
    labels = [sample["label"] for sample in samples]
    return xr.Dataset(
        {
            "cycle_deviation": (("sample", "variant", "measure", "quantity", "scene", "cycle"), values,
                                {"units": "SI of the quantity", "long_name": "RMS or peak of (scene - ideal) over each recorded cycle", "nan_meaning": "the sample does not move this scene"}),
            "settled": (("sample", "variant", "scene"), settled, {"units": "1", "long_name": "1 if the scene settled (1 where the sample does not move it)"}),
        },
        coords={
            "sample": ("sample", np.array(labels, dtype=object), {"units": "1", "long_name": "sample"}),
            "variant": ("variant", np.array([variant], dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "measure": ("measure", np.array(["rms", "peak"], dtype=object), {"units": "1", "long_name": "deviation measure"}),
            "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
            "scene": ("scene", np.array(COMPARED, dtype=object), {"units": "1", "long_name": "scene"}),
            "cycle": ("cycle", np.arange(1, cycles + 1), {"units": "1", "long_name": "recorded cycle (after settling)"}),
        },
        attrs={"title": f"clearance input uncertainty: variant {variant}, {len(labels)} samples, deviations of the moved scenes"},
    )


def sample_judgement(nominal: Any, moved: Any | None, batch: int, confidence: float, ratio: float) -> tuple[list[float], np.ndarray]:
    """The claims at one sample of one variant: the moved scenes' statistics from their short record (``moved``,
    NaN where not moved), the others' and every numerical error from the nominal claims (``nominal``, one variant).
    Returns (per claim: the decided outcome, or the nominal outcome on the means where a margin decides at the
    sample, so that noise of a short record is not read as an effect of the input; the means (measure, quantity, scene))."""
    from .statistics import HOLDS, UNDETERMINED, mean_ci
    from .studies import judge, stats_for_judging

    stats = np.stack([nominal.mean_deviation.values, nominal.ci_half_width.values, nominal.standard_error.values, nominal.ci_dof.values], axis=-1)
    if moved is not None:
        for idx in np.ndindex(stats.shape[:3]):
            x = moved.cycle_deviation.values[idx]
            if np.isfinite(x).any():
                n = int(np.isfinite(x).sum())
                mean, half, se, dof = mean_ci(x, max(1, min(batch, n // 2)), confidence)  # a short record: at least two batches
                if not moved.settled.values[idx[2]]:
                    half, se = float("inf"), float("inf")
                stats[idx] = (mean, half, se, dof)
    verdict = judge(stats_for_judging(stats, nominal.numerical_error.values), ratio, confidence)
    out = [float(o == HOLDS) if o != UNDETERMINED else float(p) for o, p in zip(verdict["outcome"], nominal.holds.values, strict=True)]
    return out, stats[..., 0]


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], claims: Any, published: Mapping[str, Any]):
    """Rule study: the claims at every sample (moved scenes from the batches, the others from the nominal
    runs in ``claims``), evaluated as the comparison reads them, with the ranges; beside them each sample's
    mean deviations (so that the report can show what an input such as the film cap e0 moves)."""
    import xarray as xr

    from ...pipeline.uncertainty import evaluate, evaluated_dataset

    ratio = cfg["claims"]["close_to_ideal_ratio"]
    batch_cycles, confidence = cfg["statistics"]["batch_cycles"], cfg["statistics"]["confidence"]
    moved = {(str(label), str(b.variant.values[0])): b.isel(sample=i, variant=0) for b in batches for i, label in enumerate(b.sample.values)}
    variants = [str(v) for v in claims.variant.values]
    ins = inputs(cfg)
    design = _design(cfg)
    rows, means = [], []
    for sample in design:
        holds, sample_means = [], []
        for variant in variants:
            out, m = sample_judgement(claims.sel(variant=variant), moved.get((sample.label, variant)), batch_cycles, confidence, ratio)
            holds.append(out)
            sample_means.append(m)
        judged = xr.Dataset({"holds": (("variant", "claim"), np.array(holds))}, coords={"variant": variants, "claim": claims.claim.values})
        rows.append(evaluate(published, [judged]))
        means.append(sample_means)
    ds = summary([evaluated_dataset(rows, ins, design)], ins)
    ds["sample_mean_deviation"] = (("sample", "variant", "measure", "response", "scene"), np.array(means),
                                   {"units": "SI of the quantity", "long_name": "mean over the recorded cycles of the deviation from the ideal curve at the sample"})
    ds = ds.assign_coords(variant=("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
                          measure=("measure", claims.measure.values, {"units": "1", "long_name": "deviation measure"}),
                          response=("response", claims.quantity.values, {"units": "1", "long_name": "compared response"}),
                          scene=("scene", claims.scene.values, {"units": "1", "long_name": "scene"}))
    ds.attrs["title"] = "Clearance: assumed joint length, friction thresholds and film cap, propagated"
    ds.attrs["sample_rule"] = ("a sample's claim is its outcome beyond the margins (its moved scenes' own short-record intervals, the nominal "
                               "numerical errors; batches of at most half the short record, so that it has two); where a margin decides at the sample, the nominal outcome")
    return ds
