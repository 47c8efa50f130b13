"""The clearance sweep (radial clearance x crank speed) on one scene: first a validity map, then the claims'
measure with its cycle-to-cycle scatter, and the gathered grid with the facts that interpret it.

Per point: the deepest penetration over the clearance (the Hertz law's validity measure), the peak contact force
and its ratio to the largest reaction of the ideal joints (how far impacts dominate the load), and per recorded
cycle the claims' measure (RMS deviation from the ideal joints, relative to the ideal response), stored as its
mean over the recorded cycles and its cycle-to-cycle spread (largest - smallest per-cycle value).  The dry
response does not settle into a periodic one, so a change of the measure over the grid is only a trend where it
exceeds that spread (``pipeline.sweeps.resolved_trend``).

The scene with both joints in clearance is the one the paper's orderings (claims 1 and 2) rank largest; the
orderings themselves need the single-joint scenes, which the sweep does not run.  The threshold drawn is the one
that decides whether the claims' verdicts describe contact at all: the Hertz law's validity limit
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

#: What the scenes and variants a sweep may run are, in words (for captions).
SCENE_WORDS = {"dry_1": "joint 1 (A) with dry clearance", "dry_2": "joint 2 (B) with dry clearance",
               "dry_both": "both joints with dry clearance", "lubricated_1": "joint 1 (A) lubricated",
               "lubricated_2": "joint 2 (B) lubricated", "lubricated_both": "both joints lubricated"}
VARIANT_WORDS = {"slender": "slender links (J = m L^2 / 12)", "decoded": "link inertias as printed"}

#: The measures recorded per cycle: (sweep output, series index in the integrated output, ideal series).
PER_CYCLE = {"rocker_acceleration_deviation": (0, "rocker_acceleration"), "crank_torque_deviation": (1, "crank_torque")}
#: Suffix of an output's cycle-to-cycle spread.
SCATTER = "_cycle_spread"


def _times(points_per_cycle: int, settle: int, record: int, period: float) -> tuple[np.ndarray, np.ndarray]:
    """(output times (s), mask of the recorded cycles): ``settle`` cycles discarded, then ``record`` recorded."""
    t = np.arange((settle + record) * points_per_cycle + 1) * period / points_per_cycle
    return t, t >= settle * period - 1e-12


def relative_rms_deviation(run: np.ndarray, ideal: np.ndarray) -> float:
    """RMS of (run - ideal) over RMS of ideal, on the same samples (the last sample closes the cycle: left out)."""
    d, r = (run - ideal)[:-1], ideal[:-1]
    return float(np.sqrt(np.mean(d**2)) / np.sqrt(np.mean(r**2)))


def per_cycle_deviation(run: np.ndarray, ideal_cycle: np.ndarray) -> np.ndarray:
    """``relative_rms_deviation`` on each recorded cycle of ``run`` (cycles of ``ideal_cycle.size - 1`` samples, the
    closing sample shared) against the ideal response over one cycle (periodic: the same for every cycle)."""
    n = ideal_cycle.size - 1
    return np.array([relative_rms_deviation(run[k * n : (k + 1) * n + 1], ideal_cycle) for k in range((run.size - 1) // n)])


def sweep_point(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> dict[str, float]:
    """Validity measures, peak contact force and the claims' measures (mean and cycle spread) at one point.

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
    ppc = cfg["numerics"]["points_per_cycle"]
    t, rec = _times(ppc, spec["settle_cycles"], spec["record_cycles"], 2 * np.pi / p.crank_speed)
    _, d, *_ = integrate(p, joints, effects, t, cfg["integrators"][integrator_kind(cfg["scenes"][name])])
    d = d[rec]
    ideal = inverse_dynamics(p, t[rec][: ppc + 1], "gravity" in effects)  # one cycle: the ideal response is periodic
    forces = np.nan_to_num(d[:, [7 + 6 * k for k in range(len(joints))]], nan=0.0)
    penetration = d[:, [5 + 6 * k for k in range(len(joints))]]
    ideal_peak = max(float(np.max(ideal["force_A" if j == 1 else "force_B"])) for j in joints)
    out = {"penetration_over_clearance": validity.penetration_ratio(penetration, p.clearance),
           "peak_joint_force": float(forces.max()), "peak_force_over_ideal": float(forces.max()) / ideal_peak}
    for key, (column, series) in PER_CYCLE.items():
        per_cycle = per_cycle_deviation(d[:, column], ideal[series])
        out[key], out[key + SCATTER] = float(per_cycle.mean()), float(per_cycle.max() - per_cycle.min())
    return out


#: Units and long names of the sweep outputs.
SWEEP_OUTPUTS = {
    "penetration_over_clearance": ("1", "deepest penetration / radial clearance"),
    "peak_joint_force": ("N", "peak dry contact force over the clearance joints"),
    "peak_force_over_ideal": ("1", "peak contact force / largest reaction of the ideal joints"),
    "rocker_acceleration_deviation": ("1", "RMS deviation of the rocker acceleration from the ideal joints / RMS of the ideal, mean over the recorded cycles"),
    "rocker_acceleration_deviation" + SCATTER: ("1", "cycle-to-cycle spread (largest - smallest recorded cycle) of the rocker acceleration's deviation"),
    "crank_torque_deviation": ("1", "RMS deviation of the crank torque from the ideal joints / RMS of the ideal, mean over the recorded cycles"),
    "crank_torque_deviation" + SCATTER: ("1", "cycle-to-cycle spread (largest - smallest recorded cycle) of the crank torque's deviation"),
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
    """Rule study: the clearance sweep's jobs on their grid with the facts that interpret it (trends, those that
    exceed the cycle-to-cycle spread, where the validity limit is crossed, colour ranges); ``cfg``: grid size,
    axes, the sweep's spec and the reference point."""
    scatter = {k: k + SCATTER for k in PER_CYCLE}
    grid_ds = gather(cfg["axes"], points)
    for k, spread in scatter.items():  # the spread relative to the mean: what a change must exceed, as a fraction
        grid_ds[k + "_relative" + SCATTER] = (grid_ds[spread] / grid_ds[k]).assign_attrs(
            units="1", long_name=f"{grid_ds[spread].attrs['long_name']} / its mean")
    ds = interpret(grid_ds, cfg["reference"], THRESHOLDS, scatter=scatter)
    spec = cfg["spec"]
    ds.attrs.update(title=f"clearance sweep ({cfg['grid']} grid)", scene=spec["scene"], variant=spec["variant"],
                    scene_description=SCENE_WORDS.get(spec["scene"], spec["scene"]),
                    variant_description=VARIANT_WORDS.get(spec["variant"], spec["variant"]),
                    settle_cycles=spec["settle_cycles"], record_cycles=spec["record_cycles"])
    return ds
