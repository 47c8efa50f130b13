"""The transplanter paper's studies: the section optimisation and the KED responses at the initial and our
optimal diameters."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.optimize import PenaltyProblem, slsqp, sumt
from ...units import angle_grid_deg
from .adapter import allowable, discretisation, dynamic_settings, material, mechanism, member_lengths
from .adapter import gravity as gravity_of
from .model import MEMBERS, bar_mass, ked, rigid_motion, signed_extreme

def solve(cfg, diameters, solution, theta_deg, *, mech=None, mat=None, gravity=None, disc=None):
    """KED over the crank angles ``theta_deg`` (deg) with the config's mesh, gravity and (dynamic) Newmark settings."""
    dynamic = {} if solution == "quasi-static" else dynamic_settings(cfg)
    return ked(
        mech or mechanism(cfg), disc or discretisation(cfg), diameters, mat or material(cfg), np.radians(theta_deg),
        solution=solution, gravity=gravity_of(cfg) if gravity is None else gravity, **dynamic,
    )


def inertia_only_peaks(cfg: Mapping[str, Any], diameters, tip_force=(0.0, 0.0)) -> np.ndarray:
    """Largest quasi-static eq. (8) stress (Pa) per member over the report grid at ``diameters`` (m) under the
    inertia loads alone (no gravity), plus a constant tip force ``tip_force`` (N, global x and y; none by default)."""
    r = ked(
        mechanism(cfg), discretisation(cfg), np.asarray(diameters, dtype=float), material(cfg),
        np.radians(report_grid(cfg)), "quasi-static", gravity=0.0, tip_force=tip_force,
    )
    return r.stress.max(axis=0)


def report_grid(cfg: Mapping[str, Any]) -> np.ndarray:
    """The crank angles (deg) on which every stress maximum is taken: the optimiser's constraint, the responses
    and the comparison (``fe.angle_step_deg``)."""
    return angle_grid_deg(cfg["fe"]["angle_step_deg"])


def problem(cfg: Mapping[str, Any], theta_deg: np.ndarray | None = None) -> PenaltyProblem:
    """The paper's section-design problem: quasi-static member stress maxima over the crank angles ``theta_deg``
    (deg; default: the report grid)."""
    mech, mat, disc = mechanism(cfg), material(cfg), discretisation(cfg)
    theta = np.radians(report_grid(cfg) if theta_deg is None else np.asarray(theta_deg, dtype=float))
    gravity = gravity_of(cfg)

    def stresses(x):
        return ked(mech, disc, x, mat, theta, "quasi-static", gravity=gravity).stress.max(axis=0)

    return PenaltyProblem(
        stresses, member_lengths(cfg), allowable(cfg), float(cfg["optimization"]["reference_diameter_m"]["value"]),
        float(cfg["minimum_diameter_m"]),
    )


def peak_indices(stress: np.ndarray, spread: int) -> set[int]:
    """Indices of the report grid (periodic) within ``spread`` steps of each member's largest stress (stress: (n,
    4))."""
    n = stress.shape[0]
    return {int((i + k) % n) for i in np.argmax(stress, axis=0) for k in range(-spread, spread + 1)}


def optimise_on_report_grid(
    cfg: Mapping[str, Any], x0: np.ndarray, first: Callable, again: Callable
) -> tuple[np.ndarray, list, dict[str, Any]]:
    """The optimum whose stress maxima are those of the report grid, by exchange of crank angles.

    The optimiser evaluates an active subset of the report grid: the coarse grid ``optimization.angle_step_deg``
    plus the grid points within ``optimization.peak_spread_steps`` of each member's peak at the start. At each
    optimum the whole report grid is checked; where a member's peak lies outside the active subset, its
    neighbourhood joins the subset and the optimiser resumes from there (``again``), at most
    ``optimization.exchange_rounds`` times. On return every member's largest stress over the active subset is its
    largest over the report grid, so the objective and the constraints are those of the report grid.
    ``first(prob, x0)`` and ``again(prob, x)`` return (x, record)."""
    opt = cfg["optimization"]
    fine = report_grid(cfg)
    full = problem(cfg)
    coarse_every = int(round(opt["angle_step_deg"] / cfg["fe"]["angle_step_deg"]))
    spread = int(opt["peak_spread_steps"])
    theta_fine = np.radians(fine)
    mech, mat, disc, gravity = mechanism(cfg), material(cfg), discretisation(cfg), gravity_of(cfg)

    def fine_stress(x):
        return ked(mech, disc, x, mat, theta_fine, "quasi-static", gravity=gravity).stress

    active = set(range(0, fine.size, coarse_every)) | peak_indices(fine_stress(x0), spread)
    x, record = first(problem(cfg, fine[sorted(active)]), x0)
    records, rounds = [record], 0
    while True:
        new = peak_indices(fine_stress(x), 0) - active
        if not new or rounds >= opt["exchange_rounds"]:
            break
        active |= peak_indices(fine_stress(x), spread)
        rounds += 1
        x, record = again(problem(cfg, fine[sorted(active)]), x)
        records.append(record)
    info = {
        "exchange_rounds": rounds,
        "active_angles": len(active),
        "grid_angles": int(fine.size),
        "peaks_in_active": not new,
        "stress": full.stresses(x),
        "constraints": full.constraints(x),
    }
    return x, records, info


