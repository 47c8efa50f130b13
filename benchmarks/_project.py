"""Shared by the benchmark scripts: a temporary copy of the project for benchmarks that run Snakemake, and
where the measured figures go (benchmarks/measured/<name>.json, committed; the README's measured figures
are rendered from them by benchmarks/readme.py)."""

from __future__ import annotations

import contextlib
import os
import shutil
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
MEASURED = PROJECT / "benchmarks" / "measured"
COPIED = ("Snakefile", "config", "workflow", "lib", "reports", "profiles")


@contextlib.contextmanager
def project_copy() -> Iterator[tuple[Path, dict[str, str]]]:
    """(root of a fresh copy without results/, environment that runs this Python and the copy's lib)."""
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        env = dict(
            os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}",
            PYTHONPATH=str(root / "lib"),
        )
        for name in COPIED:
            src = PROJECT / name
            if src.is_dir():
                shutil.copytree(src, root / name, ignore=shutil.ignore_patterns("__pycache__"))
            else:
                shutil.copy2(src, root / name)
        yield root, env


def speed_probe_s() -> float:
    """Seconds for ten million additions in a pure-Python loop (best of three): how fast this machine is today, so
    that figures taken on different days (machines of one name differ by two to three times) can be compared."""
    import time

    best = float("inf")
    for _ in range(3):
        t0, total = time.perf_counter(), 0
        for i in range(10_000_000):
            total += i
        best = min(best, time.perf_counter() - t0)
    return best


#: The import probe's modules: what every job of the pipeline imports before it computes anything.
PROBE_IMPORTS = "import numpy, scipy.optimize, xarray, numba"


def import_probe_s() -> float:
    """Seconds for a fresh interpreter to import numpy, scipy.optimize, xarray and numba (median of three): the
    start-up every job pays, which a tight loop (``speed_probe_s``) does not exercise (many files read, large code
    run once), so that the two probes together say what kind of machine a figure came from."""
    import statistics
    import subprocess
    import time

    runs = []
    for _ in range(3):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", PROBE_IMPORTS], check=True)
        runs.append(time.perf_counter() - t0)
    return statistics.median(runs)


def machine() -> dict[str, object]:
    """What the figures were measured on: cores, CPU model, Python, date (UTC), the two speed probes (s)."""
    import datetime
    import platform

    model = ""
    with contextlib.suppress(OSError):
        model = next(
            (
                line.split(":", 1)[1].strip()
                for line in Path("/proc/cpuinfo").read_text().splitlines()
                if line.startswith("model name")
            ),
            "",
        )
    return {
        "cpu_count": os.cpu_count(),
        "cpu_model": model or platform.processor(),
        "python": platform.python_version(),
        "date": datetime.datetime.now(datetime.timezone.utc).date().isoformat(),
        "speed_probe_s": speed_probe_s(),
        "import_probe_s": import_probe_s(),
    }


def write_figures(name: str, figures: dict[str, object], method: str) -> Path:
    """Write a benchmark's figures with its method and the machine to benchmarks/measured/<name>.json."""
    import json

    MEASURED.mkdir(parents=True, exist_ok=True)
    out = MEASURED / f"{name}.json"
    tmp = out.with_suffix(".json.tmp")
    tmp.write_text(json.dumps({"machine": machine(), "method": " ".join(method.split()), **figures}, indent=2) + "\n")
    tmp.replace(out)
    print(f"wrote {out.relative_to(PROJECT)}", flush=True)
    return out
