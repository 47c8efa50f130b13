"""Wall clock of the test suite, per selection, as `make test` runs it (after the install).

Run: python benchmarks/tests.py [--repeats N]

Method: `python -m pytest -q -p no:cacheprovider -m <selection>` in the project, whole process timed with
time.perf_counter; the numba compile cache as it is on this machine; the test count read from pytest's summary line; the
README-rendering check of these figures is deselected (see OWN_CHECK).  Figures go to benchmarks/measured/tests.json.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import time
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402

SELECTIONS = ("not workflow", "workflow")
#: The check that the README shows what this very benchmark writes cannot pass before it has written it (it takes
#: milliseconds; it is left out of the timed run).
OWN_CHECK = "tests/test_pipeline.py::test_readme_measured_figures_are_rendered_from_the_benchmark_files"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    suites = {}
    for selection in SELECTIONS:
        runs, count = [], 0
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            done = subprocess.run(
                [
                    sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-m", selection, "--deselect",
                    OWN_CHECK,
                ],
                cwd=PROJECT,
                capture_output=True,
                text=True,
            )
            runs.append(time.perf_counter() - t0)
            if done.returncode != 0:
                sys.exit(f"pytest -m {selection!r} failed:\n{done.stdout[-3000:]}")
            count = int(re.search(r"(\d+) passed", done.stdout)[1])
        suites[f"pytest -m '{selection}'"] = {"runs_s": runs, "tests": count}
        print(f"pytest -m {selection!r}: {count} tests, {', '.join(f'{r:.0f}' for r in runs)} s", flush=True)
    write_figures("tests", {"suites": suites}, __doc__.split("Method:", 1)[1].split("Figures go")[0])


if __name__ == "__main__":
    main()