def optim(cfg: Mapping[str, Any]) -> xr.Dataset:
    """SUMT iterates with the objective parts and constraints, and the SLSQP cross-check, both with the stress
    maxima of the report grid."""
    opt = cfg["optimization"]
    x0 = np.array(cfg["initial_diameters_m"], dtype=float)
    r_last = opt["r0"] * opt["r_factor"] ** (opt["iterations"] - 1)
    sumt_first = lambda prob, x: (lambda r: (r.x, r))(
        sumt(prob, x, opt["r0"], opt["r_factor"], opt["iterations"], opt["xtol_m"], opt["inner_maxiter"])
    )  # noqa: E731
    sumt_again = lambda prob, x: (lambda r: (r.x, r))(
        sumt(prob, x, r_last, 1.0, 1, opt["xtol_m"], opt["inner_maxiter"])
    )  # noqa: E731
    x_opt, runs, info = optimise_on_report_grid(cfg, x0, sumt_first, sumt_again)
    run_slsqp = lambda prob, x: slsqp(prob, x, opt["slsqp_ftol"])  # noqa: E731
    xs, slsqp_runs, slsqp_info = optimise_on_report_grid(cfg, x0, run_slsqp, run_slsqp)
    info_s = slsqp_runs[-1]
    prob = problem(cfg)  # the report grid
    h = [{**e, "round": i} for i, run in enumerate(runs) for e in run.history]
    member = ("member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member (AB, BC, CD, BE)"})
    ds = xr.Dataset(
        {
            "r": ("iteration", np.array([e["r"] for e in h]), {"units": "1", "long_name": "penalty factor r(k)"}),
            "exchange_round": (
                "iteration", np.array([e["round"] for e in h]),
                {"units": "1", "long_name": "exchange round of the crank angles (0: first run)"},
            ),
            "x": (
                ("iteration", "member"), np.array([e["x"] for e in h]) * 1e3,
                {"units": "mm", "long_name": "diameters after iteration k"},
            ),
            **{
                p: ("iteration", np.array([e[p] for e in h]), {"units": "1", "long_name": f"objective part {p}"})
                for p in ("SY", "SZ", "SG", "SH", "SS")
            },
            "g": (
                ("iteration", "constraint"), np.array([e["g"] for e in h]),
                {"units": "1", "long_name": "constraints g_1..g_8 (>= 0 feasible)"},
            ),
            "d_opt": ("member", x_opt * 1e3, {"units": "mm", "long_name": "optimal diameters (SUMT)"}),
            "d_slsqp": (
                "member", xs * 1e3,
                {"units": "mm", "long_name": "optimal diameters (SLSQP on SY + SZ, explicit constraints)"},
            ),
            "sumt_slsqp_difference": (
                (), float(np.abs(x_opt - xs).max() * 1e3),
                {"units": "mm", "long_name": "largest |SUMT - SLSQP| diameter difference"},
            ),
            "stress_opt": (
                "member", info["stress"] / 1e6,
                {"units": "MPa", "long_name": "largest stress per member at the SUMT optimum (report grid)"},
            ),
            "constraints_opt": (
                "constraint",
                info["constraints"],
                {
                    "units": "1",
                    "long_name": "constraints g_1..g_8 at the SUMT optimum on the report grid (>= 0 feasible)",
                },
            ),
            "stress_inertia_only_opt": (
                "member",
                inertia_only_peaks(cfg, x_opt) / 1e6,
                {
                    "units": "MPa",
                    "long_name": (
                        "largest quasi-static stress per member at the SUMT optimum under the inertia loads alone"
                    ),
                },
            ),
            "mass_opt": (
                (), bar_mass(member_lengths(cfg), x_opt, material(cfg).density) * 1e3,
                {"units": "g", "long_name": "mass of the four bars at the SUMT optimum"},
            ),
            "allowable": (
                (), prob.allowable / 1e6, {"units": "MPa", "long_name": "allowable stress (yield / safety factor)"},
            ),
            "SS_opt": (
                (), prob.parts(x_opt, h[-1]["r"])["SS"],
                {"units": "1", "long_name": "SS(X*, r(k)) at the SUMT optimum, last r(k), report grid"},
            ),
            "evaluations": (
                (), sum(run.evaluations for run in runs), {"units": "1", "long_name": "objective evaluations (SUMT)"},
            ),
        },
        coords={
            "iteration": ("iteration", np.arange(len(h)), {"units": "1", "long_name": "outer iteration k"}),
            "member": member,
            "constraint": (
                "constraint", np.arange(1, 9),
                {"units": "1", "long_name": "constraint index (1-4 diameter, 5-8 stress)"},
            ),
        },
    )
    ds.attrs.update(
        title="Section optimisation (mixed penalty SUMT)", slsqp_success=str(info_s["success"]),
        slsqp_message=info_s["message"], slsqp_evaluations=sum(r["evaluations"] for r in slsqp_runs),
        reference_diameter_m=prob.reference_diameter, angle_step_deg=cfg["fe"]["angle_step_deg"],
        coarse_angle_step_deg=opt["angle_step_deg"], active_angles=info["active_angles"],
        grid_angles=info["grid_angles"], exchange_rounds=info["exchange_rounds"],
        peaks_in_active=int(info["peaks_in_active"]), slsqp_exchange_rounds=slsqp_info["exchange_rounds"],
    )
    return ds


