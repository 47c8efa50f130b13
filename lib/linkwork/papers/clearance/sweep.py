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
that decides whether the claims' verdicts describe contact at all: the elastic law's validity limit
(``validity.penetration_limit``, a fraction of the clearance that depends on the radii).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from .fourbar import inverse_dynamics
from ...pipeline.sweeps import gather, interpret, points_dataset
from ...engines.multibody import validity
from .adapter import integrator_kind, parameters, scene_effects

#: What the scenes and variants a sweep may run are, in words (for captions).
SCENE_WORDS = {"dry_1": "joint 1 (A) with dry clearance", "dry_2": "joint 2 (B) with dry clearance",
               "dry_both": "both joints with dry clearance", "lubricated_1": "joint 1 (A) lubricated",
               "lubricated_2": "joint 2 (B) lubricated", "lubricated_both": "both joints lubricated"}
VARIANT_WORDS = {"slender": "slender links (J = m L^2 / 12)", "decoded": "link inertias as printed"}

#: The measures recorded per cycle: (sweep output, row of the per-cycle RMS measures (settling.MEASURE_ROWS), ideal
#: series).
PER_CYCLE = {"rocker_acceleration_deviation": (0, "rocker_acceleration"), "crank_torque_deviation": (1, "crank_torque")}
#: Suffix of an output's cycle-to-cycle spread.
SCATTER = "_cycle_spread"


#: Section points kept per sweep point for the bifurcation diagram (the judged turns' last ones; a period-k orbit shows
#: k).
SECTION_POINTS = 8


