"""The heald paper's comparison and findings: each claim per chain model at the assumed parameters, and the
ranges of each swept parameter over which it holds."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, count_text, counts_dataset, findings_attrs, tolerance_of, where_true
from ...units import RAD_S_PER_RPM

#: Model A is the physical linkage (defensible); model B is the chain of the form of the paper's eq. (2).
DEFENSIBLE, PAPER_MODEL = "A", "B"
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


def numerical_errors(chain: xr.Dataset, accuracy: xr.Dataset) -> dict[str, tuple[float, str]]:
    """Our numerical error bar of each claim's measure (the same for both models, relative ones scaled per model)."""
    pipeline = float(accuracy.wp_error.values[np.flatnonzero(accuracy.wp_pipeline.values)[0]])
    out = {}
    for m in chain.model.values:
        s = chain.sel(model=m)
        out[str(m)] = {
            "force_E_many_times_F": (pipeline * float(s.ratio_EF_min), "extremes on the frequency grid: the accuracy study's error at the pipeline's density"),
            "forces_grow_with_frequency": (float(s.growth_fraction_refinement), "change when the frequency grid is halved"),
            "limit_41_89": (1e-9 * float(s.first_resonance), "eigenvalues of the condensed chain (float rounding)"),
        }
    return out


def compare(cfg: Mapping[str, Any], published: Mapping[str, Any], chain: xr.Dataset, accuracy: xr.Dataset, uncertainty: xr.Dataset) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table per model and the support ranges of every claim."""
    table = compare_datasets(published, [chain], errors=numerical_errors(chain, accuracy), uncertainty=uncertainty)
    pub = {q["id"]: q for q in published["quantities"]}
    limit = float(pub["limit_41_89"]["value"])
    many_times = float(pub["force_E_many_times_F"]["value"])
    sup = support(chain, many_times, limit, tolerance_of(pub["limit_41_89"]))
    findings = xr.Dataset(
        {
            "holds_for": (("model", "claim", "sweep"), sup["text"], {"units": "1", "long_name": "sub-ranges of the swept parameter over which the claim holds"}),
            "limit_rad_s": ((), limit, {"units": "rad s-1", "long_name": "the paper's speed limit"}),
            "limit_rpm": ((), limit / RAD_S_PER_RPM, {"units": "min-1", "long_name": "the paper's speed limit as a shaft speed"}),
            "limit_band": ((), tolerance_of(pub["limit_41_89"]), {"units": "rad s-1", "long_name": "half-width of the band around the limit (our reading)"}),
            "many_times": ((), many_times, {"units": "1", "long_name": "ratio read as 'many times' (our reading)"}),
        },
        coords={
            "model": ("model", np.array(sup["models"], dtype=object), {"units": "1", "long_name": "chain model"}),
            "claim": ("claim", np.array(CLAIMS, dtype=object), {"units": "1", "long_name": "published claim"}),
            "sweep": ("sweep", np.array(SWEEPS, dtype=object), {"units": "1", "long_name": "swept parameter"}),
        },
    )
    findings = findings.merge(counts_dataset(table))
    findings.attrs.update(findings_attrs("Heald paper: comparison findings", DEFENSIBLE, PAPER_MODEL, answer(table, chain)))
    return table, findings


def answer(table: pd.DataFrame, chain: xr.Dataset) -> str:
    """Does the paper hold up? One sentence from the comparison."""
    deciders = sorted({name.strip() for d in table.decided_by.dropna() if d and d != "jointly" for name in d.split("(largest alone: ")[-1].rstrip(")").split(",")})
    return (
        f"Not decidable from the paper, which prints no parameter. Its eq. (2) is exactly the mobility of a driven node carrying three "
        f"spring–mass branches (agreement {float(chain.eq2_relative_difference):.0e}). On the physical linkage (model A) the claims: "
        f"{count_text(table, DEFENSIBLE)}; on eq. (2)'s chain (model B): {count_text(table, PAPER_MODEL)}"
        + (f"; the assumed {', '.join(deciders)} decide them" if deciders else "") + "."
    )
