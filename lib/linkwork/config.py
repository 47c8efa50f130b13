"""Validate the whole config before any job runs.

Two layers: the JSON schema (types, ranges, no unknown keys) and physical
checks (a linkage must assemble at every crank angle it is asked for).  Every
error names the config key and the offending value.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from typing import Any

import jsonschema
import numpy as np

from . import from_config
from .kinematics import FourBar, four_bar

_NUMBERLIKE = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")


class ConfigError(ValueError):
    """A config value is invalid; the message names the key and the value."""


def _key(path) -> str:
    return ".".join(str(p) for p in path) or "<root>"


def _schema_message(error: jsonschema.ValidationError) -> str:
    key = _key(error.absolute_path)
    value = error.instance
    if error.validator == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        extra = sorted(set(value) - set(allowed)) if isinstance(value, dict) else []
        names = ", ".join(f"{key}.{e}" if key != "<root>" else e for e in extra)
        return f"config key {names}: unknown key (allowed here: {', '.join(allowed)})"
    if error.validator == "type" and isinstance(value, str) and _NUMBERLIKE.match(value):
        return (
            f"config key {key}: value {value!r} was read as a string, not a number "
            "(YAML needs a dot and a signed exponent, e.g. 1.0e-6)"
        )
    return f"config key {key}: value {value!r}: {error.message}"


def validate_schema(config: Mapping[str, Any], schema: Mapping[str, Any]) -> None:
    """Check ``config`` against the JSON schema; raise ConfigError listing every problem."""
    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(config), key=lambda e: [str(p) for p in e.absolute_path])
    if errors:
        raise ConfigError("invalid config:\n  " + "\n  ".join(_schema_message(e) for e in errors))


def check_stiffness(section: Mapping[str, Any], key: str = "stiffness") -> None:
    """The stiffness linkage must assemble on both crank-angle grids."""
    if section["reference_form"] not in section["forms"]:
        raise ConfigError(
            f"config key {key}.reference_form: value {section['reference_form']!r} is not one of "
            f"{key}.forms {section['forms']!r}"
        )
    numerics = section["numerics"]
    linkage = section["linkage"]
    try:
        lw = from_config.four_bar(linkage, numerics["assembly_tol"])
    except ValueError as exc:
        raise ConfigError(f"config key {key}.linkage: {exc}") from None
    for grid_key in ("paper_step_deg", "fine_step_deg"):
        step = section["grids"][grid_key]
        n = 360.0 / step
        if abs(n - round(n)) > 1e-9:
            raise ConfigError(f"config key {key}.grids.{grid_key}: value {step!r} does not divide 360 deg")
        try:
            four_bar(lw, np.radians(from_config.angle_grid_deg(step)))
        except ValueError as exc:
            values = ", ".join(f"{k}={linkage[k]!r}" for k in ("crank_m", "coupler_m", "rocker_m", "ground_m"))
            raise ConfigError(f"config key {key}.linkage ({values}): {exc}") from None


def _grid_divides_turn(section: Mapping[str, Any], key: str, grid_key: str) -> None:
    step = section["grids"][grid_key]
    n = 360.0 / step
    if abs(n - round(n)) > 1e-9:
        raise ConfigError(f"config key {key}.grids.{grid_key}: value {step!r} does not divide 360 deg")


def check_beatup(section: Mapping[str, Any], key: str = "beatup") -> None:
    """Both six-bars (printed and scaled crank) and every swept four-bar must turn fully; S_w < stroke."""
    for grid_key in ("paper_step_deg", "fine_step_deg"):
        _grid_divides_turn(section, key, grid_key)
    from .beatup import sley_motion

    turn = np.radians(from_config.angle_grid_deg(section["grids"]["fine_step_deg"]))
    sixbar = section["sixbar"]
    for crank_key, crank in (("sixbar.l1_m", sixbar["l1_m"]), ("comparison.scaled_crank_m", section["comparison"]["scaled_crank_m"])):
        try:
            sley_motion(from_config.six_bar(sixbar, crank_m=crank), turn)
        except ValueError as exc:
            raise ConfigError(f"config key {key}.{crank_key} (value {crank!r}) with {key}.sixbar: six-bar {exc}") from None
    fourbar = section["fourbar"]
    for ratio in [from_config.labelled(fourbar["arm_to_crank"]), *section["sweep"]["arm_to_crank"]]:
        try:
            from_config.four_bar_beatup(fourbar, arm_to_crank=ratio).sword_angle(turn)
        except ValueError as exc:
            raise ConfigError(f"config key {key}.fourbar (arm_to_crank={ratio!r}): {exc}") from None
    stroke = section["comparison"]["stroke_m"]
    sw = from_config.labelled(fourbar["weft_clearance_m"])
    if sw >= stroke:
        raise ConfigError(f"config key {key}.fourbar.weft_clearance_m: value {sw!r} is not smaller than the stroke {key}.comparison.stroke_m = {stroke!r}")
    sweep = section["sweep"]["weft_clearance_m"]
    if not sweep["start"] < sweep["stop"] < stroke:
        raise ConfigError(
            f"config key {key}.sweep.weft_clearance_m: value {dict(sweep)!r} needs start < stop < stroke ({stroke!r} m)"
        )


HEALD_NONNEGATIVE = ("c_O", "c_joint", "clearance_E", "clearance_F")


def check_heald(section: Mapping[str, Any], key: str = "heald") -> None:
    """Masses and stiffnesses positive, damping and clearance >= 0, lever ratios non-zero; the chains must build."""
    from .heald import build
    from .heald_dataset import parameters

    for name, entry in section["parameters"].items():
        value = entry["value"]
        if name.startswith("eta"):
            if value == 0:
                raise ConfigError(f"config key {key}.parameters.{name}.value: value {value!r}: a lever ratio cannot be 0")
        elif name in HEALD_NONNEGATIVE:
            if value < 0:
                raise ConfigError(f"config key {key}.parameters.{name}.value: value {value!r} must be >= 0")
        elif value <= 0:
            raise ConfigError(f"config key {key}.parameters.{name}.value: value {value!r} must be > 0 (a mass, stiffness or reaction)")
    speeds = section["speeds"]
    if speeds["min_rpm"] >= speeds["max_rpm"]:
        raise ConfigError(f"config key {key}.speeds: min_rpm {speeds['min_rpm']!r} must be below max_rpm {speeds['max_rpm']!r}")
    for model in section["models"]:
        try:
            build(model, parameters(section), "elastic")
        except ValueError as exc:
            raise ConfigError(f"config key {key}.parameters (model {model}): {exc}") from None


def check_transplanter(section: Mapping[str, Any], key: str = "transplanter", pivot_clearance: float = 0.005) -> None:
    """Known material; the linkage turns fully; the arm never sweeps within 5 mm of the pivot D or the pin C.

    The crank pivot A is not checked: the 254 mm arm, carried round A by the 42 mm crank, crosses A in
    plan view at every arm angle (the paper's own geometry passes within 0.2 mm), so arm and crank
    shaft necessarily work in different planes.
    """
    from .transplanter import rigid_motion
    from .transplanter_dataset import mechanism

    name = section["material"]["name"]
    if name not in section["materials"]:
        raise ConfigError(f"config key {key}.material.name: value {name!r} is not a material in {key}.materials ({', '.join(section['materials'])})")
    for grid_key in (("fe", "angle_step_deg"), ("optimization", "angle_step_deg")):
        step = section[grid_key[0]][grid_key[1]]
        if abs(360.0 / step - round(360.0 / step)) > 1e-9:
            raise ConfigError(f"config key {key}.{'.'.join(grid_key)}: value {step!r} does not divide 360 deg")
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    geometry = section["geometry"]
    try:
        motion = rigid_motion(mechanism(section), theta)
    except ValueError as exc:
        raise ConfigError(f"config key {key}.geometry: {exc}") from None
    b, e = motion.pos[:, 1], motion.pos[:, 4]
    for label, point in (("D", np.asarray(geometry["pivot_D_m"], dtype=float)), ("C", motion.pos[:, 2])):
        seg = e - b
        t = np.clip(np.einsum("ij,ij->i", point - b, seg) / np.einsum("ij,ij->i", seg, seg), 0.0, 1.0)
        dist = np.hypot(*(b + t[:, None] * seg - point).T)
        if dist.min() < pivot_clearance:
            raise ConfigError(
                f"config key {key}.geometry.arm_angle_deg: value {geometry['arm_angle_deg']!r} sweeps the arm BE "
                f"within {dist.min() * 1e3:.1f} mm of pivot {label} (crank angle {np.degrees(theta[np.argmin(dist)]):.0f} deg)"
            )


def check_clearance(section: Mapping[str, Any], key: str = "clearance") -> None:
    """Positive clearance, the method each scene names is configured, viscosity where lubrication is named,
    integrator settings complete, the linkage assembles."""
    joints = section["joints"]
    if joints["journal_radius_m"] >= joints["bearing_radius_m"]:
        raise ConfigError(
            f"config key {key}.joints.journal_radius_m: value {joints['journal_radius_m']!r} is not smaller than "
            f"{key}.joints.bearing_radius_m = {joints['bearing_radius_m']!r} (the clearance must be > 0)"
        )
    for name, scene in section["scenes"].items():
        effects = scene["effects"]
        if "lubrication" in effects and joints.get("viscosity_Pa_s", 0.0) <= 0.0:
            raise ConfigError(
                f"config key {key}.scenes.{name}.effects: value {effects!r} names lubrication but "
                f"{key}.joints.viscosity_Pa_s is {joints.get('viscosity_Pa_s', 'missing')!r}"
            )
        if "friction" in effects and "contact" not in effects:
            raise ConfigError(f"config key {key}.scenes.{name}.effects: value {effects!r}: friction needs contact")
        if (effects and not scene["clearance_joints"]) and set(effects) - {"gravity"}:
            raise ConfigError(f"config key {key}.scenes.{name}.effects: value {effects!r} names joint effects but no clearance joint")
    for group in ("integrators", "tight_integrators"):
        for kind, integ in section[group].items():
            needed = ("step_s",) if integ["method"] == "rk4" else ("rtol", "atol", "first_step_s", "max_step_s")
            missing = [n for n in needed if n not in integ]
            if missing:
                raise ConfigError(f"config key {key}.{group}.{kind}: method {integ['method']!r} needs {', '.join(missing)}")
    if section["work_precision"]["variant"] not in section["variants"]:
        raise ConfigError(f"config key {key}.work_precision.variant: value {section['work_precision']['variant']!r} is not a variant")
    b = section["bodies"]
    lw = FourBar(b["crank"]["length_m"], b["coupler"]["length_m"], b["rocker"]["length_m"], section["ground_m"])
    try:
        four_bar(lw, np.radians(np.arange(0.0, 360.0, 1.0)))
    except ValueError as exc:
        raise ConfigError(f"config key {key}.bodies: {exc}") from None


def check_sweeps(section: Mapping[str, Any], key: str = "sweeps", config: Mapping[str, Any] | None = None) -> None:
    """The swept clearance scene and variant must exist."""
    if config is None:
        return
    spec = section["clearance"]
    if spec["scene"] not in config["clearance"]["scenes"]:
        raise ConfigError(f"config key {key}.clearance.scene: value {spec['scene']!r} is not a scene of clearance.scenes")
    if spec["variant"] not in config["clearance"]["variants"]:
        raise ConfigError(f"config key {key}.clearance.variant: value {spec['variant']!r} is not a variant of clearance.variants")


#: Physical checks per paper section; a paper adds its own here.
PHYSICAL_CHECKS: dict[str, Callable[[Mapping[str, Any], str], None]] = {
    "stiffness": check_stiffness,
    "beatup": check_beatup,
    "heald": check_heald,
    "transplanter": check_transplanter,
    "clearance": check_clearance,
}


def validate_config(config: Mapping[str, Any], schema: Mapping[str, Any]) -> None:
    """Schema first, then the physical checks of every paper section present."""
    validate_schema(config, schema)
    for key, check in PHYSICAL_CHECKS.items():
        if key in config:
            check(config[key], key)
    if "sweeps" in config:
        check_sweeps(config["sweeps"], "sweeps", config)
