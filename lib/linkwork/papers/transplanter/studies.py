"""The transplanter paper's studies: the section optimisation and the KED responses at the initial and our
optimal diameters."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.optimize import PenaltyProblem, slsqp, sumt
from ...units import angle_grid_deg
from .adapter import allowable, discretisation, dynamic_settings, material, mechanism, member_lengths
from .adapter import gravity as gravity_of
from .model import MEMBERS, ked, rigid_motion, signed_extreme

def solve(cfg, diameters, solution, theta_deg, *, mech=None, mat=None, gravity=None, disc=None):
    """KED over the crank angles ``theta_deg`` (deg) with the config's mesh, gravity and (dynamic) Newmark settings."""
    dynamic = {} if solution == "quasi-static" else dynamic_settings(cfg)
    return ked(
        mech or mechanism(cfg), disc or discretisation(cfg), diameters, mat or material(cfg), np.radians(theta_deg),
        solution=solution, gravity=gravity_of(cfg) if gravity is None else gravity, **dynamic,
    )


def problem(cfg: Mapping[str, Any]) -> PenaltyProblem:
    """The paper's section-design problem: quasi-static member stress maxima on the optimisation's crank-angle grid."""
    opt = cfg["optimization"]
    mech, mat, disc = mechanism(cfg), material(cfg), discretisation(cfg)
    theta = np.radians(angle_grid_deg(opt["angle_step_deg"]))
    gravity = gravity_of(cfg)

    def stresses(x):
        return ked(mech, disc, x, mat, theta, "quasi-static", gravity=gravity).stress.max(axis=0)

    return PenaltyProblem(stresses, member_lengths(cfg), allowable(cfg), float(opt["reference_diameter_m"]["value"]), float(cfg["minimum_diameter_m"]))


