"""Peak memory and wall time of every job of the full reproduction, per rule: the figures behind the
cluster profile's resource requests (profiles/slurm/config.yaml, set-resources).

Method: in a temporary copy of the project with an empty compile cache (as a fresh clone), `snakemake`
runs the whole DAG with a `sitecustomize` on PYTHONPATH that, when a job's process exits, records the
rule, the process's peak resident memory (getrusage ru_maxrss of the process and of its waited-for
children) and its wall time from interpreter start to exit (time.perf_counter). Per rule the maximum over
its jobs is kept. Figures go to benchmarks/measured/job_resources.json.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import project_copy, write_figures  # noqa: E402

HOOK = """
import atexit, json, os, resource, sys, time
_start = time.perf_counter()
_main = sys.modules.get("__main__")  # the script's module: IPython (the report renderer) later replaces the entry

def _record():
    job = getattr(_main, "snakemake", None)
    if job is None:
        return
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    rss_kb = max(own.ru_maxrss, children.ru_maxrss)
    row = {"rule": job.rule, "rss_mb": rss_kb / 1024, "wall_s": time.perf_counter() - _start}
    with open(os.path.join(os.environ["LINKWORK_RESOURCES_DIR"], f"{os.getpid()}.json"), "w") as f:
        json.dump(row, f)

atexit.register(_record)
"""


def main() -> None:
    with project_copy() as (root, env), tempfile.TemporaryDirectory() as hook, tempfile.TemporaryDirectory() as rows, \
            tempfile.TemporaryDirectory() as cache:
        Path(hook, "sitecustomize.py").write_text(HOOK)
        env = {
            **env,
            "PYTHONPATH": f"{hook}:{env['PYTHONPATH']}",
            "LINKWORK_RESOURCES_DIR": rows,
            "LINKWORK_CACHE": cache,
        }
        print("job_resources: the full reproduction with a per-job recorder ...", flush=True)
        subprocess.run([sys.executable, "-m", "snakemake", "--quiet", "rules"], cwd=root, env=env, check=True)
        per_rule: dict[str, dict[str, float]] = {}
        for path in Path(rows).glob("*.json"):
            row = json.loads(path.read_text())
            entry = per_rule.setdefault(row["rule"], {"jobs": 0, "max_rss_mb": 0.0, "max_wall_s": 0.0})
            entry["jobs"] += 1
            entry["max_rss_mb"] = max(entry["max_rss_mb"], row["rss_mb"])
            entry["max_wall_s"] = max(entry["max_wall_s"], row["wall_s"])
    for rule, entry in sorted(per_rule.items()):
        print(
            f"  {rule:32s} {entry['jobs']:3d} jobs  peak {entry['max_rss_mb']:7.0f} MB  longest"
            f" {entry['max_wall_s']:6.1f} s"
        )
    write_figures(
        "job_resources", {"rules": dict(sorted(per_rule.items()))},
        __doc__.split("Method:", 1)[1].split("Figures go")[0],
    )


if __name__ == "__main__":
    main()
