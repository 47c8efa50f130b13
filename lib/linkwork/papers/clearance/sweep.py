"""The clearance sweep (radial clearance x crank speed) on one scene: per point the claims' measure (RMS deviation
from the ideal joints, relative to the ideal response), the peak contact force and the validity measure
(deepest penetration over the clearance), then the gathered grid with the facts that interpret it.

The scene with both joints in clearance is the one the paper's orderings (claims 1 and 2) rank largest; the
sweep shows how that scene's deviation from the ideal grows with clearance and speed.  The orderings
themselves need the single-joint scenes, which the sweep does not run.  The threshold drawn is the one that
decides whether the claims' verdicts describe contact at all: the Hertz law's validity limit
(``validity.PENETRATION_LIMIT`` times the clearance).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from ...engines.multibody.model import inverse_dynamics
from ...engines.multibody.simulate import integrate
from ...pipeline.sweeps import gather, interpret, points_dataset
from . import validity
from .adapter import integrator_kind, parameters, scene_effects


def _times(points_per_cycle: int, settle: int, record: int, period: float) -> tuple[np.ndarray, np.ndarray]:
    """(output times (s), mask of the recorded cycles): ``settle`` cycles discarded, then ``record`` recorded."""
    t = np.arange((settle + record) * points_per_cycle + 1) * period / points_per_cycle
    return t, t >= settle * period - 1e-12


def relative_rms_deviation(run: np.ndarray, ideal: np.ndarray) -> float:
    """RMS of (run - ideal) over RMS of ideal, on the same samples (the last sample closes the cycle: left out)."""
    d, r = (run - ideal)[:-1], ideal[:-1]
    return float(np.sqrt(np.mean(d**2)) / np.sqrt(np.mean(r**2)))


def sweep_point(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> dict[str, float]:
    """The claims' measures, peak contact force and validity measure at one (clearance, crank speed) point.

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
    t, rec = _times(cfg["numerics"]["points_per_cycle"], spec["settle_cycles"], spec["record_cycles"], 2 * np.pi / p.crank_speed)
    _, d, *_ = integrate(p, joints, effects, t, cfg["integrators"][integrator_kind(cfg["scenes"][name])])
    d = d[rec]
    ideal = inverse_dynamics(p, t[rec], "gravity" in effects)
    forces = np.nan_to_num(d[:, [7 + 6 * k for k in range(len(joints))]], nan=0.0)
    penetration = d[:, [5 + 6 * k for k in range(len(joints))]]
    return {
        "rocker_acceleration_deviation": relative_rms_deviation(d[:, 0], ideal["rocker_acceleration"]),
        "crank_torque_deviation": relative_rms_deviation(d[:, 1], ideal["crank_torque"]),
        "penetration_over_clearance": validity.penetration_ratio(penetration, p.clearance),
        "peak_joint_force": float(forces.max()),
    }


#: Units and long names of the sweep outputs.
SWEEP_OUTPUTS = {
    "rocker_acceleration_deviation": ("1", "RMS deviation of the rocker acceleration from the ideal joints / RMS of the ideal"),
    "crank_torque_deviation": ("1", "RMS deviation of the crank torque from the ideal joints / RMS of the ideal"),
    "penetration_over_clearance": ("1", "deepest penetration / radial clearance"),
    "peak_joint_force": ("N", "peak dry contact force over the clearance joints"),
}

#: The threshold drawn on the map: where the Hertz contact law leaves its range (the clearance report's limit).
THRESHOLDS = {
    "penetration_over_clearance": {"value": validity.PENETRATION_LIMIT, "along": "clearance_m",
                                   "label": "Hertz validity limit: penetration = clearance"},
}


def sweep(cfg: Mapping[str, Any], points: Sequence[Mapping[str, float]], spec: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: the points of one job of the clearance sweep as a Dataset (coordinates and outputs)."""
    ds = points_dataset(points, [sweep_point(cfg, p, spec) for p in points], SWEEP_OUTPUTS)
    ds.attrs["title"] = f"clearance sweep, {len(points)} point(s)"
    return ds


def gathered(cfg: Mapping[str, Any], points: Sequence[xr.Dataset]) -> xr.Dataset:
    """Rule study: the clearance sweep's jobs on their grid with the facts that interpret it (trends, where the
    validity limit is crossed, colour ranges); ``cfg``: grid size, axes, the sweep's spec and the reference point."""
    ds = interpret(gather(cfg["axes"], points), cfg["reference"], THRESHOLDS)
    ds.attrs.update(title=f"clearance sweep ({cfg['grid']} grid)", scene=cfg["spec"]["scene"], variant=cfg["spec"]["variant"],
                    settle_cycles=cfg["spec"]["settle_cycles"], record_cycles=cfg["spec"]["record_cycles"])
    return ds
