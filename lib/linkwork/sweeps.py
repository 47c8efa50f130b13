"""Parameter sweeps that fan out: one independent job per grid point, gathered into one Dataset.

clearance: radial clearance x crank speed on one clearance scene -> peak and RMS joint contact
force and rocker angular acceleration over the recorded cycles.
heald: joint clearance x heald-frame mass on one chain model -> peak |Q_E|, |Q_F| over the speed band.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np
import xarray as xr

AXES = {"clearance": ("clearance_m", "crank_speed_rad_s"), "heald": ("clearance_m", "heald_mass_kg")}
UNITS = {"clearance_m": "m", "crank_speed_rad_s": "rad s-1", "heald_mass_kg": "kg"}


def grid(sweeps: Mapping[str, Any], name: str) -> list[tuple[float, float]]:
    """The points of a sweep for the selected grid size (config sweeps.grid: small or large)."""
    spec = sweeps[name][sweeps["grid"]]
    a, b = AXES[name]
    return list(itertools.product(spec[a], spec[b]))


def clearance_point(config: Mapping[str, Any], sweeps: Mapping[str, Any], index: int) -> dict[str, float]:
    from .clearance_dataset import integrate, output_times, parameters

    spec = sweeps["clearance"]
    c, w = grid(sweeps, "clearance")[index]
    section = config["clearance"]
    p = parameters(section, spec["variant"])
    p = replace(p, journal_radius=p.bearing_radius - c, crank_speed=w, e0=p.e0 * c / p.clearance)
    scene = section["scenes"][spec["scene"]]
    numerics = {**section, "numerics": {**section["numerics"], "settle_cycles": spec["settle_cycles"], "record_cycles": spec["record_cycles"]}}
    t, rec = output_times(numerics, p)
    integ = section["integrators"][scene.get("integrator", "explicit")]
    _, d, *_ = integrate(p, tuple(scene["clearance_joints"]), tuple(scene["effects"]), t, integ)
    d = d[rec]
    forces = np.nan_to_num(d[:, [7 + 6 * k for k in range(len(scene["clearance_joints"]))]], nan=0.0)
    return {
        "peak_joint_force": float(forces.max()),
        "rms_joint_force": float(np.sqrt(np.mean(forces.max(axis=1) ** 2))),
        "peak_rocker_acceleration": float(np.abs(d[:, 0]).max()),
        "rms_rocker_acceleration": float(np.sqrt(np.mean(d[:, 0] ** 2))),
    }


def heald_point(config: Mapping[str, Any], sweeps: Mapping[str, Any], index: int) -> dict[str, float]:
    from .heald_dataset import joint_forces, omega_grid, parameters

    spec = sweeps["heald"]
    c, m = grid(sweeps, "heald")[index]
    section = config["heald"]
    p = {**parameters(section), "clearance_E": c, "clearance_F": c, "M_P": m}
    amp = float(section["excitation"]["displacement_amplitude_m"]["value"])
    _, q_e, q_f, _ = joint_forces(spec["model"], p, "elastic", omega_grid(section), amp)
    return {"peak_Q_E": float(np.abs(q_e).max()), "peak_Q_F": float(np.abs(q_f).max()),
            "ratio_EF_min": float((np.abs(q_e) / np.abs(q_f)).min())}


POINT = {"clearance": clearance_point, "heald": heald_point}
LONG_NAMES = {
    "peak_joint_force": ("N", "peak dry contact force over the clearance joints"),
    "rms_joint_force": ("N", "RMS of the largest joint contact force"),
    "peak_rocker_acceleration": ("rad s-2", "peak |rocker angular acceleration|"),
    "rms_rocker_acceleration": ("rad s-2", "RMS rocker angular acceleration"),
    "peak_Q_E": ("N", "peak |Q_E| over the speed band"),
    "peak_Q_F": ("N", "peak |Q_F| over the speed band"),
    "ratio_EF_min": ("1", "min |Q_E|/|Q_F| over the speed band"),
}


def point_dataset(config, sweeps, name: str, index: int) -> xr.Dataset:
    a, b = AXES[name]
    va, vb = grid(sweeps, name)[index]
    values = POINT[name](config, sweeps, index)
    data = {k: ((), v, {"units": LONG_NAMES[k][0], "long_name": LONG_NAMES[k][1]}) for k, v in values.items()}
    data[a] = ((), va, {"units": UNITS[a], "long_name": a})
    data[b] = ((), vb, {"units": UNITS[b], "long_name": b})
    return xr.Dataset(data)


def gather(sweeps, name: str, points: list[xr.Dataset]) -> xr.Dataset:
    a, b = AXES[name]
    spec = sweeps[name][sweeps["grid"]]
    av, bv = np.array(spec[a], dtype=float), np.array(spec[b], dtype=float)
    variables = [k for k in points[0].data_vars if k not in (a, b)]
    out = {k: np.full((av.size, bv.size), np.nan) for k in variables}
    for ds in points:
        i, j = int(np.argmin(np.abs(av - float(ds[a])))), int(np.argmin(np.abs(bv - float(ds[b]))))
        for k in variables:
            out[k][i, j] = float(ds[k])
    return xr.Dataset(
        {k: ((a, b), v, points[0][k].attrs) for k, v in out.items()},
        coords={a: (a, av, {"units": UNITS[a], "long_name": a}), b: (b, bv, {"units": UNITS[b], "long_name": b})},
    )
