"""The clearance paper's comparison: each claim per parameter variant (the paper prints no number)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, count_text, counts_dataset, findings_attrs


#: The slender-rod inertias are the defensible variant: with the decoded (printed) ones the Hertz
#: penetration exceeds the clearance itself (``answer`` states by how much).
DEFENSIBLE, PAPER_MODEL = "slender", "decoded"


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
    findings = counts_dataset(table)
    findings.attrs.update(findings_attrs("Clearance paper: comparison findings", DEFENSIBLE, PAPER_MODEL, answer(table, claims)))
    return table, findings


def answer(table: pd.DataFrame, claims: xr.Dataset) -> str:
    """Does the paper hold up? One sentence from the claims' verdicts per variant."""
    penetration = float(claims.summary_max_penetration_ratio.sel(variant=PAPER_MODEL).max())
    return (
        f"No claim is confirmed. On the physically consistent slender-rod variant the three claims: {count_text(table, DEFENSIBLE)}. "
        f"With the inertias as decoded from the text: {count_text(table, PAPER_MODEL)}; that parameter set is not physically consistent "
        f"(the dry penetration reaches {penetration:.1f} times the clearance, far outside Hertz contact). The paper prints no number, so "
        f"each claim is judged on our own measures of its figures."
    )
