"""Input uncertainty of the clearance paper: the assumed joint length, friction thresholds and film cap.

Each input is moved alone to both ends of its range.  A batch is one sample in one parameter variant; it
reruns only the scenes whose model reads a moved input (the pipeline's tolerance) and keeps their
deviation from the ideal curve (RMS and peak per recorded cycle).  Its config holds only those scenes'
keys and the moved values come as arguments, so an edit reruns only the batches whose scenes read the
edited key.  The gather step judges the claims for every sample, taking the nominal runs' deviations for
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
    """The batches of the whole clearance section ``cfg``: one per sample (but the nominal one) and parameter
    variant, with the sample's label and moved values and the compared scenes whose model reads a moved
    input.  A batch's config holds only those scenes' keys."""
    from .adapter import model_keys
    from .studies import COMPARED

    jobs = []
    for sample in _design(cfg)[1:]:
        moved = [path.removesuffix(".value") for path in sample.values]
        for variant in cfg["variants"]:
            scenes = [name for name in COMPARED if any(m in model_keys(cfg, variant, name) for m in moved)]
            jobs.append({"sample": sample.label, "values": dict(sample.values), "variant": variant, "scenes": scenes})
    return jobs


def batch(cfg: Mapping[str, Any], sample: str, values: Mapping[str, Any], variant: str, ideal: Any):
    """Rule study: one sample (its label and moved values) in one variant: the deviations from the ideal run
    of the scenes it moves (``cfg['scenes']`` holds exactly those; the gather step takes the nominal
    deviations of the others)."""
    import xarray as xr

    from .studies import COMPARED, QUANTITIES, deviation_measures, scene

    cycles = cfg["numerics"]["record_cycles"]
    local = apply(cfg, values)
    rms = np.full((1, 1, len(QUANTITIES), len(COMPARED), cycles), np.nan)
    peak = np.full_like(rms, np.nan)
    for k, name in enumerate(COMPARED):
        if name in cfg.get("scenes", {}):
            run = scene(local, variant, name, "pipeline")
            for q, quantity in enumerate(QUANTITIES):
                m = deviation_measures(run, ideal, quantity, cycles)
                rms[0, 0, q, k], peak[0, 0, q, k] = m["rms"], m["peak"]
    dims = ("sample", "variant", "quantity", "scene", "cycle")
    return xr.Dataset(
        {
            "rms_deviation": (dims, rms, {"units": "SI of the quantity", "long_name": "RMS of (scene - ideal) over a cycle", "nan_meaning": "the sample does not move this scene"}),
            "peak_deviation": (dims, peak, {"units": "SI of the quantity", "long_name": "peak |scene - ideal| over a cycle", "nan_meaning": "the sample does not move this scene"}),
        },
        coords={
            "sample": ("sample", np.array([sample], dtype=object), {"units": "1", "long_name": "sample"}),
            "variant": ("variant", np.array([variant], dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
            "scene": ("scene", np.array(COMPARED, dtype=object), {"units": "1", "long_name": "scene"}),
            "cycle": ("cycle", np.arange(1, cycles + 1), {"units": "1", "long_name": "recorded cycle"}),
        },
        attrs={"title": f"clearance input uncertainty: {sample}, variant {variant}, deviations of the moved scenes"},
    )


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], claims: Any, published: Mapping[str, Any]):
    """Rule study: the claims at every sample (moved scenes from the batches, the others from the nominal
    runs' deviations in ``claims``), evaluated as the comparison reads them, with the ranges."""
    import xarray as xr

    from ...pipeline.uncertainty import evaluate, evaluated_dataset
    from .studies import claims_hold

    ratio = cfg["claims"]["close_to_ideal_ratio"]
    nominal = claims.sel(tolerance_set="pipeline")
    moved = {(str(b.sample.values[0]), str(b.variant.values[0])): b.isel(sample=0, variant=0) for b in batches}
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
