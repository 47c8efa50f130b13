"""Wall clock of `make test` (the command CI runs), from an empty compile cache as on CI's fresh machine.

Run: python benchmarks/tests.py [--repeats N]

Method: `make test` in the project (installed already), whole process timed with time.perf_counter, LINKWORK_CACHE an
empty temporary folder for each run (every kernel compiled, as on a fresh machine); the test count read from pytest's
summary line and the workflow tests' build (the `built` fixture's setup) from its slowest-durations list; the check that
the page shows these figures is deselected (see OWN_CHECK).  The machine's speed is given by a probe: ten million
additions in a pure-Python loop, best of three.  Figures go to benchmarks/measured/tests.json.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402

#: The check that the page shows what this very benchmark writes cannot pass before it has written it (it takes
#: milliseconds; it is left out of the timed run).
OWN_CHECK = "tests/test_pipeline.py::test_readme_measured_figures_are_rendered_from_the_benchmark_files"
BUILD = re.compile(r"([\d.]+)s setup\s+tests/test_workflow\.py::")


def one_run() -> tuple[float, int, float]:
    """(wall clock s, tests passed, the workflow build's setup s) of one `make test` from an empty compile cache."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, LINKWORK_CACHE=cache, PYTEST_ADDOPTS=f"-p no:cacheprovider --deselect {OWN_CHECK}")
        t0 = time.perf_counter()
        done = subprocess.run(["make", "test"], cwd=PROJECT, env=env, capture_output=True, text=True)
        wall = time.perf_counter() - t0
    if done.returncode != 0:
        sys.exit(f"make test failed:\n{done.stdout[-3000:]}\n{done.stderr[-2000:]}")
    passed = int(re.search(r"(\d+) passed", done.stdout)[1])
    build = BUILD.search(done.stdout)
    return wall, passed, float(build[1]) if build else float("nan")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    runs, builds, count = [], [], 0
    for _ in range(args.repeats):
        wall, count, build = one_run()
        runs.append(wall)
        builds.append(build)
        print(f"make test: {count} tests in {wall:.0f} s (workflow build {build:.0f} s)", flush=True)
    figures = {"make_test": {"runs_s": runs, "workflow_build_s": builds, "tests": count}}
    write_figures("tests", figures, __doc__.split("Method:", 1)[1].split("Figures go")[0])


if __name__ == "__main__":
    main()
