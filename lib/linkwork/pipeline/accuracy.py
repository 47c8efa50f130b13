"""What accuracy costs in time, for every numerical method of the pipeline, in one table.

Each paper's accuracy study adds to its own Dataset a standard summary (``summary_variables``):
per point the method, the setting, the error against that method's reference and whether the
pipeline uses that setting; its timings side file holds ``summary_s``, the wall time of each setting.
``collect`` concatenates them.  Errors go into netCDF and timings into JSON side files, so that
reruns stay byte-identical.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

DIM = "wp_point"


def summary_variables(
    method: str | Sequence[str], settings: Sequence[str], errors: Sequence[float], pipeline: str | Sequence[str]
) -> dict[str, Any]:
    """Data variables of the standard accuracy summary for one method, or one method per point (dimension ``wp_point``).

    ``pipeline``: the setting(s) the pipeline uses; ``highlights`` shows one pipeline setting per method, so a study
    whose pipeline uses several settings (the clearance integrators: one per kind of scene) names one method per
    setting.  Errors are relative; an exact method is entered at the rounding level (1e-16) so that it shows on a
    log axis.
    """
    chosen = {pipeline} if isinstance(pipeline, str) else set(pipeline)
    n = len(settings)
    methods = [method] * n if isinstance(method, str) else list(method)
    if len(methods) != n:
        raise ValueError(f"summary_variables: {len(methods)} methods for {n} settings")
    return {
        "wp_method": (DIM, np.array(methods, dtype=object), {"units": "1", "long_name": "numerical method"}),
        "wp_setting": (
            DIM, np.array(list(settings), dtype=object), {"units": "1", "long_name": "setting of that point"},
        ),
        "wp_error": (
            DIM, np.asarray(errors, dtype=float),
            {"units": "1", "long_name": "relative error against the method's reference"},
        ),
        "wp_pipeline": (
            DIM, np.array([int(s in chosen) for s in settings]),
            {"units": "1", "long_name": "1 for the setting the pipeline uses"},
        ),
    }


def collect(studies: Sequence[xr.Dataset], timings: Sequence[Mapping[str, Any]]) -> tuple[xr.Dataset, dict[str, Any]]:
    """One table over every method: errors (Dataset) and times (dict ``method/setting`` -> s)."""
    methods, settings, errors, pipeline, seconds = [], [], [], [], {}
    for study, times in zip(studies, timings, strict=True):
        for m, s, e, p in zip(
            study.wp_method.values, study.wp_setting.values, study.wp_error.values, study.wp_pipeline.values,
            strict=True,
        ):
            methods.append(str(m))
            settings.append(str(s))
            errors.append(float(e))
            pipeline.append(int(p))
            seconds[f"{m}/{s}"] = float(times["summary_s"][str(s)])
    variables = summary_variables("", settings, errors, [])
    variables["wp_method"] = (DIM, np.array(methods, dtype=object), variables["wp_method"][2])
    variables["wp_pipeline"] = (DIM, np.array(pipeline), variables["wp_pipeline"][2])
    ds = xr.Dataset({k.removeprefix("wp_"): v for k, v in variables.items()})
    ds = ds.rename({DIM: "point"}).assign_coords(
        point=("point", np.arange(len(errors)), {"units": "1", "long_name": "study point"})
    )
    ds.attrs.update(title="What accuracy costs in time, per numerical method")
    return ds, seconds


def highlights(ds: xr.Dataset, seconds: Mapping[str, float]) -> dict[str, dict[str, Any]]:
    """Per method: the pipeline's setting (error, time) beside the most accurate other setting (its error and
    its time as a multiple of the pipeline's).  Times are wall-clock, so these go to the timings side file."""
    out: dict[str, dict[str, Any]] = {}
    for method in dict.fromkeys(str(m) for m in ds.method.values):
        rows = [
            (str(s), float(e), int(p), seconds[f"{method}/{s}"])
            for m, s, e, p in zip(ds.method.values, ds.setting.values, ds.error.values, ds.pipeline.values, strict=True)
            if m == method
        ]
        chosen = [r for r in rows if r[2]]
        others = [r for r in rows if not r[2]]
        if not chosen or not others:
            continue
        pipe = min(chosen, key=lambda r: r[1])
        best = min(others, key=lambda r: (r[1], r[3]))
        out[method] = {
            "pipeline_setting": pipe[0], "pipeline_error": pipe[1], "pipeline_s": pipe[3],
            "best_other_setting": best[0], "best_other_error": best[1], "best_other_time_ratio": best[3] / pipe[3],
        }
    return out


def summary(cfg: Mapping[str, Any], **studies: Any) -> tuple[xr.Dataset, dict[str, Any]]:
    """Rule study: gather every paper's accuracy study (inputs named <paper> and <paper>_t)."""
    names = [k for k in studies if not k.endswith("_t")]
    ds, seconds = collect([studies[k] for k in names], [studies[f"{k}_t"] for k in names])
    return ds, {
        "method": "median of repeats after a warm-up, time.perf_counter, measured inside each study",
        "seconds": seconds,
        "highlights": highlights(ds, seconds),
    }