def summary(result) -> dict[str, float]:
    """Signed extremes of the tip's elastic displacement (m), the largest distortion (m) and stress (MPa)."""
    return {
        "Ux": signed_extreme(result.tip[:, 0]),
        "Uy": signed_extreme(result.tip[:, 1]),
        "distortion": float(np.hypot(result.tip[:, 0], result.tip[:, 1]).max()),
        "stress_max": float(result.stress.max() / 1e6),
    }


SUMMARY_ATTRS = {
    "Ux": ("m", "signed extreme of the tip's elastic x displacement"),
    "Uy": ("m", "signed extreme of the tip's elastic y displacement"),
    "distortion": ("m", "largest elastic tip displacement magnitude"),
    "stress_max": ("MPa", "largest eq. (8) stress over members and crank angles"),
}
SNAPSHOT_ANGLES_DEG = (0.0, 90.0, 180.0, 270.0)


#: Linear (small-deflection) beam theory: an elastic tip deflection beyond this fraction of the arm length
#: (the longest member) makes the neglected geometric terms, of order (deflection / length)^2, exceed 1 % of the
#: response.
SMALL_DEFLECTION_LIMIT = 0.1


def newmark_step_study(cfg: Mapping[str, Any], diameters: np.ndarray) -> dict[str, Any]:
    """Dynamic stress at ``diameters`` against the Newmark step (deg of crank angle), every run sampled on the grid
    of the largest studied step, against a reference run with ``fe.newmark_study.reference_step_deg``.

    Two errors per step, relative to the reference peak: of the peak stress itself, and of the stress field (the
    largest |sigma - sigma_ref| over members and sampled angles). The field error bounds the peak's error
    (|max a - max b| <= max |a - b|) and converges smoothly, whereas the peak's own error jumps where the sampled
    maximum moves to a neighbouring angle; the observed order is the field error's, between neighbouring steps.
    The error at the pipeline's own step (fe.angle_step_deg / fe.substeps) is the field error interpolated
    log-log between the studied steps."""
    study = cfg["fe"]["newmark_study"]
    steps = np.array(sorted(study["steps_deg"], reverse=True), dtype=float)
    out_step = steps[0]
    theta = np.radians(angle_grid_deg(out_step))
    mech, mat, disc, gravity = mechanism(cfg), material(cfg), discretisation(cfg), gravity_of(cfg)
    settings = dynamic_settings(cfg)

    def stress(step):
        r = ked(mech, disc, diameters, mat, theta, "dynamic", gravity=gravity, damping_ratio=settings["damping_ratio"],
                revolutions=settings["revolutions"], substeps=int(round(out_step / step)))
        return r.stress / 1e6

    runs = [stress(h) for h in steps]
    reference = stress(float(study["reference_step_deg"]))
    ref_peak = float(reference.max())
    peaks = np.array([float(r.max()) for r in runs])
    peak_error = np.abs(peaks - ref_peak) / ref_peak
    field_error = np.array([float(np.abs(r - reference).max()) for r in runs]) / ref_peak
    order = np.log(field_error[:-1] / field_error[1:]) / np.log(steps[:-1] / steps[1:])
    pipeline_step = cfg["fe"]["angle_step_deg"] / cfg["fe"]["substeps"]
    at_pipeline = float(np.exp(np.interp(np.log(pipeline_step), np.log(steps[::-1]), np.log(field_error[::-1]))))
    return {
        "steps": steps,
        "peaks": peaks,
        "reference": ref_peak,
        "peak_error": peak_error,
        "field_error": field_error,
        "order": order,
        "output_step": out_step,
        "pipeline_step": pipeline_step,
        "pipeline_error": at_pipeline,
    }


