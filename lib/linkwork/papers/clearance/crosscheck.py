"""The clearance paper's ideal four-bar in an established engine (Exudyn) beside linkwork's inverse dynamics.

For each parameter variant and each Exudyn step, the largest difference of the crank torque and of the
rocker's angular acceleration from linkwork's ideal scene (inverse dynamics at the same times), relative
to the largest value of ours, over ``crosscheck.cycles`` crank turns from the dead point.  The two engines
agree if the difference at the finest step is below ``crosscheck.agreement`` and shrinks as the step does
(the difference is then Exudyn's discretisation error, not a difference of the models).

The dry scenes never repeat exactly, so they are compared as distributions: both engines run the scene from
the same initial state, settle, and record ``crosscheck.record_cycles`` cycles; per cycle, the claims' measure
(RMS deviation of the rocker acceleration and of the crank torque from the ideal curve).  The means differ
beyond the numerical error if the difference exceeds the sum of linkwork's (pipeline vs tight tolerance) and
Exudyn's (its two steps) changes of the mean plus twice the standard error of the difference of the means.
The lubricated scenes are not modelled in Exudyn.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from .fourbar import inverse_dynamics
from .adapter import parameters
from .studies import QUANTITIES


def relative_difference(theirs: np.ndarray, ours: np.ndarray) -> float:
    """max |theirs - ours| / max |ours| (1)."""
    return float(np.max(np.abs(theirs - ours)) / np.max(np.abs(ours)))


def observed_orders(steps: np.ndarray, differences: np.ndarray) -> np.ndarray:
    """log(d_i / d_(i+1)) / log(h_i / h_(i+1)) between successive steps (steps in decreasing order)."""
    return np.log(differences[:-1] / differences[1:]) / np.log(steps[:-1] / steps[1:])


def ideal(cfg: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: the ideal scene of every variant in Exudyn at every step of ``crosscheck.steps_s``."""
    from .fourbar import exudyn_ideal as ideal_run

    check = cfg["crosscheck"]
    variants = list(cfg["variants"])
    steps = np.array(sorted(check["steps_s"], reverse=True), dtype=float)
    diff = np.empty((len(variants), len(QUANTITIES), steps.size))
    wall = np.empty((len(variants), steps.size))
    version = ""
    for i, variant in enumerate(variants):
        p = parameters(cfg, variant, "ideal")
        end = check["cycles"] * 2 * np.pi / p.crank_speed
        for k, step in enumerate(steps):
            run = ideal_run(p, end, float(step), check["newton_tolerance"], gravity=True)
            ours = inverse_dynamics(p, run["t"], True)
            for q, quantity in enumerate(QUANTITIES):
                diff[i, q, k] = relative_difference(run[quantity], ours[quantity])
            wall[i, k] = run["wall_s"]
            version = run["version"]
            print(f"clearance_crosscheck: {variant} ideal, Exudyn step {step:.0e} s: torque {diff[i, 1, k]:.1e}, "
                  f"rocker acceleration {diff[i, 0, k]:.1e} (relative), {wall[i, k]:.1f} s", flush=True)
    orders = np.stack(
        [[observed_orders(steps, diff[i, q]) for q in range(len(QUANTITIES))] for i in range(len(variants))]
    )
    agree = (diff[..., -1] <= check["agreement"]) & np.all(diff[..., 1:] < diff[..., :-1], axis=-1)
    return xr.Dataset(
        {
            "relative_difference": (
                ("variant", "quantity", "step"), diff,
                {"units": "1", "long_name": "max |Exudyn - linkwork| / max |linkwork|"},
            ),
            "observed_order": (
                ("variant", "quantity", "refinement"), orders,
                {"units": "1", "long_name": "observed order of the difference between successive steps"},
            ),
            "exudyn_wall_s": (
                ("variant", "step"), wall,
                {"units": "s", "long_name": "Exudyn's solver wall time (time.perf_counter, one run)"},
            ),
            "agree": (
                ("variant", "quantity"),
                agree,
                {
                    "units": "1",
                    "long_name": "difference below the agreement bound at the finest step and shrinking with the step",
                },
            ),
            "all_agree": ((), bool(agree.all()), {"units": "1", "long_name": "every variant and quantity agrees"}),
            "finest_difference": (
                (), float(diff[..., -1].max()),
                {"units": "1", "long_name": "largest relative difference at the finest step"},
            ),
            "order_low": ((), float(orders.min()), {"units": "1", "long_name": "smallest observed order"}),
            "order_high": ((), float(orders.max()), {"units": "1", "long_name": "largest observed order"}),
        },
        coords={
            "variant": ("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "quantity": (
                "quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"},
            ),
            "step": ("step", steps, {"units": "s", "long_name": "Exudyn's fixed time step"}),
            "refinement": (
                "refinement", np.arange(1, steps.size), {"units": "1", "long_name": "from step i-1 to step i"},
            ),
        },
        attrs={
            "title": "Clearance paper, ideal scene: Exudyn beside linkwork's inverse dynamics",
            "engine": f"Exudyn {version}, Newmark (trapezoidal) with index-2 constraints",
            "cycles": check["cycles"],
            "agreement": check["agreement"],
            "newton_tolerance": check["newton_tolerance"],
        },
    )


