"""The heald paper's comparison and findings: each claim per chain model at the assumed parameters, and the
ranges of each swept parameter over which it holds."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, counts_dataset, tolerance_of, where_true
from ...units import RAD_S_PER_RPM

CLAIMS = ("force_E_many_times_F", "forces_grow_with_frequency", "limit_41_89")
SWEEPS = ("reaction_ratio", "clearance", "heald_mass", "warp_stiffness")


def support(chain: xr.Dataset, many_times: float, limit: float, limit_tolerance: float) -> dict[str, np.ndarray]:
    """Per model, claim and sweep: where along the sweep the claim holds (text; '' where not swept for that claim)."""
    models = [str(m) for m in chain.model.values]
    text = np.full((len(models), len(CLAIMS), len(SWEEPS)), "", dtype=object)
    for i, m in enumerate(models):
        s = chain.sel(model=m)
        tests = {
            ("force_E_many_times_F", "reaction_ratio"): s.ratio_EF_min_vs_reaction_ratio >= many_times,
            ("force_E_many_times_F", "clearance"): s.ratio_EF_min_vs_clearance >= many_times,
            ("forces_grow_with_frequency", "heald_mass"): s.growth_fraction_vs_heald_mass >= 1.0,
            ("forces_grow_with_frequency", "warp_stiffness"): s.growth_fraction_vs_warp_stiffness >= 1.0,
            ("limit_41_89", "heald_mass"): np.abs(s.first_resonance_vs_heald_mass - limit) <= limit_tolerance,
            ("limit_41_89", "warp_stiffness"): np.abs(s.first_resonance_vs_warp_stiffness - limit) <= limit_tolerance,
        }
        for (claim, sweep), ok in tests.items():
            text[i, CLAIMS.index(claim), SWEEPS.index(sweep)] = where_true(chain[sweep].values, ok.values)
    return {"models": models, "text": text}


def compare(cfg: Mapping[str, Any], published: Mapping[str, Any], chain: xr.Dataset) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table per model and the support ranges of every claim."""
    table = compare_datasets(published, [chain])
    pub = {q["id"]: q for q in published["quantities"]}
    limit = float(pub["limit_41_89"]["value"])
    sup = support(chain, cfg["claims"]["many_times"], limit, tolerance_of(pub["limit_41_89"]))
    findings = xr.Dataset(
        {
            "holds_for": (("model", "claim", "sweep"), sup["text"], {"units": "1", "long_name": "sub-ranges of the swept parameter over which the claim holds"}),
            "limit_rad_s": ((), limit, {"units": "rad s-1", "long_name": "the paper's speed limit"}),
            "limit_rpm": ((), limit / RAD_S_PER_RPM, {"units": "min-1", "long_name": "the paper's speed limit as a shaft speed"}),
            "limit_band": ((), tolerance_of(pub["limit_41_89"]), {"units": "rad s-1", "long_name": "half-width of the band around the limit (our reading)"}),
            "many_times": ((), float(cfg["claims"]["many_times"]), {"units": "1", "long_name": "ratio read as 'many times' (our reading)"}),
        },
        coords={
            "model": ("model", np.array(sup["models"], dtype=object), {"units": "1", "long_name": "chain model"}),
            "claim": ("claim", np.array(CLAIMS, dtype=object), {"units": "1", "long_name": "published claim"}),
            "sweep": ("sweep", np.array(SWEEPS, dtype=object), {"units": "1", "long_name": "swept parameter"}),
        },
    )
    findings = findings.merge(counts_dataset(table))
    findings.attrs.update(title="Heald paper: comparison findings", reference_model=str(chain.model.values[0]))
    return table, findings
