"""Config adapter of the heald paper: plain parameter values and the frequency grid (SI units)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...units import RAD_S_PER_RPM


#: Drive frequency over the main-shaft frequency, per choice of ``drive.frequency``: the paper drives the chain at the
#: shaft frequency; in plain weave a heald frame rises and falls once in two picks (one pick per shaft turn).
DRIVE_RATIO = {"shaft": 1.0, "half-shaft": 0.5}


def drive_ratio(cfg: Mapping[str, Any]) -> float:
    """The drive frequency over the main-shaft frequency of the chosen scenario (1 without a ``drive`` entry: the
    sections that do not read it, the accuracy study and the sweep, drive the chain at the shaft frequency)."""
    if "drive" not in cfg:
        return 1.0
    choice = cfg["drive"]["frequency"]["value"]
    if choice not in DRIVE_RATIO:
        raise ValueError(f"unknown drive frequency {choice!r}; expected one of {tuple(DRIVE_RATIO)}")
    return DRIVE_RATIO[choice]


def parameters(cfg: Mapping[str, Any]) -> dict[str, float]:
    """Plain values of the labelled entries of ``parameters`` (SI units: ``operating_speed_rpm`` becomes
    ``omega_op`` in rad/s, a main-shaft frequency) and ``drive_ratio``, the drive frequency over the shaft's."""
    p = {k: float(v["value"]) for k, v in cfg["parameters"].items()}
    p["omega_op"] = p.pop("operating_speed_rpm") * RAD_S_PER_RPM
    p["drive_ratio"] = drive_ratio(cfg)
    return p


def omega_grid(speeds: Mapping[str, Any]) -> np.ndarray:
    """Uniform main-shaft frequencies (rad/s) over ``speeds`` (min_rpm, max_rpm, points)."""
    return np.linspace(speeds["min_rpm"], speeds["max_rpm"], speeds["points"]) * RAD_S_PER_RPM


def amplitude(cfg: Mapping[str, Any]) -> float:
    """Drive displacement amplitude at D (m)."""
    return float(cfg["excitation"]["displacement_amplitude_m"]["value"])


def sweep_values(spec: Mapping[str, Any]) -> np.ndarray:
    """Values of a ``{start, stop, num, log}`` sweep."""
    if spec.get("log", False):
        return np.geomspace(spec["start"], spec["stop"], spec["num"])
    return np.linspace(spec["start"], spec["stop"], spec["num"])
