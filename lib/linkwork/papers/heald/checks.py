"""Physical checks of the heald section before any job runs (messages name the key and the value)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ...pipeline.errors import ConfigError
from .adapter import parameters
from .model import build

#: The result variables a published-numbers file's measures may name: what the comparison reads from
#: results/heald/chain.nc (tests/test_workflow.py checks that the study writes each; a new one is added here).
RESULT_VARIABLES = frozenset({"first_resonance", "growth_fraction", "ratio_EF_min"})

NONNEGATIVE = ("c_O", "c_joint", "clearance_E", "clearance_F")


def check(section: Mapping[str, Any], key: str = "heald") -> None:
    """Masses, stiffnesses and reactions > 0, damping and clearance >= 0, lever ratios non-zero; the chains build."""
    for name, entry in section["parameters"].items():
        value = entry["value"]
        if name.startswith("eta"):
            if value == 0:
                raise ConfigError(
                    f"config key {key}.parameters.{name}.value: value {value!r}: a lever ratio cannot be 0"
                )
        elif name in NONNEGATIVE:
            if value < 0:
                raise ConfigError(f"config key {key}.parameters.{name}.value: value {value!r} must be >= 0")
        elif value <= 0:
            raise ConfigError(
                f"config key {key}.parameters.{name}.value: value {value!r} must be > 0 (a mass, stiffness or reaction)"
            )
    speeds = section["speeds"]
    if speeds["min_rpm"] >= speeds["max_rpm"]:
        raise ConfigError(
            f"config key {key}.speeds: min_rpm {speeds['min_rpm']!r} must be below max_rpm {speeds['max_rpm']!r}"
        )
    band = section["accuracy"]["band_rpm"]
    if band["start"] >= band["stop"]:
        raise ConfigError(
            f"config key {key}.accuracy.band_rpm: start {band['start']!r} must be below stop {band['stop']!r}"
        )
    for name, sweep in section["sweeps"].items():
        if sweep["start"] >= sweep["stop"]:
            raise ConfigError(
                f"config key {key}.sweeps.{name}: start {sweep['start']!r} must be below stop {sweep['stop']!r}"
            )
    rise = section["cam"]["rise_fraction"]
    for what, value in (("value", rise["value"]), *((f"range.{i}", v) for i, v in enumerate(rise.get("range", ())))):
        if not 0 < value < 0.5:
            raise ConfigError(
                f"config key {key}.cam.rise_fraction.{what}: value {value!r} must lie in (0, 0.5): the rise and the"
                " return share one turn"
            )
    _check_contact(section, key)
    for model in section["models"]:
        try:
            build(model, parameters(section), "elastic")
        except ValueError as exc:
            raise ConfigError(f"config key {key}.parameters (model {model}): {exc}") from None


def _check_contact(section: Mapping[str, Any], key: str) -> None:
    """The contact scene: each case names parameters that have a range; the linkage assembles and follows the cam's
    turn with every case's parameters (the lever ratios and lengths leave it a closed linkage)."""
    from ...engines.multibody.assembly import follow_turn
    from ...engines.multibody.linkage import LinkageError
    from ...units import RAD_S_PER_RPM
    from .contact import case_parameters, linkage

    cfg, params = section["contact"], section["parameters"]
    ranges = {}
    for case, ends in cfg["cases"].items():
        for name in ends:
            if name not in params or "range" not in params[name]:
                raise ConfigError(
                    f"config key {key}.contact.cases.{case}.{name}: not a parameter of {key}.parameters with a range"
                )
            ranges[name] = tuple(params[name]["range"])
    p = parameters(section)
    rpm = max(cfg["speeds_rpm"])  # the lever's motion is the same at every speed: one turn followed per case
    for case, ends in cfg["cases"].items():
        try:
            follow_turn(
                linkage(cfg, section["cam"], case_parameters(p, ranges, ends), rpm * RAD_S_PER_RPM, clearances=False)
            )
        except LinkageError as exc:
            raise ConfigError(f"config key {key}.contact (case {case}): the heald linkage {exc}") from None
