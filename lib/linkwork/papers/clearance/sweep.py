"""One point of the clearance sweep (radial clearance x crank speed) on one scene."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.multibody.simulate import integrate
from ...pipeline.sweeps import point_dataset
from .adapter import integrator_kind, parameters, scene_effects
from .studies import output_times


def sweep_point(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> dict[str, float]:
    """Peak and RMS joint contact force and rocker acceleration at one (clearance, crank speed) point.

    ``point`` holds clearance_m and crank_speed_rad_s; ``spec`` the sweep's scene, variant and cycles.
    """
    name, variant = spec["scene"], spec["variant"]
    bearing = cfg["joints"]["bearing_radius_m"]
    local = {**cfg, "crank_speed_rad_s": point["crank_speed_rad_s"], "joints": {**cfg["joints"], "journal_radius_m": bearing - point["clearance_m"]}}
    joints, effects = scene_effects(cfg, name)
    if "lubrication" in effects:  # keep the film's eccentricity cap: e0 scales with the clearance
        c0 = bearing - cfg["joints"]["journal_radius_m"]
        local["assumed"] = {**cfg["assumed"], "e0_m": {**cfg["assumed"]["e0_m"], "value": cfg["assumed"]["e0_m"]["value"] * point["clearance_m"] / c0}}
    p = parameters(local, variant, name)
    t, rec = output_times({"points_per_cycle": cfg["numerics"]["points_per_cycle"], "settle_cycles": spec["settle_cycles"], "record_cycles": spec["record_cycles"]}, p)
    _, d, *_ = integrate(p, joints, effects, t, cfg["integrators"][integrator_kind(cfg["scenes"][name])])
    d = d[rec]
    forces = np.nan_to_num(d[:, [7 + 6 * k for k in range(len(joints))]], nan=0.0)
    return {
        "peak_joint_force": float(forces.max()),
        "rms_joint_force": float(np.sqrt(np.mean(forces.max(axis=1) ** 2))),
        "peak_rocker_acceleration": float(np.abs(d[:, 0]).max()),
        "rms_rocker_acceleration": float(np.sqrt(np.mean(d[:, 0] ** 2))),
    }


#: Units and long names of the sweep outputs.
SWEEP_OUTPUTS = {
    "peak_joint_force": ("N", "peak dry contact force over the clearance joints"),
    "rms_joint_force": ("N", "RMS of the largest joint contact force"),
    "peak_rocker_acceleration": ("rad s-2", "peak |rocker angular acceleration|"),
    "rms_rocker_acceleration": ("rad s-2", "RMS rocker angular acceleration"),
}


def sweep(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: one sweep point as a Dataset (its coordinates and outputs)."""
    ds = point_dataset(point, sweep_point(cfg, point, spec), SWEEP_OUTPUTS)
    ds.attrs["title"] = "sweep point " + ", ".join(f"{k} = {v:g}" for k, v in point.items())
    return ds
