"""The clearance paper's studies: one scene run and the claims across scenes.  Each takes the config
values its rule passes (see ``adapter``) and returns a result Dataset."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr

from .fourbar import integrate, inverse_dynamics, start_angle
from ...engines.multibody import validity
from .adapter import COMPARED, DRY, LUBRICATED, integrator_kind, parameters, scene_effects
from .settling import MEASURES, RESPONSES

JOINT_IDS = (1, 2)
QUANTITIES = RESPONSES  # the compared responses, in the order of the measure rows


#: Attributes of a per-joint variable: NaN where the scene gives the joint no clearance.
NO_CLEARANCE = {"nan_meaning": "the joint has no clearance in this scene"}


#: Attributes of an interval that a record cut short by the cycle cap does not have (stored NaN, read as inf).
NO_INTERVAL = {"nan_meaning": "no interval: the record reached the cycle cap (its mean may drift)"}


def stored(stats: np.ndarray) -> np.ndarray:
    """Statistics (..., [mean, half-width, standard error, dof, cycles]) as written: inf (no interval; a periodic
    orbit's degrees of freedom) as NaN, since a result file holds no inf."""
    return np.where(np.isinf(stats), np.nan, stats)


def read(stats: np.ndarray) -> np.ndarray:
    """Statistics as ``stored`` wrote them, back to inf where an interval or degrees of freedom is missing."""
    out = np.array(stats, dtype=float)
    out[..., 1:4] = np.where(np.isnan(out[..., 1:4]) & np.isfinite(out[..., :1]), np.inf, out[..., 1:4])
    return out


#: Attributes of an ideal-joint reaction: NaN in scenes with clearance joints.
NOT_IDEAL = {"nan_meaning": "a scene with clearance joints has no ideal reaction"}


def cycle(p) -> float:
    """Period of one crank revolution (s)."""
    return 2 * np.pi / p.crank_speed


def output_times(numerics: Mapping[str, Any], p) -> tuple[np.ndarray, np.ndarray]:
    """(all output times (s), mask of the recorded cycles): settle cycles, then the recorded ones (a fixed record:
    the Exudyn cross-check's)."""
    per = numerics["points_per_cycle"]
    total = numerics["settle_cycles"] + numerics["record_cycles"]
    t = np.arange(total * per + 1) * cycle(p) / per
    return t, t >= numerics["settle_cycles"] * cycle(p) - 1e-12


def periodic_ideal(p, per: int, n_cycles: int, gravity: bool) -> dict[str, np.ndarray]:
    """The ideal linkage's response at ``per`` points a cycle over ``n_cycles`` cycles (plus the end point): under a
    constant-speed drive it is a function of the crank angle alone, so one cycle of inverse dynamics, repeated."""
    one = inverse_dynamics(p, np.arange(per + 1) * cycle(p) / per, gravity)
    return {k: np.r_[np.tile(v[:-1], n_cycles), v[-1:]] for k, v in one.items()}


def cycle_deviations(values: Mapping[str, np.ndarray], ideal: Mapping[str, np.ndarray], per: int) -> np.ndarray:
    """Per cycle, the RMS and the peak of (scene - ideal) of each of QUANTITIES: (measure [rms, peak], quantity, cycle);
    ``values``/``ideal`` sampled at ``per`` points a cycle plus the end point."""
    out = []
    for q in QUANTITIES:
        d = (np.asarray(values[q]) - np.asarray(ideal[q]))[:-1]
        d = d.reshape(-1, per)
        out.append((np.sqrt(np.mean(d**2, axis=1)), np.abs(d).max(axis=1)))
    return np.moveaxis(np.array(out), 1, 0)


def contact_frequency(p, penetration: float, joint: int) -> float:
    """Linearised contact frequency (Hz) of the dry contact of clearance joint ``joint`` (1 or 2) at a penetration
    (m): sqrt(k / m) / 2 pi with the contact stiffness k = 1.5 K delta^0.5 (eq. 9 differentiated) and m the lightest
    of the two bodies the joint connects (the highest frequency the joint can ring at); NaN without penetration."""
    if not np.isfinite(penetration) or penetration <= 0:
        return float("nan")
    bodies = {1: (0, 1), 2: (1, 2)}
    mass = min(p.masses[b] for b in bodies[joint])
    return float(np.sqrt(1.5 * p.hertz_stiffness * np.sqrt(penetration) / mass) / (2 * np.pi))


def scene(
    cfg: Mapping[str, Any], variant: str, scene: str, first_start_only: bool = False, check: bool = True, memory=None
) -> xr.Dataset:
    """One scene of one parameter variant.  The ideal scene is inverse dynamics over ``numerics.record_cycles``
    cycles.  A scene with clearance joints runs from each start of ``states.starts`` until its state is found
    (``settling``), keeps per start the Poincaré section and the per-cycle RMS and peak deviation from the ideal
    curve of every cycle from the start, the state (period or 'not periodic', transient, judged window), the
    claims' measures on the state with their interval and the numerical error bar from the check integrators, and
    the time series of the first start's last ``numerics.record_cycles`` cycles (the paper's figures).
    ``first_start_only``: the first start alone; ``check`` False: no check reruns (numerical error NaN): an
    input-uncertainty sample's run, which takes the nominal run's error bar; ``memory``: start the first start from
    this run state instead (a nominal state's ``window_memory``: a sample continues from the nominal state)."""
    p = parameters(cfg, variant, scene)
    joints, effects = scene_effects(cfg, scene)
    numerics = cfg["numerics"]
    per, shown = numerics["points_per_cycle"], numerics["record_cycles"]
    if not joints:
        return _ideal_scene(p, variant, scene, effects, per, shown)
    return _dynamic_scene(cfg, p, variant, scene, joints, effects, per, shown, first_start_only, check, memory)


def _ideal_scene(p, variant: str, scene: str, effects, per: int, shown: int) -> xr.Dataset:
    """The ideal scene: kinematics and inverse dynamics over ``shown`` cycles, no integration."""
    t = np.arange(shown * per + 1) * cycle(p) / per
    ideal = periodic_ideal(p, per, shown, "gravity" in effects)
    theta = np.degrees(start_angle(p) + p.crank_speed * t)
    dims = ("time",)
    ds = xr.Dataset(
        {
            "crank_angle": (dims, theta, {"units": "deg", "long_name": "crank angle (unwrapped)"}),
            "rocker_acceleration": (
                dims, ideal["rocker_acceleration"], {"units": "rad s-2", "long_name": "rocker angular acceleration"},
            ),
            "crank_torque": (dims, ideal["crank_torque"], {"units": "N m", "long_name": "crank driving torque"}),
            "energy": (dims, ideal["energy"], {"units": "J", "long_name": "mechanical energy (kinetic + gravity)"}),
            "ideal_joint_force_A": (dims, ideal["force_A"], {"units": "N", "long_name": "reaction in joint 1 (A)"}),
            "ideal_joint_force_B": (dims, ideal["force_B"], {"units": "N", "long_name": "reaction in joint 2 (B)"}),
            "recorded_max_abs_torque": (
                (), float(np.abs(ideal["crank_torque"]).max()),
                {"units": "N m", "long_name": "largest |crank driving torque|"},
            ),
        },
        coords={"time": ("time", t, {"units": "s", "long_name": "time from the dead point"})},
    )
    ds.attrs.update(
        title=f"Four-bar with ideal joints: {variant}", scene=scene, variant=variant, effects=",".join(effects),
        clearance_joints="", integrator="none (inverse dynamics)", steps=0, crank_mass_kg=p.masses[0],
        shown_cycles=shown,
    )
    return ds


def _dynamic_scene(
    cfg, p, variant, scene, joints, effects, per, shown, first_start_only=False, check=True, memory=None
) -> xr.Dataset:
    from .settling import EXTREMES, CycleRunner, check_state, judged_statistics, reach_state, settle_start, start_state

    st, stats = cfg["states"], cfg["statistics"]
    kind = integrator_kind(cfg["scenes"][scene])
    integ, checks = cfg["integrators"][kind], (cfg["check_integrators"][kind] if check else [])
    ideal_cycle = inverse_dynamics(p, np.arange(per + 1) * cycle(p) / per, "gravity" in effects)
    starts = st["starts"][:1] if first_start_only else st["starts"]

    def make_runner(integrator, memory=None, y0=None):
        return CycleRunner(
            p, joints, effects, integrator, ideal_cycle, per, shown, cfg["claims"]["ripple_cutoff_hz"], y0=y0,
            memory=memory,
        )

    found, runners, checked, reached = [], [], [], []
    for k, start in enumerate(starts):
        from_memory = memory is not None and k == 0
        runner = (
            make_runner(integ, memory=memory) if from_memory else make_runner(integ, y0=start_state(p, joints, start))
        )
        f = settle_start(runner, st, stats["confidence"])
        found.append(f)
        runners.append(runner)
        checked.append(check_state(make_runner, f, runner, checks, st))
        if checks and not from_memory:  # the start once more from its initial state at the first check integrator
            reached.append(
                reach_state(
                    make_runner, f, {"y0": start_state(p, joints, start)}, checks[0], st, stats["batch_cycles"],
                    stats["confidence"],
                )
            )
            print(
                f"clearance_scene: {variant} {scene}, start {start['label']}: {f['status']} (period {f['period']},"
                f" {f['points'].shape[0]} turns); from the start at rtol {checks[0]['rtol']:g}: {reached[-1]['status']}"
                f" (period {reached[-1]['period']}, {reached[-1]['cycles']} turns)",
                flush=True,
            )
    runs = SceneRuns(joints, effects, integ, checks, starts, found, runners, checked, reached)
    return _scene_dataset(p, cfg, variant, scene, runs, ideal_cycle, per, shown, EXTREMES, judged_statistics)


def ripple_by_cutoff(turn: np.ndarray, cutoffs_hz: np.ndarray, crank_speed: float) -> np.ndarray:
    """The ripple (``settling.ripple``) of one turn ``turn`` (rows x (n + 1) samples, the end point included) at each
    cutoff (Hz) at ``crank_speed`` (rad/s): rows x cutoffs."""
    from .settling import ripple, ripple_harmonic

    return np.stack([ripple(turn, ripple_harmonic(c, crank_speed)) for c in cutoffs_hz], axis=-1)


@dataclass(frozen=True)
class SceneRuns:
    """What a dynamic scene's runs left, per start (``starts``, in order): the settled state ``found``, the
    ``CycleRunner`` that ran it, the check integrators' record ``checked`` and the run from the start at the first check
    integrator ``reached`` (empty: none ran); with the scene's clearance joints, named effects, the pipeline's
    integrator ``integ`` and the check integrators ``checks``."""

    joints: tuple
    effects: tuple
    integ: Mapping[str, Any]
    checks: Sequence[Mapping[str, Any]]
    starts: Sequence[Mapping[str, Any]]
    found: Sequence[Mapping[str, Any]]
    runners: Sequence[Any]
    checked: Sequence[Mapping[str, Any]]
    reached: Sequence[Mapping[str, Any]] = ()


def _measure_shape(*lead: int) -> tuple[int, ...]:
    return (*lead, len(MEASURES), len(QUANTITIES))


def _start_records(
    runs: SceneRuns, stats: Mapping[str, Any], extremes_names, judged_statistics
) -> dict[str, np.ndarray]:
    """Per start, padded with NaN to the longest record: the Poincaré section, the per-cycle measures, the judged
    statistics, the judged window's extremes per joint and the check integrators' records."""
    ns, nc = len(runs.starts), len(runs.checks)
    n_max = max(f["points"].shape[0] for f in runs.found)
    out = {
        "section": np.full((ns, n_max, runs.found[0]["points"].shape[1]), np.nan),
        "per_cycle": np.full((*_measure_shape(ns), n_max), np.nan),
        "judged": np.full((*_measure_shape(ns), 5), np.nan),
        "window_ext": np.full((ns, len(extremes_names), 2), np.nan),
        "delta": np.full(_measure_shape(ns, nc), np.nan),
        "check_mean": np.full(_measure_shape(ns, nc), np.nan),
        "kept": np.full((ns, nc), np.nan),
        "check_period": np.zeros((ns, nc), dtype=int),
        "check_distance": np.full((ns, nc), np.nan),
    }
    for i, (f, r, c) in enumerate(zip(runs.found, runs.runners, runs.checked, strict=True)):
        n = f["points"].shape[0]
        out["section"][i, :n] = f["points"]
        out["per_cycle"][i, ..., :n] = f["measures"].T.reshape(*_measure_shape(), n)
        judged = judged_statistics(f["measures"], f, stats["batch_cycles"], stats["confidence"])
        out["judged"][i] = stored(judged).reshape(*_measure_shape(), 5)
        first, stop = f["window"]
        ext = np.array(r.extremes)[first:stop]  # cycle, joint, extreme
        for k, j in enumerate(runs.joints):
            out["window_ext"][i, :, j - 1] = np.nanmax(ext[:, k, :], axis=0)
        out["delta"][i] = c["delta"].reshape(_measure_shape(nc))
        out["check_mean"][i] = c["mean"].reshape(_measure_shape(nc))
        out["kept"][i], out["check_period"][i], out["check_distance"][i] = c["kept"], c["period"], c["distance"]
    return out


def _reach_records(runs: SceneRuns) -> dict[str, np.ndarray]:
    """Per start, the run from its initial state at the first check integrator (``settling.reach_state``): the
    measures' change against the pipeline's state, whether it reached the same orbit, its period and status."""
    ns = len(runs.starts)
    out = {
        "delta": np.full(_measure_shape(ns), np.nan),
        "same": np.full(ns, np.nan),
        "period": np.full(ns, -1),
        "status": np.full(ns, "not run", dtype=object),
    }
    for i, r in enumerate(runs.reached):
        out["delta"][i] = r["delta"].reshape(_measure_shape())
        out["same"][i], out["period"][i], out["status"][i] = r["same"], r["period"], r["status"]
    return out


def _error_bar(runs: SceneRuns, delta: np.ndarray, reach_delta: np.ndarray) -> dict[str, np.ndarray]:
    """The numerical error of each start's measures: the largest change over the check integrators' reruns and the
    run from the start (NaN: no check ran, or every one failed), plus what the sampling misses of a narrow peak
    (parabolic refinement, the largest over the judged turns; peak measure only), plus what a periodic state still
    converging can move its measure."""
    from .settling import convergence_error

    numerical = np.full(delta.shape[:1] + delta.shape[2:], np.nan)
    if len(runs.checks):
        both = np.concatenate([delta, reach_delta[:, None]], axis=1)
        largest = np.max(np.where(np.isfinite(both), np.abs(both), -np.inf), axis=1)
        numerical = np.where(np.isfinite(largest), largest, np.nan)
    sampling = np.array(
        [np.max(np.array(r.peak_refinement)[f["window"][0] : f["window"][1]], axis=0)
         for f, r in zip(runs.found, runs.runners, strict=True)]
    )
    numerical[:, MEASURES.index("peak"), :] += sampling
    converging = np.array([convergence_error(f["measures"], f).reshape(_measure_shape()) for f in runs.found])
    return {"numerical": numerical + converging, "sampling": sampling, "converging": converging}


def _shown_cycles(p, runs: SceneRuns, ideal_cycle, per: int, cutoffs_hz: np.ndarray) -> dict[str, Any]:
    """The first start's last cycles, the figures' time series: times ``t`` (s), the recorded columns ``d``, the
    ideal linkage at the same instants, the clearance joints' records (joint, column, time) and the ripple of the
    last turn at each cutoff of the sensitivity list."""
    last = runs.runners[0].last
    t = np.concatenate([last[0][0]] + [x[0][1:] for x in last[1:]])
    d = np.concatenate([last[0][1]] + [x[1][1:] for x in last[1:]])
    ideal = {k: np.r_[np.tile(v[:-1], len(last)), v[-1:]] for k, v in ideal_cycle.items()}
    turn = np.stack([d[-(per + 1) :, col] - ideal[q][-(per + 1) :] for col, q in enumerate(QUANTITIES)])
    per_joint = np.full((2, 6, t.size), np.nan)
    for k, j in enumerate(runs.joints):
        per_joint[j - 1] = d[:, 4 + 6 * k : 10 + 6 * k].T
    return {"t": t, "d": d, "ideal": ideal, "per_joint": per_joint,
            "by_cutoff": ripple_by_cutoff(turn, cutoffs_hz, p.crank_speed)}


def _series_variables(p, shown: Mapping[str, Any]) -> dict[str, tuple]:
    """The time-series variables of the first start's last cycles (``_shown_cycles``)."""
    t, d, ideal, per_joint = shown["t"], shown["d"], shown["ideal"], shown["per_joint"]
    dims, jd = ("time",), ("joint", "time")
    same = "of the ideal linkage at the same instants"
    return {
        "crank_angle": (dims, np.degrees(start_angle(p) + p.crank_speed * t),
                        {"units": "deg", "long_name": "crank angle (unwrapped)"}),
        "rocker_acceleration": (dims, d[:, 0], {"units": "rad s-2", "long_name": "rocker angular acceleration"}),
        "crank_torque": (dims, d[:, 1], {"units": "N m", "long_name": "crank driving torque"}),
        "ideal_rocker_acceleration": (dims, ideal["rocker_acceleration"],
                                      {"units": "rad s-2", "long_name": f"rocker angular acceleration {same}"}),
        "ideal_crank_torque": (dims, ideal["crank_torque"],
                               {"units": "N m", "long_name": f"crank driving torque {same}"}),
        "energy": (dims, d[:, 2], {"units": "J", "long_name": "mechanical energy (kinetic + gravity + contact)"}),
        "constraint_drift": (dims, d[:, 3], {"units": "m", "long_name": "|Phi| of the ideal constraints"}),
        "eccentricity": (jd, per_joint[:, 0], {"units": "m", "long_name": "journal eccentricity |e|", **NO_CLEARANCE}),
        "penetration": (jd, per_joint[:, 1],
                        {"units": "m", "long_name": "penetration |e| - c (> 0 in contact)", **NO_CLEARANCE}),
        "contact_force": (jd, per_joint[:, 3], {"units": "N", "long_name": "dry normal contact force", **NO_CLEARANCE}),
        "film_radial_force": (jd, per_joint[:, 4],
                              {"units": "N", "long_name": "film force along e (on the journal)", **NO_CLEARANCE}),
        "film_tangential_force": (jd, per_joint[:, 5],
                                  {"units": "N", "long_name": "film force across e (on the journal)", **NO_CLEARANCE}),
        "recorded_max_abs_torque": ((), float(np.abs(d[:, 1]).max()),
                                    {"units": "N m", "long_name": "largest |crank driving torque| over the cycles "
                                                                  "shown (first start)"}),
    }


def _state_variables(runs: SceneRuns, rec: Mapping[str, np.ndarray]) -> dict[str, tuple]:
    """The states found from each start: the section, the per-cycle measures, how and where the state was found."""
    found = runs.found
    shorter = "the start's record is shorter"

    def per_start(key, index=None):
        return np.array([f[key] if index is None else f[key][index] for f in found])

    return {
        "section": (("start", "run_cycle", "component"), rec["section"],
                    {"units": "1", "long_name": "Poincaré section at the dead point, once per crank turn",
                     "nan_meaning": shorter}),
        "cycle_deviation": (("start", "measure", "quantity", "run_cycle"), rec["per_cycle"],
                            {"units": "SI of the quantity",
                             "long_name": "RMS and peak of (scene - ideal) over each cycle from the start",
                             "nan_meaning": shorter}),
        "state_status": ("start", np.array([f["status"] for f in found], dtype=object),
                         {"units": "1",
                          "long_name": "how the state was found: periodic, stationary, or cycle cap reached"}),
        "state_period": ("start", per_start("period"),
                         {"units": "1", "long_name": "period of the settled state in crank turns (0: not periodic)"}),
        "state_transient": ("start", per_start("transient"),
                            {"units": "1", "long_name": "cycles before the state (the transient, never judged)"}),
        "window_first": ("start", per_start("window", 0),
                         {"units": "1", "long_name": "first judged cycle (0-based, from the start)"}),
        "window_stop": ("start", per_start("window", 1),
                        {"units": "1", "long_name": "end of the judged cycles (exclusive)"}),
        "record_cycles": ("start", np.array([f["points"].shape[0] for f in found]),
                          {"units": "1", "long_name": "cycles run from the start"}),
        "state_change": ("start", per_start("change"),
                         {"units": "1", "long_name": "largest relative change of a measure between the record's middle "
                                                     "and last third (not periodic)"}),
    }


def _judged_variables(judged: np.ndarray, confidence: float) -> dict[str, tuple]:
    """The claims' measures on each start's state, with their interval (``statistics.judged_statistics``)."""
    sd, si = ("start", "measure", "quantity"), "SI of the quantity"
    return {
        "judged_mean": (sd, judged[..., 0],
                        {"units": si, "long_name": "claims' measure on the state: mean over one period, or over the "
                                                   "judged window"}),
        "judged_half_width": (sd, judged[..., 1],
                              {"units": si,
                               "long_name": f"{confidence:.0%} half-width of the mean (0 on a periodic orbit)",
                               **NO_INTERVAL}),
        "judged_standard_error": (sd, judged[..., 2],
                                  {"units": si,
                                   "long_name": "standard error of the mean (batch means; 0 on a periodic orbit)",
                                   **NO_INTERVAL}),
        "judged_dof": (sd, judged[..., 3],
                       {"units": "1", "long_name": "degrees of freedom of the interval",
                        "nan_meaning": "a periodic orbit (exact: infinitely many) or no interval"}),
        "judged_cycles": (sd, judged[..., 4], {"units": "1", "long_name": "cycles the measure is taken over"}),
    }


def _check_variables(runs: SceneRuns, rec, reach, error) -> dict[str, tuple]:
    """What the check integrators and the run from the start found, and the error bar they give (``_error_bar``)."""
    sd, sc, si = ("start", "measure", "quantity"), ("start", "check"), "SI of the quantity"
    cd = ("start", "check", "measure", "quantity")
    failed = "the check integrator failed (gave up on a step)"
    not_periodic = "the state is not periodic: not testable"
    memories = np.array([r.memories[f["window"][0]] for f, r in zip(runs.found, runs.runners, strict=True)])
    return {
        "check_delta": (cd, rec["delta"],
                        {"units": si, "long_name": "measure at the check integrator - measure at the pipeline's, on "
                                                   "the same state", "nan_meaning": failed}),
        "check_mean": (cd, rec["check_mean"],
                       {"units": si, "long_name": "measure at the check integrator on the same state: over its last "
                                                  "period (periodic), or over all its cycles (a state that is not "
                                                  "periodic: a few cycles, against the same cycles of the window in "
                                                  "check_delta)", "nan_meaning": failed}),
        "check_kept_state": (sc, rec["kept"],
                             {"units": "1", "long_name": "1 if the check run stays on the pipeline's periodic orbit "
                                                         "(its period, within the state tolerance)",
                              "nan_meaning": not_periodic}),
        "check_distance": (sc, rec["check_distance"],
                           {"units": "1", "long_name": "largest section component's distance of the check run's last "
                                                       "point from the pipeline orbit, over max(1, |component|)",
                            "nan_meaning": "the state is not periodic, or the check failed"}),
        "check_period": (sc, rec["check_period"],
                         {"units": "1", "long_name": "period found in the check run (0: none)"}),
        "window_memory": (("start", "memory"), memories,
                          {"units": "SI (t in s, then the state y, latched impact velocities, contact flags)",
                           "long_name": "the run's whole state at the start of the judged window (restartable)"}),
        "convergence_error": (sd, error["converging"],
                              {"units": si, "long_name": "what a periodic state still converging can move its "
                                                         "measure (from the per-period changes)"}),
        "peak_sampling_error": (("start", "quantity"), error["sampling"],
                                {"units": si, "long_name": "largest rise of a judged turn's peak when refined by a "
                                                           "parabola through its largest samples"}),
        "reach_status": ("start", reach["status"],
                         {"units": "1", "long_name": "the state the start reaches when settled from its initial state "
                                                     "at the first check integrator: how it was found",
                          "nan_meaning": "'not run': an input-uncertainty sample's run or a start continued from a "
                                         "saved state"}),
        "reach_period": ("start", reach["period"],
                         {"units": "1", "long_name": "period of the state reached at the first check integrator (0: "
                                                     "not periodic; -1: not run or failed)"}),
        "reach_same_state": ("start", reach["same"],
                             {"units": "1", "long_name": "1 if the start reaches, at the first check integrator, an "
                                                         "orbit of the pipeline's period whose last section point lies "
                                                         "within the state tolerance of the pipeline's orbit (its "
                                                         "measures can still differ: reach_delta), 0 if it reaches "
                                                         "another state",
                              "nan_meaning": "the pipeline state is not periodic (not testable) or the run did not "
                                             "run or failed"}),
        "reach_delta": (sd, reach["delta"],
                        {"units": si, "long_name": "measure of the state reached from the start at the first check "
                                                   "integrator - the pipeline's",
                         "nan_meaning": "not run, or the check integrator failed"}),
        "numerical_error": (sd, error["numerical"],
                            {"units": si, "long_name": "largest of |check_delta| over the check integrators and "
                                                       "|reach_delta|, plus the convergence error (peaks: plus the "
                                                       "peak sampling error)",
                             "nan_meaning": "no check ran (an input-uncertainty sample's run) or every check failed"}),
    }


def _window_variables(runs: SceneRuns, window_ext: np.ndarray, fc: np.ndarray) -> dict[str, tuple]:
    """The judged window's extremes per start and joint, the contact frequency and the starts' initial states."""
    sj = ("start", "joint")
    return {
        "window_max_penetration": (sj, window_ext[:, 0],
                                   {"units": "m", "long_name": "largest |e| - c over the judged cycles",
                                    **NO_CLEARANCE}),
        "window_max_eccentricity": (sj, window_ext[:, 1],
                                    {"units": "m", "long_name": "largest |e| over the judged cycles", **NO_CLEARANCE}),
        "window_max_contact_force": (sj, window_ext[:, 2],
                                     {"units": "N", "long_name": "largest dry contact force over the judged cycles",
                                      **NO_CLEARANCE}),
        "window_max_film_force": (sj, window_ext[:, 3],
                                  {"units": "N", "long_name": "largest |film force along e| over the judged cycles",
                                   **NO_CLEARANCE}),
        "contact_frequency": ("joint", fc,
                              {"units": "Hz", "long_name": "linearised contact frequency at the first start's deepest "
                                                           "penetration (lightest connected body)",
                               "nan_meaning": "no clearance or no contact at this joint"}),
        "start_eccentricity": (("start", "axis"), np.array([s["eccentricity"] for s in runs.starts], dtype=float),
                               {"units": "1", "long_name": "initial eccentricity / c"}),
        "start_rate": (("start", "axis"), np.array([s["rate"] for s in runs.starts], dtype=float),
                       {"units": "1", "long_name": "initial eccentricity rate / (c omega)"}),
    }


def _names(values) -> np.ndarray:
    """Labels as an object array (netCDF strings)."""
    return np.array(values, dtype=object)


def _scene_coords(runs: SceneRuns, n_max: int, t: np.ndarray, cutoffs_hz: np.ndarray) -> dict[str, tuple]:
    comps = [f"joint {j} {name}" for j in runs.joints
             for name in ("e_x / c", "e_y / c", "e_x' / (c omega)", "e_y' / (c omega)")]

    return {
        "start": ("start", _names([s["label"] for s in runs.starts]),
                  {"units": "1", "long_name": "initial state of the journals"}),
        "check": ("check", _names([f"rtol {c['rtol']:g}" for c in runs.checks]),
                  {"units": "1", "long_name": "check integrator setting"}),
        "component": ("component", _names(comps), {"units": "1", "long_name": "section component"}),
        "axis": ("axis", _names(["x", "y"]), {"units": "1", "long_name": "fixed-frame axis"}),
        "run_cycle": ("run_cycle", np.arange(n_max), {"units": "1", "long_name": "cycle from the start (0-based)"}),
        "measure": ("measure", _names(MEASURES), {"units": "1", "long_name": "deviation measure"}),
        "quantity": ("quantity", _names(QUANTITIES), {"units": "1", "long_name": "compared response"}),
        "time": ("time", t - t[0], {"units": "s", "long_name": "time from the start of the cycles shown"}),
        "joint": ("joint", np.array(JOINT_IDS),
                  {"units": "1", "long_name": "joint 1 (crank-coupler), 2 (coupler-rocker)"}),
        "ripple_cutoff": ("ripple_cutoff", cutoffs_hz,
                          {"units": "Hz", "long_name": "ripple cutoff (the sensitivity list)"}),
    }


def _settle_rule(st: Mapping[str, Any], confidence: float) -> str:
    """The settling rule in words (an attribute of every scene)."""
    return (
        f"chunks of {st['chunk_cycles']} cycles until the section repeats with a period up to {st['max_period']} to"
        f" {st['section_tolerance']:g} (in c and c omega) over {st['periods']} periods, or the per-cycle measures'"
        f" last third agrees with their middle third ({confidence:.0%} Welch interval) with at least"
        f" {st['min_cycles']} cycles in the last two thirds; at most {st['max_cycles']} cycles; the transient cut and"
        " the thirds read the RMS and peak measures (the ripple is judged on the window they give)"
    )


def _scene_attrs(p, cfg, variant: str, scene: str, runs: SceneRuns, per: int, shown: int, window_ext, per_joint,
                 fc) -> dict:
    """The scene's attributes: what ran (integrator, steps, evaluations per effect), the sampling against the
    contact frequency, the settling rule, and the validity of the contact and film models on the recorded state."""
    runners, joints, effects, integ = runs.runners, runs.joints, runs.effects, runs.integ
    counts = sum(r.run.counts for r in runners)
    sampling = per / cycle(p)
    cap = 1.0 - p.e0 / p.clearance if "lubrication" in effects else None
    over_contact = float(sampling / np.nanmax(fc)) if np.isfinite(fc).any() else float("nan")
    index = np.array(joints) - 1
    limit = validity.penetration_limit(p.elastic_law, p.journal_radius, p.bearing_radius)
    return dict(
        title=f"Four-bar with clearance joints: {variant}, {scene}", scene=scene, variant=variant,
        effects=",".join(effects), clearance_joints=",".join(map(str, joints)),
        integrator=integ["method"], steps=int(sum(r.run.steps for r in runners)),
        rejected_steps=int(sum(r.run.rejected for r in runners)),
        ndf_fallbacks=int(
            sum(r.fallbacks for r in runners) + sum(c["fallbacks"] for c in runs.checked)
            + sum(r["fallbacks"] for r in runs.reached)
        ),
        evaluations_contact=int(counts[0]), evaluations_friction=int(counts[1]),
        evaluations_lubrication=int(counts[2]), evaluations_gravity=int(counts[3]),
        crank_mass_kg=p.masses[0], shown_cycles=shown, hertz_stiffness=p.hertz_stiffness, clearance=p.clearance,
        sampling_rate_hz=sampling, sampling_over_contact_frequency=over_contact,
        settle_rule=_settle_rule(cfg["states"], cfg["statistics"]["confidence"]),
        ripple_cutoff_hz=float(cfg["claims"]["ripple_cutoff_hz"]), ripple_harmonic=int(runners[0].harmonic),
        **({"film_eccentricity_cap": cap} if cap is not None else {}),
        **validity.attributes(window_ext[0, 0][index][:, None], per_joint[index, 0], p.clearance, cap, limit),
        **{f"integrator_{k}": v for k, v in integ.items()},
    )


def _scene_dataset(p, cfg, variant: str, scene: str, runs: SceneRuns, ideal_cycle, per: int, shown: int,
                   extremes_names, judged_statistics) -> xr.Dataset:
    """The scene's result Dataset (see ``scene``), in named steps: the per-start records, the runs from the starts,
    the error bar, the first start's cycles shown; then the variables, coordinates and attributes."""
    rec = _start_records(runs, cfg["statistics"], extremes_names, judged_statistics)
    reach = _reach_records(runs)
    error = _error_bar(runs, rec["delta"], reach["delta"])
    cutoffs = np.array(cfg["claims"]["ripple_cutoff_sensitivity_hz"], dtype=float)
    shown_ = _shown_cycles(p, runs, ideal_cycle, per, cutoffs)
    window_ext = rec["window_ext"]
    fc = np.array([contact_frequency(p, window_ext[0, 0, j - 1], j) if j in runs.joints else np.nan
                   for j in JOINT_IDS])
    ripple = {"ripple_by_cutoff": (("quantity", "ripple_cutoff"), shown_["by_cutoff"],
                                   {"units": "SI of the quantity",
                                    "long_name": "ripple of the first start's last turn run, at each cutoff of the "
                                                 "sensitivity list"})}
    ds = xr.Dataset(
        {
            **_series_variables(p, shown_),
            **_state_variables(runs, rec),
            **_judged_variables(rec["judged"], cfg["statistics"]["confidence"]),
            **ripple,
            **_check_variables(runs, rec, reach, error),
            **_window_variables(runs, window_ext, fc),
        },
        coords=_scene_coords(runs, rec["section"].shape[1], shown_["t"], cutoffs),
    )
    ds.attrs.update(_scene_attrs(p, cfg, variant, scene, runs, per, shown, window_ext, shown_["per_joint"], fc))
    return ds


def fixed_record(
    cfg: Mapping[str, Any], variant: str, scene: str, integrator: Mapping[str, Any], settle: int, record: int
) -> np.ndarray:
    """The per-cycle RMS deviation (quantity, cycle) of ``record`` cycles after ``settle`` discarded ones from the
    centred start (a fixed record, no settling rule: the Exudyn cross-check compares the same cycles)."""
    p = parameters(cfg, variant, scene)
    joints, effects = scene_effects(cfg, scene)
    per = cfg["numerics"]["points_per_cycle"]
    n = settle + record
    t = np.arange(n * per + 1) * cycle(p) / per
    _, diags, *_ = integrate(p, joints, effects, t, integrator)
    ideal = periodic_ideal(p, per, n, "gravity" in effects)
    dev = cycle_deviations({"rocker_acceleration": diags[:, 0], "crank_torque": diags[:, 1]}, ideal, per)
    return dev[0][:, settle:]


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
    """Every ordering the claims are made of: (claim, label, measure, quantity, terms (coefficient, scene)); an ordering
    holds where sum of coefficient x mean > 0.  The order claims use the RMS and the peak deviation; 'lubrication close
    to ideal' the RMS: each lubricated scene below ``ratio`` times its dry one (both responses), and the ripple of the
    rocker acceleration with joint 2 lubricated (alone, and with joint 1) above joint 1's alone (the "small fluctuation
    peaks" the paper sees where joint 2 has clearance, Figs. 6 and 7: the content above the ripple cutoff, not the size
    of the deviation)."""
    out = []
    for claim, quantity, first in (
        ("acceleration_order", "rocker_acceleration", ("dry_2", "dry_1")),
        ("torque_order", "crank_torque", ("dry_1", "dry_2")),
    ):
        for measure in ("rms", "peak"):
            for a, b in (first, ("dry_both", "dry_1"), ("dry_both", "dry_2")):
                out.append((claim, f"{measure} {quantity}: {a} > {b}", measure, quantity, ((1.0, a), (-1.0, b))))
    for quantity in QUANTITIES:
        for dry, lub in zip(DRY, LUBRICATED, strict=True):
            out.append(
                (
                    "lubrication_close", f"rms {quantity}: {lub} < {ratio:g} x {dry}", "rms", quantity,
                    ((ratio, dry), (-1.0, lub)),
                )
            )
    # the ripples the paper sees left at joint 2 (Fig. 6, the rocker acceleration; it says nothing of them in the
    # torque): its
    # "small fluctuation peaks" are high-frequency content, which the ripple measures and a size does not
    for joint_2 in ("lubricated_2", "lubricated_both"):  # joint 2 lubricated, alone (Fig. 6) and with joint 1 (Fig. 7)
        out.append(
            (
                "lubrication_close", f"ripple rocker_acceleration: {joint_2} > lubricated_1", "ripple",
                "rocker_acceleration", ((1.0, joint_2), (-1.0, "lubricated_1")),
            )
        )
    return out


def judge(
    scene_stats: Mapping[tuple[str, str, str], tuple[float, float, float, float]], ratio: float, confidence: float
) -> dict[str, Any]:
    """The claims from per-scene statistics ((measure, quantity, scene) -> (mean, standard error, degrees of
    freedom, numerical error)): each ordering's difference, statistical half-width, numerical error and outcome,
    and per claim the outcome on the means alone (``point``) and the decided outcome (``outcome``)."""
    from .statistics import HOLDS, UNDETERMINED, conjunction, decide, difference

    rows = []
    for claim, label, measure, quantity, terms in comparisons(ratio):
        d, stat, num = difference([(c, *scene_stats[(measure, quantity, name)]) for c, name in terms], confidence)
        outcome = decide(d, stat, num)
        unsteady = [name for _, name in terms if not np.isfinite(scene_stats[(measure, quantity, name)][1])]
        rows.append(
            {
                "claim": claim,
                "label": label,
                "difference": d,
                "statistical": stat,
                "numerical": num,
                "outcome": outcome,
                "reason": undecided_reason(d, stat, num, unsteady, measure) if outcome == UNDETERMINED else "",
            }
        )
    point = [float(all(r["difference"] > 0 for r in rows if r["claim"] == c)) for c in CLAIMS]
    outcome = [conjunction([r["outcome"] for r in rows if r["claim"] == c]) for c in CLAIMS]
    reasons = [
        claim_reason([r["reason"] for r in rows if r["claim"] == c]) if o == UNDETERMINED else ""
        for c, o in zip(CLAIMS, outcome, strict=True)
    ]
    return {
        "rows": rows,
        "point": point,
        "outcome": outcome,
        "decided": [float(o != -1) for o in outcome],
        "holds_decidedly": [float(o == HOLDS) for o in outcome],
        "reason": reasons,
    }


def undecided_reason(
    diff: float, stat_margin: float, numerical_error: float, unsteady: Sequence[str], measure: str = "rms"
) -> str:
    """Which margin leaves an ordering undetermined: a scene without a valid interval (not settled or not
    stationary; for the ripple, also a ripple that drifts over a window the settling rule found stationary), the
    statistical margin, or the numerical error (the larger one where both exceed |diff|)."""
    if unsteady:
        what = "not settled, or its ripple not stationary" if measure == "ripple" else "not settled / not stationary"
        return f"statistics ({what}: {', '.join(unsteady)})"
    if abs(diff) <= stat_margin and (abs(diff) > numerical_error or stat_margin >= numerical_error):
        return "statistical margin"
    return "numerical error"


def claim_reason(reasons: Sequence[str]) -> str:
    """The distinct reasons of a claim's undetermined orderings, in order of first appearance."""
    return "; ".join(dict.fromkeys(r for r in reasons if r))


def _scene_summary(
    runs: Mapping[tuple[str, str], xr.Dataset], variants: list[str], scenes: list[str]
) -> dict[str, Any]:
    """Per variant and scene: cost, settling, drift, effect counters and joint extremes (what the report tabulates)."""
    shape, jshape = (len(variants), len(scenes)), (len(variants), len(scenes), len(JOINT_IDS))
    out = {
        k: np.full(shape, np.nan)
        for k in (
            "steps", "max_drift", "n_contact", "n_friction", "n_lubrication", "ideal_force_A", "ideal_force_B",
            "film_cap", "hertz_stiffness", "max_abs_torque", "beyond_film_cap_fraction",
            "sampling_over_contact_frequency",
        )
    }
    out["integrator"] = np.full(shape, "", dtype=object)
    out["contact_label"] = np.full(jshape, "", dtype=object)
    out.update(
        {
            k: np.full(jshape, np.nan)
            for k in (
                "max_penetration_ratio", "max_eccentricity_ratio", "max_contact_force", "max_film_force",
                "contact_value",
            )
        }
    )
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
            out["max_drift"][v, s] = float(ds.constraint_drift.max())
            out["sampling_over_contact_frequency"][v, s] = ds.attrs["sampling_over_contact_frequency"]
            for key, attr in (("n_contact", "contact"), ("n_friction", "friction"), ("n_lubrication", "lubrication")):
                out[key][v, s] = ds.attrs[f"evaluations_{attr}"]
            c = ds.attrs["clearance"]
            for j, jid in enumerate(JOINT_IDS):
                pen = float(ds.window_max_penetration.sel(joint=jid)[0])
                if np.isfinite(pen):
                    out["max_penetration_ratio"][v, s, j] = pen / c
                    out["contact_label"][v, s, j], out["contact_value"][v, s, j] = validity.contact_extent(pen / c)
                    out["max_eccentricity_ratio"][v, s, j] = float(ds.window_max_eccentricity.sel(joint=jid)[0]) / c
                    out["max_contact_force"][v, s, j] = float(ds.window_max_contact_force.sel(joint=jid)[0])
                    out["max_film_force"][v, s, j] = float(ds.window_max_film_force.sel(joint=jid)[0])
    return out


SUMMARY_ATTRS = {
    "steps": ("1", "accepted integrator steps"),
    "max_drift": ("m", "largest constraint drift |Phi| over the cycles shown (first start)"),
    "sampling_over_contact_frequency": (
        "1",
        "output sampling rate / linearised contact frequency (peaks need at least 4)",
    ),
    "max_abs_torque": ("N m", "largest |crank driving torque| over the cycles shown (first start)"),
    "n_contact": ("1", "contact-force evaluations"),
    "n_friction": ("1", "friction evaluations"),
    "n_lubrication": ("1", "film-force evaluations"),
    "ideal_force_A": ("N", "largest reaction in joint 1 (ideal scene)"),
    "ideal_force_B": ("N", "largest reaction in joint 2 (ideal scene)"),
    "integrator": ("1", "integrator of the run"),
    "film_cap": ("1", "eccentricity ratio at which the film force is capped, 1 - e0/c"),
    "hertz_stiffness": ("N m-1.5", "Hertz stiffness K of eq. (9)"),
    "beyond_film_cap_fraction": (
        "1",
        "fraction of the recorded time at which a lubricated journal runs beyond the film cap",
    ),
    "max_penetration_ratio": (
        "1",
        (
            "largest (|e| - c) / c over the recorded cycles: > 0 is penetration into the bushing, < 0 a gap that never"
            " closed"
        ),
    ),
    "max_eccentricity_ratio": ("1", "largest eccentricity ratio |e| / c"),
    "contact_label": (
        "1",
        (
            "how the deepest contact reads: 'max penetration / c' (the journal entered the bushing) or 'min gap / c'"
            " (it never touched)"
        ),
    ),
    "contact_value": ("1", "the value of contact_label (a gap as a positive fraction of c)"),
    "max_contact_force": ("N", "largest dry contact force"),
    "max_film_force": ("N", "largest |film force along e|"),
}


def stats_for_judging(
    stats: np.ndarray, num: np.ndarray
) -> dict[tuple[str, str, str], tuple[float, float, float, float]]:
    """(measure, quantity, scene) -> (mean, standard error, degrees of freedom, numerical error) from arrays
    (measure, quantity, scene, statistic) and (measure, quantity, scene)."""
    return {
        (m, q, s): (float(stats[i, j, k, 0]), float(stats[i, j, k, 2]), float(stats[i, j, k, 3]), float(num[i, j, k]))
        for i, m in enumerate(MEASURES)
        for j, q in enumerate(QUANTITIES)
        for k, s in enumerate(COMPARED)
    }


def start_statistics(run: xr.Dataset, k: int) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Start ``k`` of a scene run: ((measure, quantity, [mean, half-width, standard error, dof, cycles]), the numerical
    error (measure, quantity), why its interval is missing or its state in doubt ('' if neither))."""
    stats = read(
        np.stack(
            [
                run[v].values[k]
                for v in ("judged_mean", "judged_half_width", "judged_standard_error", "judged_dof", "judged_cycles")
            ],
            axis=-1,
        )
    )
    num = run.numerical_error.values[k]
    status = str(run.state_status.values[k])
    doubt = []
    if status not in ("periodic", "stationary"):
        doubt.append("not settled by the cycle cap")
    kept = run.check_kept_state.values[k]
    if np.any(kept == 0):
        doubt.append("the state changes with the tolerance")
    if doubt:
        stats = stats.copy()
        stats[..., 1:3] = np.inf
    return stats, num, doubt


def judge_start(
    runs: Mapping[str, xr.Dataset], k: int, ratio: float, confidence: float
) -> tuple[dict[str, Any], np.ndarray, np.ndarray]:
    """The claims on start ``k`` of every compared scene (``runs``: scene -> run): ``judge``'s verdict, with the
    reason of an undetermined ordering naming a scene whose state is in doubt; and the stacked statistics
    (measure, quantity, scene, statistic) and numerical errors (measure, quantity, scene)."""
    stats = np.full((len(MEASURES), len(QUANTITIES), len(COMPARED), 5), np.nan)
    num = np.full((len(MEASURES), len(QUANTITIES), len(COMPARED)), np.nan)
    doubts = {}
    for s, name in enumerate(COMPARED):
        stats[:, :, s], num[:, :, s], doubt = start_statistics(runs[name], k)
        if doubt:
            doubts[name] = "; ".join(doubt)
    verdict = judge(stats_for_judging(stats, num), ratio, confidence)
    if doubts:
        for row in verdict["rows"]:
            if row["reason"].startswith("statistics"):
                row["reason"] = "state: " + ", ".join(f"{n} ({doubts[n]})" for n in doubts if n in row["label"])
        verdict["reason"] = [claim_reason([r["reason"] for r in verdict["rows"] if r["claim"] == c]) if o == -1 else ""
                             for c, o in zip(CLAIMS, verdict["outcome"], strict=True)]
    return verdict, stats, num


def reached_point(
    runs: Mapping[str, xr.Dataset], k: int, stats: np.ndarray, num: np.ndarray, ratio: float, confidence: float
) -> np.ndarray:
    """Per claim, 1 if every ordering holds on the means of the states start ``k`` reaches at the first check
    tolerance (the pipeline's means plus each scene's ``reach_delta``), else 0; NaN where a scene has no such run."""
    moved = stats.copy()
    for s, name in enumerate(COMPARED):
        moved[:, :, s, 0] = stats[:, :, s, 0] + runs[name].reach_delta.values[k]
    if not np.isfinite(moved[..., 0]).all():
        return np.full(len(CLAIMS), np.nan)
    return np.array(judge(stats_for_judging(moved, num), ratio, confidence)["point"], dtype=float)


def states_differ(stats: np.ndarray, num: np.ndarray) -> np.ndarray:
    """Per variant and scene: 1 where some measure of two starts differs by more than the sum of their half-widths
    and numerical errors (``stats``: variant, start, measure, quantity, scene, statistic; ``num``: the same without
    the statistic)."""
    mean, half = stats[..., 0], np.where(np.isfinite(stats[..., 1]), stats[..., 1], np.inf)
    margin = half + np.nan_to_num(num, nan=np.inf)
    out = np.zeros((stats.shape[0], stats.shape[4]), dtype=int)
    for a in range(stats.shape[1]):
        for b in range(a + 1, stats.shape[1]):
            apart = np.abs(mean[:, a] - mean[:, b]) > margin[:, a] + margin[:, b]  # variant, measure, quantity, scene
            out |= apart.any(axis=(1, 2)).astype(int)
    return out


def claims(cfg: Mapping[str, Any], scenes: Sequence[xr.Dataset]) -> xr.Dataset:
    """The three claims per variant and start, judged on the state each scene settles into from that start: the
    claims' measures on the state (one period, or batch means over the judged window), their interval, and the
    numerical error bar from the check integrators on the same state; plus each scene's cost, state and extremes.
    The variables without a start dimension are the first start's (the nominal initial state).  In named steps:
    judge every variant and start, then the claims' variables, each scene's record gathered, the summaries, the
    coordinates and the attributes."""
    confidence, ratio = cfg["statistics"]["confidence"], cfg["claims"]["close_to_ideal_ratio"]
    variants = list(cfg["variants"])
    runs = _by_key(scenes)
    judged = _judge_every_start(runs, variants, ratio, confidence)
    data = {
        **_claim_variables(judged, confidence),
        **_gathered_scene_variables(runs, variants),
    }
    data.update(_claims_summary_variables(runs, variants, data["scene_check_distance"][1], judged))
    ds = xr.Dataset(data, coords=_claims_coords(runs, variants, ratio))
    ds.attrs.update(_claims_attrs(cfg, runs, variants))
    return ds


def _judge_every_start(runs, variants: Sequence[str], ratio: float, confidence: float) -> dict[str, np.ndarray]:
    """``judge_start`` and ``reached_point`` for every variant and start: the measures' statistics and numerical
    errors, each ordering's difference, margins and outcome, and each claim's outcome (variant, start, ...)."""
    starts = runs[(variants[0], COMPARED[0])].start.values
    nv, nk, nl, nc = len(variants), len(starts), len(comparisons(ratio)), len(CLAIMS)
    out = {
        "stats": np.full((nv, nk, len(MEASURES), len(QUANTITIES), len(COMPARED), 5), np.nan),
        "num": np.full((nv, nk, len(MEASURES), len(QUANTITIES), len(COMPARED)), np.nan),
        "comp": np.full((nv, nk, nl, 4), np.nan),
        "comp_reason": np.full((nv, nk, nl), "", dtype=object),
        "holds": np.zeros((nv, nk, nc)),
        "decided": np.zeros((nv, nk, nc)),
        "outcome": np.zeros((nv, nk, nc), dtype=int),
        "reached": np.full((nv, nk, nc), np.nan),
        "claim_reasons": np.full((nv, nk, nc), "", dtype=object),
    }
    for v, variant in enumerate(variants):
        scene_runs = {name: runs[(variant, name)] for name in COMPARED}
        for k in range(nk):
            verdict, out["stats"][v, k], out["num"][v, k] = judge_start(scene_runs, k, ratio, confidence)
            rows = verdict["rows"]
            out["comp"][v, k] = [[r["difference"], r["statistical"], r["numerical"], r["outcome"]] for r in rows]
            out["comp_reason"][v, k] = [r["reason"] for r in rows]
            out["claim_reasons"][v, k] = verdict["reason"]
            out["holds"][v, k], out["decided"][v, k] = verdict["point"], verdict["decided"]
            out["outcome"][v, k] = verdict["outcome"]
            out["reached"][v, k] = reached_point(scene_runs, k, out["stats"][v, k], out["num"][v, k], ratio,
                                                 confidence)
    return out


def _finite(x: np.ndarray) -> np.ndarray:
    return np.where(np.isfinite(x), x, np.nan)


def _claim_variables(judged: Mapping[str, np.ndarray], confidence: float) -> dict[str, tuple]:
    """The claims' measures with their intervals and numerical errors, the orderings and the claims' outcomes."""
    stats, comp, holds, decided = judged["stats"], judged["comp"], judged["holds"], judged["decided"]
    sd, si = ("variant", "start", "measure", "quantity", "scene"), "SI of the quantity"
    vsc, vsk, vk = ("variant", "start", "comparison"), ("variant", "start", "claim"), ("variant", "claim")
    in_doubt = "the state is in doubt"
    return {
        "mean_deviation": (sd, stats[..., 0],
                           {"units": si, "long_name": "claims' measure on the state (one period, or the mean over the "
                                                      "judged window)"}),
        "ci_half_width": (sd, _finite(stats[..., 1]),
                          {"units": si, "long_name": f"half-width of the {confidence:.0%} confidence interval of the "
                                                     "measure (0 on a periodic orbit)",
                           "nan_meaning": f"{in_doubt} (not settled by the cycle cap, or it changes with the "
                                          "tolerance): no interval"}),
        "standard_error": (sd, _finite(stats[..., 2]),
                           {"units": si, "long_name": "standard error of the measure (batch means; 0 on a periodic "
                                                      "orbit)", "nan_meaning": in_doubt}),
        "ci_dof": (sd, _finite(stats[..., 3]),
                   {"units": "1", "long_name": "degrees of freedom of the interval",
                    "nan_meaning": "a periodic orbit (exact) or no interval"}),
        "judged_cycles": (sd, stats[..., 4], {"units": "1", "long_name": "cycles the measure is taken over"}),
        "numerical_error": (sd, judged["num"],
                            {"units": si, "long_name": "the scene run's numerical error: the largest |measure at a "
                                                       "check integrator - measure at the pipeline's|, on the same "
                                                       "state and on the state the start reaches at the first check "
                                                       "tolerance, plus the convergence and peak-sampling terms"}),
        "comparison_difference": (vsc, comp[..., 0],
                                  {"units": si, "long_name": "difference of the measures the ordering is about (> 0: "
                                                             "as claimed)"}),
        "comparison_statistical": (vsc, _finite(comp[..., 1]),
                                   {"units": si, "long_name": f"{confidence:.0%} half-width of the difference",
                                    "nan_meaning": "a scene of the ordering has no interval (its state is in doubt)"}),
        "comparison_numerical": (vsc, comp[..., 2], {"units": si, "long_name": "numerical error of the difference"}),
        "comparison_outcome": (vsc, comp[..., 3].astype(int),
                               {"units": "1", "long_name": "1 holds, 0 fails, -1 undetermined (within a margin)"}),
        "comparison_decided_by": (vsc, judged["comp_reason"],
                                  {"units": "1", "long_name": "which margin leaves the ordering undetermined (empty: "
                                                              "decided)"}),
        "holds_by_start": (vsk, holds,
                           {"units": "1", "long_name": "1 if every ordering of the claim holds on the measures, per "
                                                       "start"}),
        "outcome_by_start": (vsk, judged["outcome"],
                             {"units": "1", "long_name": "1 holds, 0 fails decidedly, -1 undetermined, per start"}),
        "holds_on_reached_states": (vsk, judged["reached"],
                                    {"units": "1", "long_name": "1 if every ordering of the claim holds on the "
                                                                "measures of the states the starts reach at the first "
                                                                "check tolerance (their means only)",
                                     "nan_meaning": "a scene's run from the start at the check tolerance did not run "
                                                    "or failed"}),
        "claim_decided_by_start": (vsk, judged["claim_reasons"],
                                   {"units": "1", "long_name": "which margin leaves the claim undetermined, per start "
                                                               "(empty: decided)"}),
        "holds": (vk, holds[:, 0],
                  {"units": "1", "long_name": "1 if every ordering of the claim holds on the measures (first start)"}),
        "decided": (vk, decided[:, 0],
                    {"units": "1", "long_name": "1 if the claim's outcome is beyond the statistical and numerical "
                                                "margins (first start)"}),
        "undecided": (vk, 1.0 - decided[:, 0],
                      {"units": "1", "long_name": "1 if a margin decides the claim (the verdict's error bar; first "
                                                  "start)"}),
        "claim_decided_by": (vk, judged["claim_reasons"][:, 0],
                             {"units": "1", "long_name": "which margin leaves the claim undetermined (first start; "
                                                         "empty: decided)"}),
    }


#: The scenes' per-start records the claims gather (variant, scene, start), with the check dimension for the last two.
GATHERED_STATE = ("state_status", "state_period", "state_transient", "window_first", "window_stop", "record_cycles",
                  "state_change", "reach_status", "reach_period", "reach_same_state")
GATHERED_CHECKS = ("check_kept_state", "check_distance")
#: The error bar's parts, gathered with their own dimensions after (variant, scene).
GATHERED_ERROR = ("check_delta", "check_mean", "convergence_error")


def _gathered_scene_variables(runs, variants: Sequence[str]) -> dict[str, tuple]:
    """Each compared scene's records gathered over the variants (variant, scene, then the scene's dimensions), with
    the scene's own attributes."""
    first = runs[(variants[0], COMPARED[0])]

    def gathered(key):
        return np.array([[runs[(v, n)][key].values for n in COMPARED] for v in variants])

    data = {}
    for key in GATHERED_STATE:
        arr = gathered(key)
        data[f"scene_{key}"] = (("variant", "scene", "start"), arr.astype(object) if key.endswith("status") else arr,
                                dict(first[key].attrs))
    for key in GATHERED_CHECKS:
        data[f"scene_{key}"] = (("variant", "scene", "start", "check"), gathered(key), dict(first[key].attrs))
    for key in ("reach_delta", *GATHERED_ERROR, "ripple_by_cutoff"):
        data[f"scene_{key}"] = (("variant", "scene") + first[key].dims, gathered(key), dict(first[key].attrs))
    return data


