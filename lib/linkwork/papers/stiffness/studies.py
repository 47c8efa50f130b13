"""The stiffness paper's studies: K_h, K_c, beta, gamma on two crank-angle grids for every model form,
with the analysis the report states (moment continuity at B, axial shares, how far from constant, the
pinned mechanism's output stiffness, the printed sections' size).

One grid for every quoted number: every extreme, mean and largest value is taken over the paper's frames
(``grids.paper_step_deg``, 36 frames), the grid the published numbers are read on; the fine grid only
draws the curves."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...units import angle_grid_deg
from .adapter import linkage_and_sections
from .model import (
    MEMBERS,
    MOBILITY_CASES,
    PINNED_PARTS,
    axial_share,
    equivalent_stiffness,
    moment_jump_at_b,
    paper_angles,
    pinned_output_compliance,
    planar_mobility,
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
    coord = xr.DataArray(
        alpha_deg, dims=dim, attrs={"units": "deg", "long_name": f"crank angle alpha ({step_deg:g} deg grid)"}
    )
    return {
        "coords": {dim: coord},
        "beta" + suffix: xr.DataArray(
            np.degrees(first.beta), dims=dim,
            attrs={"units": "deg", "long_name": "rocker angle beta = 180 deg - direction of O'B"},
        ),
        "gamma" + suffix: xr.DataArray(
            np.degrees(first.gamma), dims=dim,
            attrs={"units": "deg", "long_name": "coupler angle gamma = direction of AB"},
        ),
        "K_h" + suffix: xr.DataArray(
            np.stack([c.linear for c in curves]), dims=("form", dim),
            attrs={"units": "N m-1", "long_name": "equivalent linear stiffness K_h = 1/x_O'"},
        ),
        "K_c" + suffix: xr.DataArray(
            np.stack([c.rotational for c in curves]), dims=("form", dim),
            attrs={"units": "N m rad-1", "long_name": "equivalent rotational stiffness K_c = 1/phi_O'"},
        ),
    }


def _load_case_forces(cfg: Mapping[str, Any], form: str, alpha: np.ndarray):
    linkage, _ = linkage_and_sections(cfg)
    a, b, g = paper_angles(linkage, alpha)
    l1, _, _, l4 = linkage.lengths
    return {
        "unit force": unit_force_internal_forces(l1, a, b, g, form),
        "unit moment": unit_moment_internal_forces(l1, l4, a, b, g, form),
    }


def continuity_and_axial(cfg: Mapping[str, Any]) -> dict[str, xr.DataArray]:
    """Moment jump at the rigid joint B and the axial share of the compliance, per force-defined form and load
    case, largest over the paper's frames."""
    linkage, members = linkage_and_sections(cfg)
    l1, l2, l3, _ = linkage.lengths
    alpha = np.radians(angle_grid_deg(cfg["grids"]["paper_step_deg"]))
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
            "force_form": (
                "force_form", np.array(forms, dtype=object),
                {"units": "1", "long_name": "model form defined by internal forces"},
            ),
            "load_case": (
                "load_case", np.array(LOAD_CASES, dtype=object), {"units": "1", "long_name": "unit load at O'"},
            ),
        },
        "moment_jump_B": (
            dims, jump,
            {"units": unit, "long_name": "largest jump of |M| at the rigid joint B over the paper's frames"},
        ),
        "moment_BO_at_B": (
            dims, moment_b, {"units": unit, "long_name": "largest |M| in BO' at B over the paper's frames"},
        ),
        "axial_share_max": (
            dims, share,
            {"units": "1", "long_name": "largest axial share of the unit-load displacement over the paper's frames"},
        ),
    }


def _statistics(v: xr.DataArray, angle: xr.DataArray, dim: str) -> dict[str, xr.DataArray]:
    values = {
        "min": v.min(dim), "argmin": angle[v.argmin(dim)].drop_vars(dim),
        "max": v.max(dim), "argmax": angle[v.argmax(dim)].drop_vars(dim),
        "mean": v.mean(dim),
    }
    values["spread"] = (values["max"] - values["min"]) / values["mean"]
    values["cv"] = v.std(dim) / values["mean"]
    values["max_over_min"] = values["max"] / values["min"]
    return values


def variation(ds: xr.Dataset) -> dict[str, Any]:
    """How far from constant K_h and K_c are over a turn, per form, over the paper's frames (the grid of every
    quoted extreme)."""
    out: dict[str, Any] = {}
    for var in ("K_h", "K_c"):
        v = ds[var]
        values = _statistics(v, ds.crank_angle, "crank_angle")
        for stat, (text, stat_unit) in STATISTICS.items():
            out[f"{var}_{stat}"] = xr.DataArray(
                np.asarray(values[stat].values, dtype=float), dims="form",
                attrs={"units": stat_unit or v.attrs["units"], "long_name": f"{var} {text} (over the paper's frames)"},
            )
    return out


