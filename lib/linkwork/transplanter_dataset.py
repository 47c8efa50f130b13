"""The transplanter paper's result Datasets: optimisation, KED responses, the published point, accuracy."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np
import xarray as xr

from .from_config import angle_grid_deg
from .optimize import PenaltyProblem, gradient, slsqp, sumt
from .timing import median_time
from .transplanter import MEMBERS, Material, Transplanter, discretise, ked, signed_extreme

RPM = 2 * np.pi / 60.0


def mechanism(section: Mapping[str, Any], **override) -> Transplanter:
    g = section["geometry"]
    mech = Transplanter(
        crank=g["crank_m"],
        coupler=g["coupler_m"],
        rocker=g["rocker_m"],
        arm=g["arm_m"],
        pivot_d=(g["pivot_D_m"][0], g["pivot_D_m"][1]),
        arm_angle=float(np.radians(g["arm_angle_deg"])),
        arm_side=g["arm_side"],
        branch=g["branch"],
        crank_speed=section["crank_speed_rpm"] * RPM,
    )
    return replace(mech, **override) if override else mech


def material(section: Mapping[str, Any], **override) -> Material:
    name = section["material"]["name"]
    props = section["materials"][name]
    m = Material(
        youngs_modulus=float(props["youngs_modulus_Pa"]["value"]),
        density=float(props["density_kg_m3"]["value"]),
        allowable=float(props["yield_Pa"]["value"]) / float(section["material"]["safety_factor"]),
    )
    return replace(m, **override) if override else m


def discretisation(section: Mapping[str, Any], kind: str | None = None, elements=None):
    fe = section["fe"]
    return discretise(tuple(elements or fe["elements_per_member"]), kind or fe["element"])


def _solve(section, diameters, solution, theta_deg, *, mech=None, mat=None, gravity=None, disc=None):
    fe = section["fe"]
    return ked(
        mech or mechanism(section),
        disc or discretisation(section),
        diameters,
        mat or material(section),
        np.radians(theta_deg),
        solution=solution,
        gravity=fe["gravity_m_s2"] if gravity is None else gravity,
        damping_ratio=fe["damping_ratio"],
        revolutions=fe["revolutions"],
        substeps=fe["substeps"],
    )


def problem(section: Mapping[str, Any]) -> PenaltyProblem:
    opt = section["optimization"]
    mech, mat, disc = mechanism(section), material(section), discretisation(section)
    theta = np.radians(angle_grid_deg(opt["angle_step_deg"]))
    fe = section["fe"]

    def stresses(x):
        return ked(mech, disc, x, mat, theta, "quasi-static", gravity=fe["gravity_m_s2"]).stress.max(axis=0)

    g = section["geometry"]
    return PenaltyProblem(
        stresses,
        np.array([g["crank_m"], g["coupler_m"], g["rocker_m"], g["arm_m"]]),
        mat.allowable,
        float(opt["reference_diameter_m"]["value"]),
        float(section["minimum_diameter_m"]),
    )


def optim_dataset(section: Mapping[str, Any]) -> xr.Dataset:
    """SUMT iterates with the objective parts and constraints, and the SLSQP cross-check."""
    opt = section["optimization"]
    prob = problem(section)
    x0 = np.array(section["initial_diameters_m"], dtype=float)
    res = sumt(prob, x0, opt["r0"], opt["r_factor"], opt["iterations"], opt["xtol_m"], opt["inner_maxiter"])
    xs, info = slsqp(prob, x0, opt["slsqp_ftol"])
    h = res.history
    it = np.arange(len(h))
    member = ("member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member (AB, BC, CD, BE)"})
    ds = xr.Dataset(
        {
            "r": ("iteration", np.array([e["r"] for e in h]), {"units": "1", "long_name": "penalty factor r(k)"}),
            "x": (("iteration", "member"), np.array([e["x"] for e in h]) * 1e3, {"units": "mm", "long_name": "diameters after iteration k"}),
            **{p: ("iteration", np.array([e[p] for e in h]), {"units": "1", "long_name": f"objective part {p}"}) for p in ("SY", "SZ", "SG", "SH", "SS")},
            "g": (("iteration", "constraint"), np.array([e["g"] for e in h]), {"units": "1", "long_name": "constraints g_1..g_8 (>= 0 feasible)"}),
            "d_opt": ("member", res.x * 1e3, {"units": "mm", "long_name": "optimal diameters (SUMT)"}),
            "d_slsqp": ("member", xs * 1e3, {"units": "mm", "long_name": "optimal diameters (SLSQP on SY + SZ, explicit constraints)"}),
            "stress_opt": ("member", prob.stresses(res.x) / 1e6, {"units": "MPa", "long_name": "largest stress per member at the SUMT optimum"}),
            "SS_opt": ((), h[-1]["SS"], {"units": "1", "long_name": "SS(X*, r(k)) at the SUMT optimum, last r(k)"}),
            "evaluations": ((), res.evaluations, {"units": "1", "long_name": "objective evaluations (SUMT)"}),
        },
        coords={"iteration": ("iteration", it, {"units": "1", "long_name": "outer iteration k"}), "member": member,
                "constraint": ("constraint", np.arange(1, 9), {"units": "1", "long_name": "constraint index (1-4 diameter, 5-8 stress)"})},
    )
    ds.attrs.update(slsqp_success=str(info["success"]), slsqp_message=info["message"], slsqp_evaluations=info["evaluations"],
                    reference_diameter_m=prob.reference_diameter, angle_step_deg=opt["angle_step_deg"])
    return ds


def _summary(result) -> dict[str, float]:
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


def ked_dataset(section: Mapping[str, Any], optimal_mm: np.ndarray) -> xr.Dataset:
    """Tip path, tip deformation and member stresses over crank angle for the initial and our optimal
    diameters, quasi-static and dynamic; natural frequencies; a resonance warning."""
    theta_deg = angle_grid_deg(section["fe"]["angle_step_deg"])
    sets = {"initial": np.array(section["initial_diameters_m"], dtype=float), "optimal": np.asarray(optimal_mm) / 1e3}
    solutions = ("quasi-static", "dynamic")
    tip = np.empty((len(sets), len(solutions), theta_deg.size, 2))
    tip_ax = np.empty((len(sets), len(solutions), theta_deg.size))
    tip_tr = np.empty_like(tip_ax)
    stress = np.empty((len(sets), len(solutions), theta_deg.size, 4))
    freqs = np.empty((len(sets), 4))
    periodicity = np.empty(len(sets))
    for i, d in enumerate(sets.values()):
        for j, sol in enumerate(solutions):
            r = _solve(section, d, sol, theta_deg)
            tip[i, j], tip_ax[i, j], tip_tr[i, j], stress[i, j] = r.tip, r.tip_axial, r.tip_transverse, r.stress / 1e6
            if sol == "dynamic":
                periodicity[i] = r.periodicity
            freqs[i] = r.first_frequencies
    from .transplanter import rigid_motion

    path = rigid_motion(mechanism(section), np.radians(theta_deg)).pos[:, 4]
    omega = section["crank_speed_rpm"] * RPM
    ratio = float(freqs.min() / omega)
    dims3 = ("diameters", "solution", "crank_angle")
    ds = xr.Dataset(
        {
            "tip_x": ("crank_angle", path[:, 0], {"units": "m", "long_name": "planting-arm tip E, rigid path, x"}),
            "tip_y": ("crank_angle", path[:, 1], {"units": "m", "long_name": "planting-arm tip E, rigid path, y"}),
            "Ux": (dims3, tip[..., 0], {"units": "m", "long_name": "elastic displacement of the tip, x"}),
            "Uy": (dims3, tip[..., 1], {"units": "m", "long_name": "elastic displacement of the tip, y"}),
            "U_axial": (dims3, tip_ax, {"units": "m", "long_name": "elastic tip displacement along the arm"}),
            "U_transverse": (dims3, tip_tr, {"units": "m", "long_name": "elastic tip displacement across the arm"}),
            "stress": ((*dims3, "member"), stress, {"units": "MPa", "long_name": "largest eq. (8) stress in the member"}),
            "diameter": (("diameters", "member"), np.array(list(sets.values())) * 1e3, {"units": "mm", "long_name": "member diameters"}),
            "natural_frequency": (("diameters", "mode"), freqs, {"units": "rad s-1", "long_name": "lowest natural frequencies at crank angle 0"}),
            "periodicity": ("diameters", periodicity, {"units": "1", "long_name": "dynamic: change of the tip response between the last two revolutions / its range"}),
        },
        coords={
            "diameters": ("diameters", np.array(list(sets), dtype=object), {"units": "1", "long_name": "initial or our optimal diameters"}),
            "solution": ("solution", np.array(solutions, dtype=object), {"units": "1", "long_name": "quasi-static K^-1 F, or Newmark over revolutions"}),
            "crank_angle": ("crank_angle", theta_deg, {"units": "deg", "long_name": "crank angle"}),
            "member": ("member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member (AB, BC, CD, BE)"}),
            "mode": ("mode", np.arange(1, 5), {"units": "1", "long_name": "mode number"}),
        },
    )
    warn = section["fe"]["resonance_warning_ratio"]
    ds.attrs.update(
        first_frequency_over_crank_speed=ratio,
        resonance_warning=(f"crank speed within a factor {warn:g} of the first natural frequency ({ratio:.2f})" if ratio < warn else "none"),
        element=section["fe"]["element"], elements_per_member=str(section["fe"]["elements_per_member"]),
    )
    return ds


def published_point_dataset(section: Mapping[str, Any], published_mm: np.ndarray, published_ss: float) -> xr.Dataset:
    """Comparison data at the published optimum: our model's response there, what moves it, SS and stationarity.

    The published diameters and SS enter here only to evaluate our model at the paper's point, for
    comparison; nothing computed here feeds our own optimum.
    """
    d = np.asarray(published_mm, dtype=float) / 1e3
    theta = angle_grid_deg(section["fe"]["angle_step_deg"])
    sens = section["sensitivity"]
    cases = {
        "baseline (quasi-static)": {},
        "dynamic (Newmark)": {"solution": "dynamic"},
        f"E = {sens['youngs_modulus_low_Pa'] / 1e9:g} GPa": {"mat": material(section, youngs_modulus=sens["youngs_modulus_low_Pa"])},
        f"E = {sens['youngs_modulus_high_Pa'] / 1e9:g} GPa": {"mat": material(section, youngs_modulus=sens["youngs_modulus_high_Pa"])},
        f"density {sens['density_high_kg_m3']:g} kg/m3": {"mat": material(section, density=sens["density_high_kg_m3"])},
        "gravity on": {"gravity": 9.80665},
        f"{sens['coarse_angle_step_deg']:g} deg crank sampling": {"theta": angle_grid_deg(sens["coarse_angle_step_deg"])},
        "frame6 elements": {"disc": discretisation(section, kind="frame6")},
    }
    rows = []
    for spec in cases.values():
        spec = dict(spec)
        sol = spec.pop("solution", "quasi-static")
        th = spec.pop("theta", theta)
        rows.append(_summary(_solve(section, d, sol, th, **spec)))
    # assembly branch and arm side: which reproduces the published deformation pattern
    combos = [(s, b) for s in (1, -1) for b in (1, -1)]
    combo_rows = []
    for s, b in combos:
        try:
            combo_rows.append(_summary(_solve(section, d, "quasi-static", theta, mech=mechanism(section, arm_side=s, branch=b))))
        except ValueError:
            combo_rows.append({k: np.nan for k in SUMMARY_ATTRS})
    prob = problem(section)
    r_last = section["optimization"]["r0"] * section["optimization"]["r_factor"] ** (section["optimization"]["iterations"] - 1)
    parts = prob.parts(d, r_last)
    barrier = float(np.sum(1.0 / parts["g"][parts["g"] > 0]))
    r_consistent = (published_ss - parts["SY"] - parts["SZ"]) / barrier
    step = section["optimization"]["gradient_step_m"]
    grad = gradient(lambda x: prob.ss(x, r_last), d, step)
    grad_sz = gradient(lambda x: prob.parts(x, r_last)["SY"] + prob.parts(x, r_last)["SZ"], d, step)
    data = {
        k: ("case", np.array([r[k] for r in rows]), {"units": u, "long_name": f"{n}, at the published optimum"}) for k, (u, n) in SUMMARY_ATTRS.items()
    }
    data.update({
        f"{k}_assembly": ("assembly", np.array([r[k] for r in combo_rows]), {"units": u, "long_name": f"{n}, by assembly"}) for k, (u, n) in SUMMARY_ATTRS.items()
    })
    data.update(
        {
            "stress_members": ("member", prob.stresses(d) / 1e6, {"units": "MPa", "long_name": f"largest stress per member ({section['optimization']['angle_step_deg']:g} deg sampling)"}),
            "SY_at_published": ((), parts["SY"], {"units": "1", "long_name": "SY at the published optimum"}),
            "SZ_at_published": ((), parts["SZ"], {"units": "1", "long_name": "SZ at the published optimum ([x_S1] from config)"}),
            "SG_at_published": ((), parts["SG"], {"units": "1", "long_name": "SG at the published optimum, last r(k)"}),
            "SS_at_published": ((), parts["SS"], {"units": "1", "long_name": "SS at the published optimum, last r(k)"}),
            "r_consistent": ((), r_consistent, {"units": "1", "long_name": "r that would make SS equal the printed 21.9665 with our SY, SZ"}),
            "gradient_SS": ("member", grad * 1e-3, {"units": "mm-1", "long_name": "dSS/dx at the published optimum (per mm), last r(k)"}),
            "gradient_SY_SZ": ("member", grad_sz * 1e-3, {"units": "mm-1", "long_name": "d(SY + SZ)/dx at the published optimum (per mm)"}),
        }
    )
    return xr.Dataset(
        data,
        coords={
            "case": ("case", np.array(list(cases), dtype=object), {"units": "1", "long_name": "model choice"}),
            "assembly": ("assembly", np.array([f"arm side {s:+d}, branch {b:+d}" for s, b in combos], dtype=object), {"units": "1", "long_name": "arm side and assembly branch"}),
            "member": ("member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member"}),
        },
        attrs={"published_diameters_mm": str(list(published_mm)), "r_last": r_last},
    )


def accuracy_dataset(section: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Elements per member and modes vs error in tip deflection and peak stress, and solve time."""
    acc = section["accuracy"]
    d = np.array(section["initial_diameters_m"], dtype=float)
    theta = angle_grid_deg(section["fe"]["angle_step_deg"])
    base = np.array(section["fe"]["elements_per_member"])
    ref_r = _solve(section, d, "quasi-static", theta, disc=discretisation(section, kind="quintic8", elements=tuple(base * acc["reference_refinement"])))
    ref_tip, ref_stress = np.abs(ref_r.tip[:, 1]).max(), ref_r.stress.max()
    kinds, levels = acc["elements"], acc["refinements"]
    tip_err = np.empty((len(kinds), len(levels)))
    stress_err = np.empty_like(tip_err)
    dofs = np.empty_like(tip_err)
    times = {}
    for i, kind in enumerate(kinds):
        for j, level in enumerate(levels):
            disc = discretisation(section, kind=kind, elements=tuple(base * level))
            r = _solve(section, d, "quasi-static", theta, disc=disc)
            tip_err[i, j] = abs(np.abs(r.tip[:, 1]).max() - ref_tip) / ref_tip
            stress_err[i, j] = abs(r.stress.max() - ref_stress) / ref_stress
            dofs[i, j] = disc.mesh.dof_indices()[0]
            times[f"{kind}x{level}"] = median_time(lambda disc=disc: _solve(section, d, "quasi-static", theta, disc=disc), acc["repeats"], warmup=False)
    # mode superposition (the paper's route to K^-1 F): modes kept vs error, on the base mesh
    from .transplanter import ked_modal

    disc = discretisation(section)
    modes = [n for n in acc["modes"] if n <= disc.mesh.dof_indices()[0]]
    modal_tip, modal_stress, modal_time = [], [], {}
    full = _solve(section, d, "quasi-static", theta, disc=disc)
    for n in modes:
        tip, stress = ked_modal(mechanism(section), disc, d, material(section), np.radians(theta), n, section["fe"]["gravity_m_s2"])
        modal_tip.append(abs(np.abs(tip[:, 1]).max() - np.abs(full.tip[:, 1]).max()) / np.abs(full.tip[:, 1]).max())
        modal_stress.append(abs(stress.max() - full.stress.max()) / full.stress.max())
        modal_time[str(n)] = median_time(
            lambda n=n: ked_modal(mechanism(section), disc, d, material(section), np.radians(theta), n, section["fe"]["gravity_m_s2"]), 1, warmup=False
        )
    ds = xr.Dataset(
        {
            "tip_error": (("element", "refinement"), tip_err, {"units": "1", "long_name": "relative error of the peak |Uy| vs a fine quintic reference"}),
            "stress_error": (("element", "refinement"), stress_err, {"units": "1", "long_name": "relative error of the peak stress vs the reference"}),
            "dofs": (("element", "refinement"), dofs, {"units": "1", "long_name": "system coordinates"}),
            "modal_tip_error": ("modes", np.array(modal_tip), {"units": "1", "long_name": "relative error of the peak |Uy|, modes kept vs all (base mesh)"}),
            "modal_stress_error": ("modes", np.array(modal_stress), {"units": "1", "long_name": "relative error of the peak stress, modes kept vs all"}),
        },
        coords={
            "modes": ("modes", np.array(modes), {"units": "1", "long_name": "modes kept in the superposition"}),
            "element": ("element", np.array(kinds, dtype=object), {"units": "1", "long_name": "element type"}),
            "refinement": ("refinement", np.array(levels), {"units": "1", "long_name": "elements per member, multiple of the base mesh"}),
        },
        attrs={"reference_refinement": acc["reference_refinement"], "base_mesh": str(list(base))},
    )
    timings = {"method": f"median of {acc['repeats']} runs after a warm-up, time.perf_counter (modal: one run)", "ked_360_s": times, "modal_s": modal_time}
    return ds, timings
