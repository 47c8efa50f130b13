"""Config adapter of the stiffness paper: the linkage and member sections from config (SI units,
degrees converted at this boundary)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...engines.kinematics import DEFAULT_ASSEMBLY_TOL, FourBar
from .model import MEMBERS, Section


def four_bar(linkage: Mapping[str, Any], assembly_tol: float = DEFAULT_ASSEMBLY_TOL) -> FourBar:
    """FourBar from a ``linkage`` section (crank_m, coupler_m, rocker_m, ground_m, branch; m)."""
    return FourBar(
        crank=float(linkage["crank_m"]),
        coupler=float(linkage["coupler_m"]),
        rocker=float(linkage["rocker_m"]),
        ground=float(linkage["ground_m"]),
        branch=int(linkage["branch"]),
        ground_angle=float(np.radians(linkage.get("ground_angle_deg", 0.0))),
        assembly_tol=assembly_tol,
    )


def sections(members: Mapping[str, Any]) -> tuple[Section, Section, Section]:
    """(OA, AB, BO') sections from a ``members`` section (Pa, m^2, m^4)."""
    return tuple(  # type: ignore[return-value]
        Section(
            youngs_modulus=float(members[key]["youngs_modulus_Pa"]),
            area=float(members[key]["area_m2"]),
            second_moment=float(members[key]["second_moment_m4"]),
        )
        for key in MEMBERS
    )


def linkage_and_sections(cfg: Mapping[str, Any]) -> tuple[FourBar, tuple[Section, Section, Section]]:
    """The frozen linkage and its member sections from a stiffness config."""
    return four_bar(cfg["linkage"], cfg["numerics"]["assembly_tol"]), sections(cfg["members"])
