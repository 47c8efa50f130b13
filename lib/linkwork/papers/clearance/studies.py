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
#: A scene whose recorded per-cycle RMS deviation spreads by less than this fraction of its mean is reported as
#: periodic to within it (a description of the result; no decision uses it).
PERIODIC_SPREAD = 0.01


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


def periodic_ideal(p, per: int, n_cycles: int, gravity: bool) -> dict[str, np.ndarray]:
    """The ideal linkage's response at ``per`` points a cycle over ``n_cycles`` cycles (plus the end point): under a
    constant-speed drive it is a function of the crank angle alone, so one cycle of inverse dynamics, repeated."""
    one = inverse_dynamics(p, np.arange(per + 1) * cycle(p) / per, gravity)
    return {k: np.r_[np.tile(v[:-1], n_cycles), v[-1:]] for k, v in one.items()}


def record_count(cfg: Mapping[str, Any], tolerance: str) -> int:
    """Cycles a scene run records after settling: the long statistics at the pipeline tolerance, a short
    record at the tight one (its numerical-error estimate compares the same cycles)."""
    return cfg["statistics"]["record_cycles" if tolerance == "pipeline" else "tight_record_cycles"]


def cycle_deviations(values: Mapping[str, np.ndarray], ideal: Mapping[str, np.ndarray], per: int) -> np.ndarray:
    """Per cycle, the RMS and the peak of (scene - ideal) of each of QUANTITIES: (measure [rms, peak], quantity, cycle);
    ``values``/``ideal`` sampled at ``per`` points a cycle plus the end point."""
    out = []
    for q in QUANTITIES:
        d = (np.asarray(values[q]) - np.asarray(ideal[q]))[:-1]
        d = d.reshape(-1, per)
        out.append((np.sqrt(np.mean(d**2, axis=1)), np.abs(d).max(axis=1)))
    return np.moveaxis(np.array(out), 1, 0)


