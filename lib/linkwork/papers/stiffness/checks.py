"""Physical checks of the stiffness section before any job runs (messages name the key and the value)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...engines.kinematics import CHANGE_POINT_MARGIN, change_point_distance, four_bar
from ...pipeline.errors import ConfigError
from ...units import angle_grid_deg, divides_turn
from .adapter import four_bar as linkage_from_config

#: The result variables a published-numbers file's measures may name: what the comparison reads from
#: results/stiffness/stiffness.nc (tests/test_workflow.py checks that the study writes each; a new one is added here).
RESULT_VARIABLES = frozenset({"K_c", "K_h", "beta", "gamma"})


def check(section: Mapping[str, Any], key: str = "stiffness") -> None:
    """The forms the findings compare are computed; the grids divide a turn; the linkage assembles on both grids."""
    for needed in ("equilibrium", "tables"):  # the findings compare the defensible form with the paper's own
        if needed not in section["forms"]:
            raise ConfigError(
                f"config key {key}.forms: value {section['forms']!r} lacks {needed!r} (the comparison needs the"
                " statics-consistent form and the paper's tables)"
            )
    linkage = section["linkage"]
    try:
        lw = linkage_from_config(linkage, section["numerics"]["assembly_tol"])
    except ValueError as exc:
        raise ConfigError(f"config key {key}.linkage: {exc}") from None
    values = ", ".join(f"{k}={linkage[k]!r}" for k in ("crank_m", "coupler_m", "rocker_m", "ground_m"))
    if change_point_distance(lw.lengths) < CHANGE_POINT_MARGIN:
        raise ConfigError(
            f"config key {key}.linkage ({values}): within {CHANGE_POINT_MARGIN:.1%} of a change-point linkage (s + l ="
            " p + q): it passes a singular configuration every turn, where the energy method's stiffness is undefined"
        )
    for grid_key in ("paper_step_deg", "fine_step_deg"):
        step = section["grids"][grid_key]
        if not divides_turn(step):
            raise ConfigError(f"config key {key}.grids.{grid_key}: value {step!r} does not divide 360 deg")
        try:
            four_bar(lw, np.radians(angle_grid_deg(step)))
        except ValueError as exc:
            raise ConfigError(f"config key {key}.linkage ({values}): {exc}") from None
