"""How much the clearance scenes' states depend on the rounding of their start.

Run: python benchmarks/start_rounding.py [--workers 2]   (after `snakemake`: it compares with results/clearance/)

Method: every dynamic clearance scene of every variant is run again by the pipeline's own study
(``papers.clearance.studies.scene``), from starts computed by the engine's generic assembly of the linkage
description (``engines.multibody.assembly.start_state``: Newton's method on the description's constraints) instead of
the paper's closed form (``papers.clearance.fourbar``): the two starts agree to rounding (largest difference of any
state component, printed).  The right-hand side is the same to the bit.  Per scene and start, the state found (period,
transient) and the judged measures (RMS deviation from the ideal, rocker acceleration and crank torque) are compared
with the pipeline's results: a measure moves beyond its error bar when |difference| exceeds the sum of both runs'
numerical error and 95 % interval half-width.  Figures go to benchmarks/measured/start_rounding.json.
"""

from __future__ import annotations

import argparse
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import yaml

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402


def _generic_starts() -> None:
    """Replace the paper's starts by the engine's generic assembly in this process."""
    from linkwork.engines.multibody import assembly
    from linkwork.papers.clearance import fourbar, settling

    def initial_state(p, joints=(), offset=(0.0, 0.0)):
        y0 = assembly.start_state(fourbar.linkage(p, joints, ("contact",) if joints else ()))
        y0[3] += offset[0]
        y0[4] += offset[1]
        return y0

    def offset_start(p, joints, eccentricity, rate):
        names = [fourbar.JOINT_NAMES[j] for j in joints]
        return assembly.start_state(
            fourbar.linkage(p, joints, ("contact",)), dict.fromkeys(names, tuple(eccentricity)),
            dict.fromkeys(names, tuple(rate)),
        )

    fourbar.initial_state, fourbar.offset_start = initial_state, offset_start
    settling.initial_state, settling.offset_start = initial_state, offset_start
    fourbar.run.__globals__["initial_state"] = initial_state


def _one(job: tuple[str, str]) -> dict:
    variant, scene = job
    _generic_starts()
    from linkwork.papers.clearance.studies import scene as scene_study

    section = yaml.safe_load((PROJECT / "config" / "config.yaml").read_text())["clearance"]
    ds = scene_study(section, variant, scene)
    return {
        "variant": variant,
        "scene": scene,
        "period": ds.state_period.values.tolist(),
        "transient": ds.state_transient.values.tolist(),
        "judged_mean": ds.judged_mean.values.tolist(),
        "numerical_error": ds.numerical_error.values.tolist(),
        "half_width": ds.judged_half_width.values.tolist(),
    }


def _start_gap(section) -> float:
    """Largest |generic - paper| over every state component of every start of every dynamic scene (m, rad, m/s,
    rad/s)."""
    from linkwork.engines.multibody import assembly
    from linkwork.papers.clearance import fourbar
    from linkwork.papers.clearance.adapter import parameters, scene_effects

    gap = 0.0
    for variant in section["variants"]:
        for scene in section["scenes"]:
            joints, _ = scene_effects(section, scene)
            if not joints:
                continue
            p = parameters(section, variant, scene)
            c, w = p.clearance, p.crank_speed
            gap = max(
                gap,
                float(
                    np.abs(
                        fourbar.initial_state(p, joints)
                        - assembly.start_state(fourbar.linkage(p, joints, ("contact",)))
                    ).max()
                ),
            )
            for start in section["states"]["starts"]:
                ecc, rate = np.asarray(start["eccentricity"]) * c, np.asarray(start["rate"]) * c * w
                names = [fourbar.JOINT_NAMES[j] for j in joints]
                ours = assembly.start_state(
                    fourbar.linkage(p, joints, ("contact",)), dict.fromkeys(names, tuple(ecc)),
                    dict.fromkeys(names, tuple(rate)),
                )
                gap = max(gap, float(np.abs(fourbar.offset_start(p, joints, ecc, rate) - ours).max()))
    return gap


def main() -> None:
    import xarray as xr

    parser = argparse.ArgumentParser()
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    section = yaml.safe_load((PROJECT / "config" / "config.yaml").read_text())["clearance"]
    jobs = [(v, s) for v in section["variants"] for s, spec in section["scenes"].items() if spec["clearance_joints"]]
    with ProcessPoolExecutor(args.workers) as pool:
        runs = list(pool.map(_one, jobs))
    rows, moved, changed, total = [], 0, 0, 0
    for r in runs:
        base = xr.open_dataset(PROJECT / "results" / "clearance" / r["variant"] / f"{r['scene']}.nc")
        mean, err = np.array(r["judged_mean"]), np.array(r["numerical_error"]) + np.nan_to_num(
            np.array(r["half_width"])
        )
        bar = err + base.numerical_error.values + np.nan_to_num(base.judged_half_width.values)
        diff = np.abs(mean - base.judged_mean.values)
        beyond = diff > bar
        state_changed = [bool(a != b) for a, b in zip(r["period"], base.state_period.values.tolist(), strict=True)]
        total += beyond.size
        moved += int(beyond.sum())
        changed += sum(state_changed)
        rows.append(
            {
                **{k: r[k] for k in ("variant", "scene")},
                "period_paper_start": base.state_period.values.tolist(),
                "period_generic_start": r["period"],
                "measures_beyond_bar": int(beyond.sum()),
                "measures": int(beyond.size),
                "largest_move_over_bar": float(np.nanmax(diff / np.where(bar > 0, bar, np.nan))),
            }
        )
        print(rows[-1], flush=True)
    figures = {"start_gap": _start_gap(section), "scenes": rows, "measures_beyond_bar": moved, "measures": total,
               "starts_with_another_period": changed, "starts": sum(len(r["period"]) for r in runs)}
    write_figures("start_rounding", figures, __doc__.split("Method:", 1)[1].split("Figures go")[0])


if __name__ == "__main__":
    main()
