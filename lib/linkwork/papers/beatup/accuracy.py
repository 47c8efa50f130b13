"""The beat-up paper's accuracy study: analytic derivatives vs central finite differences, error and cost."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...pipeline.accuracy import summary_variables
from ...pipeline.timing import median_time
from ...units import angle_grid_deg
from .adapter import six_bar
from .model import sley_motion
from .studies import fd_rates

ROUNDING = 1e-16  # error entered for an exact method


def accuracy(section: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Analytic derivatives vs central finite differences over a step sweep: error (Dataset) and time (dict).

    Times are the median of ``repeats`` runs after a warm-up (time.perf_counter); they go to a
    side file so that the netCDF stays byte-identical between runs.
    """
    mech = six_bar(section["sixbar"])
    acc = section["accuracy"]
    theta1 = np.radians(angle_grid_deg(acc["grid_step_deg"]))
    steps = np.radians(np.asarray(acc["fd_steps_deg"], dtype=float))
    exact = sley_motion(mech, theta1)

    errors = np.empty((2, steps.size))
    fd_times = np.empty(steps.size)
    for j, h in enumerate(steps):
        _, _, r6, a6 = fd_rates(mech, theta1, h)
        errors[0, j] = np.abs(r6 - exact.theta6_rate).max()
        errors[1, j] = np.abs(a6 - exact.theta6_accel).max()
        fd_times[j] = median_time(lambda h=h: fd_rates(mech, theta1, h), acc["repeats"])
    analytic_time = median_time(lambda: sley_motion(mech, theta1), acc["repeats"])
    scale = np.abs(exact.theta6_accel).max()
    settings = [f"central differences h={s:g} deg" for s in np.degrees(steps)] + ["analytic"]
    ds = xr.Dataset(
        {
            "error": xr.DataArray(
                errors,
                dims=("derivative", "fd_step"),
                attrs={
                    "units": "rad rad-1 (rate), rad rad-2 (accel)",
                    "long_name": "max |central difference - analytic| over the grid",
                },
            ),
            "best_error": xr.DataArray(
                errors.min(axis=1),
                dims="derivative",
                attrs={
                    "units": "rad rad-1 (rate), rad rad-2 (accel)",
                    "long_name": "smallest error over the step sweep",
                },
            ),
            **summary_variables("kinematics derivatives", settings, [*(errors[1] / scale), ROUNDING], "analytic"),
        },
        coords={
            "derivative": (
                "derivative", np.array(["theta6_rate", "theta6_accel"], dtype=object),
                {"units": "1", "long_name": "which derivative"},
            ),
            "fd_step": (
                "fd_step", np.degrees(steps), {"units": "deg", "long_name": "finite-difference step in crank angle"},
            ),
        },
    )
    ds.attrs.update(
        title="Analytic vs finite-difference derivatives (beat-up six-bar)", grid_step_deg=acc["grid_step_deg"],
        repeats=acc["repeats"],
    )
    timings = {
        "method": f"median of {acc['repeats']} runs after a warm-up, time.perf_counter",
        "points": int(theta1.size),
        "analytic_s": analytic_time,
        "fd_s": dict(zip([f"{s:g}" for s in np.degrees(steps)], fd_times.tolist(), strict=True)),
        "fd_over_analytic_median": float(np.median(fd_times) / analytic_time),
        "summary_s": dict(zip(settings, [*fd_times.tolist(), analytic_time], strict=True)),
    }
    return ds, timings
