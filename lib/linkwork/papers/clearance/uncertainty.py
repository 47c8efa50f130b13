"""Input uncertainty of the clearance paper: the assumed joint length, friction thresholds and film cap.

Each input is moved alone to both ends of its range.  A batch is one parameter variant's samples that move
the same scenes (the dry ones or the lubricated ones); it reruns only those scenes (the pipeline's tolerance)
and keeps their deviation from the ideal curve (RMS and peak per recorded cycle).  Its config holds only
those scenes' keys and the samples' moved values come as arguments, so an edit reruns only the batches whose
scenes read the edited key; samples that move the same scenes share one process (and its compiled scenes).  The gather step judges the claims for every sample, taking the nominal runs' deviations for
every other scene, so an edit of a claim's threshold reruns no scene.  The joint length and the film cap e0 enter the lubricated scenes, the friction thresholds v0 and v1 the
dry ones.
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


def batch(cfg: Mapping[str, Any], samples: Sequence[Mapping[str, Any]], variant: str, ideal: Any):
    """Rule study: the samples (each a label and its moved values) of one variant that move the same scenes:
    the deviations from the ideal run of those scenes (``cfg['scenes']`` holds exactly them; the gather step
    takes the nominal deviations of the others)."""
    import xarray as xr

    from .studies import COMPARED, QUANTITIES, deviation_measures, scene

    cycles = cfg["numerics"]["record_cycles"]
    rms = np.full((len(samples), 1, len(QUANTITIES), len(COMPARED), cycles), np.nan)
    peak = np.full_like(rms, np.nan)
    for i, sample in enumerate(samples):
        local = apply(cfg, sample["values"])
        for k, name in enumerate(COMPARED):
            if name in cfg.get("scenes", {}):
                run = scene(local, variant, name, "pipeline")
                for q, quantity in enumerate(QUANTITIES):
                    m = deviation_measures(run, ideal, quantity, cycles)
                    rms[i, 0, q, k], peak[i, 0, q, k] = m["rms"], m["peak"]
    labels = [sample["label"] for sample in samples]
    dims = ("sample", "variant", "quantity", "scene", "cycle")
    return xr.Dataset(
        {
            "rms_deviation": (dims, rms, {"units": "SI of the quantity", "long_name": "RMS of (scene - ideal) over a cycle", "nan_meaning": "the sample does not move this scene"}),
            "peak_deviation": (dims, peak, {"units": "SI of the quantity", "long_name": "peak |scene - ideal| over a cycle", "nan_meaning": "the sample does not move this scene"}),
        },
        coords={
            "sample": ("sample", np.array(labels, dtype=object), {"units": "1", "long_name": "sample"}),
            "variant": ("variant", np.array([variant], dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
            "scene": ("scene", np.array(COMPARED, dtype=object), {"units": "1", "long_name": "scene"}),
            "cycle": ("cycle", np.arange(1, cycles + 1), {"units": "1", "long_name": "recorded cycle"}),
        },
        attrs={"title": f"clearance input uncertainty: variant {variant}, {len(labels)} samples, deviations of the moved scenes"},
    )


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], claims: Any, published: Mapping[str, Any]):
    """Rule study: the claims at every sample (moved scenes from the batches, the others from the nominal
    runs' deviations in ``claims``), evaluated as the comparison reads them, with the ranges."""
    import xarray as xr

    from ...pipeline.uncertainty import evaluate, evaluated_dataset
    from .studies import claims_hold

    ratio = cfg["claims"]["close_to_ideal_ratio"]
    nominal = claims.sel(tolerance_set="pipeline")
    moved = {(str(label), str(b.variant.values[0])): b.isel(sample=i, variant=0) for b in batches for i, label in enumerate(b.sample.values)}
    variants = [str(v) for v in nominal.variant.values]
    ins = inputs(cfg)
    design = _design(cfg)
    rows = []
    for sample in design:
        holds = []
        for variant in variants:
            base = nominal.sel(variant=variant)
            rms, peak = base.rms_deviation.values, base.peak_deviation.values
            if (sample.label, variant) in moved:
                part = moved[(sample.label, variant)]
                rms = np.where(np.isnan(part.rms_deviation.values), rms, part.rms_deviation.values)
                peak = np.where(np.isnan(part.peak_deviation.values), peak, part.peak_deviation.values)
            holds.append([[h] for h in claims_hold(rms, peak, ratio)])
        judged = xr.Dataset({"holds": (("variant", "claim", "tolerance_set"), np.array(holds))},
                            coords={"variant": variants, "claim": claims.claim.values, "tolerance_set": ["pipeline"]})
        rows.append(evaluate(published, [judged]))
    ds = summary([evaluated_dataset(rows, ins, design)], ins)
    ds.attrs["title"] = "Clearance: assumed joint length, friction thresholds and film cap, propagated"
    return ds
