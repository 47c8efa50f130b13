"""Library objects built from (already validated) config sections.

Config files hold lengths in m and angles in degrees; this is the boundary
where degrees become radians.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .beatup import FourBarBeatup, SixBar
from .kinematics import DEFAULT_ASSEMBLY_TOL, FourBar
from .stiffness import Section

STIFFNESS_MEMBER_KEYS = ("OA", "AB", "BO")


def four_bar(linkage: Mapping[str, Any], assembly_tol: float = DEFAULT_ASSEMBLY_TOL) -> FourBar:
    """FourBar from a ``linkage`` section (crank_m, coupler_m, rocker_m, ground_m, branch)."""
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
    """(OA, AB, BO') sections from a ``members`` section."""
    return tuple(  # type: ignore[return-value]
        Section(
            youngs_modulus=float(members[key]["youngs_modulus_Pa"]),
            area=float(members[key]["area_m2"]),
            second_moment=float(members[key]["second_moment_m4"]),
        )
        for key in STIFFNESS_MEMBER_KEYS
    )


def angle_grid_deg(step_deg: float) -> NDArray[np.float64]:
    """Crank angles 0, step, ... < 360 (deg); the step must divide 360."""
    n = int(round(360.0 / step_deg))
    return np.arange(n) * (360.0 / n)


def six_bar(section: Mapping[str, Any], crank_m: float | None = None) -> SixBar:
    """SixBar from a ``beatup.sixbar`` section (lengths in m, angles in deg); optionally another crank (m)."""
    lengths = [float(section[f"l{i}_m"]) for i in range(1, 8)]
    if crank_m is not None:
        lengths[0] = float(crank_m)
    return SixBar(
        *lengths,
        theta4=float(np.radians(section["theta4_deg"])),
        theta7=float(np.radians(section["theta7_deg"])),
        branch_rocker=int(section["branch_rocker"]),
        branch_sley=int(section["branch_sley"]),
    )


def labelled(entry: Mapping[str, Any]) -> float:
    """The value of a labelled config entry ``{value, status, reason}``."""
    return float(entry["value"])


def four_bar_beatup(section: Mapping[str, Any], arm_to_crank: float | None = None) -> FourBarBeatup:
    """FourBarBeatup from a ``beatup.fourbar`` section of labelled entries; optionally another L/R."""
    ratio = labelled(section["arm_to_crank"]) if arm_to_crank is None else float(arm_to_crank)
    crank = labelled(section["crank_m"])
    return FourBarBeatup(
        crank=crank,
        arm=ratio * crank,
        sword_radius=labelled(section["sword_radius_m"]),
        offset=labelled(section["offset_m"]),
    )
