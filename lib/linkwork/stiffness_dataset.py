"""The stiffness paper's result Dataset: angles and K_h, K_c on two crank-angle grids."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from . import from_config
from .stiffness import equivalent_stiffness

FORM_DESCRIPTIONS = {
    "equilibrium": "internal forces from statics (moment continuous at the joints)",
    "tables": "internal forces as printed in Tables 1-2 (sign of the l1 term in AB flipped)",
    "printed": "eqs. (8) and (14) letter for letter (eq. 14 with E2 I2 in its l3^3 term)",
}


def _grid_variables(section: Mapping[str, Any], step_deg: float, suffix: str) -> dict[str, Any]:
    linkage = from_config.four_bar(section["linkage"], section["numerics"]["assembly_tol"])
    members = from_config.sections(section["members"])
    alpha_deg = from_config.angle_grid_deg(step_deg)
    dim = "crank_angle" + suffix
    forms = list(section["forms"])
    curves = [equivalent_stiffness(linkage, members, np.radians(alpha_deg), form) for form in forms]
    first = curves[0]
    coord = xr.DataArray(alpha_deg, dims=dim, attrs={"units": "deg", "long_name": f"crank angle alpha ({step_deg:g} deg grid)"})
    return {
        "coords": {dim: coord},
        "beta" + suffix: xr.DataArray(
            np.degrees(first.beta), dims=dim, attrs={"units": "deg", "long_name": "rocker angle beta = 180 deg - direction of O'B"}
        ),
        "gamma" + suffix: xr.DataArray(
            np.degrees(first.gamma), dims=dim, attrs={"units": "deg", "long_name": "coupler angle gamma = direction of AB"}
        ),
        "K_h" + suffix: xr.DataArray(
            np.stack([c.linear for c in curves]),
            dims=("form", dim),
            attrs={"units": "N m-1", "long_name": "equivalent linear stiffness K_h = 1/x_O'"},
        ),
        "K_c" + suffix: xr.DataArray(
            np.stack([c.rotational for c in curves]),
            dims=("form", dim),
            attrs={"units": "N m rad-1", "long_name": "equivalent rotational stiffness K_c = 1/phi_O'"},
        ),
    }


def build_dataset(section: Mapping[str, Any]) -> xr.Dataset:
    """K_h, K_c, beta, gamma on the paper's grid and on the fine grid, for every form."""
    paper = _grid_variables(section, section["grids"]["paper_step_deg"], "")
    fine = _grid_variables(section, section["grids"]["fine_step_deg"], "_fine")
    forms = list(section["forms"])
    coords = {
        **paper.pop("coords"),
        **fine.pop("coords"),
        "form": xr.DataArray(
            np.array(forms, dtype=object),
            dims="form",
            attrs={"units": "1", "long_name": "; ".join(f"{f}: {FORM_DESCRIPTIONS[f]}" for f in forms)},
        ),
    }
    return xr.Dataset({**paper, **fine}, coords=coords)