def _claims_summary_variables(runs, variants: Sequence[str], distance: np.ndarray, judged) -> dict[str, tuple]:
    """The largest check distance, whether two starts reach different states, the ideal linkage's RMS response and
    each scene's summary (``_scene_summary``)."""
    largest = np.max(np.where(np.isfinite(distance), distance, -np.inf), axis=-1)
    ideal_rms = np.array([[np.sqrt(np.mean(runs[(v, "ideal")][q].values[:-1] ** 2)) for q in QUANTITIES]
                          for v in variants])
    data = {
        "scene_check_distance_max": (("variant", "scene", "start"), _finite(largest),
                                     {"units": "1", "long_name": "largest distance of a check rerun from the pipeline "
                                                                 "orbit",
                                      "nan_meaning": "not periodic, or every check failed"}),
        "scene_states_differ": (("variant", "scene"), states_differ(judged["stats"], judged["num"]),
                                {"units": "1", "long_name": "1 if two starts' measures differ beyond their intervals "
                                                            "and numerical errors (different states)"}),
        "ideal_rms": (("variant", "quantity"), ideal_rms,
                      {"units": "SI of the quantity", "long_name": "RMS of the ideal linkage's response over its "
                                                                   "record"}),
    }
    not_applicable = ("does not apply to this scene or joint (the ideal scene integrates nothing; a joint without "
                      "clearance has no contact)")
    for key, arr in _scene_summary(runs, variants, _all_scenes(runs)).items():
        unit, long_name = SUMMARY_ATTRS[key]
        data[f"summary_{key}"] = (("variant", "run") + (("joint",) if arr.ndim == 3 else ()), arr,
                                  {"units": unit, "long_name": long_name, "nan_meaning": not_applicable})
    return data


