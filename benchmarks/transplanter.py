"""Benchmark of the transplanter KED and optimisation (issue: one KED pass over 360 crank positions <= 2 s,
the optimisation <= 60 s).

Run: python benchmarks/transplanter.py [--repeats N] [--baseline REV] [--rounds K]

Method: wall clock (time.perf_counter); the KED pass (quasi-static, the paper's 35-coordinate mesh,
360 crank angles) is the median of N repeats after a warm-up; the dynamic pass (Newmark, the
configured revolutions) likewise; the optimisation (SUMT + SLSQP, as the rule runs it) once.
With --baseline REV: both KED passes of this tree and of git revision REV (`git archive`), each in a
fresh process with its own lib first on the path, K rounds taken in turn (this tree, then REV), each
round the median of N repeats at diameters drawn within 10 % of the initial ones (what a search or an
optimiser asks for); per tree the median over the rounds, and the ratio of ours to REV's.
Figures go to benchmarks/measured/transplanter.json.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
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



#: One round of both KED passes in a fresh process of the tree whose lib is first on the path: JSON of the medians (s).
ROUND = """
import json, sys
import numpy as np, yaml
from linkwork.papers.transplanter.adapter import discretisation, material, mechanism
from linkwork.papers.transplanter.model import ked
from linkwork.pipeline.timing import median_time
section = yaml.safe_load(open(sys.argv[1]))["transplanter"]
mech, mat, disc = mechanism(section), material(section), discretisation(section)
theta = np.radians(np.arange(0.0, 360.0, 1.0))
d0, rng, revolutions = np.array(section["initial_diameters_m"]), np.random.default_rng(0), section["fe"]["revolutions"]
near = lambda: d0 * rng.uniform(0.9, 1.1, d0.size)
print(json.dumps({
    "quasi_static_s": median_time(lambda: ked(mech, disc, near(), mat, theta), int(sys.argv[2])),
    "dynamic_s": median_time(lambda: ked(mech, disc, near(), mat, theta, "dynamic", revolutions=revolutions),
                             int(sys.argv[2])),
}))
"""


def _round(root: Path, repeats: int) -> dict[str, float]:
    """Both KED passes timed once (``ROUND``) in a fresh process of the tree at ``root``."""
    env = dict(os.environ, PYTHONPATH=str(root / "lib"))
    out = subprocess.run(
        [sys.executable, "-c", ROUND, str(root / "config" / "config.yaml"), str(repeats)], env=env, check=True,
        capture_output=True, text=True,
    ).stdout
    return json.loads(out.strip().splitlines()[-1])


def against(rev: str, rounds: int, repeats: int) -> dict[str, object]:
    """This tree's KED passes against revision ``rev``'s, ``rounds`` rounds in turn: medians and ratios."""
    commit = subprocess.run(
        ["git", "rev-parse", "--short", rev], cwd=PROJECT, check=True, capture_output=True, text=True
    ).stdout.strip()
    ours, theirs = [], []
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        archive = subprocess.run(["git", "archive", commit, "lib", "config"], cwd=PROJECT, check=True,
                                 capture_output=True).stdout
        subprocess.run(["tar", "-x"], cwd=root, input=archive, check=True)
        for _ in range(rounds):
            ours.append(_round(PROJECT, repeats))
            theirs.append(_round(root, repeats))
    out: dict[str, object] = {"revision": commit, "rounds": rounds}
    for key in ("quasi_static_s", "dynamic_s"):
        out[key] = statistics.median(r[key] for r in ours)
        out[f"baseline_{key}"] = statistics.median(r[key] for r in theirs)
        out[f"ratio_{key}"] = statistics.median(a[key] / b[key] for a, b in zip(ours, theirs, strict=True))
        print(f"KED {key}: ours {out[key]:.4f} s, {commit} {out[f'baseline_{key}']:.4f} s, ratio "
              f"{out[f'ratio_{key}']:.2f} (median of {rounds} rounds)", flush=True)
    return out


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--baseline", default="", help="a git revision whose KED passes are timed in turn with ours")
    parser.add_argument("--rounds", type=int, default=5)
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
    if args.baseline:
        figures["baseline"] = against(args.baseline, args.rounds, args.repeats)
    write_figures(
        "transplanter", {**figures, "repeats": args.repeats, "targets": TARGETS},
        __doc__.split("Method:", 1)[1].split("Figures go")[0],
    )
    if any(figures[k] > v for k, v in TARGETS.items()):
        sys.exit("a transplanter benchmark missed its target")


if __name__ == "__main__":
    main()