def cycle_measures(
    t: np.ndarray, theirs: Mapping[str, np.ndarray], ideal_run: Mapping[str, np.ndarray], settle: int, cycles: int
) -> np.ndarray:
    """Per recorded cycle, the RMS of (scene - ideal) for each of QUANTITIES: (quantity, cycle)."""
    out = np.empty((len(QUANTITIES), cycles))
    for q, quantity in enumerate(QUANTITIES):
        d = np.asarray(theirs[quantity]) - np.asarray(ideal_run[quantity])
        per = (d.size - 1) // (settle + cycles)
        recorded = d[settle * per : (settle + cycles) * per]
        out[q] = np.sqrt(np.mean(recorded.reshape(cycles, per) ** 2, axis=1))
    return out


def dry(cfg: Mapping[str, Any], variant: str, scene: str) -> xr.Dataset:
    """Rule study: one dry scene of one variant in both engines, per-cycle measures and their comparison."""
    import copy

    from .fourbar import exudyn_dry as exudyn_run
    from .adapter import integrator_kind, scene_effects
    from .studies import fixed_record, output_times

    check = cfg["crosscheck"]
    local = copy.deepcopy(dict(cfg))
    local["numerics"] = {**cfg["numerics"], "record_cycles": check["record_cycles"]}
    settle, cycles = local["numerics"]["settle_cycles"], check["record_cycles"]
    p = parameters(local, variant, scene)
    joints, _ = scene_effects(local, scene)
    t, _ = output_times(local["numerics"], p)
    ideal_at = inverse_dynamics(p, t, True)
    steps = np.array(sorted(check["dry_steps_s"], reverse=True), dtype=float)
    measures = np.empty((2 + steps.size, len(QUANTITIES), cycles))
    wall = np.full(2 + steps.size, np.nan)
    settings = []
    # our run over the same fixed cycles (no settling rule) at the pipeline setting and the first check setting
    kind = integrator_kind(cfg["scenes"][scene])
    for k, integ in enumerate((cfg["integrators"][kind], cfg["check_integrators"][kind][0])):
        measures[k] = fixed_record(local, variant, scene, integ, settle, cycles)
        settings.append(f"linkwork {integ['method']} rtol {integ['rtol']:.0e}")
    for k, step in enumerate(steps):
        run = exudyn_run(p, joints, float(t[-1]), float(step), check["newton_tolerance"], float(t[1] - t[0]))
        n = min(run["t"].size, t.size)
        measures[2 + k] = cycle_measures(
            t[:n], {q: run[q][:n] for q in QUANTITIES}, {q: ideal_at[q][:n] for q in QUANTITIES}, settle, cycles
        )
        wall[2 + k] = run["wall_s"]
        settings.append(f"Exudyn step {step:.0e} s")
        print(
            f"clearance_crosscheck_dry: {variant}/{scene}, Exudyn step {step:.0e} s: {run['wall_s']:.1f} s", flush=True
        )
    mean = measures.mean(axis=-1)
    se = measures.std(axis=-1, ddof=1) / np.sqrt(cycles)
    ours, theirs = mean[0], mean[-1]
    margin = np.abs(mean[1] - mean[0]) + np.abs(mean[-1] - mean[-2]) + 2.0 * np.hypot(se[0], se[-1])
    return xr.Dataset(
        {
            "cycle_rms_deviation": (
                ("setting", "quantity", "cycle"), measures,
                {"units": "SI of the quantity", "long_name": "RMS of (scene - ideal) over each recorded cycle"},
            ),
            "mean": (
                ("setting", "quantity"), mean,
                {"units": "SI of the quantity", "long_name": "mean over the recorded cycles"},
            ),
            "standard_error": (
                ("setting", "quantity"), se,
                {"units": "SI of the quantity", "long_name": "standard error of the mean over the cycles"},
            ),
            "relative_difference": (
                ("quantity",),
                (theirs - ours) / ours,
                {
                    "units": "1",
                    "long_name": "(Exudyn finest step - linkwork pipeline) / linkwork pipeline, of the means",
                },
            ),
            "margin": (
                ("quantity",),
                margin,
                {
                    "units": "SI of the quantity",
                    "long_name": (
                        "numerical margin: |pipeline - tight| + |Exudyn steps| + 2 standard errors of the difference"
                    ),
                },
            ),
            "agree": (
                ("quantity",), np.abs(theirs - ours) <= margin,
                {"units": "1", "long_name": "difference of the means within the numerical margin"},
            ),
            "wall_s": (
                ("setting",),
                wall,
                {
                    "units": "s",
                    "long_name": "Exudyn's solver wall time (one run)",
                    "nan_meaning": "a linkwork run (not timed here)",
                },
            ),
        },
        coords={
            "setting": (
                "setting", np.array(settings, dtype=object),
                {"units": "1", "long_name": "engine and numerical setting"},
            ),
            "quantity": (
                "quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"},
            ),
            "cycle": ("cycle", np.arange(1, cycles + 1), {"units": "1", "long_name": "recorded cycle"}),
        },
        attrs={
            "title": f"Clearance paper, {scene} ({variant}): Exudyn beside linkwork over {cycles} cycles",
            "variant": variant,
            "scene": scene,
            "settle_cycles": settle,
            "record_cycles": cycles,
        },
    )


