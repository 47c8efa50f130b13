"""Benchmark of the transplanter KED and optimisation (issue: one KED pass over 360 crank positions <= 2 s,
the optimisation <= 60 s).

Run: python benchmarks/transplanter.py [--repeats N]

Method: wall clock (time.perf_counter); the KED pass (quasi-static, the paper's 35-coordinate mesh,
360 crank angles) is the median of N repeats after a warm-up; the dynamic pass (Newmark, the
configured revolutions) likewise; the optimisation (SUMT + SLSQP, as the rule runs it) once.
Figures go to benchmarks/measured/transplanter.json.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import yaml

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
from linkwork.papers.transplanter.adapter import discretisation, material, mechanism  # noqa: E402
from linkwork.papers.transplanter.model import ked  # noqa: E402
from linkwork.papers.transplanter.studies import optim as optim_dataset  # noqa: E402
from linkwork.pipeline.timing import median_time  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402

TARGETS = {"ked_quasi_static_360_s": 2.0, "optimisation_s": 60.0}



def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    section = yaml.safe_load((PROJECT / "config" / "config.yaml").read_text())["transplanter"]
    mech, mat, disc = mechanism(section), material(section), discretisation(section)
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    d = np.array(section["initial_diameters_m"])
    figures = {
        "ked_quasi_static_360_s": median_time(lambda: ked(mech, disc, d, mat, theta), args.repeats),
        "ked_dynamic_360_s": median_time(
            lambda: ked(mech, disc, d, mat, theta, "dynamic", revolutions=section["fe"]["revolutions"]), args.repeats
        ),
    }
    t0 = time.perf_counter()
    optim_dataset(section)
    figures["optimisation_s"] = time.perf_counter() - t0
    for key, value in figures.items():
        print(f"{key}: {value:.3f} s", flush=True)
    write_figures(
        "transplanter", {**figures, "repeats": args.repeats, "targets": TARGETS},
        __doc__.split("Method:", 1)[1].split("Figures go")[0],
    )
    if any(figures[k] > v for k, v in TARGETS.items()):
        sys.exit("a transplanter benchmark missed its target")


if __name__ == "__main__":
    main()
