"""Physical checks of the transplanter section before any job runs (messages name the key and the value)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...pipeline.errors import ConfigError
from ...units import divides_turn
from .adapter import mechanism
from .model import rigid_motion

#: The result variables a published-numbers file's measures may name: what the comparison reads from
#: results/transplanter/optim.nc and at_published.nc (tests/test_workflow.py checks that the study writes each; a new
#: one is added here).
RESULT_VARIABLES = frozenset(
    {"Ux", "Uy", "distortion", "distortion_ratio", "governing_elasticity", "mass_ratio", "stress_max"}
)


def check(section: Mapping[str, Any], key: str = "transplanter", pivot_clearance: float = 0.005) -> None:
    """Known material; the grids divide a turn; the linkage turns fully; the arm never sweeps within 5 mm of
    the pivot D or the pin C.

    The crank pivot A is not checked: the 254 mm arm, carried round A by the 42 mm crank, crosses A in
    plan view at every arm angle (the paper's own geometry passes within 0.2 mm), so arm and crank
    shaft necessarily work in different planes.
    """
    name = section["material"]["name"]
    if name not in section["materials"]:
        raise ConfigError(
            f"config key {key}.material.name: value {name!r} is not a material in {key}.materials"
            f" ({', '.join(section['materials'])})"
        )
    for group, field in (("fe", "angle_step_deg"), ("optimization", "angle_step_deg")):
        step = section[group][field]
        if not divides_turn(step):
            raise ConfigError(f"config key {key}.{group}.{field}: value {step!r} does not divide 360 deg")
    fine, coarse = section["fe"]["angle_step_deg"], section["optimization"]["angle_step_deg"]
    if not _multiple(coarse, fine):
        raise ConfigError(
            f"config key {key}.optimization.angle_step_deg: value {coarse!r} is not a multiple of fe.angle_step_deg"
            f" ({fine!r}): the optimiser's crank angles must be points of the report grid"
        )
    study = section["fe"]["newmark_study"]
    largest = max(study["steps_deg"])
    if not divides_turn(largest):
        raise ConfigError(
            f"config key {key}.fe.newmark_study.steps_deg: the largest step {largest!r} does not divide 360 deg"
        )
    for step in [*study["steps_deg"], study["reference_step_deg"]]:
        if not _multiple(largest, step):
            raise ConfigError(
                f"config key {key}.fe.newmark_study: step {step!r} does not divide the largest step {largest!r} (the"
                " output grid)"
            )
    if study["reference_step_deg"] >= min(study["steps_deg"]):
        raise ConfigError(
            f"config key {key}.fe.newmark_study.reference_step_deg: value {study['reference_step_deg']!r} is not finer"
            " than every studied step"
        )
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
                f"config key {key}.geometry.arm_angle_deg: value {geometry['arm_angle_deg']!r} sweeps the arm BE within"
                f" {dist.min() * 1e3:.1f} mm of pivot {label} (crank angle {np.degrees(theta[np.argmin(dist)]):.0f}"
                " deg)"
            )


def _multiple(big: float, small: float, tol: float = 1e-9) -> bool:
    """True if ``big`` is a whole multiple of ``small``."""
    n = big / small
    return round(n) >= 1 and abs(n - round(n)) <= tol
