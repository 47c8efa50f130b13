"""What accuracy costs in time, for every numerical method of the pipeline, in one table.

Each method contributes points (setting, error against its reference) and, in a separate timing
dict, the wall time of each point; one setting per method is the pipeline's.  Errors go into the
netCDF, timings into a side file, so that reruns stay byte-identical.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from . import from_config
from .stiffness import paper_angles, trapezoid_displacement, unit_force_internal_forces, unit_load_displacement
from .timing import median_time

ROUNDING = 1e-16  # error plotted for an exact method


def stiffness_points(section: Mapping[str, Any], panels: list[int], repeats: int) -> list[tuple[str, str, float, float, bool]]:
    """Trapezoid quadrature of the strain energy vs the closed form (the pipeline's), K_h on the 1 deg grid."""
    linkage = from_config.four_bar(section["linkage"], section["numerics"]["assembly_tol"])
    sections = from_config.sections(section["members"])
    a, b, g = paper_angles(linkage, np.radians(from_config.angle_grid_deg(section["grids"]["fine_step_deg"])))
    l1, l2, l3, _ = linkage.lengths
    forces = unit_force_internal_forces(l1, a, b, g, "equilibrium")
    exact = unit_load_displacement((l1, l2, l3), sections, forces)
    points = []
    for n in panels:
        approx = trapezoid_displacement((l1, l2, l3), sections, forces, n)
        err = float(np.max(np.abs(approx - exact) / exact))
        points.append(("stiffness quadrature", f"trapezoid {n} panels", err, median_time(lambda n=n: trapezoid_displacement((l1, l2, l3), sections, forces, n), repeats), False))
    points.append(("stiffness quadrature", "closed form", ROUNDING, median_time(lambda: unit_load_displacement((l1, l2, l3), sections, forces), repeats), True))
    return points


def collect(
    beatup: xr.Dataset, beatup_t: Mapping, transplanter: xr.Dataset, transplanter_t: Mapping, clearance: xr.Dataset, clearance_t: Mapping,
    heald: xr.Dataset, heald_t: Mapping, config: Mapping[str, Any], stiffness: list,
) -> tuple[xr.Dataset, dict[str, float]]:
    """All methods' (setting, error, time, pipeline?) points as a Dataset (errors) and a dict (times)."""
    pts = list(stiffness)
    # kinematics derivatives: central differences vs analytic (the pipeline's)
    for step, err in zip(beatup.fd_step.values, beatup.error.sel(derivative="theta6_accel").values, strict=True):
        pts.append(("kinematics derivatives", f"central differences h={step:g} deg", float(err), beatup_t["fd_s"][f"{step:g}"], False))
    pts.append(("kinematics derivatives", "analytic", ROUNDING, beatup_t["analytic_s"], True))
    # FE mesh (peak stress) and modes
    base = config["transplanter"]["fe"]
    for kind in transplanter.element.values:
        for level in transplanter.refinement.values:
            pipeline = kind == base["element"] and int(level) == 1
            pts.append(("FE mesh and modes", f"{kind} x{int(level)}", float(transplanter.stress_error.sel(element=kind, refinement=level)), transplanter_t["ked_360_s"][f"{kind}x{int(level)}"], pipeline))
    for n in transplanter.modes.values:
        pts.append(("FE mesh and modes", f"{int(n)} modes", max(float(transplanter.modal_stress_error.sel(modes=n)), ROUNDING), transplanter_t["modal_s"][str(int(n))], False))
    # clearance integrators (the dry scene)
    dry = str(clearance.scene.values[0])
    pipe = config["clearance"]["integrators"]["explicit"]
    pipe_label = f"{pipe['method']} rtol={pipe['rtol']:.0e}" if pipe["method"] != "rk4" else f"rk4 h={pipe['step_s']:.0e}"
    for setting in clearance.setting.values:
        err = float(clearance.error.sel(scene=dry, setting=setting))
        if np.isfinite(err):
            pts.append(("clearance integrators", f"{setting} ({dry})", max(err, ROUNDING), clearance_t["runs"][f"{dry}/{setting}"], str(setting) == pipe_label))
    # chain frequency grid
    n_pipe = config["heald"]["speeds"]["points"]
    for n, err in zip(heald.grid_points.values, heald.peak_error.values, strict=True):
        pts.append(("chain frequency grid", f"{int(n)} points", max(float(err), ROUNDING), heald_t["grid_s"][str(int(n))], False))
    # mark the grid density closest to the pipeline's (points over the study band scaled to its whole band)
    heald_rows = [i for i, p in enumerate(pts) if p[0] == "chain frequency grid"]
    band = heald.attrs["band_rad_s"]
    s = config["heald"]["speeds"]
    density = n_pipe * (band[1] - band[0]) / ((s["max_rpm"] - s["min_rpm"]) * 2 * np.pi / 60)
    best = min(heald_rows, key=lambda i: abs(np.log(int(pts[i][1].split()[0]) / density)))
    pts[best] = (*pts[best][:4], True)
    labels = [f"{m}/{s}" for m, s, *_ in pts]
    ds = xr.Dataset(
        {
            "error": ("point", np.array([p[2] for p in pts]), {"units": "1", "long_name": "relative error against the method's reference"}),
            "pipeline": ("point", np.array([int(p[4]) for p in pts]), {"units": "1", "long_name": "1 for the setting the pipeline uses"}),
        },
        coords={
            "point": ("point", np.arange(len(pts)), {"units": "1", "long_name": "study point"}),
            "method": ("point", np.array([p[0] for p in pts], dtype=object), {"units": "1", "long_name": "numerical method"}),
            "setting": ("point", np.array([p[1] for p in pts], dtype=object), {"units": "1", "long_name": "setting of that point"}),
        },
    )
    return ds, dict(zip(labels, [float(p[3]) for p in pts], strict=True))