def pinned(cfg: Mapping[str, Any], ds: xr.Dataset) -> dict[str, Any]:
    """The real, pinned mechanism beside the paper's rigid frame: the rocker's rotational stiffness at O' with
    the crank held (pins at A and B, O' pivoted on the frame), on both grids, its parts and statistics over the
    paper's frames, its ratio to K_c per form, and the mobilities that say why K_h has no pinned counterpart."""
    linkage, members = linkage_and_sections(cfg)
    parts = pinned_output_compliance(linkage, members, np.radians(ds.crank_angle.values))
    fine = pinned_output_compliance(linkage, members, np.radians(ds.crank_angle_fine.values)).sum(axis=-1)
    name = "rotational stiffness of the rocker at O', pinned mechanism, crank held"
    k = xr.DataArray(1.0 / parts.sum(axis=-1), dims="crank_angle", attrs={"units": "N m rad-1", "long_name": name})
    out: dict[str, Any] = {
        "K_pinned": k,
        "K_pinned_fine": xr.DataArray(
            1.0 / fine, dims="crank_angle_fine", attrs={"units": "N m rad-1", "long_name": name}
        ),
        "pinned_share_max": xr.DataArray(
            (parts / parts.sum(axis=-1, keepdims=True)).max(axis=0),
            dims="pinned_part",
            attrs={
                "units": "1",
                "long_name": "largest share of each part in the pinned output's compliance over the paper's frames",
            },
        ),
        "pinned_share_min": xr.DataArray(
            (parts / parts.sum(axis=-1, keepdims=True)).min(axis=0),
            dims="pinned_part",
            attrs={
                "units": "1",
                "long_name": "smallest share of each part in the pinned output's compliance over the paper's frames",
            },
        ),
    }
    values = _statistics(k, ds.crank_angle, "crank_angle")
    for stat, (text, stat_unit) in STATISTICS.items():
        out[f"K_pinned_{stat}"] = xr.DataArray(
            float(values[stat]),
            attrs={
                "units": stat_unit or "N m rad-1",
                "long_name": f"pinned output stiffness {text} (over the paper's frames)",
            },
        )
    ratio = k / ds.K_c
    out["K_pinned_over_K_c_min"] = xr.DataArray(
        ratio.min("crank_angle").values, dims="form",
        attrs={"units": "1", "long_name": "smallest K_pinned / K_c over the paper's frames"},
    )
    out["K_pinned_over_K_c_max"] = xr.DataArray(
        ratio.max("crank_angle").values, dims="form",
        attrs={"units": "1", "long_name": "largest K_pinned / K_c over the paper's frames"},
    )
    out["mobility"] = xr.DataArray(
        np.array([planar_mobility(*c) for c in MOBILITY_CASES.values()]), dims="mobility_case",
        attrs={"units": "1", "long_name": "Grübler mobility 3 (bodies - 1) - 2 pins"},
    )
    return out


def sections_size(cfg: Mapping[str, Any]) -> dict[str, Any]:
    """The printed sections beside the links: each area's square side against the member's length."""
    linkage, members = linkage_and_sections(cfg)
    lengths = np.array(linkage.lengths[:3])
    area = np.array([m.area for m in members])
    side = np.sqrt(area)
    return {
        "member_length": xr.DataArray(lengths, dims="member", attrs={"units": "m", "long_name": "member length"}),
        "section_area": xr.DataArray(
            area, dims="member", attrs={"units": "m2", "long_name": "printed cross-section area"}
        ),
        "section_side": xr.DataArray(
            side, dims="member", attrs={"units": "m", "long_name": "side of a square of the printed area"}
        ),
        "section_side_over_length": xr.DataArray(
            side / lengths, dims="member",
            attrs={"units": "1", "long_name": "square side of the printed area over the member's length"},
        ),
        "youngs_modulus": xr.DataArray(
            np.array([m.youngs_modulus for m in members]), dims="member",
            attrs={"units": "Pa", "long_name": "Young's modulus as printed"},
        ),
    }


def stiffness(cfg: Mapping[str, Any]) -> xr.Dataset:
    """K_h, K_c, beta, gamma on the paper's and the fine grid for every form, with their analysis."""
    paper = _grid_variables(cfg, cfg["grids"]["paper_step_deg"], "")
    fine = _grid_variables(cfg, cfg["grids"]["fine_step_deg"], "_fine")
    forms = list(cfg["forms"])
    analysis = continuity_and_axial(cfg)
    coords = {
        **paper.pop("coords"),
        **fine.pop("coords"),
        **analysis.pop("coords"),
        "form": xr.DataArray(
            np.array(forms, dtype=object), dims="form",
            attrs={"units": "1", "long_name": "; ".join(f"{f}: {FORM_DESCRIPTIONS[f]}" for f in forms)},
        ),
    }
    coords["pinned_part"] = (
        "pinned_part", np.array(PINNED_PARTS, dtype=object),
        {"units": "1", "long_name": "part of the pinned output's compliance"},
    )
    coords["mobility_case"] = (
        "mobility_case", np.array(list(MOBILITY_CASES), dtype=object),
        {"units": "1", "long_name": "mechanism (bodies counted with the frame)"},
    )
    coords["member"] = (
        "member", np.array(MEMBERS, dtype=object), {"units": "1", "long_name": "member (BO: the rocker BO')"},
    )
    ds = xr.Dataset({**paper, **fine, **analysis}, coords=coords)
    ds = ds.assign(variation(ds))
    ds = ds.assign(pinned(cfg, ds))
    ds = ds.assign(sections_size(cfg))
    frames = ds.sizes["crank_angle"]
    ds.attrs.update(
        title="Equivalent stiffness of the needle crank-rocker (energy method)",
        assembly_tol=cfg["numerics"]["assembly_tol"],
        extremes_grid=(
            f"the paper's {frames} frames ({cfg['grids']['paper_step_deg']:g} deg grid); the"
            f" {cfg['grids']['fine_step_deg']:g} deg grid only draws curves"
        ),
        frames=frames,
    )
    return ds
