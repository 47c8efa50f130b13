"""The clearance paper's studies: one scene run and the claims across scenes.  Each takes the config
values its rule passes (see ``adapter``) and returns a result Dataset."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from ...engines.multibody.model import inverse_dynamics, start_angle
from ...engines.multibody.simulate import integrate
from . import validity
from .adapter import TOLERANCE_SETS, integrator_kind, parameters, scene_effects

JOINT_IDS = (1, 2)
DRY = ("dry_1", "dry_2", "dry_both")
LUBRICATED = ("lubricated_1", "lubricated_2", "lubricated_both")
COMPARED = DRY + LUBRICATED  # the scenes the claims compare, in this order
QUANTITIES = ("rocker_acceleration", "crank_torque")


#: Attributes of a per-joint variable: NaN where the scene gives the joint no clearance.
NO_CLEARANCE = {"nan_meaning": "the joint has no clearance in this scene"}


#: Attributes of an ideal-joint reaction: NaN in scenes with clearance joints.
NOT_IDEAL = {"nan_meaning": "a scene with clearance joints has no ideal reaction"}


def cycle(p) -> float:
    """Period of one crank revolution (s)."""
    return 2 * np.pi / p.crank_speed


def output_times(numerics: Mapping[str, Any], p) -> tuple[np.ndarray, np.ndarray]:
    """(all output times (s), mask of the recorded cycles): settle cycles, then the recorded ones."""
    per = numerics["points_per_cycle"]
    total = numerics["settle_cycles"] + numerics["record_cycles"]
    t = np.arange(total * per + 1) * cycle(p) / per
    return t, t >= numerics["settle_cycles"] * cycle(p) - 1e-12


def _ideal_run(p, t_rec, gravity: bool, n_cycles: int) -> tuple[dict[str, np.ndarray], dict[str, Any], np.ndarray]:
    ideal = inverse_dynamics(p, t_rec, gravity)
    per_joint = np.full((2, 6, t_rec.size), np.nan)
    meta = {"integrator": "none (inverse dynamics)", "steps": 0, "rejected": 0, "counts": [0, 0, 0, 0]}
    series = {"acc": ideal["rocker_acceleration"], "torque": ideal["crank_torque"], "energy": ideal["energy"],
              "drift": np.zeros(t_rec.size), "per_joint": per_joint, "force_A": ideal["force_A"], "force_B": ideal["force_B"]}
    return series, meta, np.zeros(n_cycles - 1)


def scene(cfg: Mapping[str, Any], variant: str, scene: str, tolerance: str = "pipeline") -> xr.Dataset:
    """One scene of one parameter variant over the recorded cycles (the ideal scene by inverse dynamics)."""
    p = parameters(cfg, variant, scene)
    joints, effects = scene_effects(cfg, scene)
    numerics = cfg["numerics"]
    t, rec = output_times(numerics, p)
    n_cycles = numerics["settle_cycles"] + numerics["record_cycles"]
    integ: Mapping[str, Any] = {}
    if not joints:  # kinematics and inverse dynamics, no integration
        series, meta, change = _ideal_run(p, t[rec], "gravity" in effects, n_cycles)
    else:
        integ = cfg[TOLERANCE_SETS[tolerance]][integrator_kind(cfg["scenes"][scene])]
        _, diags, steps, rejected, counts, _ = integrate(p, joints, effects, t, integ)
        d = diags[rec]
        per_joint = np.full((2, 6, rec.sum()), np.nan)
        for k, j in enumerate(joints):
            per_joint[j - 1] = d[:, 4 + 6 * k : 10 + 6 * k].T
        nan = np.full(rec.sum(), np.nan)
        series = {"acc": d[:, 0], "torque": d[:, 1], "energy": d[:, 2], "drift": d[:, 3], "per_joint": per_joint, "force_A": nan, "force_B": nan}
        meta = {"integrator": integ["method"], "steps": steps, "rejected": rejected, "counts": counts.tolist()}
        whole = diags[:-1, 0].reshape(-1, numerics["points_per_cycle"])
        change = np.sqrt(np.mean((whole[1:] - whole[:-1]) ** 2, axis=1)) / np.sqrt(np.mean(whole[-1] ** 2))
    theta = np.degrees(start_angle(p) + p.crank_speed * t[rec])
    dims, jd = ("time",), ("joint", "time")
    pj = series["per_joint"]
    ds = xr.Dataset(
        {
            "crank_angle": (dims, theta, {"units": "deg", "long_name": "crank angle (unwrapped)"}),
            "rocker_acceleration": (dims, series["acc"], {"units": "rad s-2", "long_name": "rocker angular acceleration"}),
            "crank_torque": (dims, series["torque"], {"units": "N m", "long_name": "crank driving torque"}),
            "energy": (dims, series["energy"], {"units": "J", "long_name": "mechanical energy (kinetic + gravity + contact)"}),
            "constraint_drift": (dims, series["drift"], {"units": "m", "long_name": "|Phi| of the ideal constraints"}),
            "eccentricity": (jd, pj[:, 0], {"units": "m", "long_name": "journal eccentricity |e|", **NO_CLEARANCE}),
            "penetration": (jd, pj[:, 1], {"units": "m", "long_name": "penetration |e| - c (> 0 in contact)", **NO_CLEARANCE}),
            "contact_force": (jd, pj[:, 3], {"units": "N", "long_name": "dry normal contact force", **NO_CLEARANCE}),
            "film_radial_force": (jd, pj[:, 4], {"units": "N", "long_name": "film force along e (on the journal)", **NO_CLEARANCE}),
            "film_tangential_force": (jd, pj[:, 5], {"units": "N", "long_name": "film force across e (on the journal)", **NO_CLEARANCE}),
            "ideal_joint_force_A": (dims, series["force_A"], {"units": "N", "long_name": "reaction in joint 1 (A), ideal scene only", **NOT_IDEAL}),
            "ideal_joint_force_B": (dims, series["force_B"], {"units": "N", "long_name": "reaction in joint 2 (B), ideal scene only", **NOT_IDEAL}),
            "cycle_change": ("cycle_pair", change, {"units": "1", "long_name": "RMS change of the rocker acceleration from one cycle to the next / RMS of the last cycle"}),
        },
        coords={
            "cycle_pair": ("cycle_pair", np.arange(1, change.size + 1), {"units": "1", "long_name": "cycle k vs cycle k + 1 (from the start)"}),
            "time": ("time", t[rec] - t[rec][0], {"units": "s", "long_name": "time from the start of the recorded cycles"}),
            "joint": ("joint", np.array(JOINT_IDS), {"units": "1", "long_name": "joint 1 (crank-coupler), 2 (coupler-rocker)"}),
        },
    )
    ds.attrs.update(
        title=f"Four-bar with clearance joints: {variant}, {scene}", scene=scene, variant=variant, tolerance_set=tolerance,
        effects=",".join(effects), clearance_joints=",".join(map(str, joints)),
        integrator=meta["integrator"], steps=meta["steps"], rejected_steps=meta["rejected"],
        evaluations_contact=meta["counts"][0], evaluations_friction=meta["counts"][1],
        evaluations_lubrication=meta["counts"][2], evaluations_gravity=meta["counts"][3],
        settle_cycles=numerics["settle_cycles"], record_cycles=numerics["record_cycles"],
        **({"hertz_stiffness": p.hertz_stiffness, "clearance": p.clearance} if joints else {}),
        **({"film_eccentricity_cap": 1.0 - p.e0 / p.clearance} if "lubrication" in effects else {}),
        **(validity.attributes(ds.penetration.values, ds.eccentricity.values, p.clearance,
                               1.0 - p.e0 / p.clearance if "lubrication" in effects else None) if joints else {"validity_warnings": ""}),
        **{f"integrator_{k}": v for k, v in integ.items()},
    )
    return ds


def deviation_measures(run: xr.Dataset, ideal: xr.Dataset, variable: str, cycles: int) -> dict[str, np.ndarray]:
    """RMS and peak of (scene - ideal) per recorded cycle (SI units of the variable)."""
    d = (run[variable] - ideal[variable]).values
    parts = np.array_split(d[:-1], cycles)
    return {"rms": np.array([np.sqrt(np.mean(x**2)) for x in parts]), "peak": np.array([np.abs(x).max() for x in parts])}


def _by_key(runs: Sequence[xr.Dataset]) -> dict[tuple[str, str], xr.Dataset]:
    return {(r.attrs["variant"], r.attrs["scene"]): r for r in runs}


def order_as_claimed(values: np.ndarray, quantity: str) -> bool:
    """The claimed order of the dry scenes (dry_1, dry_2, dry_both first in ``values``): for the rocker
    acceleration joint 2 > joint 1, for the crank torque joint 1 > joint 2; both joints the largest."""
    one, two, both = values[:3]
    first = two > one if quantity == "rocker_acceleration" else one > two
    return bool(first and both > max(one, two))


def claims_hold(rms: np.ndarray, peak: np.ndarray, ratio: float) -> list[float]:
    """The three claims for one variant and one tolerance set from (quantity, scene, cycle) arrays; a claim
    holds only if it holds on the RMS and on the peak deviation in every recorded cycle."""
    ordered = [all(np.all([order_as_claimed(m[q, :, c], QUANTITIES[q]) for c in range(m.shape[-1])]) for m in (rms, peak)) for q in range(len(QUANTITIES))]
    lub, dry = rms[:, 3:], rms[:, :3]
    close = np.all(lub < ratio * dry) and np.all(lub[:, 1] > lub[:, 0])
    return [float(ordered[0]), float(ordered[1]), float(close)]


def _scene_summary(runs: Mapping[tuple[str, str], xr.Dataset], variants: list[str], scenes: list[str]) -> dict[str, Any]:
    """Per variant and scene: cost, settling, drift, effect counters and joint extremes (what the report tabulates)."""
    shape, jshape = (len(variants), len(scenes)), (len(variants), len(scenes), len(JOINT_IDS))
    out = {k: np.full(shape, np.nan) for k in ("steps", "first_change", "last_change", "max_drift", "n_contact", "n_friction", "n_lubrication", "ideal_force_A", "ideal_force_B", "film_cap", "hertz_stiffness")}
    out["integrator"] = np.full(shape, "", dtype=object)
    out.update({k: np.full(jshape, np.nan) for k in ("max_penetration_ratio", "max_eccentricity_ratio", "max_contact_force", "max_film_force")})
    for v, variant in enumerate(variants):
        for s, name in enumerate(scenes):
            ds = runs.get((variant, name))
            if ds is None:
                continue
            out["integrator"][v, s] = ds.attrs["integrator"]
            if name == "ideal":
                out["ideal_force_A"][v, s] = float(ds.ideal_joint_force_A.max())
                out["ideal_force_B"][v, s] = float(ds.ideal_joint_force_B.max())
                continue
            out["film_cap"][v, s] = ds.attrs.get("film_eccentricity_cap", np.nan)
            out["hertz_stiffness"][v, s] = ds.attrs["hertz_stiffness"]
            out["steps"][v, s] = ds.attrs["steps"]
            out["first_change"][v, s], out["last_change"][v, s] = float(ds.cycle_change[0]), float(ds.cycle_change[-1])
            out["max_drift"][v, s] = float(ds.constraint_drift.max())
            for key, attr in (("n_contact", "contact"), ("n_friction", "friction"), ("n_lubrication", "lubrication")):
                out[key][v, s] = ds.attrs[f"evaluations_{attr}"]
            c = ds.attrs["clearance"]
            for j, jid in enumerate(JOINT_IDS):
                pen = ds.penetration.sel(joint=jid).values
                if np.isfinite(pen).any():
                    out["max_penetration_ratio"][v, s, j] = np.nanmax(pen) / c
                    out["max_eccentricity_ratio"][v, s, j] = np.nanmax(ds.eccentricity.sel(joint=jid).values) / c
                    out["max_contact_force"][v, s, j] = np.nanmax(ds.contact_force.sel(joint=jid).values)
                    out["max_film_force"][v, s, j] = np.nanmax(np.abs(ds.film_radial_force.sel(joint=jid).values))
    return out


SUMMARY_ATTRS = {
    "steps": ("1", "accepted integrator steps"),
    "first_change": ("1", "cycle-to-cycle change of the rocker acceleration, first cycle pair"),
    "last_change": ("1", "cycle-to-cycle change of the rocker acceleration, last cycle pair"),
    "max_drift": ("m", "largest constraint drift |Phi| over the recorded cycles"),
    "n_contact": ("1", "contact-force evaluations"),
    "n_friction": ("1", "friction evaluations"),
    "n_lubrication": ("1", "film-force evaluations"),
    "ideal_force_A": ("N", "largest reaction in joint 1 (ideal scene)"),
    "ideal_force_B": ("N", "largest reaction in joint 2 (ideal scene)"),
    "integrator": ("1", "integrator of the run"),
    "film_cap": ("1", "eccentricity ratio at which the film force is capped, 1 - e0/c"),
    "hertz_stiffness": ("N m-1.5", "Hertz stiffness K of eq. (9)"),
    "max_penetration_ratio": ("1", "largest (|e| - c) / c: > 0 is penetration into the bushing, < 0 a gap that never closed"),
    "max_eccentricity_ratio": ("1", "largest eccentricity ratio |e| / c"),
    "max_contact_force": ("N", "largest dry contact force"),
    "max_film_force": ("N", "largest |film force along e|"),
}


def claims(cfg: Mapping[str, Any], scenes: Sequence[xr.Dataset], tight: Sequence[xr.Dataset]) -> xr.Dataset:
    """The three claims per variant, judged on RMS and peak deviation from the ideal, per cycle and for
    two integrator tolerances; plus each scene's cost, settling, drift and joint extremes."""
    cycles = cfg["numerics"]["record_cycles"]
    variants = list(cfg["variants"])
    runs, tight_runs = _by_key(scenes), _by_key(tight)
    compared = COMPARED
    rms = np.full((len(variants), len(QUANTITIES), len(compared), 2, cycles), np.nan)  # variant, quantity, scene, tolerance, cycle
    peak = np.full_like(rms, np.nan)
    for v, variant in enumerate(variants):
        ideal = runs[(variant, "ideal")]
        for qi, qname in enumerate(QUANTITIES):
            for s, name in enumerate(compared):
                for k, source in enumerate((runs, tight_runs)):
                    if (variant, name) in source:
                        m = deviation_measures(source[(variant, name)], ideal, qname, cycles)
                        rms[v, qi, s, k], peak[v, qi, s, k] = m["rms"], m["peak"]
    ratio = cfg["claims"]["close_to_ideal_ratio"]
    holds = np.array([[claims_hold(rms[v, :, :, k], peak[v, :, :, k], ratio) for k in range(len(TOLERANCE_SETS))] for v in range(len(variants))])
    holds = np.moveaxis(holds, 1, 2)  # variant, claim, tolerance set
    measures = np.stack([rms, peak], axis=1)  # variant, measure, quantity, scene, tolerance, cycle
    order = np.zeros(measures.shape[:3] + measures.shape[4:], dtype=int)
    lub_over_dry = np.full(order.shape, np.nan)
    for idx in np.ndindex(order.shape):
        v, m, q, k, c = idx
        values = measures[v, m, q, :, k, c]
        order[idx] = int(order_as_claimed(values, QUANTITIES[q]))
        lub_over_dry[idx] = np.max(values[3:] / values[:3])
    all_scenes = sorted({name for (_, name) in runs}, key=lambda n: (n != "ideal", n))
    summary = _scene_summary(runs, variants, all_scenes)
    dims = ("variant", "quantity", "scene", "tolerance_set", "cycle")
    data = {
        "rms_deviation": (dims, rms, {"units": "SI of the quantity", "long_name": "RMS of (scene - ideal) over a cycle"}),
        "peak_deviation": (dims, peak, {"units": "SI of the quantity", "long_name": "peak |scene - ideal| over a cycle"}),
        "holds": (("variant", "claim", "tolerance_set"), holds, {"units": "1", "long_name": "1 if the claim holds on the RMS and the peak measure in every recorded cycle"}),
        "order_as_claimed": (("variant", "measure", "quantity", "tolerance_set", "cycle"), order, {"units": "1", "long_name": "1 if the dry scenes are in the claimed order"}),
        "lubricated_over_dry_max": (("variant", "measure", "quantity", "tolerance_set", "cycle"), lub_over_dry, {"units": "1", "long_name": "largest lubricated / dry deviation over the joint configurations"}),
    }
    for key, arr in summary.items():
        unit, long_name = SUMMARY_ATTRS[key]
        data[f"summary_{key}"] = (("variant", "run") + (("joint",) if arr.ndim == 3 else ()), arr,
                                  {"units": unit, "long_name": long_name, "nan_meaning": "does not apply to this scene or joint (the ideal scene integrates nothing; a joint without clearance has no contact)"})
    coords = {
        "variant": ("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
        "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
        "measure": ("measure", np.array(["rms", "peak"], dtype=object), {"units": "1", "long_name": "deviation measure"}),
        "scene": ("scene", np.array(compared, dtype=object), {"units": "1", "long_name": "scene"}),
        "run": ("run", np.array(all_scenes, dtype=object), {"units": "1", "long_name": "scene run (pipeline tolerance)"}),
        "joint": ("joint", np.array(JOINT_IDS), {"units": "1", "long_name": "joint 1 (crank-coupler), 2 (coupler-rocker)"}),
        "tolerance_set": ("tolerance_set", np.array(list(TOLERANCE_SETS), dtype=object), {"units": "1", "long_name": "integrator setting"}),
        "cycle": ("cycle", np.arange(1, cycles + 1), {"units": "1", "long_name": "recorded cycle"}),
        "claim": ("claim", np.array(["acceleration_order", "torque_order", "lubrication_close"], dtype=object), {"units": "1", "long_name": "claim"}),
    }
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(title="Claims of the clearance paper, per parameter variant", close_to_ideal_ratio=ratio)
    return ds
