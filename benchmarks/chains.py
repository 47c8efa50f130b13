"""Benchmark of the mechanical-chain solver (issue: 1e4 frequencies for a 20-element chain <= 0.5 s).

Run: python benchmarks/chains.py [--repeats N]

Method: a chain of 10 springs and 10 masses (20 elements), velocity-driven,
solved by linkwork.engines.chains.solve_network at 1e4 frequencies; wall clock (time.perf_counter),
median of N repeats after a warm-up; with and without the per-frequency singularity check.
Figures go to benchmarks/measured/chains.json.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
from linkwork.engines.chains import GROUND, Element, Network, solve_matrices, solve_network  # noqa: E402
from linkwork.pipeline.timing import median_time  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402

TARGET_S = 0.5


def chain20() -> Network:
    nodes = tuple(f"n{i}" for i in range(11))
    els = []
    for i in range(10):
        els.append(Element(f"k{i}", "spring", nodes[i], nodes[i + 1], 1e5 * (i + 1)))
        els.append(Element(f"m{i}", "mass", nodes[i + 1], GROUND, 1.0 + i))
    return Network(nodes, tuple(els), (), "n0", "velocity")



def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    net, w = chain20(), np.linspace(1.0, 1000.0, 10_000)
    figures = {
        "network_with_singularity_check_s": median_time(lambda: solve_network(net, w), args.repeats),
        "network_without_check_s": median_time(lambda: solve_network(net, w, singular_rcond=0), args.repeats),
        "matrix_route_s": median_time(lambda: solve_matrices(net, w), args.repeats),
        "elements": len(net.elements),
        "frequencies": int(w.size),
        "target_s": TARGET_S,
    }
    for key, value in figures.items():
        print(f"{key}: {value:.4f}" if isinstance(value, float) else f"{key}: {value}")
    write_figures("chains", {**figures, "repeats": args.repeats}, __doc__.split("Method:", 1)[1].split("Figures go")[0])
    if figures["network_with_singularity_check_s"] > TARGET_S:
        sys.exit("the chain benchmark missed its target")


if __name__ == "__main__":
    main()
