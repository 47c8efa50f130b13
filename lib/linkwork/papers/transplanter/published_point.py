"""Comparison data of the transplanter paper: our model evaluated at the published optimum."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.optimize import gradient
from ...units import angle_grid_deg
from .adapter import allowable, compared_solution, discretisation, mechanism
from .claims import RESPONSES, claim_measures
from .missing_load import inertia_only, inferred_loads
from .model import MEMBERS, signed_extreme
from .studies import SUMMARY_ATTRS, problem, report_grid, solve, summary


def at_published(cfg: Mapping[str, Any], published: Mapping[str, Any]) -> xr.Dataset:
    """Comparison data at the published optimum: our model's response there, what moves it, SS and stationarity.

    The published diameters and SS enter here only to evaluate our model at the paper's point, for
    comparison; nothing computed here feeds our own optimum.
    """
    published_mm = np.array(published["optimum_diameters_mm"], dtype=float)
    published_ss = float(next(q["value"] for q in published["quantities"] if q["id"] == "SS"))
    d = published_mm / 1e3
    theta = report_grid(cfg)
    checks = cfg["numerical_checks"]
    compared = compared_solution(cfg)
    # the baseline (the compared solution), the other solution, and two numerical choices (the assumed inputs
    # are the uncertainty study's)
    cases = {
        "baseline": {"solution": compared},
        **{f"{s} solution": {"solution": s} for s in ("quasi-static", "dynamic") if s != compared},
        f"{checks['coarse_angle_step_deg']:g} deg crank sampling": {
            "theta": angle_grid_deg(checks["coarse_angle_step_deg"]),
            "solution": compared,
        },
        "frame6 elements": {"disc": discretisation(cfg, kind="frame6"), "solution": compared},
    }
    rows, curves = [], {}
    for spec in cases.values():
        spec = dict(spec)
        sol = spec.pop("solution", "quasi-static")
        th = spec.pop("theta", theta)
        r = solve(cfg, d, sol, th, **spec)
        rows.append(summary(r))
        if th is theta and not spec:
            curves[sol] = r  # the two solutions on the report grid, for the figures
    base = curves[compared]
    solutions = ("quasi-static", "dynamic")
    combos = [(s, b) for s in (1, -1) for b in (1, -1)]  # which assembly reproduces the published deformation pattern
    combo_rows = []
    for s, b in combos:
        try:
            combo_rows.append(summary(solve(cfg, d, "quasi-static", theta, mech=mechanism(cfg, arm_side=s, branch=b))))
        except ValueError:
            combo_rows.append({k: np.nan for k in SUMMARY_ATTRS})
    prob = problem(cfg)  # the report grid
    opt = cfg["optimization"]
    r_last = opt["r0"] * opt["r_factor"] ** (opt["iterations"] - 1)
    parts = prob.parts(d, r_last)
    barrier = float(np.sum(1.0 / parts["g"][parts["g"] > 0]))
    step = opt["gradient_step_m"]
    grad = gradient(lambda x: prob.ss(x, r_last), d, step)
    grad_sz = gradient(lambda x: prob.parts(x, r_last)["SY"] + prob.parts(x, r_last)["SZ"], d, step)
    claims = claim_measures(cfg, d, compared)
    loads = inferred_loads(cfg, d, allowable(cfg))
    data = {
        k: ("case", np.array([r[k] for r in rows]), {"units": u, "long_name": f"{n}, at the published optimum"})
        for k, (u, n) in SUMMARY_ATTRS.items()
    }
    data.update(
        {
            f"{k}_assembly": (
                "assembly", np.array([r[k] for r in combo_rows]), {"units": u, "long_name": f"{n}, by assembly"},
            )
            for k, (u, n) in SUMMARY_ATTRS.items()
        }
    )
    data.update(
        {
            "stress_members": (
                "member", prob.stresses(d) / 1e6,
                {"units": "MPa", "long_name": f"largest stress per member ({cfg['fe']['angle_step_deg']:g} deg grid)"},
            ),
            "U_along_arm": (
                (),
                signed_extreme(base.tip_axial),
                {
                    "units": "m",
                    "long_name": (
                        "signed extreme of the tip's elastic displacement along the arm BE (compared solution)"
                    ),
                },
            ),
            "U_across_arm": (
                (),
                signed_extreme(base.tip_transverse),
                {
                    "units": "m",
                    "long_name": (
                        "signed extreme of the tip's elastic displacement across the arm BE (compared solution)"
                    ),
                },
            ),
            "Ux_curve": (
                ("solution", "crank_angle"), np.array([curves[s].tip[:, 0] for s in solutions]),
                {"units": "m", "long_name": "elastic tip displacement x at the published optimum"},
            ),
            "Uy_curve": (
                ("solution", "crank_angle"), np.array([curves[s].tip[:, 1] for s in solutions]),
                {"units": "m", "long_name": "elastic tip displacement y at the published optimum"},
            ),
            "stress_curve": (
                ("solution", "crank_angle", "member"), np.array([curves[s].stress for s in solutions]) / 1e6,
                {"units": "MPa", "long_name": "largest eq. (8) stress in the member at the published optimum"},
            ),
            "SY_at_published": ((), parts["SY"], {"units": "1", "long_name": "SY at the published optimum"}),
            "SZ_at_published": (
                (), parts["SZ"], {"units": "1", "long_name": "SZ at the published optimum ([x_S1] from config)"},
            ),
            "SY_SZ_at_published": (
                (), parts["SY"] + parts["SZ"], {"units": "1", "long_name": "SY + SZ at the published optimum"},
            ),
            "SG_at_published": ((), parts["SG"], {"units": "1", "long_name": "SG at the published optimum, last r(k)"}),
            "SS_at_published": ((), parts["SS"], {"units": "1", "long_name": "SS at the published optimum, last r(k)"}),
            "r_consistent": (
                (), (published_ss - parts["SY"] - parts["SZ"]) / barrier,
                {"units": "1", "long_name": "r that would make SS equal the printed value with our SY, SZ"},
            ),
            "gradient_SS": (
                "member", grad * 1e-3,
                {"units": "mm-1", "long_name": "dSS/dx at the published optimum (per mm), last r(k)"},
            ),
            "gradient_SY_SZ": (
                "member", grad_sz * 1e-3,
                {"units": "mm-1", "long_name": "d(SY + SZ)/dx at the published optimum (per mm)"},
            ),
            "published_diameter": (
                "member", published_mm,
                {"units": "mm", "long_name": "the published optimum (where our model is evaluated)"},
            ),
            "stress_inertia_only": (
                "member",
                inertia_only(cfg, d) / 1e6,
                {
                    "units": "MPa",
                    "long_name": (
                        "largest quasi-static stress per member under the inertia loads alone (no gravity, no external"
                        " load)"
                    ),
                },
            ),
            "inferred_load": (
                ("direction", "member"),
                loads["load"],
                {
                    "units": "N",
                    "long_name": (
                        "smallest tip force on the arm making the member's peak stress the allowable (our inference)"
                    ),
                    "nan_meaning": "no force up to the scan's maximum brings the member to the allowable",
                },
            ),
            "inferred_load_stress": (
                ("direction", "loaded", "member"),
                loads["stress"] / 1e6,
                {
                    "units": "MPa",
                    "long_name": "peak stress per member under the force that makes the loaded member active",
                },
            ),
            **claim_variables(claims),
        }
    )
    return xr.Dataset(
        data,
        coords={
            "case": ("case", np.array(list(cases), dtype=object), {"units": "1", "long_name": "model choice"}),
            "assembly": (
                "assembly", np.array([f"arm side {s:+d}, branch {b:+d}" for s, b in combos], dtype=object),
                {"units": "1", "long_name": "arm side and assembly branch"},
            ),
            "member": ("member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member"}),
            "solution": (
                "solution", np.array(solutions, dtype=object),
                {"units": "1", "long_name": "quasi-static K^-1 F, or Newmark over revolutions"},
            ),
            "crank_angle": ("crank_angle", theta, {"units": "deg", "long_name": "crank angle"}),
            "direction": (
                "direction", np.array(cfg["missing_load"]["directions_deg"], dtype=float),
                {"units": "deg", "long_name": "direction of the tip force, from +x counter-clockwise"},
            ),
            "loaded": (
                "loaded", np.array(MEMBERS, dtype=object),
                {"units": "1", "long_name": "member the tip force makes stress-active"},
            ),
            "response": (
                "response", np.array(RESPONSES, dtype=object),
                {"units": "1", "long_name": "response whose sensitivity is measured"},
            ),
        },
        attrs={
            "title": "Our model at the published optimum (comparison)",
            "r_last": r_last,
            "missing_load_max_N": float(cfg["missing_load"]["max_N"]),
            "missing_load_xtol_N": float(cfg["missing_load"]["xtol_N"]),
            "missing_load_scan_points": int(cfg["missing_load"]["scan_points"]),
            "elasticity_step": float(cfg["claims"]["elasticity_step"]),
        },
    )


def claim_variables(claims) -> dict[str, tuple]:
    """The claims' measures (claims.claim_measures) as Dataset variables: masses in g, displacements in m."""
    described = {
        "mass_initial": (1e3, "g", "mass of the four bars at the initial diameters"),
        "mass_published": (1e3, "g", "mass of the four bars at the published optimum"),
        "mass_ratio": (1.0, "1", "mass at the published optimum over the mass at the initial diameters"),
        "distortion_initial": (1.0, "m", "largest elastic tip displacement at the initial diameters"),
        "distortion_published": (1.0, "m", "largest elastic tip displacement at the published optimum"),
        "distortion_ratio": (
            1.0, "1", "largest tip displacement at the published optimum over that at the initial diameters",
        ),
        "stress_initial": (1e-6, "MPa", "peak stress at the initial diameters"),
    }
    out = {k: ((), claims[k] * f, {"units": u, "long_name": n}) for k, (f, u, n) in described.items()}
    if "elasticity" in claims:  # every member's (the uncertainty study's evaluations differentiate the governing ones)
        out["elasticity"] = (("response", "member"), claims["elasticity"],
                             {"units": "1", "long_name": "d ln(response) / d ln(diameter) at the published optimum"})
    out["governing_elasticity"] = (
        "response", claims["governing_elasticity"],
        {"units": "1", "long_name": "smaller |elasticity| of the arm and the coupler, per response"},
    )
    return out