def damping_study(cfg: Mapping[str, Any], diameters: np.ndarray, allowable_mpa: float) -> dict[str, Any]:
    """Dynamic peak stress (MPa) at ``diameters`` over the damping ratio's assumed range (evenly,
    ``fe.damping_study.points``), and the damping ratio at which the peak equals ``allowable_mpa`` where the range holds
    one (Brent's method). The revolutions grow as 1/damping below the nominal damping, so that the start transient
    decays alike."""
    from scipy.optimize import brentq

    fe = cfg["fe"]
    entry, study = fe["damping_ratio"], fe["damping_study"]
    lo, hi = (float(v) for v in entry["range"])
    nominal = float(entry["value"])
    theta = np.radians(report_grid(cfg))
    mech, mat, disc, gravity = mechanism(cfg), material(cfg), discretisation(cfg), gravity_of(cfg)

    def run(zeta):
        revolutions = max(int(fe["revolutions"]), int(np.ceil(fe["revolutions"] * nominal / zeta)))
        r = ked(
            mech, disc, diameters, mat, theta, "dynamic", gravity=gravity, damping_ratio=zeta, revolutions=revolutions,
            substeps=fe["substeps"],
        )
        return float(r.stress.max() / 1e6), r.periodicity, revolutions

    ratios = np.linspace(lo, hi, int(study["points"]))
    runs = [run(z) for z in ratios]
    peaks = np.array([r[0] for r in runs])
    excess = peaks - allowable_mpa
    threshold = np.nan
    crossing = np.flatnonzero(np.sign(excess[:-1]) != np.sign(excess[1:]))
    if crossing.size:
        i = int(crossing[0])
        threshold = float(
            brentq(lambda z: run(z)[0] - allowable_mpa, ratios[i], ratios[i + 1], xtol=float(study["threshold_xtol"]))
        )
    return {
        "ratios": ratios,
        "peaks": peaks,
        "periodicity": np.array([r[1] for r in runs]),
        "revolutions": np.array([r[2] for r in runs]),
        "threshold": threshold,
        "crossings": int(crossing.size),
    }