def scene(cfg: Mapping[str, Any], variant: str, scene: str, tolerance: str = "pipeline", record: int | None = None) -> xr.Dataset:
    """One scene of one parameter variant: settle until the running mean of the claims' measure is steady
    (``statistics``), record ``record`` cycles (default: by tolerance), keep every cycle's RMS and peak deviation
    from the ideal curve, the recorded extremes, and the time series of the first ``numerics.record_cycles``
    recorded cycles (the paper's figures).  The ideal scene is inverse dynamics over those cycles."""
    from .statistics import running_change, settle_point

    p = parameters(cfg, variant, scene)
    joints, effects = scene_effects(cfg, scene)
    numerics = cfg["numerics"]
    per, shown = numerics["points_per_cycle"], numerics["record_cycles"]
    stat = cfg["statistics"] if joints else {"settle_window_cycles": 1, "settle_tolerance": 0.0, "settle_max_cycles": 0}
    record = (record_count(cfg, tolerance) if record is None else record) if joints else shown
    n_cycles = stat["settle_max_cycles"] + record
    t = np.arange(n_cycles * per + 1) * cycle(p) / per
    ideal = periodic_ideal(p, per, n_cycles, "gravity" in effects)
    integ: Mapping[str, Any] = {}
    if not joints:  # kinematics and inverse dynamics, no integration
        diags = None
        meta = {"integrator": "none (inverse dynamics)", "steps": 0, "rejected": 0, "counts": [0, 0, 0, 0]}
        deviations = np.zeros((2, len(QUANTITIES), n_cycles))
        settled, ok, change = 0, True, np.zeros(n_cycles - 1)
    else:
        integ = cfg[TOLERANCE_SETS[tolerance]][integrator_kind(cfg["scenes"][scene])]
        _, diags, steps, rejected, counts, _ = integrate(p, joints, effects, t, integ)
        meta = {"integrator": integ["method"], "steps": steps, "rejected": rejected, "counts": counts.tolist()}
        deviations = cycle_deviations({"rocker_acceleration": diags[:, 0], "crank_torque": diags[:, 1]}, ideal, per)
        settled, ok = settle_point(deviations[0], stat["settle_window_cycles"], stat["settle_tolerance"], stat["settle_max_cycles"])
        whole = diags[:-1, 0].reshape(-1, per)
        change = np.sqrt(np.mean((whole[1:] - whole[:-1]) ** 2, axis=1)) / np.sqrt(np.mean(whole[-1] ** 2))
    start = settled * per
    window = slice(start, start + shown * per + 1)
    t_fig = t[window]
    if diags is None:
        per_joint = np.full((2, 6, t_fig.size), np.nan)
        series = {"acc": ideal["rocker_acceleration"][window], "torque": ideal["crank_torque"][window], "energy": ideal["energy"][window],
                  "drift": np.zeros(t_fig.size), "force_A": ideal["force_A"][window], "force_B": ideal["force_B"][window]}
        extremes = np.full((5, 2), np.nan)
        max_torque = float(np.abs(ideal["crank_torque"]).max())
    else:
        d = diags[window]
        rec = diags[start:]
        per_joint = np.full((2, 6, t_fig.size), np.nan)
        extremes = np.full((5, 2), np.nan)  # penetration, eccentricity, contact force, |film radial|, |film tangential| (recorded cycles)
        for k, j in enumerate(joints):
            per_joint[j - 1] = d[:, 4 + 6 * k : 10 + 6 * k].T
            r = rec[:, 4 + 6 * k : 10 + 6 * k]
            extremes[:, j - 1] = [np.nanmax(r[:, 1]), np.nanmax(r[:, 0]), np.nanmax(r[:, 3]), np.nanmax(np.abs(r[:, 4])), np.nanmax(np.abs(r[:, 5]))]
        nan = np.full(t_fig.size, np.nan)
        series = {"acc": d[:, 0], "torque": d[:, 1], "energy": d[:, 2], "drift": d[:, 3], "force_A": nan, "force_B": nan}
        max_torque = float(np.abs(rec[:, 1]).max())
    theta = np.degrees(start_angle(p) + p.crank_speed * t_fig)
    dims, jd = ("time",), ("joint", "time")
    pj = per_joint
    rc = running_change(deviations[0], stat["settle_window_cycles"])
    ds = xr.Dataset(
        {
            "crank_angle": (dims, theta, {"units": "deg", "long_name": "crank angle (unwrapped)"}),
            "rocker_acceleration": (dims, series["acc"], {"units": "rad s-2", "long_name": "rocker angular acceleration"}),
            "crank_torque": (dims, series["torque"], {"units": "N m", "long_name": "crank driving torque"}),
            "ideal_rocker_acceleration": (dims, ideal["rocker_acceleration"][window], {"units": "rad s-2", "long_name": "rocker angular acceleration of the ideal linkage at the same instants"}),
            "ideal_crank_torque": (dims, ideal["crank_torque"][window], {"units": "N m", "long_name": "crank driving torque of the ideal linkage at the same instants"}),
            "energy": (dims, series["energy"], {"units": "J", "long_name": "mechanical energy (kinetic + gravity + contact)"}),
            "constraint_drift": (dims, series["drift"], {"units": "m", "long_name": "|Phi| of the ideal constraints"}),
            "eccentricity": (jd, pj[:, 0], {"units": "m", "long_name": "journal eccentricity |e|", **NO_CLEARANCE}),
            "penetration": (jd, pj[:, 1], {"units": "m", "long_name": "penetration |e| - c (> 0 in contact)", **NO_CLEARANCE}),
            "contact_force": (jd, pj[:, 3], {"units": "N", "long_name": "dry normal contact force", **NO_CLEARANCE}),
            "film_radial_force": (jd, pj[:, 4], {"units": "N", "long_name": "film force along e (on the journal)", **NO_CLEARANCE}),
            "film_tangential_force": (jd, pj[:, 5], {"units": "N", "long_name": "film force across e (on the journal)", **NO_CLEARANCE}),
            "ideal_joint_force_A": (dims, series["force_A"], {"units": "N", "long_name": "reaction in joint 1 (A), ideal scene only", **NOT_IDEAL}),
            "ideal_joint_force_B": (dims, series["force_B"], {"units": "N", "long_name": "reaction in joint 2 (B), ideal scene only", **NOT_IDEAL}),
            "recorded_max_penetration": (("joint",), extremes[0], {"units": "m", "long_name": "largest |e| - c over the recorded cycles", **NO_CLEARANCE}),
            "recorded_max_eccentricity": (("joint",), extremes[1], {"units": "m", "long_name": "largest |e| over the recorded cycles", **NO_CLEARANCE}),
            "recorded_max_contact_force": (("joint",), extremes[2], {"units": "N", "long_name": "largest dry contact force over the recorded cycles", **NO_CLEARANCE}),
            "recorded_max_film_force": (("joint",), extremes[3], {"units": "N", "long_name": "largest |film force along e| over the recorded cycles", **NO_CLEARANCE}),
            "recorded_max_abs_torque": ((), max_torque, {"units": "N m", "long_name": "largest |crank driving torque| over the recorded cycles"}),
            "cycle_deviation": (("measure", "quantity", "run_cycle"), deviations, {"units": "SI of the quantity", "long_name": "RMS and peak of (scene - ideal) over each cycle from the start"}),
            "running_change": (("quantity", "run_cycle"), rc, {"units": "1", "long_name": "settling criterion: change of the running mean of the RMS deviation over the window", "nan_meaning": "fewer than two windows of cycles so far"}),
            "cycle_change": ("cycle_pair", change, {"units": "1", "long_name": "RMS change of the rocker acceleration from one cycle to the next / RMS of the last cycle"}),
        },
        coords={
            "cycle_pair": ("cycle_pair", np.arange(1, change.size + 1), {"units": "1", "long_name": "cycle k vs cycle k + 1 (from the start)"}),
            "run_cycle": ("run_cycle", np.arange(1, deviations.shape[-1] + 1), {"units": "1", "long_name": "cycle from the start"}),
            "measure": ("measure", np.array(["rms", "peak"], dtype=object), {"units": "1", "long_name": "deviation measure"}),
            "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
            "time": ("time", t_fig - t_fig[0], {"units": "s", "long_name": "time from the start of the recorded cycles"}),
            "joint": ("joint", np.array(JOINT_IDS), {"units": "1", "long_name": "joint 1 (crank-coupler), 2 (coupler-rocker)"}),
        },
    )
    cap = 1.0 - p.e0 / p.clearance if "lubrication" in effects else None
    ds.attrs.update(
        title=f"Four-bar with clearance joints: {variant}, {scene}", scene=scene, variant=variant, tolerance_set=tolerance,
        effects=",".join(effects), clearance_joints=",".join(map(str, joints)),
        integrator=meta["integrator"], steps=meta["steps"], rejected_steps=meta["rejected"],
        evaluations_contact=meta["counts"][0], evaluations_friction=meta["counts"][1],
        evaluations_lubrication=meta["counts"][2], evaluations_gravity=meta["counts"][3],
        crank_mass_kg=p.masses[0], settle_cycles=int(settled), settled=int(ok), record_cycles=int(n_cycles - settled) if joints else 0, shown_cycles=shown,
        settle_criterion="none (inverse dynamics)" if not joints else (f"running mean of the per-cycle RMS deviation (both quantities) over {stat['settle_window_cycles']} cycles changes by at most "
                          f"{stat['settle_tolerance']:g} of the mean over the {stat['settle_window_cycles']} cycles before, by cycle {stat['settle_max_cycles']} at the latest"),
        **({"hertz_stiffness": p.hertz_stiffness, "clearance": p.clearance} if joints else {}),
        **({"film_eccentricity_cap": cap} if cap is not None else {}),
        **(validity.attributes(diags[start:, [5 + 6 * k for k in range(len(joints))]].T, diags[start:, [4 + 6 * k for k in range(len(joints))]].T,
                               p.clearance, cap) if joints else {"validity_warnings": ""}),
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


CLAIMS = ("acceleration_order", "torque_order", "lubrication_close")


def comparisons(ratio: float) -> list[tuple[str, str, str, str, tuple[tuple[float, str], ...]]]:
    """Every ordering the claims are made of: (claim, label, measure, quantity, terms (coefficient, scene)); an
    ordering holds where sum of coefficient x mean > 0.  The order claims use the RMS and the peak deviation;
    'lubrication close to ideal' the RMS: each lubricated scene below ``ratio`` times its dry one, and joint 2's
    lubricated deviation above joint 1's (the ripples left at joint 2)."""
    out = []
    for claim, quantity, first in (("acceleration_order", "rocker_acceleration", ("dry_2", "dry_1")), ("torque_order", "crank_torque", ("dry_1", "dry_2"))):
        for measure in ("rms", "peak"):
            for a, b in (first, ("dry_both", "dry_1"), ("dry_both", "dry_2")):
                out.append((claim, f"{measure} {quantity}: {a} > {b}", measure, quantity, ((1.0, a), (-1.0, b))))
    for quantity in QUANTITIES:
        for dry, lub in zip(DRY, LUBRICATED, strict=True):
            out.append(("lubrication_close", f"rms {quantity}: {lub} < {ratio:g} x {dry}", "rms", quantity, ((ratio, dry), (-1.0, lub))))
        out.append(("lubrication_close", f"rms {quantity}: lubricated_2 > lubricated_1", "rms", quantity, ((1.0, "lubricated_2"), (-1.0, "lubricated_1"))))
    return out


def judge(scene_stats: Mapping[tuple[str, str, str], tuple[float, float, float, float]], ratio: float, confidence: float) -> dict[str, Any]:
    """The claims from per-scene statistics ((measure, quantity, scene) -> (mean, standard error, degrees of
    freedom, numerical error)): each ordering's difference, statistical half-width, numerical error and outcome,
    and per claim the outcome on the means alone (``point``) and the decided outcome (``outcome``)."""
    from .statistics import HOLDS, UNDETERMINED, conjunction, decide, difference

    rows = []
    for claim, label, measure, quantity, terms in comparisons(ratio):
        d, stat, num = difference([(c, *scene_stats[(measure, quantity, name)]) for c, name in terms], confidence)
        outcome = decide(d, stat, num)
        unsteady = [name for _, name in terms if not np.isfinite(scene_stats[(measure, quantity, name)][1])]
        rows.append({"claim": claim, "label": label, "difference": d, "statistical": stat, "numerical": num, "outcome": outcome,
                     "reason": undecided_reason(d, stat, num, unsteady) if outcome == UNDETERMINED else ""})
    point = [float(all(r["difference"] > 0 for r in rows if r["claim"] == c)) for c in CLAIMS]
    outcome = [conjunction([r["outcome"] for r in rows if r["claim"] == c]) for c in CLAIMS]
    reasons = [claim_reason([r["reason"] for r in rows if r["claim"] == c]) if o == UNDETERMINED else "" for c, o in zip(CLAIMS, outcome, strict=True)]
    return {"rows": rows, "point": point, "outcome": outcome, "decided": [float(o != -1) for o in outcome], "holds_decidedly": [float(o == HOLDS) for o in outcome],
            "reason": reasons}


def undecided_reason(diff: float, stat_margin: float, numerical_error: float, unsteady: Sequence[str]) -> str:
    """Which margin leaves an ordering undetermined: a scene without a valid interval (not settled or not
    stationary), the statistical margin, or the numerical error (the larger one where both exceed |diff|)."""
    if unsteady:
        return f"statistics (not settled / not stationary: {', '.join(unsteady)})"
    if abs(diff) <= stat_margin and (abs(diff) > numerical_error or stat_margin >= numerical_error):
        return "statistical margin"
    return "numerical error"


def claim_reason(reasons: Sequence[str]) -> str:
    """The distinct reasons of a claim's undetermined orderings, in order of first appearance."""
    return "; ".join(dict.fromkeys(r for r in reasons if r))


def recorded(run: xr.Dataset) -> np.ndarray:
    """The per-cycle deviations of a scene's recorded cycles (after settling): (measure, quantity, cycle)."""
    return run.cycle_deviation.values[..., int(run.attrs["settle_cycles"]):]


def numerical_error(run: xr.Dataset, tight: xr.Dataset) -> np.ndarray:
    """|mean over the common recorded cycles of (tight - pipeline)| per measure and quantity: the same cycles
    (from the pipeline run's settle point) at the two tolerances; in a scene that never repeats it also holds
    the divergence of the impact sequence, so it errs on the large side."""
    k = int(run.attrs["settle_cycles"])
    n = min(run.cycle_deviation.shape[-1], tight.cycle_deviation.shape[-1])
    return np.abs(np.mean(tight.cycle_deviation.values[..., k:n] - run.cycle_deviation.values[..., k:n], axis=-1))


def _scene_summary(runs: Mapping[tuple[str, str], xr.Dataset], variants: list[str], scenes: list[str]) -> dict[str, Any]:
    """Per variant and scene: cost, settling, drift, effect counters and joint extremes (what the report tabulates)."""
    shape, jshape = (len(variants), len(scenes)), (len(variants), len(scenes), len(JOINT_IDS))
    out = {k: np.full(shape, np.nan) for k in ("steps", "first_change", "last_change", "max_drift", "n_contact", "n_friction", "n_lubrication", "ideal_force_A", "ideal_force_B", "film_cap", "hertz_stiffness",
                                             "settle_cycles", "settled", "recorded_cycles", "max_abs_torque", "beyond_film_cap_fraction")}
    out["integrator"] = np.full(shape, "", dtype=object)
    out["contact_label"] = np.full(jshape, "", dtype=object)
    out.update({k: np.full(jshape, np.nan) for k in ("max_penetration_ratio", "max_eccentricity_ratio", "max_contact_force", "max_film_force", "contact_value")})
    for v, variant in enumerate(variants):
        for s, name in enumerate(scenes):
            ds = runs.get((variant, name))
            if ds is None:
                continue
            out["integrator"][v, s] = ds.attrs["integrator"]
            out["max_abs_torque"][v, s] = float(ds.recorded_max_abs_torque)
            if name == "ideal":
                out["ideal_force_A"][v, s] = float(ds.ideal_joint_force_A.max())
                out["ideal_force_B"][v, s] = float(ds.ideal_joint_force_B.max())
                continue
            out["film_cap"][v, s] = ds.attrs.get("film_eccentricity_cap", np.nan)
            out["beyond_film_cap_fraction"][v, s] = ds.attrs.get("validity_beyond_film_cap_fraction", np.nan)
            out["hertz_stiffness"][v, s] = ds.attrs["hertz_stiffness"]
            out["steps"][v, s] = ds.attrs["steps"]
            out["first_change"][v, s], out["last_change"][v, s] = float(ds.cycle_change[0]), float(ds.cycle_change[-1])
            out["max_drift"][v, s] = float(ds.constraint_drift.max())
            for key, attr in (("n_contact", "contact"), ("n_friction", "friction"), ("n_lubrication", "lubrication")):
                out[key][v, s] = ds.attrs[f"evaluations_{attr}"]
            out["settle_cycles"][v, s], out["settled"][v, s] = ds.attrs["settle_cycles"], ds.attrs["settled"]
            out["recorded_cycles"][v, s] = ds.attrs["record_cycles"]
            c = ds.attrs["clearance"]
            for j, jid in enumerate(JOINT_IDS):
                pen = float(ds.recorded_max_penetration.sel(joint=jid))
                if np.isfinite(pen):
                    out["max_penetration_ratio"][v, s, j] = pen / c
                    out["contact_label"][v, s, j], out["contact_value"][v, s, j] = validity.contact_extent(pen / c)
                    out["max_eccentricity_ratio"][v, s, j] = float(ds.recorded_max_eccentricity.sel(joint=jid)) / c
                    out["max_contact_force"][v, s, j] = float(ds.recorded_max_contact_force.sel(joint=jid))
                    out["max_film_force"][v, s, j] = float(ds.recorded_max_film_force.sel(joint=jid))
    return out


SUMMARY_ATTRS = {
    "steps": ("1", "accepted integrator steps"),
    "first_change": ("1", "cycle-to-cycle change of the rocker acceleration, first cycle pair"),
    "last_change": ("1", "cycle-to-cycle change of the rocker acceleration, last cycle pair"),
    "max_drift": ("m", "largest constraint drift |Phi| over the cycles shown"),
    "settle_cycles": ("1", "cycles discarded before recording (the settling criterion, see the scene's settle_criterion)"),
    "settled": ("1", "1 if the settling criterion held by the latest allowed cycle"),
    "recorded_cycles": ("1", "cycles recorded after settling"),
    "max_abs_torque": ("N m", "largest |crank driving torque| over the recorded cycles"),
    "n_contact": ("1", "contact-force evaluations"),
    "n_friction": ("1", "friction evaluations"),
    "n_lubrication": ("1", "film-force evaluations"),
    "ideal_force_A": ("N", "largest reaction in joint 1 (ideal scene)"),
    "ideal_force_B": ("N", "largest reaction in joint 2 (ideal scene)"),
    "integrator": ("1", "integrator of the run"),
    "film_cap": ("1", "eccentricity ratio at which the film force is capped, 1 - e0/c"),
    "hertz_stiffness": ("N m-1.5", "Hertz stiffness K of eq. (9)"),
    "beyond_film_cap_fraction": ("1", "fraction of the recorded time at which a lubricated journal runs beyond the film cap"),
    "max_penetration_ratio": ("1", "largest (|e| - c) / c over the recorded cycles: > 0 is penetration into the bushing, < 0 a gap that never closed"),
    "max_eccentricity_ratio": ("1", "largest eccentricity ratio |e| / c"),
    "contact_label": ("1", "how the deepest contact reads: 'max penetration / c' (the journal entered the bushing) or 'min gap / c' (it never touched)"),
    "contact_value": ("1", "the value of contact_label (a gap as a positive fraction of c)"),
    "max_contact_force": ("N", "largest dry contact force"),
    "max_film_force": ("N", "largest |film force along e|"),
}


def scene_stationarity(run: xr.Dataset, tolerance: float, confidence: float) -> tuple[bool, np.ndarray]:
    """(stationary?, relative change between the record's halves per quantity) of the RMS deviation of a scene's
    recorded cycles (the measure the settling criterion uses); see ``statistics.stationary``."""
    from .statistics import stationary

    return stationary(recorded(run)[0], tolerance, confidence)


def scene_statistics(run: xr.Dataset, batch: int, confidence: float, steady: bool = True) -> np.ndarray:
    """(measure, quantity, [mean, half-width, standard error, degrees of freedom, lag-1 autocorrelation, cycles])
    of a scene's recorded per-cycle deviations; an unsettled scene, or one whose record is not stationary
    (``steady`` False), gets an infinite half-width (its mean drifts)."""
    from .statistics import lag1_autocorrelation, mean_ci

    values = recorded(run)
    out = np.empty(values.shape[:2] + (6,))
    for idx in np.ndindex(values.shape[:2]):
        mean, half, se, dof = mean_ci(values[idx], batch, confidence)
        if not run.attrs["settled"] or not steady:
            half, se = float("inf"), float("inf")
        out[idx] = (mean, half, se, dof, lag1_autocorrelation(values[idx]), values.shape[-1])
    return out


def stats_for_judging(stats: np.ndarray, num: np.ndarray) -> dict[tuple[str, str, str], tuple[float, float, float, float]]:
    """(measure, quantity, scene) -> (mean, standard error, degrees of freedom, numerical error) from arrays
    (measure, quantity, scene, statistic) and (measure, quantity, scene)."""
    return {(m, q, s): (float(stats[i, j, k, 0]), float(stats[i, j, k, 2]), float(stats[i, j, k, 3]), float(num[i, j, k]))
            for i, m in enumerate(("rms", "peak")) for j, q in enumerate(QUANTITIES) for k, s in enumerate(COMPARED)}


STATISTICS = ("mean", "half_width", "standard_error", "dof", "lag1_autocorrelation", "cycles")


def claims(cfg: Mapping[str, Any], scenes: Sequence[xr.Dataset], tight: Sequence[xr.Dataset]) -> xr.Dataset:
    """The three claims per variant, judged on the mean over the recorded cycles of the RMS and peak deviation
    from the ideal curve, with a confidence interval and the numerical error (pipeline against tight tolerance);
    plus each scene's cost, settling, drift and joint extremes."""
    from .statistics import CI_METHOD, DECISION_RULE

    st = cfg["statistics"]
    batch, confidence, ratio = st["batch_cycles"], st["confidence"], cfg["claims"]["close_to_ideal_ratio"]
    stationarity_tolerance = st["stationarity_tolerance"]
    variants = list(cfg["variants"])
    runs, tight_runs = _by_key(scenes), _by_key(tight)
    n_max = max(recorded(runs[(v, s)]).shape[-1] for v in variants for s in COMPARED)
    per_cycle = np.full((len(variants), 2, len(QUANTITIES), len(COMPARED), n_max), np.nan)  # variant, measure, quantity, scene, cycle
    stats = np.full((len(variants), 2, len(QUANTITIES), len(COMPARED), len(STATISTICS)), np.nan)
    num = np.full((len(variants), 2, len(QUANTITIES), len(COMPARED)), np.nan)
    labels = [c[1] for c in comparisons(ratio)]
    comp = np.full((len(variants), len(labels), 4), np.nan)  # difference, statistical, numerical, outcome
    holds, decided = np.zeros((len(variants), len(CLAIMS))), np.zeros((len(variants), len(CLAIMS)))
    steady = np.zeros((len(variants), len(COMPARED)), dtype=int)
    half_change = np.full((len(variants), len(QUANTITIES), len(COMPARED)), np.nan)
    spread = np.full((len(variants), len(QUANTITIES), len(COMPARED)), np.nan)
    comp_reason = np.full((len(variants), len(labels)), "", dtype=object)
    claim_reasons = np.full((len(variants), len(CLAIMS)), "", dtype=object)
    for v, variant in enumerate(variants):
        for s, name in enumerate(COMPARED):
            run = runs[(variant, name)]
            values = recorded(run)
            per_cycle[v, :, :, s, : values.shape[-1]] = values
            ok, half_change[v, :, s] = scene_stationarity(run, stationarity_tolerance, confidence)
            rms = values[0]
            spread[v, :, s] = (rms.max(axis=-1) - rms.min(axis=-1)) / np.abs(rms.mean(axis=-1))
            steady[v, s] = int(ok)
            stats[v, :, :, s] = scene_statistics(run, batch, confidence, steady=ok)
            num[v, :, :, s] = numerical_error(run, tight_runs[(variant, name)])
        verdict = judge(stats_for_judging(stats[v], num[v]), ratio, confidence)
        comp[v] = [[r["difference"], r["statistical"], r["numerical"], r["outcome"]] for r in verdict["rows"]]
        comp_reason[v] = [r["reason"] for r in verdict["rows"]]
        claim_reasons[v] = verdict["reason"]
        holds[v], decided[v] = verdict["point"], verdict["decided"]
    all_scenes = sorted({name for (_, name) in runs}, key=lambda n: (n != "ideal", n))
    summary = _scene_summary(runs, variants, all_scenes)
    sd = ("variant", "measure", "quantity", "scene")
    data = {
        "cycle_deviation": (sd + ("cycle",), per_cycle, {"units": "SI of the quantity", "long_name": "RMS or peak of (scene - ideal) over each recorded cycle (after settling)",
                                                          "nan_meaning": "the scene recorded fewer cycles"}),
        "mean_deviation": (sd, stats[..., 0], {"units": "SI of the quantity", "long_name": "mean over the recorded cycles"}),
        "ci_half_width": (sd, np.where(np.isfinite(stats[..., 1]), stats[..., 1], np.nan), {"units": "SI of the quantity", "long_name": f"half-width of the {confidence:.0%} confidence interval of the mean",
                                                                                            "nan_meaning": "the scene did not settle or its record is not stationary: its mean is not a statistic (no ordering with it is decided)"}),
        "standard_error": (sd, np.where(np.isfinite(stats[..., 2]), stats[..., 2], np.nan), {"units": "SI of the quantity", "long_name": "standard error of the mean (batch means)",
                                                                                             "nan_meaning": "the scene did not settle or its record is not stationary"}),
        "ci_dof": (sd, stats[..., 3], {"units": "1", "long_name": "degrees of freedom of the interval (batches - 1)"}),
        "lag1_autocorrelation": (sd, stats[..., 4], {"units": "1", "long_name": "lag-1 autocorrelation of the per-cycle values", "nan_meaning": "the values are constant"}),
        "recorded_cycles": (sd, stats[..., 5], {"units": "1", "long_name": "cycles recorded after settling"}),
        "numerical_error": (sd, num, {"units": "SI of the quantity", "long_name": "|mean of (tight - pipeline)| over the common recorded cycles"}),
        "comparison_difference": (("variant", "comparison"), comp[..., 0], {"units": "SI of the quantity", "long_name": "difference of the means the ordering is about (> 0: as claimed)"}),
        "comparison_statistical": (("variant", "comparison"), np.where(np.isfinite(comp[..., 1]), comp[..., 1], np.nan),
                                   {"units": "SI of the quantity", "long_name": f"{confidence:.0%} half-width of the difference", "nan_meaning": "a scene of the ordering did not settle or is not stationary (undetermined)"}),
        "comparison_numerical": (("variant", "comparison"), comp[..., 2], {"units": "SI of the quantity", "long_name": "numerical error of the difference"}),
        "comparison_outcome": (("variant", "comparison"), comp[..., 3].astype(int), {"units": "1", "long_name": "1 holds, 0 fails, -1 undetermined (within a margin)"}),
        "holds": (("variant", "claim"), holds, {"units": "1", "long_name": "1 if every ordering of the claim holds on the means"}),
        "decided": (("variant", "claim"), decided, {"units": "1", "long_name": "1 if the claim's outcome is beyond the statistical and numerical margins"}),
        "undecided": (("variant", "claim"), 1.0 - decided, {"units": "1", "long_name": "1 if a margin decides the claim (the verdict's error bar)"}),
        "claim_decided_by": (("variant", "claim"), claim_reasons, {"units": "1", "long_name": "which margin leaves the claim undetermined (empty: decided)"}),
        "comparison_decided_by": (("variant", "comparison"), comp_reason, {"units": "1", "long_name": "which margin leaves the ordering undetermined (empty: decided)"}),
        "stationary": (("variant", "scene"), steady, {"units": "1", "long_name": f"1 if the recorded RMS deviation is stationary: its halves' means differ by at most "
                                                                                 f"{stationarity_tolerance:g} of the mean or within their {confidence:.0%} Welch interval (every quantity)"}),
        "cycle_spread": (("variant", "quantity", "scene"), spread, {"units": "1", "long_name": "(largest - smallest) / mean of the recorded per-cycle RMS deviation"}),
        "half_change": (("variant", "quantity", "scene"), half_change, {"units": "1", "long_name": "|mean of the second half - mean of the first half| / mean of the recorded RMS deviation"}),
    }
    for key, arr in summary.items():
        unit, long_name = SUMMARY_ATTRS[key]
        data[f"summary_{key}"] = (("variant", "run") + (("joint",) if arr.ndim == 3 else ()), arr,
                                  {"units": unit, "long_name": long_name, "nan_meaning": "does not apply to this scene or joint (the ideal scene integrates nothing; a joint without clearance has no contact)"})
    coords = {
        "variant": ("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
        "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
        "measure": ("measure", np.array(["rms", "peak"], dtype=object), {"units": "1", "long_name": "deviation measure"}),
        "scene": ("scene", np.array(COMPARED, dtype=object), {"units": "1", "long_name": "scene"}),
        "run": ("run", np.array(all_scenes, dtype=object), {"units": "1", "long_name": "scene run (pipeline tolerance)"}),
        "joint": ("joint", np.array(JOINT_IDS), {"units": "1", "long_name": "joint 1 (crank-coupler), 2 (coupler-rocker)"}),
        "cycle": ("cycle", np.arange(1, n_max + 1), {"units": "1", "long_name": "recorded cycle (after settling)"}),
        "claim": ("claim", np.array(CLAIMS, dtype=object), {"units": "1", "long_name": "claim"}),
        "comparison": ("comparison", np.array(labels, dtype=object), {"units": "1", "long_name": "ordering a claim is made of"}),
        "comparison_claim": ("comparison", np.array([c[0] for c in comparisons(ratio)], dtype=object), {"units": "1", "long_name": "claim of the ordering"}),
    }
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(title="Claims of the clearance paper, per parameter variant", close_to_ideal_ratio=ratio, ci_method=CI_METHOD,
                    crank_mass_kg=runs[(variants[0], "ideal")].attrs["crank_mass_kg"],
                    decision_rule=DECISION_RULE, confidence=confidence, batch_cycles=batch, stationarity_tolerance=stationarity_tolerance, periodic_spread=PERIODIC_SPREAD,
                    numerical_error_method="per scene: |mean over the common recorded cycles of (tight - pipeline tolerance)|; of a difference: the sum over its scenes",
                    tight_settings="; ".join(sorted({f"{r.attrs['integrator']} rtol {r.attrs['integrator_rtol']:g}, atol {r.attrs['integrator_atol']:g}" for r in tight})))
    return ds