def sweep_point(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> dict[str, float]:
    """Validity measures, peak contact force, the claims' measures (mean and cycle spread over the judged turns) and
    the state (period, transient, the last section points of joint 1's e_x / c) at one point, the scene settled from
    the first start by the clearance scenes' own rule (``states``).

    ``point`` holds clearance_m and crank_speed_rad_s; ``spec`` the sweep's scene and variant.
    """
    from ...engines.states import PERIODIC
    from .settling import CycleRunner, judged_statistics, settle_start, start_state

    name, variant = spec["scene"], spec["variant"]
    bearing = cfg["joints"]["bearing_radius_m"]
    local = {
        **cfg,
        "crank_speed_rad_s": point["crank_speed_rad_s"],
        "joints": {**cfg["joints"], "journal_radius_m": bearing - point["clearance_m"]},
    }
    joints, effects = scene_effects(cfg, name)
    if "lubrication" in effects:  # keep the film's eccentricity cap: e0 scales with the clearance
        c0 = bearing - cfg["joints"]["journal_radius_m"]
        local["assumed"] = {
            **cfg["assumed"],
            "e0_m": {**cfg["assumed"]["e0_m"], "value": cfg["assumed"]["e0_m"]["value"] * point["clearance_m"] / c0},
        }
    p = parameters(local, variant, name)
    ppc = cfg["numerics"]["points_per_cycle"]
    period = 2 * np.pi / p.crank_speed
    ideal = inverse_dynamics(
        p, np.arange(ppc + 1) * period / ppc, "gravity" in effects
    )  # one cycle: the ideal response is periodic
    runner = CycleRunner(
        p, joints, effects, cfg["integrators"][integrator_kind(cfg["scenes"][name])], ideal, ppc, 1,
        cfg["claims"]["ripple_cutoff_hz"], y0=start_state(p, joints, cfg["states"]["starts"][0]),
    )
    found = settle_start(runner, cfg["states"], cfg["statistics"]["confidence"])
    first, stop = found["window"]
    ext = np.array(runner.extremes)[first:stop]  # cycle, joint, (penetration, eccentricity, contact force, film force)
    scale = {"rocker_acceleration_deviation": np.sqrt(np.mean(ideal["rocker_acceleration"][:-1] ** 2)),
             "crank_torque_deviation": np.sqrt(np.mean(ideal["crank_torque"][:-1] ** 2))}
    ideal_peak = max(float(np.max(ideal["force_A" if j == 1 else "force_B"])) for j in joints)
    pen = float(np.nanmax(ext[:, :, 0]) / p.clearance)
    out = {
        "penetration_over_clearance": pen,
        "penetration_over_limit": pen / validity.penetration_limit(p.elastic_law, p.journal_radius, p.bearing_radius),
        "peak_joint_force": float(np.nanmax(ext[:, :, 2])),
        "peak_force_over_ideal": float(np.nanmax(ext[:, :, 2])) / ideal_peak,
        "state_period": float(found["period"]),
        "state_transient": float(found["transient"]),
        "state_periodic": float(found["status"] == PERIODIC),
    }
    judged = judged_statistics(
        found["measures"], found, cfg["statistics"]["batch_cycles"], cfg["statistics"]["confidence"]
    )  # as the scenes judge
    for key, (row, _) in PER_CYCLE.items():
        per_cycle = found["measures"][first:stop, row] / scale[key]
        out[key], out[key + SCATTER] = float(judged[row, 0] / scale[key]), float(per_cycle.max() - per_cycle.min())
    last = found["points"][first:stop][-SECTION_POINTS:]
    for k in range(SECTION_POINTS):
        out[f"section_{k}"] = float(last[k, 0]) if k < last.shape[0] else float("nan")
        out[f"section_rate_{k}"] = float(last[k, 2]) if k < last.shape[0] else float("nan")
    return out


#: Units and long names of the sweep outputs.
SWEEP_OUTPUTS = {
    "penetration_over_clearance": ("1", "deepest penetration / radial clearance"),
    "penetration_over_limit": (
        "1",
        "deepest penetration / the elastic law's penetration limit (1: the edge of its range)",
    ),
    "peak_joint_force": ("N", "peak dry contact force over the clearance joints"),
    "peak_force_over_ideal": ("1", "peak contact force / largest reaction of the ideal joints"),
    "rocker_acceleration_deviation": (
        "1",
        (
            "RMS deviation of the rocker acceleration from the ideal joints / RMS of the ideal, mean over the recorded"
            " cycles"
        ),
    ),
    "rocker_acceleration_deviation" + SCATTER: (
        "1",
        "cycle-to-cycle spread (largest - smallest recorded cycle) of the rocker acceleration's deviation",
    ),
    "crank_torque_deviation": (
        "1",
        "RMS deviation of the crank torque from the ideal joints / RMS of the ideal, mean over the recorded cycles",
    ),
    "crank_torque_deviation" + SCATTER: (
        "1",
        "cycle-to-cycle spread (largest - smallest recorded cycle) of the crank torque's deviation",
    ),
    "state_period": ("1", "period of the settled state in crank turns (0: not periodic)"),
    "state_transient": ("1", "crank turns before the state (never judged)"),
    "state_periodic": ("1", "1 if the state is a periodic orbit"),
    **{
        f"section_{k}": (
            "1",
            (
                f"joint 1's e_x / c at the dead point, judged turn {k + 1} of the last {SECTION_POINTS} (the"
                " bifurcation diagram)"
            ),
            "the state was judged on fewer turns",
        )
        for k in range(SECTION_POINTS)
    },
    **{
        f"section_rate_{k}": (
            "1", f"joint 1's e_x' / (c omega) at the dead point, judged turn {k + 1} of the last {SECTION_POINTS}",
            "the state was judged on fewer turns",
        )
        for k in range(SECTION_POINTS)
    },
}

#: The threshold drawn on the map: where the Hertz contact law leaves its range (the clearance report's limit).
THRESHOLDS = {
    "penetration_over_limit": {"value": 1.0, "along": "clearance_m",
                               "label": "the elastic law's validity limit (eq. (9)'s sphere law: a short contact arc)"},
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
    states = [
        k for k in grid_ds.data_vars if k.startswith(("section_", "state_"))
    ]  # the bifurcation diagram's: no trends of them
    ds = interpret(grid_ds.drop_vars(states), cfg["reference"], THRESHOLDS, scatter=scatter).merge(grid_ds[states])
    periodic = grid_ds.state_periodic.values == 1
    ds["periodic_points"] = (
        (), int(periodic.sum()), {"units": "1", "long_name": "grid points whose state is a periodic orbit"},
    )
    ds["grid_points"] = ((), int(periodic.size), {"units": "1", "long_name": "grid points"})
    ds.attrs["periods_found"] = ", ".join(
        str(int(k)) for k in sorted(set(grid_ds.state_period.values[periodic].ravel().tolist()))
    )
    spec = cfg["spec"]
    ds.attrs.update(title=f"clearance sweep ({cfg['grid']} grid)", scene=spec["scene"], variant=spec["variant"],
                    scene_description=SCENE_WORDS.get(spec["scene"], spec["scene"]),
                    variant_description=VARIANT_WORDS.get(spec["variant"], spec["variant"]),
                    settle_rule="the clearance scenes' settling rule (states), first start")
    return ds
