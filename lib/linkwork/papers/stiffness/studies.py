"""The stiffness paper's studies: K_h, K_c, beta, gamma on two crank-angle grids for every model form,
with the analysis the report states (moment continuity at B, axial shares, how far from constant)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...units import angle_grid_deg
from .adapter import linkage_and_sections
from .model import (
    axial_share,
    equivalent_stiffness,
    moment_jump_at_b,
    paper_angles,
    unit_force_internal_forces,
    unit_moment_internal_forces,
)

FORM_DESCRIPTIONS = {
    "equilibrium": "internal forces from statics (moment continuous at the joints)",
    "tables": "internal forces as printed in Tables 1-2 (sign of the l1 term in AB flipped)",
    "printed": "eqs. (8) and (14) letter for letter (eq. 14 with E2 I2 in its l3^3 term)",
}
LOAD_CASES = ("unit force", "unit moment")
#: The forms defined by internal forces (the printed equations have none).
FORCE_FORMS = ("equilibrium", "tables")
STATISTICS = {
    "min": ("minimum over a turn", None),
    "argmin": ("crank angle of the minimum", "deg"),
    "max": ("maximum over a turn", None),
    "argmax": ("crank angle of the maximum", "deg"),
    "mean": ("mean over a turn", None),
    "spread": ("(max - min) / mean", "1"),
    "cv": ("coefficient of variation std / mean", "1"),
    "max_over_min": ("max / min", "1"),
}


def _grid_variables(cfg: Mapping[str, Any], step_deg: float, suffix: str) -> dict[str, Any]:
    linkage, members = linkage_and_sections(cfg)
    alpha_deg = angle_grid_deg(step_deg)
    dim = "crank_angle" + suffix
    curves = [equivalent_stiffness(linkage, members, np.radians(alpha_deg), form) for form in cfg["forms"]]
    first = curves[0]
    coord = xr.DataArray(alpha_deg, dims=dim, attrs={"units": "deg", "long_name": f"crank angle alpha ({step_deg:g} deg grid)"})
    return {
        "coords": {dim: coord},
        "beta" + suffix: xr.DataArray(np.degrees(first.beta), dims=dim, attrs={"units": "deg", "long_name": "rocker angle beta = 180 deg - direction of O'B"}),
        "gamma" + suffix: xr.DataArray(np.degrees(first.gamma), dims=dim, attrs={"units": "deg", "long_name": "coupler angle gamma = direction of AB"}),
        "K_h" + suffix: xr.DataArray(np.stack([c.linear for c in curves]), dims=("form", dim), attrs={"units": "N m-1", "long_name": "equivalent linear stiffness K_h = 1/x_O'"}),
        "K_c" + suffix: xr.DataArray(np.stack([c.rotational for c in curves]), dims=("form", dim), attrs={"units": "N m rad-1", "long_name": "equivalent rotational stiffness K_c = 1/phi_O'"}),
    }


def _load_case_forces(cfg: Mapping[str, Any], form: str, alpha: np.ndarray):
    linkage, _ = linkage_and_sections(cfg)
    a, b, g = paper_angles(linkage, alpha)
    l1, _, _, l4 = linkage.lengths
    return {"unit force": unit_force_internal_forces(l1, a, b, g, form), "unit moment": unit_moment_internal_forces(l1, l4, a, b, g, form)}


def continuity_and_axial(cfg: Mapping[str, Any]) -> dict[str, xr.DataArray]:
    """Moment jump at the rigid joint B and the axial share of the compliance, per force-defined form and load case (fine grid)."""
    linkage, members = linkage_and_sections(cfg)
    l1, l2, l3, _ = linkage.lengths
    alpha = np.radians(angle_grid_deg(cfg["grids"]["fine_step_deg"]))
    forms = [f for f in FORCE_FORMS if f in cfg["forms"]]
    jump, moment_b, share = (np.empty((len(forms), len(LOAD_CASES))) for _ in range(3))
    for i, form in enumerate(forms):
        cases = _load_case_forces(cfg, form, alpha)
        for j, case in enumerate(LOAD_CASES):
            forces = cases[case]
            jump[i, j] = moment_jump_at_b(l2, l3, forces).max()
            moment_b[i, j] = np.abs(forces[2].m0 + forces[2].m1 * l3).max()
            share[i, j] = axial_share((l1, l2, l3), members, forces).max()
    dims = ("force_form", "load_case")
    unit = "N m per unit load (N for the force case, N m for the moment case)"
    return {
        "coords": {
            "force_form": ("force_form", np.array(forms, dtype=object), {"units": "1", "long_name": "model form defined by internal forces"}),
            "load_case": ("load_case", np.array(LOAD_CASES, dtype=object), {"units": "1", "long_name": "unit load at O'"}),
        },
        "moment_jump_B": (dims, jump, {"units": unit, "long_name": "largest jump of |M| at the rigid joint B over a turn (fine grid)"}),
        "moment_BO_at_B": (dims, moment_b, {"units": unit, "long_name": "largest |M| in BO' at B over a turn (fine grid)"}),
        "axial_share_max": (dims, share, {"units": "1", "long_name": "largest axial share of the unit-load displacement over a turn (fine grid)"}),
    }


def variation(ds: xr.Dataset) -> dict[str, Any]:
    """How far from constant K_h and K_c are over a turn, per form (fine grid)."""
    out: dict[str, Any] = {}
    for var in ("K_h", "K_c"):
        v = ds[var + "_fine"]
        unit = v.attrs["units"]
        angle = ds.crank_angle_fine
        values = {
            "min": v.min("crank_angle_fine"), "argmin": angle[v.argmin("crank_angle_fine")].drop_vars("crank_angle_fine"),
            "max": v.max("crank_angle_fine"), "argmax": angle[v.argmax("crank_angle_fine")].drop_vars("crank_angle_fine"),
            "mean": v.mean("crank_angle_fine"),
        }
        values["spread"] = (values["max"] - values["min"]) / values["mean"]
        values["cv"] = v.std("crank_angle_fine") / values["mean"]
        values["max_over_min"] = values["max"] / values["min"]
        for stat, (text, stat_unit) in STATISTICS.items():
            out[f"{var}_{stat}_fine"] = xr.DataArray(np.asarray(values[stat].values, dtype=float), dims="form",
                                                     attrs={"units": stat_unit or unit, "long_name": f"{var} {text} (fine grid)"})
    return out


def stiffness(cfg: Mapping[str, Any]) -> xr.Dataset:
    """K_h, K_c, beta, gamma on the paper's and the fine grid for every form, with their analysis."""
    paper = _grid_variables(cfg, cfg["grids"]["paper_step_deg"], "")
    fine = _grid_variables(cfg, cfg["grids"]["fine_step_deg"], "_fine")
    forms = list(cfg["forms"])
    analysis = continuity_and_axial(cfg)
    coords = {
        **paper.pop("coords"), **fine.pop("coords"), **analysis.pop("coords"),
        "form": xr.DataArray(np.array(forms, dtype=object), dims="form",
                             attrs={"units": "1", "long_name": "; ".join(f"{f}: {FORM_DESCRIPTIONS[f]}" for f in forms)}),
    }
    ds = xr.Dataset({**paper, **fine, **analysis}, coords=coords)
    ds = ds.assign(variation(ds))
    ds.attrs.update(title="Equivalent stiffness of the needle crank-rocker (energy method)", assembly_tol=cfg["numerics"]["assembly_tol"])
    return ds
