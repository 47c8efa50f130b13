"""The clearance paper's work-precision study: integrator settings vs their error against a tight reference.

The error is measured differently in the two kinds of scene, for the same reason: it must see the integrator.

* Lubricated scenes: the claims' measure, the RMS deviation of the rocker acceleration from the ideal curve over
  ``work_precision.cycles``, relative to the reference's.  The film damps the motion: the references at two
  tolerances agree to ~1e-12 and a start moved by 1 nm moves the measure in proportion (~1e-5), not more.
* Dry scenes: the largest pointwise difference of the journal eccentricity e (journal centre minus bearing centre,
  a vector, each clearance joint) from the reference's, at the recorded samples of the first
  ``dry_error_window_cycles`` of a cycle (the first impacts), relative to the radial clearance c: the quantity the
  contact force depends on.  Over the half cycle the impacts amplify any difference of the state, the integrator's
  as much as a rounding difference or a nanometre of the start, so the RMS measure there measured the sensitivity of
  the impact sequence (references at rtol 1e-10 and 1e-12 differed by 2.2e-3, a start moved by 1-10 nm moved it by
  2e-3 to 1.7e-2).  The window ends before that amplification takes over (the window is chosen by measurement).

Each scene's reference is run a second time at ``check_rtol``: that run's error in the scene's measure is the
reference's own error (``reference_error``); and a third time from a start with the coupler displaced by
``start_perturbation_m`` (``start_sensitivity``).  The pipeline's own setting (``integrators``, the kind the scene
uses) is always among the settings, so that the accuracy summary shows it for each kind of scene.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from .fourbar import initial_state, integrate, inverse_dynamics, joint_points
from ...pipeline.accuracy import summary_variables
from ...pipeline.timing import run_and_time
from .adapter import integrator_kind, parameters, scene_effects
from .studies import cycle


#: Attributes of a per-setting variable: NaN where the setting is not run for the scene.
NOT_RUN = {"nan_meaning": "the setting is not run for this scene"}
#: The measures, in words (``error_measure`` of each scene; {window}: the window in cycles).
DRY_MEASURE = (
    "max over the recorded samples of the first {window:g} cycle of |e - e of the reference| / c: e the journal"
    " eccentricity (the vector from the bearing centre to the journal centre) of each clearance joint, c the radial"
    " clearance"
)
RMS_MEASURE = (
    "|R - R of the reference| / R of the reference: R the RMS deviation of the rocker acceleration from the ideal curve"
    " over the horizon (the claims' measure)"
)
#: The method name of the accuracy summary, per scene (one pipeline setting each).
SUMMARY_METHOD = "clearance integrators, {scene}"


def _setting(method: str, value: float, wp: Mapping[str, Any]) -> dict[str, Any]:
    if method == "rk4":
        return {"method": "rk4", "step_s": value}
    return {
        "method": method,
        "rtol": value,
        "atol": value * wp["atol_over_rtol"],
        "first_step_s": wp["first_step_s"],
        "max_step_s": wp["max_step_s"],
    }


def setting_label(s: Mapping[str, Any]) -> str:
    """'rk4 h=1e-05' or 'dopri5 rtol=1e-06': the label of an integrator setting."""
    return f"rk4 h={s['step_s']:.0e}" if s["method"] == "rk4" else f"{s['method']} rtol={s['rtol']:.0e}"


def is_dry(effects: Sequence[str]) -> bool:
    """A dry scene: clearance without the film (its error is the eccentricity's over the first impacts)."""
    return "lubrication" not in effects


def eccentricity(p, joints: Sequence[int], states: np.ndarray) -> np.ndarray:
    """Journal centre minus bearing centre (m) of each clearance joint at each sample: (samples, joints, 2)."""
    q = np.asarray(states)[:, :9]

    def point(body: int, sx: float, sy: float) -> np.ndarray:
        x, y, phi = q[:, 3 * body], q[:, 3 * body + 1], q[:, 3 * body + 2]
        c, s = np.cos(phi), np.sin(phi)
        return np.stack([x + c * sx - s * sy, y + s * sx + c * sy], axis=-1)

    points = joint_points(p)
    out = np.empty((q.shape[0], len(joints), 2))
    for k, j in enumerate(joints):
        journal_body, (jx, jy), bearing_body, (bx, by) = points[j]
        out[:, k] = point(journal_body, jx, jy) - point(bearing_body, bx, by)
    return out


def contact_error(
    states: np.ndarray, reference: np.ndarray, t: np.ndarray, window_s: float, p, joints: Sequence[int]
) -> float:
    """The dry scenes' error: max over the samples with t <= window_s of |e - e_ref| / c (every clearance joint)."""
    inside = t <= window_s * (1 + 1e-12)
    diff = eccentricity(p, joints, states[inside]) - eccentricity(p, joints, reference[inside])
    return float(np.sqrt((diff**2).sum(axis=-1)).max() / p.clearance)


def rms_error(acceleration: np.ndarray, reference: np.ndarray, ideal: np.ndarray) -> float:
    """The claims' measure's relative error: |RMS(a - ideal) - RMS(a_ref - ideal)| / RMS(a_ref - ideal)."""
    ref_rms = np.sqrt(np.mean((reference - ideal) ** 2))
    return float(abs(np.sqrt(np.mean((acceleration - ideal) ** 2)) - ref_rms) / ref_rms)


def scene_settings(
    cfg: Mapping[str, Any], scene: str, spec: Mapping[str, Sequence[float]]
) -> tuple[list[dict[str, Any]], str]:
    """The settings of a scene (method -> values of ``spec``) with the pipeline's own setting in place of the
    one of the same label (or added), and that setting's label."""
    wp = cfg["work_precision"]
    chosen = dict(cfg["integrators"][integrator_kind(cfg["scenes"][scene])])
    label = setting_label(chosen)
    settings = [_setting(m, v, wp) for m, values in spec.items() for v in values]
    return [s for s in settings if setting_label(s) != label] + [chosen], label


def work_precision(cfg: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Error against a tight reference vs wall time, per integrator setting, for one dry and one lubricated scene.

    The error is the scene's measure (the module's docstring): dry scenes, the eccentricity over the first impacts
    relative to the clearance; lubricated scenes, the claims' RMS measure.  Both measures, and the pointwise error of
    the rocker acceleration over the horizon, are kept for every scene.  In named steps: each scene's runs against
    its reference, then each integrator's best setting, then the Dataset.
    """
    wp = cfg["work_precision"]
    scenes = list(wp["scenes"])
    per_scene, chosen = {}, {}
    for name, spec in wp["scenes"].items():
        per_scene[name], chosen[name] = scene_settings(cfg, name, spec)
    labels = sorted({setting_label(s) for ss in per_scene.values() for s in ss},
                    key=lambda x: (x.split()[0], -float(x.split("=")[1])))
    timings: dict[str, Any] = {
        "method": f"median of {wp['repeats']} runs (the scene is compiled and warm from the reference run), "
                  "time.perf_counter",
        "runs": {}, "reference_s": {},
    }
    runs = [_scene_runs(cfg, name, per_scene[name], labels, timings) for name in scenes]
    found = {key: np.array([r[key] for r in runs]) for key in runs[0]}
    methods = sorted({label.split()[0] for label in labels})
    best_error, best_setting = _best_settings(scenes, labels, methods, found["error"], timings)
    timings["summary_s"] = {f"{label} ({name})": timings["runs"][f"{name}/{label}"]
                            for name in scenes for label in labels if f"{name}/{label}" in timings["runs"]}
    return _work_precision_dataset(cfg, scenes, labels, methods, chosen, found, best_error, best_setting), timings


def _scene_runs(cfg: Mapping[str, Any], name: str, settings, labels: list[str], timings: dict) -> dict[str, Any]:
    """One scene of the study: its reference (and the reference's own error at ``check_rtol``, and its sensitivity
    to a displaced start), then each setting's errors against it in the scene's measure, the RMS measure and
    pointwise, its accepted steps and its median wall time (into ``timings``)."""
    wp = cfg["work_precision"]
    p = parameters(cfg, wp["variant"], name)
    joints, effects = scene_effects(cfg, name)
    dry = is_dry(effects)
    t = np.linspace(0.0, wp["cycles"] * cycle(p), int(wp["cycles"] * wp["points_per_cycle"]) + 1)
    window_s = wp["dry_error_window_cycles"] * cycle(p)
    ideal = inverse_dynamics(p, t, True)["rocker_acceleration"]
    ref_spec = wp["reference"][name]
    reference = _setting(ref_spec["method"], ref_spec["rtol"], wp)
    check, check_d, *_ = integrate(p, joints, effects, t, _setting(ref_spec["method"], ref_spec["check_rtol"], wp))
    (ref, ref_d, *_), timings["reference_s"][name] = run_and_time(
        lambda: integrate(p, joints, effects, t, reference), 1
    )
    scale = np.abs(ref_d[:, 0]).max()

    def measure(ys, d):
        """(the scene's error, the RMS measure's error, the pointwise error of the rocker acceleration)"""
        r = rms_error(d[:, 0], ref_d[:, 0], ideal)
        scene_error = contact_error(ys, ref, t, window_s, p, joints) if dry else r
        return scene_error, r, float(np.abs(d[:, 0] - ref_d[:, 0]).max() / scale)

    out = {key: np.full(len(labels), np.nan) for key in ("error", "rms", "pointwise", "steps")}
    out["reference_error"], out["rms_reference_error"], _ = measure(check, check_d)
    y0 = initial_state(p, joints, offset=(wp["start_perturbation_m"], 0.0))
    moved, moved_d, *_ = integrate(p, joints, effects, t, reference, y0=y0)
    out["start_sensitivity"], out["rms_start_sensitivity"], _ = measure(moved, moved_d)
    out["measure"] = DRY_MEASURE.format(window=wp["dry_error_window_cycles"]) if dry else RMS_MEASURE
    for s in settings:
        j = labels.index(setting_label(s))
        (ys, d, n_steps, _, _, _), seconds = run_and_time(
            lambda s=s: integrate(p, joints, effects, t, s), wp["repeats"]
        )
        out["error"][j], out["rms"][j], out["pointwise"][j] = measure(ys, d)
        out["steps"][j] = n_steps
        timings["runs"][f"{name}/{setting_label(s)}"] = seconds
    return out


def _best_settings(scenes, labels, methods, error, timings) -> tuple[np.ndarray, np.ndarray]:
    """Per scene and integrator, the smallest error over its settings and that setting (its time into
    ``timings['best_s']``)."""
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
    return best_error, best_setting


def _summary_rows(scenes, labels, chosen, error) -> dict[str, tuple]:
    """The accuracy summary's rows: every setting run, per scene, with the pipeline's choice."""
    methods, settings, errors, pipeline = [], [], [], []
    for i, name in enumerate(scenes):
        pipeline.append(f"{chosen[name]} ({name})")
        for j, label in enumerate(labels):
            if np.isfinite(error[i, j]):
                methods.append(SUMMARY_METHOD.format(scene=name))
                settings.append(f"{label} ({name})")
                errors.append(max(error[i, j], 1e-16))
    return summary_variables(methods, settings, errors, pipeline)


def _work_precision_dataset(cfg, scenes, labels, methods, chosen, found, best_error, best_setting) -> xr.Dataset:
    """The study's Dataset: per scene and setting the errors, steps and the summary rows; per scene the reference's
    own error and start sensitivity; per integrator its best setting."""
    per_setting, per_method = ("scene", "setting"), ("scene", "wp_method_name")
    pointwise = found["pointwise"]
    rms_words = "the same for the RMS measure (rms_error)"

    def variable(dims, values, long_name, units="1", **extra):
        return (dims, values, {"units": units, "long_name": long_name, **extra})

    data = {
        **_summary_rows(scenes, labels, chosen, found["error"]),
        "error": variable(per_setting, found["error"], "error in the scene's measure (error_measure) against the "
                          "reference", **NOT_RUN),
        "rms_error": variable(per_setting, found["rms"], "relative error of the RMS deviation of the rocker "
                              "acceleration from the ideal (the claims' measure) over the horizon", **NOT_RUN),
        "pointwise_error": variable(per_setting, pointwise, "max |rocker acceleration - reference| / max |reference| "
                                    "over the horizon", **NOT_RUN),
        "steps": variable(per_setting, found["steps"], "accepted steps over the horizon", **NOT_RUN),
        "reference_error": variable("scene", found["reference_error"], "the reference's own error: the scene's "
                                    "measure of the run at check_rtol against the reference"),
        "rms_reference_error": variable("scene", found["rms_reference_error"], rms_words),
        "start_sensitivity": variable("scene", found["start_sensitivity"], "the scene's measure of the reference "
                                      "setting run from a start with the coupler displaced by start_perturbation_m"),
        "rms_start_sensitivity": variable("scene", found["rms_start_sensitivity"], rms_words),
        "best_error": variable(per_method, best_error, "smallest error of each integrator over its settings",
                               nan_meaning="the integrator is not run for this scene"),
        "best_setting": variable(per_method, best_setting, "the setting with the smallest error"),
        "pointwise_error_min": variable("scene", np.nanmin(pointwise, axis=1), "smallest pointwise error over the "
                                        "settings"),
        "pointwise_error_max": variable("scene", np.nanmax(pointwise, axis=1), "largest pointwise error over the "
                                        "settings"),
    }
    coords = {
        "scene": variable("scene", np.array(scenes, dtype=object), "scene"),
        "error_measure": variable("scene", np.array(found["measure"], dtype=object), "definition of the scene's error"),
        "setting": variable("setting", np.array(labels, dtype=object), "integrator and step or tolerance"),
        "method": variable("setting", np.array([x.split()[0] for x in labels], dtype=object), "integrator"),
        "wp_method_name": variable("wp_method_name", np.array(methods, dtype=object), "integrator"),
    }
    return xr.Dataset(data, coords=coords, attrs=_work_precision_attrs(cfg, scenes, found["reference_error"]))


def _work_precision_attrs(cfg, scenes, reference_error) -> dict[str, Any]:
    wp = cfg["work_precision"]
    ref = wp["reference"]
    return {
        "title": "Work-precision of the clearance integrators",
        "reference": "; ".join(f"{sc}: {ref[sc]['method']} rtol={ref[sc]['rtol']:.0e}" for sc in scenes),
        "reference_check": "; ".join(f"{sc}: {ref[sc]['method']} rtol={ref[sc]['check_rtol']:.0e}" for sc in scenes),
        "reference_error": "; ".join(f"{sc}: {e:.2e}" for sc, e in zip(scenes, reference_error, strict=True)),
        "dry_error_measure": DRY_MEASURE.format(window=wp["dry_error_window_cycles"]),
        "dry_error_window_cycles": wp["dry_error_window_cycles"],
        "lubricated_error_measure": RMS_MEASURE,
        "start_perturbation_m": wp["start_perturbation_m"],
        "horizon_cycles": wp["cycles"], "points_per_cycle": wp["points_per_cycle"], "variant": wp["variant"],
        "atol_over_rtol": wp["atol_over_rtol"], "first_step_s": wp["first_step_s"], "max_step_s": wp["max_step_s"],
        "pipeline_settings": "; ".join(f"{k}: {setting_label(v)}" for k, v in cfg["integrators"].items()),
        "pipeline_settings_json": json.dumps(cfg["integrators"], sort_keys=True),
    }
