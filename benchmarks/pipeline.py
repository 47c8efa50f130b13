"""Benchmark of the whole pipeline: full reproduction (warm and cold compile cache), no-op, a one-key rerun,
the cost of a job before it computes anything, and byte-identical reruns.

Run: python benchmarks/pipeline.py [--full-repeats N] [--noop-repeats N] [--edit-repeats N] [--baseline REV]

Method, in a temporary copy of the project (wall clock of whole `snakemake` processes, time.perf_counter):
1. warm: `snakemake` from an empty results/ and .snakemake/ with the numba cache of this machine as is;
   median of --full-repeats runs;
2. cold: the same once more with LINKWORK_CACHE pointing to an empty folder and no numba cache next to
   the kernels (what a fresh clone meets: every scene structure is compiled);
3. no-op `snakemake` (nothing to do), median of --noop-repeats runs; beside it the same for a one-rule
   workflow with one job (Snakemake's own start-up on this machine: the floor);
4. a one-key edit of a claim threshold (clearance.claims.close_to_ideal_ratio, toggled between two
   values) followed by `snakemake`, median of --edit-repeats runs;
5. job overhead: `snakemake --forcerun stiffness_compare` (a job that computes for about 0.2 s) minus
   the no-op time, median of --noop-repeats runs;
6. `snakemake --forceall` twice: the sha256 of every netCDF and HTML file after each run must agree;
7. with --baseline REV: the warm full reproduction of that git revision (`git archive`), one run after a
   warm-up run that fills its compile cache, on the same machine and interpreter.
Figures go to benchmarks/measured/pipeline.json.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import project_copy, write_figures  # noqa: E402

sys.path.insert(0, str(PROJECT / "lib"))
from linkwork.pipeline.fingerprint import compare, fingerprints  # noqa: E402

TARGETS = {"full_warm_s": 90.0, "full_cold_s": 120.0, "noop_s": 2.0, "claim_edit_s": 15.0}
TRIVIAL = (
    'rule all:\n    input: "x.txt"\nrule x:\n    output: "x.txt"\n    params: cfg={"a": 1}\n    shell: "touch'
    ' {output}"\n'
)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--full-repeats", type=int, default=3)
    parser.add_argument("--noop-repeats", type=int, default=7)
    parser.add_argument("--edit-repeats", type=int, default=3)
    parser.add_argument("--baseline", default="", help="a git revision to time the same way (warm full reproduction)")
    args = parser.parse_args()
    figures: dict[str, object] = {
        "full_repeats": args.full_repeats,
        "noop_repeats": args.noop_repeats,
        "edit_repeats": args.edit_repeats,
    }
    with project_copy() as (root, env), tempfile.TemporaryDirectory() as cold_cache:

        def sm(*extra, where=root, environment=env) -> float:
            t0 = time.perf_counter()
            subprocess.run(
                [sys.executable, "-m", "snakemake", *extra], cwd=where, env=environment, check=True, capture_output=True
            )
            return time.perf_counter() - t0

        def clean() -> None:
            shutil.rmtree(root / "results", ignore_errors=True)
            shutil.rmtree(root / ".snakemake", ignore_errors=True)

        warm = []
        for _ in range(args.full_repeats):
            clean()
            warm.append(sm())
        figures["full_warm_runs_s"] = warm
        figures["full_warm_s"] = statistics.median(warm)
        print(
            f"full reproduction, warm compile cache: median {figures['full_warm_s']:.0f} s"
            f" ({', '.join(f'{x:.0f}' for x in warm)} s)",
            flush=True,
        )

        clean()
        for cache in root.rglob("__pycache__"):
            shutil.rmtree(cache)
        figures["full_cold_s"] = sm(environment={**env, "LINKWORK_CACHE": cold_cache})
        print(f"full reproduction, empty compile cache: {figures['full_cold_s']:.0f} s", flush=True)

        noop = [sm() for _ in range(args.noop_repeats)]
        figures["noop_s"] = statistics.median(noop)
        trivial = Path(tempfile.mkdtemp())
        (trivial / "Snakefile").write_text(TRIVIAL)
        sm("--cores", "1", where=trivial)
        floor = [sm("--cores", "1", where=trivial) for _ in range(args.noop_repeats)]
        figures["noop_floor_s"] = statistics.median(floor)
        shutil.rmtree(trivial)
        print(f"no-op snakemake: median {figures['noop_s']:.2f} s; a one-job workflow's no-op (Snakemake's floor): "
              f"{figures['noop_floor_s']:.2f} s", flush=True)

        config = root / "config/config.yaml"
        text = config.read_text()
        assert "close_to_ideal_ratio: 0.2 " in text
        edits = []
        for k in range(args.edit_repeats):
            config.write_text(
                text.replace(
                    "close_to_ideal_ratio: 0.2 ",
                    "close_to_ideal_ratio: 0.25 " if k % 2 == 0 else "close_to_ideal_ratio: 0.2 ",
                )
            )
            edits.append(sm())
        config.write_text(text)
        sm()
        figures["claim_edit_s"] = statistics.median(edits)
        print(
            "one-key edit of clearance.claims.close_to_ideal_ratio, then snakemake: median"
            f" {figures['claim_edit_s']:.1f} s",
            flush=True,
        )

        job = [
            sm("results/stiffness/comparison.csv", "--forcerun", "stiffness_compare", "--cores", "1")
            for _ in range(args.noop_repeats)
        ]
        figures["small_job_s"] = statistics.median(job)
        figures["job_overhead_s"] = figures["small_job_s"] - figures["noop_s"]
        print(f"one small job (stiffness_compare) end to end: median {figures['small_job_s']:.2f} s, i.e. "
              f"{figures['job_overhead_s']:.2f} s beyond a no-op", flush=True)

        sm("--forceall")
        first = fingerprints(root)
        sm("--forceall")
        split = compare(first, fingerprints(root))
        figures.update(
            identical_files=len(split["identical"]), compared_files=len(first),
            differing=split["differing"] + split["missing"], measured=split["measured"],
        )
        print(
            f"byte-identical reruns: {len(split['identical'])} of {len(first)} netCDF and HTML files identical",
            flush=True,
        )
        for name in split["measured"]:
            print(f"  differs (shows wall times, declared in linkwork.pipeline.fingerprint): {name}")
        for name in split["differing"] + split["missing"]:
            print(f"  differs: {name}")
    if args.baseline:
        figures["baseline"] = baseline(args.baseline)
    figures["targets"] = TARGETS
    write_figures("pipeline", figures, __doc__.split("Method,", 1)[1].split("Figures go")[0])
    missed = [k for k, limit in TARGETS.items() if figures[k] > limit]
    if missed:
        print(f"missed targets on this machine: {', '.join(missed)}")


def baseline(rev: str) -> dict[str, object]:
    """The warm full reproduction of git revision ``rev`` (one warm-up run, then one timed run)."""
    commit = subprocess.run(
        ["git", "rev-parse", "--short", rev], cwd=PROJECT, check=True, capture_output=True, text=True
    ).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        archive = subprocess.run(["git", "archive", commit], cwd=PROJECT, check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x"], cwd=root, input=archive, check=True)
        env = dict(
            os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}",
            PYTHONPATH=str(root / "lib"),
        )
        runs = []
        for _ in range(2):
            shutil.rmtree(root / "results", ignore_errors=True)
            shutil.rmtree(root / ".snakemake", ignore_errors=True)
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "snakemake"], cwd=root, env=env, check=True, capture_output=True)
            runs.append(time.perf_counter() - t0)
    print(
        f"baseline {commit}: full reproduction, warm compile cache: {runs[1]:.0f} s (warm-up run {runs[0]:.0f} s)",
        flush=True,
    )
    return {"revision": commit, "full_warm_s": runs[1], "warm_up_run_s": runs[0], "recorded": recorded(commit)}


def recorded(commit: str) -> dict[str, object] | None:
    """What the baseline revision's own benchmark file says of its warm full reproduction (the machine of that day:
    machines of one name differ by two to three times between days), or None where it holds no such figure."""
    import json

    shown = subprocess.run(
        ["git", "show", f"{commit}:benchmarks/measured/pipeline.json"], cwd=PROJECT, capture_output=True, text=True
    )
    if shown.returncode != 0:
        return None
    figures = json.loads(shown.stdout)
    if "full_warm_s" not in figures:
        return None
    return {
        "full_warm_s": figures["full_warm_s"],
        "runs": len(figures.get("full_warm_runs_s", [figures["full_warm_s"]])),
        "date": figures.get("machine", {}).get("date", ""),
    }


if __name__ == "__main__":
    main()
