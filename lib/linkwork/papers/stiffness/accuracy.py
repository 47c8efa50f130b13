"""The stiffness paper's accuracy study: trapezoid quadrature of the strain energy vs the closed form."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...pipeline.accuracy import summary_variables
from ...pipeline.timing import median_time
from ...units import angle_grid_deg
from .adapter import linkage_and_sections
from .model import paper_angles, trapezoid_displacement, unit_force_internal_forces, unit_load_displacement

ROUNDING = 1e-16  # error plotted for an exact method


def quadrature_accuracy(cfg: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Trapezoid quadrature of the strain energy vs the closed form (the pipeline's), K_h on the fine grid.

    Errors in the Dataset, wall times (median of ``accuracy.repeats`` after a warm-up) in the timings dict.
    """
    linkage, members = linkage_and_sections(cfg)
    acc = cfg["accuracy"]
    a, b, g = paper_angles(linkage, np.radians(angle_grid_deg(cfg["grids"]["fine_step_deg"])))
    l1, l2, l3, _ = linkage.lengths
    forces = unit_force_internal_forces(l1, a, b, g, "equilibrium")
    exact = unit_load_displacement((l1, l2, l3), members, forces)
    panels = list(acc["panels"])
    errors, times = [], {}
    for n in panels:
        approx = trapezoid_displacement((l1, l2, l3), members, forces, n)
        errors.append(float(np.max(np.abs(approx - exact) / exact)))
        times[str(n)] = median_time(
            lambda n=n: trapezoid_displacement((l1, l2, l3), members, forces, n), acc["repeats"]
        )
    closed = median_time(lambda: unit_load_displacement((l1, l2, l3), members, forces), acc["repeats"])
    settings = [f"trapezoid {n} panels" for n in panels] + ["closed form"]
    ds = xr.Dataset(
        {
            "error": (
                "panels", np.array(errors),
                {"units": "1", "long_name": "max relative error of x_O' (trapezoid vs closed form)"},
            ),
            **summary_variables("stiffness quadrature", settings, [*errors, ROUNDING], "closed form"),
        },
        coords={"panels": ("panels", np.array(panels), {"units": "1", "long_name": "trapezoid panels per member"})},
        attrs={"title": "Strain-energy quadrature vs closed form (stiffness)", "repeats": acc["repeats"]},
    )
    timings = {"method": f"median of {acc['repeats']} runs after a warm-up, time.perf_counter",
               "summary_s": dict(zip(settings, [*(times[str(n)] for n in panels), closed], strict=True))}
    return ds, timings
