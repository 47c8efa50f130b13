"""Benchmark of the whole pipeline: full reproduction time, no-op time, byte-identical reruns.

Run: python benchmarks/pipeline.py [--noop-repeats N]

Method, in a temporary copy of the project (results/ empty, the numba cache of this machine as is):
1. `snakemake` from an empty results/ (and no .snakemake/), median of --full-repeats runs;
2. a no-op `snakemake` (nothing to do), median of N runs;
3. `snakemake --forceall` twice; the sha256 of every .nc file after each run must agree
   (no timestamps or host names inside; timings live in side files).
Figures go to results/benchmarks/pipeline.json.  Targets: full <= 5 min, no-op <= 5 s.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import project_copy  # noqa: E402

TARGETS = {"full_s": 300.0, "noop_s": 5.0}


def digests(root: Path) -> dict[str, str]:
    return {str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted((root / "results").rglob("*.nc"))}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--noop-repeats", type=int, default=5)
    parser.add_argument("--full-repeats", type=int, default=3)
    args = parser.parse_args()
    with project_copy() as (root, env):

        def sm(*extra):
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "snakemake", *extra], cwd=root, env=env, check=True, capture_output=True)
            return time.perf_counter() - t0

        fulls = []
        for _ in range(args.full_repeats):
            shutil.rmtree(root / "results", ignore_errors=True)
            shutil.rmtree(root / ".snakemake", ignore_errors=True)
            fulls.append(sm())
        full = statistics.median(fulls)
        print(f"full reproduction from an empty results/: median {full:.1f} s over {len(fulls)} runs "
              f"({', '.join(f'{x:.0f}' for x in fulls)} s; target {TARGETS['full_s']:.0f} s)", flush=True)
        noop = statistics.median(sm() for _ in range(args.noop_repeats))
        print(f"no-op snakemake: median {noop:.2f} s over {args.noop_repeats} runs (target {TARGETS['noop_s']:.0f} s)", flush=True)
        sm("--forceall")
        first = digests(root)
        sm("--forceall")
        second = digests(root)
        differing = sorted(k for k in first if first[k] != second.get(k))
        print(f"byte-identical reruns: {len(first) - len(differing)} of {len(first)} netCDF files identical", flush=True)
        for name in differing:
            print(f"  differs: {name}")
    figures = {"full_s": full, "noop_s": noop, "netcdf_files": len(first), "differing": differing, "cpu_count": os.cpu_count()}
    out = PROJECT / "results" / "benchmarks" / "pipeline.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(figures, indent=2))
    if differing or full > TARGETS["full_s"] or noop > TARGETS["noop_s"]:
        sys.exit("a pipeline benchmark missed its target")


if __name__ == "__main__":
    main()
