"""Config adapter of the transplanter paper: mechanism, material, allowable stress, mesh and the
optimisation problem from config (lengths in m, angles in degrees and speeds in rev/min converted here)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from ...configformat import labelled
from ...units import RAD_S_PER_RPM
from .model import Discretisation, Material, Transplanter, discretise


def mechanism(cfg: Mapping[str, Any], **override: Any) -> Transplanter:
    """The linkage and its crank speed from ``geometry`` and ``crank_speed_rpm``."""
    g = cfg["geometry"]
    mech = Transplanter(
        crank=g["crank_m"],
        coupler=g["coupler_m"],
        rocker=g["rocker_m"],
        arm=g["arm_m"],
        pivot_d=(g["pivot_D_m"][0], g["pivot_D_m"][1]),
        arm_angle=float(np.radians(g["arm_angle_deg"])),
        arm_side=g["arm_side"],
        branch=g["branch"],
        crank_speed=cfg["crank_speed_rpm"] * RAD_S_PER_RPM,
    )
    return replace(mech, **override) if override else mech


def _properties(cfg: Mapping[str, Any]) -> Mapping[str, Any]:
    return cfg["materials"][cfg["material"]["name"]]


def material(cfg: Mapping[str, Any], **override: Any) -> Material:
    """Young's modulus and density of the selected material (labelled entries)."""
    props = _properties(cfg)
    m = Material(youngs_modulus=labelled(props["youngs_modulus_Pa"]), density=labelled(props["density_kg_m3"]))
    return replace(m, **override) if override else m


def allowable(cfg: Mapping[str, Any]) -> float:
    """Allowable stress (Pa): yield strength / safety factor."""
    return labelled(_properties(cfg)["yield_Pa"]) / float(cfg["material"]["safety_factor"])


def gravity(cfg: Mapping[str, Any]) -> float:
    """Acceleration of gravity on the elastic model (m/s^2; 0 = off)."""
    return labelled(cfg["fe"]["gravity_m_s2"])


def compared_solution(cfg: Mapping[str, Any]) -> str:
    """'quasi-static' or 'dynamic': the solution whose response is compared with the paper's numbers."""
    return str(cfg["fe"]["compared_solution"]["value"])


def dynamic_settings(cfg: Mapping[str, Any]) -> dict[str, Any]:
    """Newmark settings of the dynamic solution: Rayleigh damping ratio, revolutions, substeps."""
    fe = cfg["fe"]
    return {
        "damping_ratio": labelled(fe["damping_ratio"]),
        "revolutions": fe["revolutions"],
        "substeps": fe["substeps"],
    }


def discretisation(cfg: Mapping[str, Any], kind: str | None = None, elements=None) -> Discretisation:
    """The mesh of ``fe`` (element kind, elements per member), optionally another kind or refinement."""
    fe = cfg["fe"]
    return discretise(tuple(elements or fe["elements_per_member"]), kind or fe["element"])


def member_lengths(cfg: Mapping[str, Any]) -> np.ndarray:
    """AB, BC, CD, BE (m)."""
    g = cfg["geometry"]
    return np.array([g["crank_m"], g["coupler_m"], g["rocker_m"], g["arm_m"]])
