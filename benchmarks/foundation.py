"""Benchmarks of the foundation (issue: kinematics, stiffness job, report render).

Run: make bench   (or: python benchmarks/foundation.py [--repeats N])

Method: wall-clock time.perf_counter; each measurement is repeated (after one
warm-up) and the median is reported with min and max.  The stiffness job and the
report render are timed as whole subprocesses in a temporary copy of the project
(imports and Snakemake start-up included), on whatever machine runs the script.
Figures go to benchmarks/measured/foundation.json.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
from linkwork.engines.kinematics import FourBar, four_bar  # noqa: E402
from linkwork.pipeline.timing import median_time  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import project_copy, write_figures  # noqa: E402

TARGETS = {"kinematics_1e6_s": 0.5, "stiffness_job_s": 10.0, "report_render_s": 30.0}


def timed(fn, repeats: int) -> dict[str, float]:
    return {"median": median_time(fn, repeats), "repeats": repeats}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()

    linkage = FourBar(0.015, 0.138, 0.115, 0.170)
    alpha = np.linspace(0.0, 2 * np.pi, 1_000_000)
    figures = {"kinematics_1e6_s": timed(lambda: four_bar(linkage, alpha), args.repeats)}
    print(
        "kinematics, 1e6 crank angles (positions, rates, accelerations):"
        f" {figures['kinematics_1e6_s']['median']:.3f} s",
        flush=True,
    )

    with project_copy() as (root, env):
        run = lambda *cmd: subprocess.run(cmd, cwd=root, env=env, check=True, capture_output=True)  # noqa: E731
        print("building the stiffness report once ...", flush=True)
        run(sys.executable, "-m", "snakemake", "results/reports/stiffness.html", "--cores", "1")
        figures["stiffness_job_s"] = timed(
            lambda: run(
                sys.executable, "-m", "snakemake", "results/stiffness/stiffness.nc", "--cores", "1", "--forcerun",
                "stiffness",
            ),
            args.repeats,
        )
        print(
            f"stiffness rule end to end (snakemake start-up included): {figures['stiffness_job_s']['median']:.2f} s",
            flush=True,
        )
        figures["report_render_s"] = timed(
            lambda: run(
                sys.executable, "workflow/scripts/render_report.py", "reports/stiffness.py", "results/bench.html",
                "--input", "result=results/stiffness/stiffness.nc", "--input",
                "comparison=results/stiffness/comparison.csv", "--input", "findings=results/stiffness/findings.nc",
                "--input", "published=config/published/stiffness.yaml",
            ),
            args.repeats,
        )
        print(f"stiffness report render: {figures['report_render_s']['median']:.2f} s", flush=True)

    for key, limit in TARGETS.items():
        figures[key]["target"] = limit
        figures[key]["ok"] = figures[key]["median"] <= limit
    write_figures("foundation", figures, __doc__.split("Method:", 1)[1].split("Figures go")[0])
    if not all(f["ok"] for f in figures.values() if isinstance(f, dict)):
        sys.exit("a benchmark missed its target")


if __name__ == "__main__":
    main()
