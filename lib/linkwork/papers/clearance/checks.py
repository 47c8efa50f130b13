"""Physical checks of the clearance section before any job runs (messages name the key and the value)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...engines.kinematics import CHANGE_POINT_MARGIN, FourBar, change_point_distance, four_bar, inversion
from ...pipeline.errors import ConfigError

#: The result variables a published-numbers file's measures may name: what the comparison reads from
#: results/clearance/claims.nc (tests/test_workflow.py checks that the study writes each; a new one is added here).
RESULT_VARIABLES = frozenset({"holds"})


def check(section: Mapping[str, Any], key: str = "clearance") -> None:
    """Positive clearance; viscosity where lubrication is named; friction only with contact; joint effects
    only with clearance joints, and a clearance joint held by contact or a film; e0 below the clearance; at least two
    batches in the shortest judged window; integrator settings complete; the work-precision variant exists; the
    linkage assembles."""
    joints = section["joints"]
    if joints["journal_radius_m"] >= joints["bearing_radius_m"]:
        raise ConfigError(
            f"config key {key}.joints.journal_radius_m: value {joints['journal_radius_m']!r} is not smaller than "
            f"{key}.joints.bearing_radius_m = {joints['bearing_radius_m']!r} (the clearance must be > 0)"
        )
    ideal = section["scenes"].get("ideal")
    if ideal is None or ideal["clearance_joints"]:
        raise ConfigError(
            f"config key {key}.scenes.ideal: value {ideal!r}: the scene named ideal is every claim's reference with"
            " ideal joints (it must be there, with clearance_joints: [])"
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
            raise ConfigError(
                f"config key {key}.scenes.{name}.effects: value {effects!r} names joint effects but no clearance joint"
            )
        if scene["clearance_joints"] and not {"contact", "lubrication"} & set(effects):
            raise ConfigError(
                f"config key {key}.scenes.{name}.effects: value {effects!r} names neither contact nor lubrication for"
                f" its clearance joints {scene['clearance_joints']!r} (nothing would hold the journal in its bearing)"
            )
    settings = [(f"integrators.{kind}", integ) for kind, integ in section["integrators"].items()]
    settings += [
        (f"check_integrators.{kind}[{i}]", integ)
        for kind, group in section["check_integrators"].items()
        for i, integ in enumerate(group)
    ]
    for where, integ in settings:
        needed = ("step_s",) if integ["method"] == "rk4" else ("rtol", "atol", "first_step_s", "max_step_s")
        missing = [n for n in needed if n not in integ]
        if missing:
            raise ConfigError(f"config key {key}.{where}: method {integ['method']!r} needs {', '.join(missing)}")
    clearance = joints["bearing_radius_m"] - joints["journal_radius_m"]
    e0 = section["assumed"]["e0_m"]
    for where, value in (("value", e0["value"]), ("range", max(e0.get("range", [e0["value"]])))):
        if value >= clearance:
            raise ConfigError(
                f"config key {key}.assumed.e0_m.{where}: value {value!r} is not below the radial clearance"
                f" {clearance:.6g} m ({key}.joints: bearing minus journal radius; the film's eccentricity cap 1 - e0/c"
                " would be <= 0)"
            )
    batch, least = section["statistics"]["batch_cycles"], section["states"]["min_cycles"]
    if 2 * batch > least:
        raise ConfigError(
            f"config key {key}.statistics.batch_cycles: value {batch!r} leaves fewer than two batches in the shortest"
            f" judged window ({key}.states.min_cycles = {least!r} cycles): every confidence interval would be infinite"
        )
    labels = [s["label"] for s in section["states"]["starts"]]
    if len(set(labels)) != len(labels):
        raise ConfigError(f"config key {key}.states.starts: labels {labels!r} repeat")
    wp = section["work_precision"]
    if wp["variant"] not in section["variants"]:
        raise ConfigError(
            f"config key {key}.work_precision.variant: value {wp['variant']!r} is not a variant of {key}.variants"
        )
    for name in [*wp["scenes"], *wp["reference"]]:
        if name not in section["scenes"]:
            raise ConfigError(f"config key {key}.work_precision.scenes: scene {name!r} is not a scene of {key}.scenes")
        if not section["scenes"][name]["clearance_joints"]:
            raise ConfigError(
                f"config key {key}.work_precision.scenes: scene {name!r} has no clearance joint (nothing to integrate)"
            )
    for name in wp["scenes"]:
        if name not in wp["reference"]:
            raise ConfigError(
                f"config key {key}.work_precision.reference: scene {name!r} of work_precision.scenes has no reference"
            )
    for name, ref in wp["reference"].items():
        if ref["check_rtol"] == ref["rtol"]:
            raise ConfigError(
                f"config key {key}.work_precision.reference.{name}.check_rtol: value {ref['check_rtol']!r} equals rtol"
                " (the two runs would agree trivially)"
            )
    if wp["dry_error_window_cycles"] > wp["cycles"]:
        raise ConfigError(
            f"config key {key}.work_precision.dry_error_window_cycles: value {wp['dry_error_window_cycles']!r} is"
            f" longer than work_precision.cycles ({wp['cycles']!r})"
        )
    xc = section["crosscheck"]
    wp_scene = xc["work_precision"]["scene"]
    if wp_scene not in section["scenes"] or wp_scene not in wp["reference"]:
        raise ConfigError(
            f"config key {key}.crosscheck.work_precision.scene: value {wp_scene!r} is not a scene with a reference in "
            f"{key}.work_precision.reference (the cross-check uses the same scene, horizon and reference)"
        )
    for name in xc["dry_scenes"]:
        scene = section["scenes"].get(name)
        if scene is None or not scene["clearance_joints"] or "lubrication" in scene["effects"]:
            raise ConfigError(
                f"config key {key}.crosscheck.dry_scenes: scene {name!r} is not a dry scene of {key}.scenes "
                "(clearance joints with contact, no lubrication)"
            )
    b = section["bodies"]
    lw = FourBar(b["crank"]["length_m"], b["coupler"]["length_m"], b["rocker"]["length_m"], section["ground_m"])
    try:
        four_bar(lw, np.radians(np.arange(0.0, 360.0, 1.0)))
    except ValueError as exc:
        raise ConfigError(f"config key {key}.bodies: {exc}") from None
    values = f"crank {lw.crank!r} m, coupler {lw.coupler!r} m, rocker {lw.rocker!r} m, {key}.ground_m {lw.ground!r} m"
    if change_point_distance(lw.lengths) < CHANGE_POINT_MARGIN:
        raise ConfigError(
            f"config key {key}.bodies ({values}): within {CHANGE_POINT_MARGIN:.1%} of a change-point linkage (s + l = p"
            " + q): it passes a singular configuration every turn"
        )
    if inversion(lw) != "crank-rocker":
        raise ConfigError(
            f"config key {key}.bodies ({values}): a {inversion(lw)} linkage; the scenes need a crank-rocker (the crank"
            " turns fully, the rocker swings between dead points, where every run starts)"
        )