def optim(cfg: Mapping[str, Any]) -> xr.Dataset:
    """SUMT iterates with the objective parts and constraints, and the SLSQP cross-check."""
    opt = cfg["optimization"]
    prob = problem(cfg)
    x0 = np.array(cfg["initial_diameters_m"], dtype=float)
    res = sumt(prob, x0, opt["r0"], opt["r_factor"], opt["iterations"], opt["xtol_m"], opt["inner_maxiter"])
    xs, info = slsqp(prob, x0, opt["slsqp_ftol"])
    h = res.history
    member = ("member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member (AB, BC, CD, BE)"})
    ds = xr.Dataset(
        {
            "r": ("iteration", np.array([e["r"] for e in h]), {"units": "1", "long_name": "penalty factor r(k)"}),
            "x": (("iteration", "member"), np.array([e["x"] for e in h]) * 1e3, {"units": "mm", "long_name": "diameters after iteration k"}),
            **{p: ("iteration", np.array([e[p] for e in h]), {"units": "1", "long_name": f"objective part {p}"}) for p in ("SY", "SZ", "SG", "SH", "SS")},
            "g": (("iteration", "constraint"), np.array([e["g"] for e in h]), {"units": "1", "long_name": "constraints g_1..g_8 (>= 0 feasible)"}),
            "d_opt": ("member", res.x * 1e3, {"units": "mm", "long_name": "optimal diameters (SUMT)"}),
            "d_slsqp": ("member", xs * 1e3, {"units": "mm", "long_name": "optimal diameters (SLSQP on SY + SZ, explicit constraints)"}),
            "sumt_slsqp_difference": ((), float(np.abs(res.x - xs).max() * 1e3), {"units": "mm", "long_name": "largest |SUMT - SLSQP| diameter difference"}),
            "stress_opt": ("member", prob.stresses(res.x) / 1e6, {"units": "MPa", "long_name": "largest stress per member at the SUMT optimum"}),
            "allowable": ((), prob.allowable / 1e6, {"units": "MPa", "long_name": "allowable stress (yield / safety factor)"}),
            "SS_opt": ((), h[-1]["SS"], {"units": "1", "long_name": "SS(X*, r(k)) at the SUMT optimum, last r(k)"}),
            "evaluations": ((), res.evaluations, {"units": "1", "long_name": "objective evaluations (SUMT)"}),
        },
        coords={"iteration": ("iteration", np.arange(len(h)), {"units": "1", "long_name": "outer iteration k"}), "member": member,
                "constraint": ("constraint", np.arange(1, 9), {"units": "1", "long_name": "constraint index (1-4 diameter, 5-8 stress)"})},
    )
    ds.attrs.update(title="Section optimisation (mixed penalty SUMT)", slsqp_success=str(info["success"]), slsqp_message=info["message"],
                    slsqp_evaluations=info["evaluations"], reference_diameter_m=prob.reference_diameter, angle_step_deg=opt["angle_step_deg"])
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
#: (the longest member) makes the neglected geometric terms, of order (deflection / length)^2, exceed 1 % of the response.
SMALL_DEFLECTION_LIMIT = 0.1


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
    freqs, periodicity = np.empty((len(sets), 4)), np.empty(len(sets))
    for i, d in enumerate(sets.values()):
        for j, sol in enumerate(solutions):
            r = solve(cfg, d, sol, theta_deg)
            tip[i, j], tip_ax[i, j], tip_tr[i, j], stress[i, j] = r.tip, r.tip_axial, r.tip_transverse, r.stress / 1e6
            if sol == "dynamic":
                periodicity[i] = r.periodicity
            freqs[i] = r.first_frequencies
    mech = mechanism(cfg)
    path = rigid_motion(mech, np.radians(theta_deg)).pos[:, 4]
    snapshot = rigid_motion(mech, np.radians(SNAPSHOT_ANGLES_DEG)).pos
    omega = mech.crank_speed
    ratio = float(freqs.min() / omega)
    disc = discretisation(cfg)
    dims3 = ("diameters", "solution", "crank_angle")
    ds = xr.Dataset(
        {
            "tip_x": ("crank_angle", path[:, 0], {"units": "m", "long_name": "planting-arm tip E, rigid path, x"}),
            "tip_y": ("crank_angle", path[:, 1], {"units": "m", "long_name": "planting-arm tip E, rigid path, y"}),
            "joint_position": (("snapshot", "joint", "xy"), snapshot, {"units": "m", "long_name": "joints A, B, C, D, E at the snapshot crank angles"}),
            "Ux": (dims3, tip[..., 0], {"units": "m", "long_name": "elastic displacement of the tip, x"}),
            "Uy": (dims3, tip[..., 1], {"units": "m", "long_name": "elastic displacement of the tip, y"}),
            "U_axial": (dims3, tip_ax, {"units": "m", "long_name": "elastic tip displacement along the arm"}),
            "U_transverse": (dims3, tip_tr, {"units": "m", "long_name": "elastic tip displacement across the arm"}),
            "stress": ((*dims3, "member"), stress, {"units": "MPa", "long_name": "largest eq. (8) stress in the member"}),
            "peak_stress": (("diameters", "solution"), stress.max(axis=(2, 3)), {"units": "MPa", "long_name": "largest stress over members and crank angles"}),
            "diameter": (("diameters", "member"), np.array(list(sets.values())) * 1e3, {"units": "mm", "long_name": "member diameters"}),
            "natural_frequency": (("diameters", "mode"), freqs, {"units": "rad s-1", "long_name": "lowest natural frequencies at crank angle 0"}),
            "periodicity": ("diameters", periodicity, {"units": "1", "long_name": "dynamic: change of the tip response between the last two revolutions / its range"}),
            "crank_speed": ((), omega, {"units": "rad s-1", "long_name": "crank speed"}),
            "coordinates": ((), int(disc.mesh.dof_indices()[0]), {"units": "1", "long_name": "generalized coordinates of the mesh"}),
        },
        coords={
            "diameters": ("diameters", np.array(list(sets), dtype=object), {"units": "1", "long_name": "initial or our optimal diameters"}),
            "solution": ("solution", np.array(solutions, dtype=object), {"units": "1", "long_name": "quasi-static K^-1 F, or Newmark over revolutions"}),
            "crank_angle": ("crank_angle", theta_deg, {"units": "deg", "long_name": "crank angle"}),
            "member": ("member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member (AB, BC, CD, BE)"}),
            "mode": ("mode", np.arange(1, 5), {"units": "1", "long_name": "mode number"}),
            "snapshot": ("snapshot", np.array(SNAPSHOT_ANGLES_DEG), {"units": "deg", "long_name": "crank angle of the linkage drawing"}),
            "joint": ("joint", np.array(list("ABCDE"), dtype=object), {"units": "1", "long_name": "joint"}),
            "xy": ("xy", np.array(["x", "y"], dtype=object), {"units": "1", "long_name": "coordinate"}),
        },
    )
    warn = fe["resonance_warning_ratio"]
    deflection = float(np.hypot(tip[..., 0], tip[..., 1]).max() / cfg["geometry"]["arm_m"])
    ds.attrs.update(
        title="Kineto-elastodynamics of the transplanter",
        validity_tip_deflection_over_arm=deflection, validity_deflection_limit=SMALL_DEFLECTION_LIMIT,
        validity_warnings=(f"elastic tip deflection reaches {deflection:.3g} of the arm length (limit {SMALL_DEFLECTION_LIMIT:g}): "
                           "outside small-deflection beam theory" if deflection > SMALL_DEFLECTION_LIMIT else ""),
        first_frequency_over_crank_speed=ratio,
        resonance_warning=(f"crank speed within a factor {warn:g} of the first natural frequency ({ratio:.2f})" if ratio < warn else "none"),
        element=fe["element"], elements_per_member=str(fe["elements_per_member"]),
    )
    return ds
