"""Which outputs a rerun must repeat to the byte, and their fingerprints.

Every netCDF file and every rendered report is a function of the config, the code and the published
numbers, so a rerun on any machine (locally, on a cluster) must write the same bytes. The one exception is
declared here: the reports in ``MEASURED_REPORTS`` show wall times measured during the run (the
``*timings.json`` side files), which no rerun repeats.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

# Reports that show wall-clock measurements; every other report reads deterministic results only.
MEASURED_REPORTS = ("accuracy",)


def fingerprints(root: Path) -> dict[str, str]:
    """sha256 of every netCDF file under ``root/results`` and every report in ``root/results/reports``,
    keyed by the path relative to ``root``."""
    files = sorted([*(root / "results").rglob("*.nc"), *(root / "results" / "reports").glob("*.html")])
    return {str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest() for p in files}


def is_measured(name: str) -> bool:
    """Whether a fingerprinted path is a report that shows wall times (allowed to differ between runs)."""
    path = Path(name)
    return path.parent.name == "reports" and path.suffix == ".html" and path.stem in MEASURED_REPORTS


def compare(first: dict[str, str], second: dict[str, str]) -> dict[str, list[str]]:
    """Split two fingerprint sets into 'identical', 'measured' (differ, and may), 'differing' (differ, and
    must not) and 'missing' (in one set only)."""
    out: dict[str, list[str]] = {"identical": [], "measured": [], "differing": [], "missing": []}
    for name in sorted(set(first) | set(second)):
        if name not in first or name not in second:
            out["missing"].append(name)
        elif first[name] == second[name]:
            out["identical"].append(name)
        else:
            out["measured" if is_measured(name) else "differing"].append(name)
    return out