def _all_scenes(runs) -> list[str]:
    """Every scene run, the ideal one first."""
    return sorted({name for (_, name) in runs}, key=lambda n: (n != "ideal", n))


def _claims_coords(runs, variants: Sequence[str], ratio: float) -> dict[str, tuple]:
    first = runs[(variants[0], COMPARED[0])]
    compared = comparisons(ratio)

    return {
        "variant": ("variant", _names(variants), {"units": "1", "long_name": "parameter variant"}),
        "start": ("start", _names([str(x) for x in first.start.values]),
                  {"units": "1", "long_name": "initial state of the journals (a scenario), the nominal first"}),
        "check": ("check", first.check.values, {"units": "1", "long_name": "check integrator setting (dry scenes)"}),
        "quantity": ("quantity", _names(QUANTITIES), {"units": "1", "long_name": "compared response"}),
        "measure": ("measure", _names(MEASURES), {"units": "1", "long_name": "deviation measure"}),
        "scene": ("scene", _names(COMPARED), {"units": "1", "long_name": "scene"}),
        "run": ("run", _names(_all_scenes(runs)), {"units": "1", "long_name": "scene run"}),
        "joint": ("joint", np.array(JOINT_IDS),
                  {"units": "1", "long_name": "joint 1 (crank-coupler), 2 (coupler-rocker)"}),
        "claim": ("claim", _names(CLAIMS), {"units": "1", "long_name": "claim"}),
        "comparison": ("comparison", _names([c[1] for c in compared]),
                       {"units": "1", "long_name": "ordering a claim is made of"}),
        "comparison_claim": ("comparison", _names([c[0] for c in compared]),
                             {"units": "1", "long_name": "claim of the ordering"}),
        "ripple_cutoff": ("ripple_cutoff", first.ripple_cutoff.values, dict(first.ripple_cutoff.attrs)),
    }


