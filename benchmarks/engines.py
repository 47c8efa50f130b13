"""Two engines side by side on the same dry scene, in one run: linkwork's compiled DOP853 and Exudyn's generalized-alpha
(Newmark, index 2) with its native contact, error against one reference and the time per simulated second, in the
reporting form of the IFToMM benchmark library (error, CPU time, wall time, hardware).

Run: python benchmarks/engines.py [--repeats 5]

Method: the clearance paper's four-bar, slender links, joint 2 in clearance with contact only (no friction: the two
engines' friction laws differ below full slip, so without it they solve the same model; Exudyn's contact parameters
from ``exudyn_route.native_contact``), gravity, from the dead point with the journal centred, over the first
``clearance.work_precision.dry_error_window_cycles`` of a crank turn (the first impacts, before the response's
sensitivity to the start takes over).  Error: the largest |rocker acceleration - reference| over the window, relative
to the reference's largest |value|, the reference being linkwork's DOP853 at rtol 1e-13 (its own error: the
difference to rtol 1e-12, printed).  Our ideal joints are Baumgarte-stabilised, Exudyn's exact: the drift is below
1e-12 m.  Times: the median of --repeats runs of the integration alone (time.perf_counter for wall, time.process_time
for CPU; Exudyn's SolveDynamic, our compiled integrator call), compilation and model building excluded, one process
on an otherwise idle machine; per simulated second = time / the window's duration.  At equal error: for each
linkwork setting, the least CPU time of an Exudyn step that is at least as accurate, as a multiple of linkwork's
(none where no measured step is).  Figures go to benchmarks/measured/engines.json.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import yaml

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402

RTOLS = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)
STEPS = (4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6, 6.25e-7, 3.125e-7)


def _ours(lk, t, rtol, repeats):
    """(rocker acceleration at t, median wall s, median CPU s) of linkwork's compiled DOP853 at rtol."""
    from linkwork.engines.multibody.simulate import Run

    integ = {"method": "dop853", "rtol": rtol, "atol": rtol * 1e-3, "first_step_s": 1e-7, "max_step_s": 1e-3}
    walls, cpus, out = [], [], None
    for k in range(repeats + 1):  # the first call compiles nothing new but warms the caches: not timed
        run = Run(lk, True, integ)
        w, c = time.perf_counter(), time.process_time()
        _, diags = run.advance(t)
        w, c = time.perf_counter() - w, time.process_time() - c
        if k:
            walls.append(w)
            cpus.append(c)
        out = diags[:, 0]
    return out, statistics.median(walls), statistics.median(cpus)


def _exudyn(lk, t, step, repeats):
    """(rocker acceleration at t, median wall s, median CPU s) of Exudyn at the fixed step."""
    from linkwork.engines.multibody.exudyn_route import run

    walls, cpus, out = [], [], None
    for _ in range(repeats):
        r = run(lk, float(t[-1]), step, 1e-12, float(t[1] - t[0]), True, float("inf"))
        walls.append(r["wall_s"])
        cpus.append(r["cpu_s"])
        n = min(r["t"].size, t.size)
        out = np.interp(t, r["t"][:n], r["output_acceleration"][:n])
        version = r["version"]
    return out, statistics.median(walls), statistics.median(cpus), version


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    from linkwork.engines.multibody.simulate import Run
    from linkwork.papers.clearance import fourbar
    from linkwork.papers.clearance.adapter import parameters

    section = yaml.safe_load((PROJECT / "config" / "config.yaml").read_text())["clearance"]
    p = parameters(section, "slender", "dry_2")
    lk = fourbar.linkage(p, (2,), ("contact",))
    window = section["work_precision"]["dry_error_window_cycles"] * 2 * np.pi / p.crank_speed
    t = np.linspace(0.0, window, 289)
    ref = {}
    for rtol in (1e-12, 1e-13):
        integ = {"method": "dop853", "rtol": rtol, "atol": rtol * 1e-3, "first_step_s": 1e-8, "max_step_s": 1e-4}
        ref[rtol] = Run(lk, True, integ).advance(t)[1][:, 0]
    scale = np.abs(ref[1e-13]).max()
    ref_error = float(np.abs(ref[1e-12] - ref[1e-13]).max() / scale)
    rows = {"linkwork": [], "exudyn": []}
    for rtol in RTOLS:
        acc, wall, cpu = _ours(lk, t, rtol, args.repeats)
        rows["linkwork"].append(
            {
                "setting": f"dop853 rtol {rtol:.0e}",
                "error": float(np.abs(acc - ref[1e-13]).max() / scale),
                "wall_s_per_simulated_s": wall / window,
                "cpu_s_per_simulated_s": cpu / window,
            }
        )
        print(rows["linkwork"][-1], flush=True)
    version = ""
    for step in STEPS:
        acc, wall, cpu, version = _exudyn(lk, t, step, args.repeats)
        rows["exudyn"].append({"setting": f"step {step:.1e} s", "error": float(np.abs(acc - ref[1e-13]).max() / scale),
                               "wall_s_per_simulated_s": wall / window, "cpu_s_per_simulated_s": cpu / window})
        print(rows["exudyn"][-1], flush=True)
    ex_err = np.array([r["error"] for r in rows["exudyn"]])
    ex_time = np.array([r["cpu_s_per_simulated_s"] for r in rows["exudyn"]])
    ratios = []
    for r in rows["linkwork"]:
        ok = ex_err <= r["error"]
        if ok.any():
            ratios.append(float(ex_time[ok].min() / r["cpu_s_per_simulated_s"]))
        else:  # no measured Exudyn step is that accurate
            ratios.append(float("nan"))
    figures = {"engines": rows, "reference_error": ref_error, "window_s": window, "exudyn_version": version,
               "cpu_ratio_at_equal_error": ratios}
    write_figures("engines", figures, __doc__.split("Method:", 1)[1].split("Figures go")[0])


if __name__ == "__main__":
    main()
