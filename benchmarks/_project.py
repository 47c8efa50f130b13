"""A temporary copy of the project for benchmarks that run Snakemake (shared by the benchmark scripts)."""

from __future__ import annotations

import contextlib
import os
import shutil
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
COPIED = ("Snakefile", "config", "workflow", "lib", "reports", "profiles")


@contextlib.contextmanager
def project_copy() -> Iterator[tuple[Path, dict[str, str]]]:
    """(root of a fresh copy without results/, environment that runs this Python and the copy's lib)."""
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}", PYTHONPATH=str(root / "lib"))
        for name in COPIED:
            src = PROJECT / name
            if src.is_dir():
                shutil.copytree(src, root / name, ignore=shutil.ignore_patterns("__pycache__"))
            else:
                shutil.copy2(src, root / name)
        yield root, env