#: How the numerical error bar of a scene's measure is taken (an attribute of the claims).
NUMERICAL_ERROR_METHOD = (
    "per scene and start: the largest |measure at a check integrator - measure at the pipeline's|, over reruns of the"
    " same state restarted from the section point at the start of the judged window and a run settled from the start"
    " itself at the first check integrator (which of coexisting states a start reaches can depend on the"
    " integrator), plus the convergence term (a periodic state still converging: its last per-period change times"
    " rho / (1 - rho)) and, for a peak, the sampling term (the rise of a parabolic refinement of the largest sample);"
    " of a difference: the sum over its scenes"
)


def _claims_attrs(cfg: Mapping[str, Any], runs, variants: Sequence[str]) -> dict[str, Any]:
    from .statistics import DECISION_RULE

    first = runs[(variants[0], "dry_2")]
    scenes = [runs[(variants[0], n)] for n in COMPARED]
    tight = sorted({f"{s.attrs['integrator']}: " + ", ".join(str(c) for c in s.check.values) for s in scenes})
    return dict(
        title="Claims of the clearance paper, per parameter variant and start",
        close_to_ideal_ratio=cfg["claims"]["close_to_ideal_ratio"], ci_method=CI_METHOD_STATES,
        crank_mass_kg=runs[(variants[0], "ideal")].attrs["crank_mass_kg"], decision_rule=DECISION_RULE,
        confidence=cfg["statistics"]["confidence"], batch_cycles=cfg["statistics"]["batch_cycles"],
        settle_rule=first.attrs["settle_rule"], ripple_cutoff_hz=cfg["claims"]["ripple_cutoff_hz"],
        ripple_harmonic=first.attrs["ripple_harmonic"], numerical_error_method=NUMERICAL_ERROR_METHOD,
        tight_settings="; ".join(tight),
    )


#: How the claims' measure and its interval are taken on a state.
CI_METHOD_STATES = (
    "on a periodic orbit the measure over one period (exact to the section tolerance: no interval); on a stationary"
    " state that is not periodic a batch-means t-interval over the judged window; a difference of two scenes by"
    " Welch-Satterthwaite"
)
