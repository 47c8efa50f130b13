"""The heald paper's accuracy study: frequency-grid resolution vs the error in a resonance peak, and cost."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...pipeline.accuracy import summary_variables
from ...pipeline.timing import median_time
from ...units import RAD_S_PER_RPM
from .adapter import amplitude, parameters
from .dynamics import joint_forces


def accuracy(cfg: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Frequency-grid resolution vs error in the peak joint force near a resonance, and cost.

    The band (config) brackets a damped resonance peak of the chosen force (elastic joints).  Reference: that peak
    located by bounded Brent search around the finest grid's maximum (x-tolerance from config).  Times: median of
    ``repeats`` after a warm-up.
    """
    from scipy.optimize import minimize_scalar

    p = parameters(cfg)
    amp = amplitude(cfg)
    acc = cfg["accuracy"]
    model = acc["model"]
    lo, hi = acc["band_rpm"]["start"] * RAD_S_PER_RPM, acc["band_rpm"]["stop"] * RAD_S_PER_RPM

    which = {"Q": 0, "Q_E": 1, "Q_F": 2}[acc["quantity"]]

    def force(omega: np.ndarray) -> np.ndarray:
        return np.abs(joint_forces(model, p, "elastic", omega, amp)[which])

    def peak_on(n: int) -> float:
        return float(force(np.linspace(lo, hi, n)).max())

    fine = np.linspace(lo, hi, max(acc["points"]) * 4)
    q_fine = force(fine)
    k = int(np.argmax(q_fine))
    if k in (0, fine.size - 1):
        raise ValueError(f"the peak of {acc['quantity']} lies on the edge of accuracy.band_rpm; widen or move the band")
    bracket = (fine[k - 1], fine[k + 1])
    res = minimize_scalar(
        lambda x: -float(force(np.array([x]))[0]),
        bounds=bracket,
        method="bounded",
        options={"xatol": acc["reference_xtol_rad_s"]},
    )
    ref = -float(res.fun)
    errors, times = [], []
    for n in acc["points"]:
        errors.append(abs(peak_on(n) - ref) / ref)
        times.append(median_time(lambda n=n: peak_on(n), acc["repeats"]))
    # the grid density closest to the pipeline's (its points over the whole speed band, scaled to the study band)
    speeds = cfg["speeds"]
    density = speeds["points"] * (hi - lo) / ((speeds["max_rpm"] - speeds["min_rpm"]) * RAD_S_PER_RPM)
    closest = min(acc["points"], key=lambda n: abs(np.log(n / density)))
    settings = [f"{n} points" for n in acc["points"]]
    below = [n for n, e in zip(acc["points"], errors, strict=True) if e < 1e-3]
    ds = xr.Dataset(
        {
            **summary_variables("chain frequency grid", settings, np.maximum(errors, 1e-16), f"{closest} points"),
            "pipeline_density": xr.DataArray(
                float(density),
                attrs={
                    "units": "1",
                    "long_name": "points of a uniform grid over the study band with the pipeline's spacing",
                },
            ),
            "points_for_0_1_percent": xr.DataArray(
                float(min(below)) if below else np.nan,
                attrs={"units": "1", "long_name": "fewest studied points with a peak error below 0.1 %"},
            ),
            "peak_error": xr.DataArray(
                np.array(errors), dims="grid_points",
                attrs={"units": "1", "long_name": f"relative error of the peak |{acc['quantity']}| on a uniform grid"},
            ),
            "reference_peak": xr.DataArray(
                ref, attrs={"units": "N", "long_name": f"peak |{acc['quantity']}| by bounded Brent search"}
            ),
            "reference_omega": xr.DataArray(
                float(res.x), attrs={"units": "rad s-1", "long_name": "frequency of the peak"}
            ),
            "reference_evaluations": xr.DataArray(
                int(res.nfev), attrs={"units": "1", "long_name": "force evaluations of the Brent search"}
            ),
        },
        coords={
            "grid_points": (
                "grid_points", np.array(acc["points"]),
                {"units": "1", "long_name": "points of the uniform frequency grid"},
            )
        },
    )
    ds.attrs.update(
        title="Frequency-grid resolution vs error in a resonance peak (heald)", model=model, quantity=acc["quantity"],
        reference_xtol_rad_s=acc["reference_xtol_rad_s"], repeats=acc["repeats"], band_rad_s=[lo, hi],
    )
    timings = {
        "method": f"median of {acc['repeats']} runs after a warm-up, time.perf_counter",
        "grid_s": dict(zip(map(str, acc["points"]), times, strict=True)),
        "summary_s": dict(zip(settings, times, strict=True)),
    }
    return ds, timings