def ked_responses(cfg: Mapping[str, Any], optim: xr.Dataset) -> xr.Dataset:
    """Tip path, tip deformation and member stresses over crank angle for the initial and our optimal
    diameters, quasi-static and dynamic; natural frequencies; a resonance warning; the linkage drawn
    at four crank angles; the size of the mesh."""
    fe = cfg["fe"]
    theta_deg = angle_grid_deg(fe["angle_step_deg"])
    sets = {"initial": np.array(cfg["initial_diameters_m"], dtype=float), "optimal": optim.d_opt.values / 1e3}
    solutions = ("quasi-static", "dynamic")
    tip = np.empty((len(sets), len(solutions), theta_deg.size, 2))
    tip_ax, tip_tr = np.empty(tip.shape[:-1]), np.empty(tip.shape[:-1])
    stress = np.empty((len(sets), len(solutions), theta_deg.size, 4))
    freqs, periodicity, rayleigh = np.empty((len(sets), 4)), np.empty(len(sets)), np.empty((len(sets), 2))
    for i, d in enumerate(sets.values()):
        for j, sol in enumerate(solutions):
            r = solve(cfg, d, sol, theta_deg)
            tip[i, j], tip_ax[i, j], tip_tr[i, j], stress[i, j] = r.tip, r.tip_axial, r.tip_transverse, r.stress / 1e6
            if sol == "dynamic":
                periodicity[i], rayleigh[i] = r.periodicity, r.rayleigh
            freqs[i] = r.first_frequencies
    mech = mechanism(cfg)
    path = rigid_motion(mech, np.radians(theta_deg)).pos[:, 4]
    snapshot = rigid_motion(mech, np.radians(SNAPSHOT_ANGLES_DEG)).pos
    omega = mech.crank_speed
    ratio = float(freqs.min() / omega)
    disc = discretisation(cfg)
    dims3 = ("diameters", "solution", "crank_angle")
    newmark = newmark_step_study(cfg, sets["optimal"])
    damping = damping_study(cfg, sets["optimal"], float(optim.allowable))
    ds = xr.Dataset(
        {
            "tip_x": ("crank_angle", path[:, 0], {"units": "m", "long_name": "planting-arm tip E, rigid path, x"}),
            "tip_y": ("crank_angle", path[:, 1], {"units": "m", "long_name": "planting-arm tip E, rigid path, y"}),
            "joint_position": (
                ("snapshot", "joint", "xy"), snapshot,
                {"units": "m", "long_name": "joints A, B, C, D, E at the snapshot crank angles"},
            ),
            "Ux": (dims3, tip[..., 0], {"units": "m", "long_name": "elastic displacement of the tip, x"}),
            "Uy": (dims3, tip[..., 1], {"units": "m", "long_name": "elastic displacement of the tip, y"}),
            "U_axial": (dims3, tip_ax, {"units": "m", "long_name": "elastic tip displacement along the arm"}),
            "U_transverse": (dims3, tip_tr, {"units": "m", "long_name": "elastic tip displacement across the arm"}),
            "stress": (
                (*dims3, "member"), stress, {"units": "MPa", "long_name": "largest eq. (8) stress in the member"},
            ),
            "peak_stress": (
                ("diameters", "solution"), stress.max(axis=(2, 3)),
                {"units": "MPa", "long_name": "largest stress over members and crank angles"},
            ),
            "diameter": (
                ("diameters", "member"), np.array(list(sets.values())) * 1e3,
                {"units": "mm", "long_name": "member diameters"},
            ),
            "natural_frequency": (
                ("diameters", "mode"), freqs,
                {"units": "rad s-1", "long_name": "lowest natural frequencies at crank angle 0"},
            ),
            "periodicity": (
                "diameters",
                periodicity,
                {
                    "units": "1",
                    "long_name": "dynamic: change of the tip response between the last two revolutions / its range",
                },
            ),
            "crank_speed": ((), omega, {"units": "rad s-1", "long_name": "crank speed"}),
            "coordinates": (
                (), int(disc.mesh.dof_indices()[0]), {"units": "1", "long_name": "generalized coordinates of the mesh"},
            ),
            "rayleigh_alpha": (
                "diameters", rayleigh[:, 0],
                {"units": "s-1", "long_name": "Rayleigh damping C = alpha M + beta K: alpha (dynamic solution)"},
            ),
            "rayleigh_beta": (
                "diameters", rayleigh[:, 1],
                {"units": "s", "long_name": "Rayleigh damping C = alpha M + beta K: beta (dynamic solution)"},
            ),
            "damping_ratio": (
                (), float(cfg["fe"]["damping_ratio"]["value"]),
                {"units": "1", "long_name": "assumed damping ratio at the first two natural frequencies"},
            ),
            "allowable": ((), float(optim.allowable), {"units": "MPa", "long_name": "allowable stress"}),
            "newmark_peak": (
                "newmark_step",
                newmark["peaks"],
                {
                    "units": "MPa",
                    "long_name": f"dynamic peak stress at our optimum, sampled every {newmark['output_step']:g} deg",
                },
            ),
            "newmark_reference_peak": (
                (), newmark["reference"], {"units": "MPa", "long_name": "the same with the reference step"},
            ),
            "newmark_peak_error": (
                "newmark_step", newmark["peak_error"],
                {"units": "1", "long_name": "relative error of the dynamic peak stress against the reference step"},
            ),
            "newmark_field_error": (
                "newmark_step",
                newmark["field_error"],
                {
                    "units": "1",
                    "long_name": (
                        "largest |stress - reference| over members and angles / reference peak (bounds the peak's"
                        " error)"
                    ),
                },
            ),
            "newmark_order": (
                "newmark_pair", newmark["order"],
                {"units": "1", "long_name": "observed order of the field error between neighbouring steps"},
            ),
            "newmark_pipeline_error": (
                (),
                newmark["pipeline_error"],
                {
                    "units": "1",
                    "long_name": "field error at the pipeline's step (bound of the peak's relative Newmark error)",
                },
            ),
            "newmark_pipeline_step": (
                (), newmark["pipeline_step"],
                {"units": "deg", "long_name": "the pipeline's Newmark step (fe.angle_step_deg / fe.substeps)"},
            ),
            "damping_peak": (
                "damping", damping["peaks"],
                {"units": "MPa", "long_name": "dynamic peak stress at our optimum (report grid)"},
            ),
            "damping_periodicity": (
                "damping", damping["periodicity"],
                {"units": "1", "long_name": "change of the tip response between the last two revolutions / its range"},
            ),
            "damping_revolutions": (
                "damping", damping["revolutions"],
                {"units": "1", "long_name": "Newmark revolutions (grow as 1/damping below the nominal)"},
            ),
            "damping_threshold": (
                (),
                damping["threshold"],
                {
                    "units": "1",
                    "long_name": "damping ratio at which the dynamic peak at our optimum equals the allowable",
                    "nan_meaning": "no damping ratio in the assumed range brings the peak to the allowable",
                },
            ),
        },
        coords={
            "diameters": (
                "diameters", np.array(list(sets), dtype=object),
                {"units": "1", "long_name": "initial or our optimal diameters"},
            ),
            "solution": (
                "solution", np.array(solutions, dtype=object),
                {"units": "1", "long_name": "quasi-static K^-1 F, or Newmark over revolutions"},
            ),
            "crank_angle": ("crank_angle", theta_deg, {"units": "deg", "long_name": "crank angle"}),
            "member": (
                "member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member (AB, BC, CD, BE)"},
            ),
            "mode": ("mode", np.arange(1, 5), {"units": "1", "long_name": "mode number"}),
            "snapshot": (
                "snapshot", np.array(SNAPSHOT_ANGLES_DEG),
                {"units": "deg", "long_name": "crank angle of the linkage drawing"},
            ),
            "joint": ("joint", np.array(list("ABCDE"), dtype=object), {"units": "1", "long_name": "joint"}),
            "xy": ("xy", np.array(["x", "y"], dtype=object), {"units": "1", "long_name": "coordinate"}),
            "newmark_step": (
                "newmark_step", newmark["steps"], {"units": "deg", "long_name": "Newmark step (crank angle)"},
            ),
            "newmark_pair": (
                "newmark_pair", newmark["steps"][1:], {"units": "deg", "long_name": "finer step of the pair"},
            ),
            "damping": ("damping", damping["ratios"], {"units": "1", "long_name": "Rayleigh damping ratio"}),
        },
    )
    warn = fe["resonance_warning_ratio"]
    deflection = float(np.hypot(tip[..., 0], tip[..., 1]).max() / cfg["geometry"]["arm_m"])
    ds.attrs.update(
        title="Kineto-elastodynamics of the transplanter",
        validity_tip_deflection_over_arm=deflection,
        validity_deflection_limit=SMALL_DEFLECTION_LIMIT,
        validity_warnings=(
            f"elastic tip deflection reaches {deflection:.3g} of the arm length (limit {SMALL_DEFLECTION_LIMIT:g}): "
            "outside small-deflection beam theory"
            if deflection > SMALL_DEFLECTION_LIMIT
            else ""
        ),
        first_frequency_over_crank_speed=ratio,
        resonance_warning=(
            f"crank speed within a factor {warn:g} of the first natural frequency ({ratio:.2f})"
            if ratio < warn
            else "none"
        ),
        element=fe["element"],
        elements_per_member=str(fe["elements_per_member"]),
        newmark_output_step_deg=newmark["output_step"],
        newmark_reference_step_deg=float(fe["newmark_study"]["reference_step_deg"]),
        damping_threshold_crossings=damping["crossings"],
    )
    return ds
