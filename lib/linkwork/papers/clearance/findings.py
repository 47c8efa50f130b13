"""The clearance paper's comparison: each claim per parameter variant (the paper prints no number)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, count_text, counts_dataset, findings_attrs
from .validity import PENETRATION_LIMIT


#: The slender-rod inertias are the defensible variant: with the decoded (printed) ones the Hertz
#: penetration exceeds the clearance itself (``answer`` states by how much).
DEFENSIBLE, PAPER_MODEL = "slender", "decoded"
DRY_SCENES = ("dry_1", "dry_2", "dry_both")
LUBRICATED_SCENES = ("lubricated_1", "lubricated_2", "lubricated_both")


def numerical_errors(claims: xr.Dataset) -> dict[str, dict[str, tuple[float, str]]]:
    """Per variant and claim: 1 where the claim's outcome differs between the pipeline and the tight tolerance, else 0."""
    out = {}
    for v in claims.variant.values:
        h = claims.holds.sel(variant=v)
        out[str(v)] = {str(c): (abs(float(h.sel(claim=c, tolerance_set="pipeline") - h.sel(claim=c, tolerance_set="tight"))),
                                "outcome at the pipeline tolerance against the tight tolerance") for c in claims.claim.values}
    return out


def compare(cfg: Mapping[str, Any], published: Mapping[str, Any], claims: xr.Dataset, uncertainty: xr.Dataset | None = None) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table per variant and its verdict counts."""
    table = compare_datasets(published, [claims], errors=numerical_errors(claims), uncertainty=uncertainty)
    findings = counts_dataset(table).merge(physics(claims))
    findings.attrs.update(findings_attrs("Clearance paper: comparison findings", DEFENSIBLE, PAPER_MODEL, answer(table, findings)))
    return table, findings


def physics(claims: xr.Dataset) -> xr.Dataset:
    """Per variant: the deepest dry penetration, whether the parameter set is physically consistent, the largest
    lubricated eccentricity, and how often an effect a scene does not name was evaluated (must be 0)."""
    dry = claims.summary_max_penetration_ratio.sel(run=list(DRY_SCENES)).max(("run", "joint"))
    ecc = claims.summary_max_eccentricity_ratio.sel(run=list(LUBRICATED_SCENES)).max(("run", "joint"))
    stray = claims.summary_n_lubrication.sel(run=list(DRY_SCENES)).sum("run") + claims.summary_n_friction.sel(run=list(LUBRICATED_SCENES)).sum("run")
    return xr.Dataset({
        "dry_penetration_max": (("variant",), dry.values, {"units": "1", "long_name": "deepest dry penetration over the radial clearance"}),
        "physically_consistent": (("variant",), (dry.values < PENETRATION_LIMIT).astype(int),
                                  {"units": "1", "long_name": f"1 if the dry penetration stays below {PENETRATION_LIMIT:g} times the clearance"}),
        "lubricated_eccentricity_max": (("variant",), ecc.values, {"units": "1", "long_name": "largest eccentricity ratio |e|/c in a lubricated scene"}),
        "stray_evaluations": (("variant",), stray.values, {"units": "1", "long_name": "lubrication evaluations in dry scenes plus friction evaluations in lubricated ones"}),
    }, coords={"variant": ("variant", claims.variant.values, {"units": "1", "long_name": "parameter variant"})})


def answer(table: pd.DataFrame, findings: xr.Dataset) -> str:
    """Does the paper hold up? Sentences chosen and filled from the claims' verdicts and the physics per variant."""
    headline = table[table.role == "headline"]
    confirmed = headline[headline.verdict == "matches"]

    def consistency(variant: str) -> str:
        ok = bool(findings.physically_consistent.sel(variant=variant))
        depth = float(findings.dry_penetration_max.sel(variant=variant))
        return (f"physically consistent (dry penetration at most {depth:.2f} of the clearance)" if ok else
                f"not physically consistent (the dry penetration reaches {depth:.1f} times the clearance, far outside Hertz contact)")

    lead = "No claim is confirmed." if confirmed.empty else f"{len(confirmed)} of the claims are confirmed ({', '.join(sorted(set(confirmed.model)))})."
    return (
        f"{lead} On the slender-rod variant, {consistency(DEFENSIBLE)}, the three claims: {count_text(table, DEFENSIBLE)}. "
        f"With the inertias as decoded from the text, {consistency(PAPER_MODEL)}: {count_text(table, PAPER_MODEL)}. The paper prints no "
        f"number, so each claim is judged on our own measures of its figures."
    )
