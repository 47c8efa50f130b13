"""The clearance paper's work-precision study: integrator settings vs the error in the claims' measure."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.multibody.model import inverse_dynamics
from ...engines.multibody.simulate import integrate
from ...pipeline.accuracy import summary_variables
from ...pipeline.timing import run_and_time
from .adapter import integrator_kind, parameters, scene_effects
from .studies import cycle


#: Attributes of a per-setting variable: NaN where the setting is not run for the scene.
NOT_RUN = {"nan_meaning": "the setting is not run for this scene"}


def _setting(method: str, value: float, wp: Mapping[str, Any]) -> dict[str, Any]:
    if method == "rk4":
        return {"method": "rk4", "step_s": value}
    return {"method": method, "rtol": value, "atol": value * wp["atol_over_rtol"], "first_step_s": 1e-6, "max_step_s": wp["max_step_s"]}


def setting_label(s: Mapping[str, Any]) -> str:
    """'rk4 h=1e-05' or 'dopri5 rtol=1e-06': the label of an integrator setting."""
    return f"rk4 h={s['step_s']:.0e}" if s["method"] == "rk4" else f"{s['method']} rtol={s['rtol']:.0e}"


def work_precision(cfg: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Error against a tight reference vs wall time, per integrator setting, for one dry and one lubricated scene.

    The error is that of the claims' measure, the RMS deviation of the rocker acceleration from the ideal
    curve; the pointwise error is kept too, but after the first impacts it measures the sensitivity of
    the impact sequence more than the integrator.
    """
    wp = cfg["work_precision"]
    variant = wp["variant"]
    scenes = list(wp["scenes"])
    per_scene = {name: [_setting(m, v, wp) for m, values in spec.items() for v in values] for name, spec in wp["scenes"].items()}
    labels = sorted({setting_label(s) for ss in per_scene.values() for s in ss}, key=lambda x: (x.split()[0], -float(x.split("=")[1])))
    pointwise = np.full((len(scenes), len(labels)), np.nan)
    error, steps = np.full_like(pointwise, np.nan), np.full_like(pointwise, np.nan)
    timings: dict[str, Any] = {"method": f"median of {wp['repeats']} runs (the scene is compiled and warm from the reference run), time.perf_counter", "runs": {}}
    for i, name in enumerate(scenes):
        p = parameters(cfg, variant, name)
        joints, effects = scene_effects(cfg, name)
        t = np.linspace(0.0, wp["cycles"] * cycle(p), int(wp["cycles"] * cfg["numerics"]["points_per_cycle"]) + 1)
        ideal = inverse_dynamics(p, t, True)["rocker_acceleration"]
        _, ref, *_ = integrate(p, joints, effects, t, _setting(wp["reference"][name], wp["reference_rtol"], wp))
        scale = np.abs(ref[:, 0]).max()
        ref_rms = np.sqrt(np.mean((ref[:, 0] - ideal) ** 2))
        for s in per_scene[name]:
            j = labels.index(setting_label(s))
            (_, d, n_steps, _, _, _), seconds = run_and_time(lambda s=s: integrate(p, joints, effects, t, s), wp["repeats"])
            pointwise[i, j] = np.abs(d[:, 0] - ref[:, 0]).max() / scale
            error[i, j] = abs(np.sqrt(np.mean((d[:, 0] - ideal) ** 2)) - ref_rms) / ref_rms
            steps[i, j] = n_steps
            timings["runs"][f"{name}/{setting_label(s)}"] = seconds
    summary_settings, summary_errors, pipeline = [], [], []
    for i, name in enumerate(scenes):
        chosen = setting_label(cfg["integrators"][integrator_kind(cfg["scenes"][name])])
        pipeline.append(f"{chosen} ({name})")
        for j, label in enumerate(labels):
            if np.isfinite(error[i, j]):
                summary_settings.append(f"{label} ({name})")
                summary_errors.append(max(error[i, j], 1e-16))
    methods = sorted({label.split()[0] for label in labels})
    best_error = np.full((len(scenes), len(methods)), np.nan)
    best_setting = np.full((len(scenes), len(methods)), "", dtype=object)
    timings["best_s"] = {}
    for i, name in enumerate(scenes):
        for k, method in enumerate(methods):
            cols = [j for j, label in enumerate(labels) if label.split()[0] == method and np.isfinite(error[i, j])]
            if cols:
                j = min(cols, key=lambda c: error[i, c])
                best_error[i, k], best_setting[i, k] = error[i, j], labels[j]
                timings["best_s"][f"{name}/{method}"] = timings["runs"][f"{name}/{labels[j]}"]
    timings["summary_s"] = {f"{label} ({name})": timings["runs"][f"{name}/{label}"] for name in scenes for label in labels if f"{name}/{label}" in timings["runs"]}
    ds = xr.Dataset(
        {
            **summary_variables("clearance integrators", summary_settings, summary_errors, pipeline),
            "error": (("scene", "setting"), error, {"units": "1", "long_name": "relative error of the RMS deviation of the rocker acceleration from the ideal (the claims' measure)", **NOT_RUN}),
            "pointwise_error": (("scene", "setting"), pointwise, {"units": "1", "long_name": "max |rocker acceleration - reference| / max |reference|", **NOT_RUN}),
            "steps": (("scene", "setting"), steps, {"units": "1", "long_name": "accepted steps", **NOT_RUN}),
            "best_error": (("scene", "wp_method_name"), best_error, {"units": "1", "long_name": "smallest error of each integrator over its settings", "nan_meaning": "the integrator is not run for this scene"}),
            "best_setting": (("scene", "wp_method_name"), best_setting, {"units": "1", "long_name": "the setting with the smallest error"}),
            "pointwise_error_min": ("scene", np.nanmin(pointwise, axis=1), {"units": "1", "long_name": "smallest pointwise error over the settings"}),
            "pointwise_error_max": ("scene", np.nanmax(pointwise, axis=1), {"units": "1", "long_name": "largest pointwise error over the settings"}),
        },
        coords={
            "scene": ("scene", np.array(scenes, dtype=object), {"units": "1", "long_name": "scene"}),
            "setting": ("setting", np.array(labels, dtype=object), {"units": "1", "long_name": "integrator and step or tolerance"}),
            "method": ("setting", np.array([x.split()[0] for x in labels], dtype=object), {"units": "1", "long_name": "integrator"}),
            "wp_method_name": ("wp_method_name", np.array(methods, dtype=object), {"units": "1", "long_name": "integrator"}),
        },
        attrs={"title": "Work-precision of the clearance integrators",
               "reference": "; ".join(f"{sc}: {wp['reference'][sc]} rtol={wp['reference_rtol']:.0e}" for sc in scenes),
               "horizon_cycles": wp["cycles"], "variant": variant,
               "pipeline_settings": "; ".join(f"{k}: {setting_label(v)}" for k, v in cfg["integrators"].items())},
    )
    return ds, timings
