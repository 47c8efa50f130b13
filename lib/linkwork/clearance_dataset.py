"""The clearance paper's result Datasets: one scene run, the claims across scenes, the work-precision study."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from .multibody.model import FourBarParameters, compile_scene, initial_state, inverse_dynamics, pack
from .timing import median_time

JOINT_IDS = (1, 2)


def parameters(section: Mapping[str, Any], variant: str) -> FourBarParameters:
    """FourBarParameters of a variant: 'decoded' (inertias as printed) or 'slender' (J = m L^2 / 12)."""
    b = section["bodies"]
    lengths = (b["crank"]["length_m"], b["coupler"]["length_m"], b["rocker"]["length_m"])
    masses = (b["crank"]["mass_kg"], b["coupler"]["mass_kg"], b["rocker"]["mass_kg"])
    if section["variants"][variant]["inertia"] == "decoded":
        inertias = (b["crank"]["inertia_kg_m2"], b["coupler"]["inertia_kg_m2"], b["rocker"]["inertia_kg_m2"])
    else:
        inertias = tuple(m * length**2 / 12 for m, length in zip(masses, lengths, strict=True))
    j, a = section["joints"], section["assumed"]
    return FourBarParameters(
        ground=section["ground_m"],
        lengths=lengths,
        masses=masses,
        inertias=inertias,
        crank_speed=section["crank_speed_rad_s"],
        journal_radius=j["journal_radius_m"],
        bearing_radius=j["bearing_radius_m"],
        youngs_modulus=(j["youngs_modulus_Pa"], j["youngs_modulus_Pa"]),
        poisson=(j["poisson"], j["poisson"]),
        joint_length=a["joint_length_m"]["value"],
        restitution=j["restitution"],
        friction=j["friction"],
        v0=a["v0_m_s"]["value"],
        v1=a["v1_m_s"]["value"],
        viscosity=j["viscosity_Pa_s"],
        e0=a["e0_m"]["value"],
        impact_velocity_floor=section["numerics"]["impact_velocity_floor_m_s"],
        baumgarte_alpha=section["numerics"]["baumgarte"],
        baumgarte_beta=section["numerics"]["baumgarte"],
        contact_law=j["contact_law"],
    )


def cycle(p: FourBarParameters) -> float:
    return 2 * np.pi / p.crank_speed


def output_times(section: Mapping[str, Any], p: FourBarParameters) -> tuple[np.ndarray, np.ndarray]:
    """(all output times, mask of the recorded cycles): settle cycles, then the recorded ones."""
    n = section["numerics"]
    per = n["points_per_cycle"]
    total = n["settle_cycles"] + n["record_cycles"]
    t = np.arange(total * per + 1) * cycle(p) / per
    return t, t >= n["settle_cycles"] * cycle(p) - 1e-12


def integrate(p: FourBarParameters, joints, effects, t_out, integrator: Mapping[str, Any], y0=None):
    """Run a scene; returns (states, diagnostics, steps, rejected, evaluation counts, phi0)."""
    module = compile_scene(tuple(joints), tuple(effects), p.contact_law)
    if y0 is None:
        y0, phi0 = initial_state(p)
    else:
        phi0 = initial_state(p)[1]
    params, _ = pack(p, phi0)
    latched = np.zeros(max(len(joints), 1))
    counts = np.zeros(4, dtype=np.int64)
    if integrator["method"] == "rk4":
        ys, diags, steps, rejected = module.rk4(y0, 0.0, integrator["step_s"], t_out, params, latched, counts)
    elif integrator["method"] == "dopri5":
        ys, diags, steps, rejected = module.dopri5(
            y0, 0.0, t_out, params, latched, counts, integrator["rtol"], integrator["atol"], integrator["first_step_s"], integrator["max_step_s"]
        )
    elif integrator["method"] in ("bdf", "radau"):
        ys, diags, steps, rejected = _stiff(module, y0, t_out, params, latched, counts, integrator)
    else:
        raise ValueError(f"unknown integrator {integrator['method']!r}")
    return ys, diags, int(steps), int(rejected), counts, phi0


def _stiff(module, y0, t_out, params, latched, counts, integrator):
    """Implicit multistep/Runge-Kutta (scipy BDF or Radau) stepped from Python around the compiled
    right-hand side, with the impact velocity latched at accepted steps and dense output at t_out."""
    from scipy.integrate import BDF, Radau

    diag = np.zeros(module.N_DIAG)
    scratch = np.zeros(module.N_DIAG)
    was = np.zeros(max(len(module.JOINTS), 1), dtype=bool)
    solver_cls = BDF if integrator["method"] == "bdf" else Radau
    fun = lambda t, y: module.rhs(t, y, params, latched, counts, scratch)  # noqa: E731
    ys = np.empty((t_out.size, y0.size))
    diags = np.empty((t_out.size, module.N_DIAG))
    module.rhs(t_out[0], y0, params, latched, counts, diag)
    module._latch(diag, latched, was)
    ys[0], diags[0] = y0, diag
    i = 1
    with np.errstate(over="ignore", invalid="ignore"):  # scipy's numerical Jacobian probes far steps
        solver = solver_cls(fun, t_out[0], y0, t_out[-1], rtol=integrator["rtol"], atol=integrator["atol"], max_step=integrator["max_step_s"])
        steps = 0
        while solver.status == "running":
            solver.step()
            steps += 1
            if solver.status == "failed":
                raise RuntimeError(f"{integrator['method']}: step failed at t = {solver.t}")
            module.rhs(solver.t, solver.y, params, latched, counts, diag)
            module._latch(diag, latched, was)
            if i < t_out.size and t_out[i] <= solver.t:
                dense = solver.dense_output()
                while i < t_out.size and t_out[i] <= solver.t + 1e-15:
                    y_i = dense(t_out[i])
                    module.rhs(t_out[i], y_i, params, latched, counts, scratch)
                    ys[i], diags[i] = y_i, scratch.copy()
                    i += 1
    return ys, diags, steps, 0


def scene_dataset(section: Mapping[str, Any], variant: str, scene: str, integrator: Mapping[str, Any] | None = None) -> xr.Dataset:
    """One scene of one parameter variant over the recorded cycles."""
    p = parameters(section, variant)
    spec = section["scenes"][scene]
    joints = tuple(spec["clearance_joints"])
    effects = tuple(spec["effects"])
    integ = integrator or section["integrators"][spec.get("integrator", "explicit")]
    t, rec = output_times(section, p)
    if not joints:  # the ideal scene: kinematics and inverse dynamics, no integration
        ideal = inverse_dynamics(p, t[rec], "gravity" in effects)
        acc, torque, energy = ideal["rocker_acceleration"], ideal["crank_torque"], ideal["energy"]
        drift = np.zeros(rec.sum())
        per_joint = np.full((2, 6, rec.sum()), np.nan)
        n_cycles = section["numerics"]["settle_cycles"] + section["numerics"]["record_cycles"]
        change = np.zeros(n_cycles - 1)
        meta = {"integrator": "none (inverse dynamics)", "steps": 0, "rejected": 0, "counts": [0, 0, 0, 0]}
        forces = (ideal["force_A"], ideal["force_B"])
        phi0 = float(np.radians(0))
    else:
        ys, diags, steps, rejected, counts, phi0 = integrate(p, joints, effects, t, integ)
        d = diags[rec]
        acc, torque, energy, drift = d[:, 0], d[:, 1], d[:, 2], d[:, 3]
        per_joint = np.full((2, 6, rec.sum()), np.nan)
        for k, j in enumerate(joints):
            per_joint[j - 1] = d[:, 4 + 6 * k : 10 + 6 * k].T
        meta = {"integrator": integ["method"], "steps": steps, "rejected": rejected, "counts": counts.tolist()}
        forces = (np.full(rec.sum(), np.nan), np.full(rec.sum(), np.nan))
        per = section["numerics"]["points_per_cycle"]
        whole = diags[:-1, 0].reshape(-1, per)
        change = np.sqrt(np.mean((whole[1:] - whole[:-1]) ** 2, axis=1)) / np.sqrt(np.mean(whole[-1] ** 2))
    tr = t[rec] - t[rec][0]
    from .multibody.model import start_angle

    theta = np.degrees(start_angle(p) + p.crank_speed * t[rec])
    dims = ("time",)
    jd = ("joint", "time")
    ds = xr.Dataset(
        {
            "crank_angle": (dims, theta, {"units": "deg", "long_name": "crank angle (unwrapped)"}),
            "rocker_acceleration": (dims, acc, {"units": "rad s-2", "long_name": "rocker angular acceleration"}),
            "crank_torque": (dims, torque, {"units": "N m", "long_name": "crank driving torque"}),
            "energy": (dims, energy, {"units": "J", "long_name": "mechanical energy (kinetic + gravity + contact)"}),
            "constraint_drift": (dims, drift, {"units": "m", "long_name": "|Phi| of the ideal constraints"}),
            "eccentricity": (jd, per_joint[:, 0], {"units": "m", "long_name": "journal eccentricity |e|"}),
            "penetration": (jd, per_joint[:, 1], {"units": "m", "long_name": "penetration |e| - c (> 0 in contact)"}),
            "contact_force": (jd, per_joint[:, 3], {"units": "N", "long_name": "dry normal contact force"}),
            "film_radial_force": (jd, per_joint[:, 4], {"units": "N", "long_name": "film force along e (on the journal)"}),
            "film_tangential_force": (jd, per_joint[:, 5], {"units": "N", "long_name": "film force across e (on the journal)"}),
            "ideal_joint_force_A": (dims, forces[0], {"units": "N", "long_name": "reaction in joint 1 (A), ideal scene only"}),
            "ideal_joint_force_B": (dims, forces[1], {"units": "N", "long_name": "reaction in joint 2 (B), ideal scene only"}),
            "cycle_change": ("cycle_pair", change, {"units": "1", "long_name": "RMS change of the rocker acceleration from one cycle to the next / RMS of the last cycle"}),
        },
        coords={
            "cycle_pair": ("cycle_pair", np.arange(1, change.size + 1), {"units": "1", "long_name": "cycle k vs cycle k + 1 (from the start)"}),
            "time": ("time", tr, {"units": "s", "long_name": "time from the start of the recorded cycles"}),
            "joint": ("joint", np.array(JOINT_IDS), {"units": "1", "long_name": "joint 1 (crank-coupler), 2 (coupler-rocker)"}),
        },
    )
    ds.attrs.update(
        scene=scene, variant=variant, effects=",".join(effects), clearance_joints=",".join(map(str, joints)),
        integrator=meta["integrator"], steps=meta["steps"], rejected_steps=meta["rejected"],
        evaluations_contact=meta["counts"][0], evaluations_friction=meta["counts"][1],
        evaluations_lubrication=meta["counts"][2], evaluations_gravity=meta["counts"][3],
        settle_cycles=section["numerics"]["settle_cycles"], record_cycles=section["numerics"]["record_cycles"],
        hertz_stiffness=p.hertz_stiffness, clearance=p.clearance,
        **{f"integrator_{k}": v for k, v in integ.items()},
    )
    return ds


def deviation_measures(scene: xr.Dataset, ideal: xr.Dataset, variable: str, cycles: int) -> dict[str, np.ndarray]:
    """RMS and peak of (scene - ideal) per recorded cycle."""
    d = (scene[variable] - ideal[variable]).values
    parts = np.array_split(d[:-1], cycles)
    return {"rms": np.array([np.sqrt(np.mean(x**2)) for x in parts]), "peak": np.array([np.abs(x).max() for x in parts])}


def claims_dataset(section: Mapping[str, Any], scenes: Mapping[tuple[str, str], xr.Dataset], tight: Mapping[tuple[str, str], xr.Dataset]) -> xr.Dataset:
    """The three claims per variant, judged on RMS and peak deviation from the ideal, per cycle and for
    two integrator tolerances (``scenes`` and ``tight`` hold the runs; keys (variant, scene))."""
    cycles = section["numerics"]["record_cycles"]
    variants = list(section["variants"])
    dry = ("dry_1", "dry_2", "dry_both")
    lub = ("lubricated_1", "lubricated_2", "lubricated_both")
    quantities = ("rocker_acceleration", "crank_torque")
    rms = np.full((len(variants), 2, len(dry) + len(lub), 2, cycles), np.nan)  # variant, quantity, scene, tolerance, cycle
    peak = np.full_like(rms, np.nan)
    for v, variant in enumerate(variants):
        ideal = scenes[(variant, "ideal")]
        for qi, qname in enumerate(quantities):
            for s, scene in enumerate(dry + lub):
                for k, runs in enumerate((scenes, tight)):
                    if (variant, scene) in runs:
                        m = deviation_measures(runs[(variant, scene)], ideal, qname, cycles)
                        rms[v, qi, s, k], peak[v, qi, s, k] = m["rms"], m["peak"]
    holds = np.zeros((len(variants), 3))
    ratio = section["claims"]["close_to_ideal_ratio"]
    for v in range(len(variants)):
        ok = []
        for measure in (rms, peak):
            a = measure[v, 0]  # rocker acceleration: scene, tolerance, cycle
            ok.append(np.all(a[1] > a[0]) and np.all(a[2] > np.maximum(a[0], a[1])))
        holds[v, 0] = float(all(ok))
        ok = []
        for measure in (rms, peak):
            tq = measure[v, 1]
            ok.append(np.all(tq[0] > tq[1]) and np.all(tq[2] > np.maximum(tq[0], tq[1])))
        holds[v, 1] = float(all(ok))
        lub_rms, dry_rms = rms[v, :, 3:, 0], rms[v, :, :3, 0]
        close = np.all(lub_rms < ratio * dry_rms)
        ripples_2 = np.all(lub_rms[:, 1] > lub_rms[:, 0])
        holds[v, 2] = float(close and ripples_2)
    coords = {
        "variant": ("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
        "quantity": ("quantity", np.array(quantities, dtype=object), {"units": "1", "long_name": "compared response"}),
        "scene": ("scene", np.array(dry + lub, dtype=object), {"units": "1", "long_name": "scene"}),
        "tolerance_set": ("tolerance_set", np.array(["pipeline", "tight"], dtype=object), {"units": "1", "long_name": "integrator setting"}),
        "cycle": ("cycle", np.arange(1, cycles + 1), {"units": "1", "long_name": "recorded cycle"}),
        "claim": ("claim", np.array(["acceleration_order", "torque_order", "lubrication_close"], dtype=object), {"units": "1", "long_name": "claim"}),
    }
    dims = ("variant", "quantity", "scene", "tolerance_set", "cycle")
    return xr.Dataset(
        {
            "rms_deviation": (dims, rms, {"units": "SI of the quantity", "long_name": "RMS of (scene - ideal) over a cycle"}),
            "peak_deviation": (dims, peak, {"units": "SI of the quantity", "long_name": "peak |scene - ideal| over a cycle"}),
            "holds": (("variant", "claim"), holds, {"units": "1", "long_name": "1 if the claim holds on every measure, cycle and tolerance"}),
        },
        coords=coords,
        attrs={"close_to_ideal_ratio": ratio},
    )


def accuracy_dataset(section: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Error against a tight reference vs wall time, per integrator setting, for one dry and one lubricated scene.

    The error is that of the claims' measure, the RMS deviation of the rocker acceleration from the ideal
    curve; the pointwise error is kept too, but after the first impacts it measures the sensitivity of
    the impact sequence more than the integrator.
    """
    wp = section["work_precision"]
    p = parameters(section, wp["variant"])
    horizon = wp["cycles"] * cycle(p)
    t = np.linspace(0.0, horizon, int(wp["cycles"] * section["numerics"]["points_per_cycle"]) + 1)
    def setting(method, value):
        if method == "rk4":
            return {"method": "rk4", "step_s": value}
        return {"method": method, "rtol": value, "atol": value * wp["atol_over_rtol"], "first_step_s": 1e-6, "max_step_s": wp["max_step_s"]}

    per_scene = {scene: [setting(m, v) for m, values in spec.items() for v in values] for scene, spec in wp["scenes"].items()}
    labels = sorted({_label(s) for ss in per_scene.values() for s in ss}, key=lambda x: (x.split()[0], -float(x.split("=")[1])))
    scenes = list(per_scene)
    ideal = inverse_dynamics(p, t, True)["rocker_acceleration"]
    pointwise = np.full((len(scenes), len(labels)), np.nan)
    error = np.full((len(scenes), len(labels)), np.nan)
    cost = np.full_like(error, np.nan)
    evaluations = np.full_like(error, np.nan)
    timings = {"method": f"median of {wp['repeats']} runs after a warm-up, time.perf_counter", "runs": {}}
    for i, scene in enumerate(scenes):
        spec = section["scenes"][scene]
        joints, effects = tuple(spec["clearance_joints"]), tuple(spec["effects"])
        ref_method = wp["reference"][scene]
        ref_setting = setting(ref_method, wp["reference_rtol"])
        _, ref, *_ = integrate(p, joints, effects, t, ref_setting)
        scale = np.abs(ref[:, 0]).max()
        ref_rms = np.sqrt(np.mean((ref[:, 0] - ideal) ** 2))
        for s in per_scene[scene]:
            j = labels.index(_label(s))
            counts_before = None
            _, d, steps, rejected, counts, _ = integrate(p, joints, effects, t, s)
            del counts_before
            pointwise[i, j] = np.abs(d[:, 0] - ref[:, 0]).max() / scale
            error[i, j] = abs(np.sqrt(np.mean((d[:, 0] - ideal) ** 2)) - ref_rms) / ref_rms
            evaluations[i, j] = steps
            cost[i, j] = median_time(lambda s=s: integrate(p, joints, effects, t, s), wp["repeats"])
            timings["runs"][f"{scene}/{_label(s)}"] = cost[i, j]
    ds = xr.Dataset(
        {
            "error": (("scene", "setting"), error, {"units": "1", "long_name": "relative error of the RMS deviation of the rocker acceleration from the ideal (the claims' measure)"}),
            "pointwise_error": (("scene", "setting"), pointwise, {"units": "1", "long_name": "max |rocker acceleration - reference| / max |reference|"}),
            "steps": (("scene", "setting"), evaluations, {"units": "1", "long_name": "accepted steps"}),
        },
        coords={
            "scene": ("scene", np.array(scenes, dtype=object), {"units": "1", "long_name": "scene"}),
            "setting": ("setting", np.array(labels, dtype=object), {"units": "1", "long_name": "integrator and step or tolerance"}),
            "method": ("setting", np.array([x.split()[0] for x in labels], dtype=object), {"units": "1", "long_name": "integrator"}),
        },
        attrs={"reference": "; ".join(f"{sc}: {wp['reference'][sc]} rtol={wp['reference_rtol']:.0e}" for sc in scenes), "horizon_cycles": wp["cycles"],
               "variant": wp["variant"], "pipeline_settings": "; ".join(f"{k}: {_label(v)}" for k, v in section["integrators"].items())},
    )
    return ds, timings


def _label(s: Mapping[str, Any]) -> str:
    return f"rk4 h={s['step_s']:.0e}" if s["method"] == "rk4" else f"{s['method']} rtol={s['rtol']:.0e}"
