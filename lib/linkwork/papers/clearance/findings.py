"""The clearance paper's comparison: each claim per parameter variant (the paper prints no number)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, counts_dataset


def compare(cfg: Mapping[str, Any], published: Mapping[str, Any], claims: xr.Dataset) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table per variant and its verdict counts."""
    table = compare_datasets(published, [claims])
    findings = counts_dataset(table)
    findings.attrs.update(title="Clearance paper: comparison findings", reference_model=str(claims.variant.values[0]))
    return table, findings
