"""One point of the heald sweep (joint clearance x heald-frame mass) on a chain model."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...pipeline.sweeps import point_dataset
from .adapter import amplitude, omega_grid, parameters
from .studies import joint_forces


def sweep_point(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> dict[str, float]:
    """Peak |Q_E|, |Q_F| over the speed band and the smallest E/F ratio at one (clearance, heald mass) point.

    ``point`` holds clearance_m (both joints) and heald_mass_kg; ``spec`` the sweep's chain model.
    """
    p = {**parameters(cfg), "clearance_E": point["clearance_m"], "clearance_F": point["clearance_m"], "M_P": point["heald_mass_kg"]}
    _, q_e, q_f, _ = joint_forces(spec["model"], p, "elastic", omega_grid(cfg["speeds"]), amplitude(cfg))
    return {"peak_Q_E": float(np.abs(q_e).max()), "peak_Q_F": float(np.abs(q_f).max()),
            "ratio_EF_min": float((np.abs(q_e) / np.abs(q_f)).min())}


#: Units and long names of the sweep outputs.
SWEEP_OUTPUTS = {
    "peak_Q_E": ("N", "peak |Q_E| over the speed band"),
    "peak_Q_F": ("N", "peak |Q_F| over the speed band"),
    "ratio_EF_min": ("1", "min |Q_E|/|Q_F| over the speed band"),
}


def sweep(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: one sweep point as a Dataset (its coordinates and outputs)."""
    ds = point_dataset(point, sweep_point(cfg, point, spec), SWEEP_OUTPUTS)
    ds.attrs["title"] = "sweep point " + ", ".join(f"{k} = {v:g}" for k, v in point.items())
    return ds
