"""Physical checks of the beat-up section before any job runs (messages name the key and the value)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...configformat import labelled
from ...pipeline.errors import ConfigError
from ...units import angle_grid_deg, divides_turn
from .adapter import four_bar_beatup, six_bar
from .model import sley_motion

#: The result variables a published-numbers file's measures may name: what the comparison reads from
#: results/beatup/sixbar.nc and window.nc (tests/test_workflow.py checks that the study writes each; a new one is added
#: here).
RESULT_VARIABLES = frozenset(
    {
        "accel_peak",
        "front_dead_centre",
        "rate_peak_1",
        "rate_peak_2",
        "span_front_to_back",
        "swing",
        "theta3",
        "theta3_accel",
        "theta3_rate",
        "theta6",
        "theta6_accel",
        "theta6_rate",
    }
)


def check(section: Mapping[str, Any], key: str = "beatup") -> None:
    """Both six-bars (printed and scaled crank) and every swept four-bar turn fully; each printed_rounding is half a
    unit of its parameter's last printed digit; the fit's check tolerance is the tighter; S_w < stroke."""
    for grid_key in ("paper_step_deg", "fine_step_deg"):
        if not divides_turn(section["grids"][grid_key]):
            raise ConfigError(
                f"config key {key}.grids.{grid_key}: value {section['grids'][grid_key]!r} does not divide 360 deg"
            )
    turn = np.radians(angle_grid_deg(section["grids"]["fine_step_deg"]))
    sixbar = section["sixbar"]
    for crank_key, crank in (
        ("sixbar.l1_m", sixbar["l1_m"]),
        ("comparison.scaled_crank_m", section["comparison"]["scaled_crank_m"]),
    ):
        try:
            sley_motion(six_bar(sixbar, crank_m=crank), turn)
        except ValueError as exc:
            raise ConfigError(
                f"config key {key}.{crank_key} (value {crank!r}) with {key}.sixbar: six-bar {exc}"
            ) from None
    fourbar = section["fourbar"]
    for ratio in [labelled(fourbar["arm_to_crank"]), *section["sweep"]["arm_to_crank"]]:
        try:
            four_bar_beatup(fourbar, arm_to_crank=ratio).sword_angle(turn)
        except ValueError as exc:
            raise ConfigError(f"config key {key}.fourbar (arm_to_crank={ratio!r}): {exc}") from None
    for name, half in section["printed_rounding"].items():
        digits = float(sixbar[name]) / (2 * float(half))
        if abs(digits - round(digits)) > 1e-6:
            raise ConfigError(
                f"config key {key}.printed_rounding.{name}: value {half!r} is not half a unit of the last digit of "
                f"{key}.sixbar.{name} = {sixbar[name]!r}"
            )
    fit = section["table1_fit"]
    if fit["check_tolerance"] >= fit["tolerance"]:
        raise ConfigError(
            f"config key {key}.table1_fit.check_tolerance: value {fit['check_tolerance']!r} must be tighter than "
            f"{key}.table1_fit.tolerance = {fit['tolerance']!r}"
        )
    stroke = section["comparison"]["stroke_m"]
    sw = labelled(fourbar["weft_clearance_m"])
    if sw >= stroke:
        raise ConfigError(
            f"config key {key}.fourbar.weft_clearance_m: value {sw!r} is not smaller than the stroke"
            f" {key}.comparison.stroke_m = {stroke!r}"
        )
    sweep = section["sweep"]["weft_clearance_m"]
    if not sweep["start"] < sweep["stop"] < stroke:
        raise ConfigError(
            f"config key {key}.sweep.weft_clearance_m: value {dict(sweep)!r} needs start < stop < stroke ({stroke!r} m)"
        )
