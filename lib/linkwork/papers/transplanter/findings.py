"""The transplanter paper's comparison and findings: our optimum and our model at the published optimum
beside the printed numbers, and our own finding (the paper makes no such claim) whether the quasi-statically
optimal design is safe dynamically."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ...pipeline.compare import classify, compare_datasets, count_text, counts_dataset, findings_attrs, lead_word, scalar


def numerical_errors(optim: xr.Dataset, at_published: xr.Dataset, accuracy: xr.Dataset) -> dict[str, tuple[float, str]]:
    """Our numerical error bar of each compared number: the optimiser's for the diameters; for the response at
    the published optimum the mesh error (accuracy study, the pipeline's element on the base mesh) plus the
    crank-angle sampling error, estimated as (value on the coarse grid - value on the pipeline grid) / 100
    (a sampled smooth maximum converges with the square of the step, and the coarse step is 10 times the fine)."""
    element = str(accuracy.wp_setting.values[np.flatnonzero(accuracy.wp_pipeline.values)[0]]).split()[0]
    mesh_stress = float(accuracy.stress_error.sel(element=element, refinement=1))
    mesh_tip = float(accuracy.tip_error.sel(element=element, refinement=1))
    base = at_published.sel(case="baseline")
    coarse = at_published.sel(case=[c for c in at_published.case.values if "crank sampling" in str(c)][0])
    out = {f"d{i + 1}": (float(optim.sumt_slsqp_difference), "SUMT against SLSQP on the same objective") for i in range(4)}
    for key, mesh in (("Ux", mesh_tip), ("Uy", mesh_tip), ("distortion", mesh_tip), ("stress_max", mesh_stress)):
        value = float(base[key])
        out[key] = (mesh * abs(value) + abs(float(coarse[key]) - value) / 100, "mesh error (accuracy study) + crank-angle sampling error")
    return out


def compare(cfg: Mapping[str, Any], published: Mapping[str, Any], optim: xr.Dataset, at_published: xr.Dataset, ked: xr.Dataset,
            accuracy: xr.Dataset, uncertainty: xr.Dataset) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table and findings (dynamic peak stress at our optimum against the allowable)."""
    table = compare_datasets(published, [optim, at_published], errors={"": numerical_errors(optim, at_published, accuracy)}, uncertainty=uncertainty)
    table = label_compared_solution(table, at_published)
    allowable = float(optim.allowable)
    dynamic = float(ked.peak_stress.sel(diameters="optimal", solution="dynamic"))
    quasi = float(ked.peak_stress.sel(diameters="optimal", solution="quasi-static"))
    claim = dynamic_finding(ked, accuracy, dynamic, allowable)
    findings = xr.Dataset(
        {
            "allowable": scalar(allowable, "MPa", "allowable stress"),
            "optimum_quasi_static_peak": scalar(quasi, "MPa", "largest quasi-static stress at our optimum"),
            "optimum_dynamic_peak": scalar(dynamic, "MPa", "largest dynamic (Newmark) stress at our optimum"),
            "optimum_dynamic_excess": scalar(dynamic / allowable - 1.0, "1", "dynamic peak at our optimum over the allowable, minus 1"),
            "optimum_dynamic_error": scalar(claim["error"], "MPa", "numerical error bar of the dynamic peak at our optimum (Newmark step + periodicity + mesh)"),
            "optimum_dynamic_low": scalar(claim["low"], "MPa", "lowest dynamic peak at our optimum over the damping range"),
            "optimum_dynamic_high": scalar(claim["high"], "MPa", "highest dynamic peak at our optimum over the damping range"),
            "damping_threshold": scalar(float(ked.damping_threshold), "1", "damping ratio at which the dynamic peak equals the allowable"),
            **active_bounds(cfg, optim, at_published),
        },
        coords={"member": optim.member},
    ).merge(counts_dataset(table))
    findings.damping_threshold.attrs["nan_meaning"] = "no damping ratio in the assumed range brings the peak to the allowable"
    findings.attrs["optimum_dynamic_finding"] = claim["status"]
    findings.attrs.update(findings_attrs("Transplanter paper: comparison findings", "", "", answer(table, findings, optim, at_published)))
    return table, findings


def label_compared_solution(table: pd.DataFrame, at_published: xr.Dataset) -> pd.DataFrame:
    """The paper calls its printed stress 'dynamic' (stress under the inertia loads); our number in that row is the
    compared solution (config fe.compared_solution, quasi-static or the time-integrated dynamic one): say which."""
    solution = json.loads(at_published.attrs["config_json"])["fe"]["compared_solution"]["value"]
    out = table.copy()
    row = out.id == "stress_max"
    out.loc[row, "quantity"] = out.loc[row, "quantity"].str.rstrip(")") + f"; ours: the {solution} solution)"
    return out


#: Our finding on the dynamic safety of our optimum, in words, by the class it would have as a one-sided number
#: (dynamic peak >= the allowable). Not a verdict: the paper makes no claim about it.
DYNAMIC_STATUS = {
    "matches": "unsafe at every damping ratio in the assumed range",
    "deviates": "safe at every damping ratio in the assumed range",
    "depends on assumptions": "the damping ratio decides",
    "undetermined (numerics)": "our numerical error decides",
}


def dynamic_finding(ked: xr.Dataset, accuracy: xr.Dataset, dynamic: float, allowable: float) -> dict[str, Any]:
    """Our finding "the quasi-statically optimal design exceeds the allowable stress dynamically" (the paper does not
    claim it), judged like a one-sided number (>= the allowable): the nominal dynamic peak, its numerical error bar
    (the Newmark step's field-error bound at the pipeline's step, the periodicity left after the revolutions, the mesh
    error of the peak stress from the accuracy study) and its range over the damping ratio's assumed range. The
    status is one of DYNAMIC_STATUS's values (unsafe at every damping, safe at every damping, the damping decides
    (ked.damping_threshold names the ratio), the numerical error decides)."""
    element = str(accuracy.wp_setting.values[np.flatnonzero(accuracy.wp_pipeline.values)[0]]).split()[0]
    mesh = float(accuracy.stress_error.sel(element=element, refinement=1))
    periodicity = float(ked.periodicity.sel(diameters="optimal"))
    error = (float(ked.newmark_pipeline_error) + periodicity + mesh) * dynamic
    low, high = float(ked.damping_peak.min()), float(ked.damping_peak.max())
    status = DYNAMIC_STATUS[classify(allowable, 0.0, "ge", dynamic, error, low, high)]
    return {"status": status, "error": error, "low": low, "high": high}


#: A constraint is active at a point when it is met within this fraction of its bound (diameters: of the
#: minimum diameter; stresses: of the allowable).
ACTIVE_RTOL = 0.01
#: The published point is stationary in our model when no |dSS/dx| exceeds this (per mm).
STATIONARY_PER_MM = 0.01


def active_bounds(cfg: Mapping[str, Any], optim: xr.Dataset, at_published: xr.Dataset) -> dict[str, tuple]:
    """Which bound holds each member at our optimum (minimum diameter, allowable stress), each member's stress at
    the published point over the allowable, and whether dSS/dx vanishes there (stationary) or is positive throughout."""
    d_min = float(cfg["minimum_diameter_m"]) * 1e3
    allowable = float(optim.allowable)
    grad = at_published.gradient_SS.values
    return {
        "at_minimum_diameter": ("member", (optim.d_opt.values - d_min <= ACTIVE_RTOL * d_min).astype(int),
                                {"units": "1", "long_name": f"1 if our optimal diameter is within {ACTIVE_RTOL:.0%} of the minimum"}),
        "at_allowable": ("member", (optim.stress_opt.values >= (1 - ACTIVE_RTOL) * allowable).astype(int),
                         {"units": "1", "long_name": f"1 if the member's stress at our optimum is within {ACTIVE_RTOL:.0%} of the allowable"}),
        "published_stress_fraction": ("member", at_published.stress_members.values / allowable,
                                      {"units": "1", "long_name": "member stress at the published optimum over the allowable"}),
        "published_point_stationary": scalar(bool(np.all(np.abs(grad) <= STATIONARY_PER_MM)), "1", f"1 if every |dSS/dx| at the published optimum is at most {STATIONARY_PER_MM:g} per mm"),
        "published_gradient_all_positive": scalar(bool(np.all(grad > 0)), "1", "1 if dSS/dx > 0 in every diameter at the published optimum"),
    }


def dynamic_clause(findings: xr.Dataset) -> str:
    """How our dynamic finding stands over the damping range, in words."""
    lo, hi, allowable = float(findings.optimum_dynamic_low), float(findings.optimum_dynamic_high), float(findings.allowable)
    span = f"{lo / allowable - 1:+.0%} to {hi / allowable - 1:+.0%} over the damping range"
    status = findings.attrs["optimum_dynamic_finding"]
    threshold = float(findings.damping_threshold)
    if np.isfinite(threshold):
        return f" ({span}: {status}, the threshold is a damping ratio of {threshold:.3f})."
    return f" ({span}: {status})."


def answer(table: pd.DataFrame, findings: xr.Dataset, optim: xr.Dataset, at_published: xr.Dataset) -> str:
    """Does the paper hold up? One sentence from the comparison."""
    rows = table.set_index("id")
    response = [q for q in ("Uy", "distortion", "stress_max") if rows.loc[q, "verdict"] == "depends on assumptions"]
    deciders = sorted({n.strip() for d in rows.loc[response, "decided_by"] for n in d.split("(largest alone: ")[-1].rstrip(")").split(",")}) if response else []
    gradient = ", ".join(f"{v:+.2f}" for v in at_published.gradient_SS.values)
    diameters = table[table.id.isin(["d1", "d2", "d3", "d4"])]
    response = table[table.id.isin(["Ux", "Uy", "distortion", "stress_max"])]
    reproduced = bool((diameters.verdict == "matches").all())
    excess = float(findings.optimum_dynamic_excess)
    ss = table[table.id == "SS"].verdict
    return (
        f"{lead_word(table[table.role == 'headline'])} Our model at the published optimum: {count_text(response, '')}"
        + (f" (the verdict turns on {', '.join(deciders)})" if deciders else "")
        + (". The optimum itself is reproduced" if reproduced else
           f". The optimum itself is not reproduced: ours is ({', '.join(f'{v:.2f}' for v in optim.d_opt.values)}) mm")
        + (", and the published point is stationary in our model" if bool(findings.published_point_stationary) else
           f", and the published point is not stationary in our model (dSS/dx = {gradient} per mm)")
        + (". SS cannot be checked ([x_S1] and r(k) are not printed)" if (ss == "not reproducible").all() else "")
        + ". Our own finding, not a claim of the paper: "
        + (f"our quasi-statically optimal design exceeds the allowable stress in the dynamic solution by {excess:.0%}" if excess > 0 else
           f"our quasi-statically optimal design stays below the allowable stress in the dynamic solution ({excess:+.0%})")
        + dynamic_clause(findings)
    )