def time_to_reach(errors: np.ndarray, times: np.ndarray, target: float) -> float:
    """The least wall time (s) over a method's settings whose error is at most ``target`` (its work-precision
    front, which stays monotonic where the error of single settings does not); NaN if no setting reaches it."""
    ok = np.isfinite(errors) & np.isfinite(times) & (errors <= target)
    return float(times[ok].min()) if ok.any() else float("nan")


def work_precision(cfg: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Rule study: linkwork's compiled integrators, scipy's on the compiled right-hand side and Exudyn on one
    dry scene: the error of the claims' measure against the same tight reference versus wall time, and, at each
    error linkwork's Dormand-Prince reaches, each method's least time to reach it over linkwork's."""
    import copy

    from .fourbar import exudyn_dry as exudyn_run
    from ...pipeline.timing import run_and_time
    from .accuracy import _setting
    from .accuracy import work_precision as integrator_work_precision
    from .adapter import scene_effects
    from .studies import cycle

    xc = cfg["crosscheck"]["work_precision"]
    wp = cfg["work_precision"]
    local = copy.deepcopy(dict(cfg))
    local["work_precision"] = {**wp, "scenes": {xc["scene"]: xc["methods"]}}
    ds, timings = integrator_work_precision(local)
    scene, variant = xc["scene"], wp["variant"]
    p = parameters(cfg, variant, scene)
    joints, effects = scene_effects(cfg, scene)
    t = np.linspace(0.0, wp["cycles"] * cycle(p), int(wp["cycles"] * wp["points_per_cycle"]) + 1)
    ideal_acc = inverse_dynamics(p, t, True)["rocker_acceleration"]
    from .fourbar import integrate

    _, ref, *_ = integrate(
        p, joints, effects, t, _setting(wp["reference"][scene]["method"], wp["reference"][scene]["rtol"], wp)
    )
    ref_rms = np.sqrt(np.mean((ref[:, 0] - ideal_acc) ** 2))
    steps = np.array(sorted(xc["exudyn_steps_s"], reverse=True), dtype=float)
    ex_error, ex_time = np.empty(steps.size), np.empty(steps.size)
    for k, step in enumerate(steps):
        run, seconds = run_and_time(
            lambda step=step: exudyn_run(
                p, joints, float(t[-1]), float(step), cfg["crosscheck"]["newton_tolerance"], float(t[1] - t[0]),
                progress_s=float("inf"),
            ),
            wp["repeats"],
        )
        n = min(run["t"].size, t.size)
        ex_error[k] = abs(np.sqrt(np.mean((run["rocker_acceleration"][:n] - ideal_acc[:n]) ** 2)) - ref_rms) / ref_rms
        ex_time[k] = seconds
        print(
            f"clearance_crosscheck_work_precision: Exudyn step {step:.0e} s: error {ex_error[k]:.1e}, {seconds:.2f} s",
            flush=True,
        )
    err = ds.rms_error.sel(scene=scene).values  # the claims' measure, the one Exudyn's runs are measured in
    labels = [str(x) for x in ds.setting.values]
    times = np.array([timings["runs"].get(f"{scene}/{label}", np.nan) for label in labels])
    methods = list(dict.fromkeys(x.split()[0] for x in labels if np.isfinite(err[labels.index(x)])))
    own = [i for i, x in enumerate(labels) if x.startswith("dopri5 ") and np.isfinite(err[i])]
    curves = {
        m: (
            np.array([err[i] for i, x in enumerate(labels) if x.split()[0] == m]),
            np.array([times[i] for i, x in enumerate(labels) if x.split()[0] == m]),
        )
        for m in methods
    }
    curves["exudyn"] = (ex_error, ex_time)
    compared = [m for m in curves if m != "dopri5"]
    ratio = np.full((len(compared), len(own)), np.nan)
    for a, m in enumerate(compared):
        for b, i in enumerate(own):
            ratio[a, b] = time_to_reach(*curves[m], err[i]) / time_to_reach(*curves["dopri5"], err[i])
    medians = np.array([np.nanmedian(row) if np.isfinite(row).any() else np.nan for row in ratio])
    scipy_rows = [a for a, m in enumerate(compared) if m != "exudyn" and np.isfinite(medians[a])]
    best = min(scipy_rows, key=lambda a: medians[a]) if scipy_rows else None
    threshold = 2.0
    if best is None:
        decision = "undecided: no scipy integrator reached linkwork's errors within its settings"
    elif medians[best] <= threshold:
        decision = (
            f"use scipy's {compared[best]}: {medians[best]:.1f} times linkwork's time at equal error, within the"
            f" {threshold:g}x rule"
        )
    else:
        decision = (
            f"keep the hand-written integrator: the fastest scipy integrator, {compared[best]}, needs"
            f" {medians[best]:.1f} times its time at equal error"
        )
    out = xr.Dataset(
        {
            "median_time_ratio": (
                ("compared_method",),
                medians,
                {
                    "units": "1",
                    "long_name": "median over linkwork's error levels of the time ratio",
                    "nan_meaning": "the method reached none of linkwork's errors",
                },
            ),
            "error": (
                ("setting",),
                err,
                {
                    "units": "1",
                    "long_name": "relative error of the RMS deviation of the rocker acceleration from the ideal",
                    "nan_meaning": "not run",
                },
            ),
            "time_s": (
                ("setting",), times,
                {"units": "s", "long_name": f"wall time, {timings['method']}", "nan_meaning": "not run"},
            ),
            "exudyn_error": (
                ("exudyn_step",), ex_error,
                {"units": "1", "long_name": "the same error for Exudyn (its own model: exact constraints)"},
            ),
            "exudyn_time_s": (
                ("exudyn_step",),
                ex_time,
                {
                    "units": "s",
                    "long_name": f"Exudyn's wall time, median of {wp['repeats']} runs (model build, solve, output)",
                },
            ),
            "time_ratio_at_equal_error": (
                ("compared_method", "dopri5_setting"),
                ratio,
                {
                    "units": "1",
                    "long_name": (
                        "least time of the method to reach the error of linkwork's dopri5 setting, over linkwork"
                        " dopri5's least time to reach it"
                    ),
                    "nan_meaning": "the method did not reach that error within its settings",
                },
            ),
        },
        coords={
            "setting": (
                "setting", np.array(labels, dtype=object), {"units": "1", "long_name": "integrator and tolerance"},
            ),
            "exudyn_step": ("exudyn_step", steps, {"units": "s", "long_name": "Exudyn's fixed step"}),
            "compared_method": (
                "compared_method", np.array(compared, dtype=object),
                {"units": "1", "long_name": "compared method (not `method`: sel's keyword)"},
            ),
            "dopri5_setting": (
                "dopri5_setting", np.array([labels[i] for i in own], dtype=object),
                {"units": "1", "long_name": "linkwork's dopri5 setting"},
            ),
        },
        attrs={
            "title": f"Work-precision side by side: {scene} ({variant}), {wp['cycles']} cycle",
            "reference": f"{wp['reference'][scene]['method']} rtol={wp['reference'][scene]['rtol']:.0e}",
            "scene": scene,
            "variant": variant,
            "decision_threshold": threshold,
            "decision": decision,
            "fastest_scipy": compared[best] if best is not None else "",
        },
    )
    return out, {
        "method": timings["method"],
        "runs": timings["runs"],
        "exudyn_s": dict(zip((f"{s:.0e}" for s in steps), ex_time.tolist(), strict=True)),
    }


def dry_summary(cfg: Mapping[str, Any], dry: Sequence[xr.Dataset]) -> xr.Dataset:
    """Rule study: the claimed orders of the dry scenes on each engine's means (dry_1, dry_2, dry_both of a
    variant), whether every comparison agrees, and how much each engine's own mean moves with its setting."""
    from .adapter import DRY
    from .studies import order_as_claimed

    by = {(d.attrs["variant"], d.attrs["scene"]): d for d in dry}
    variants = [v for v in cfg["variants"] if all((v, s) in by for s in DRY)]
    holds = np.zeros((len(variants), len(QUANTITIES), 2), dtype=bool)
    for i, v in enumerate(variants):
        for q, quantity in enumerate(QUANTITIES):
            for k, index in enumerate((0, -1)):  # linkwork at the pipeline tolerance, Exudyn at its finest step
                holds[i, q, k] = order_as_claimed(
                    np.array([float(by[(v, s)]["mean"].sel(quantity=quantity).values[index]) for s in DRY]), quantity
                )
    exudyn_change = max(
        float(np.max(np.abs(d["mean"].values[-1] - d["mean"].values[-2]) / d["mean"].values[-1])) for d in dry
    )
    linkwork_change = max(
        float(np.max(np.abs(d["mean"].values[1] - d["mean"].values[0]) / d["mean"].values[0])) for d in dry
    )
    return xr.Dataset(
        {
            "order_holds": (
                ("variant", "quantity", "engine"), holds,
                {"units": "1", "long_name": "the claimed order of dry_1, dry_2, dry_both holds on the means"},
            ),
            "all_agree": (
                (), all(bool(d.agree.all()) for d in dry),
                {"units": "1", "long_name": "every dry comparison within its margin"},
            ),
            "exudyn_change": (
                (), exudyn_change,
                {"units": "1", "long_name": "largest relative change of Exudyn's mean between its two steps"},
            ),
            "linkwork_change": (
                (),
                linkwork_change,
                {
                    "units": "1",
                    "long_name": "largest relative change of linkwork's mean from the pipeline to the tight tolerance",
                },
            ),
        },
        coords={
            "variant": ("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "quantity": (
                "quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"},
            ),
            "engine": ("engine", np.array(["linkwork", "Exudyn"], dtype=object), {"units": "1", "long_name": "engine"}),
        },
        attrs={"title": "Clearance paper, dry scenes in both engines: the claims on the means"},
    )
