"""The transplanter paper's comparison and findings: our optimum and our model at the published optimum
beside the printed numbers, and whether the quasi-statically optimal design is safe dynamically."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, counts_dataset, scalar


def compare(cfg: Mapping[str, Any], published: Mapping[str, Any], optim: xr.Dataset, at_published: xr.Dataset, ked: xr.Dataset) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table and findings (dynamic peak stress at our optimum against the allowable)."""
    table = compare_datasets(published, [optim, at_published])
    allowable = float(optim.allowable)
    dynamic = float(ked.peak_stress.sel(diameters="optimal", solution="dynamic"))
    quasi = float(ked.peak_stress.sel(diameters="optimal", solution="quasi-static"))
    findings = xr.Dataset(
        {
            "allowable": scalar(allowable, "MPa", "allowable stress"),
            "optimum_quasi_static_peak": scalar(quasi, "MPa", "largest quasi-static stress at our optimum"),
            "optimum_dynamic_peak": scalar(dynamic, "MPa", "largest dynamic (Newmark) stress at our optimum"),
            "optimum_dynamic_excess": scalar(dynamic / allowable - 1.0, "1", "dynamic peak at our optimum over the allowable, minus 1"),
        }
    ).merge(counts_dataset(table))
    findings.attrs.update(title="Transplanter paper: comparison findings", reference_model="")
    return table, findings
