"""Faults of the machine, not of the config: a damaged or unusable compile cache.  Each one is either repaired
(a damaged cache entry is compiled again, with one line naming it) or named in one line before any job, and nothing
is ever compiled into lib/."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from test_workflow import copy_project, snakemake

from linkwork import compilecache

PROJECT = Path(__file__).resolve().parents[1]
#: Compiles one function of each module that caches compiled code, and prints a number from each.
COMPILE = """
import numpy as np
from linkwork.engines.multibody import kernels
from linkwork.engines import fem
cs = np.zeros(2)
kernels.body_trig(np.array([0.0, 0.0, 0.5]), cs)
one = np.ones((2, 1, 1))
history = fem.newmark_history(one, one, one, np.ones((2, 1)), [0.0], [0.0], [0.0], 0.01, 3, 0.25, 0.5)
print(round(float(cs[0]), 12), round(float(history[-1, 0]), 12))
"""


def _compile(lib: Path, cache: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(lib), "LINKWORK_CACHE": str(cache)}
    env.pop("NUMBA_CACHE_DIR", None)
    return subprocess.run(
        [sys.executable, "-c", COMPILE], env=env, capture_output=True, text=True, timeout=600, check=True
    )


def _entries(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.suffix in (".nbi", ".nbc"))


def test_compiled_code_is_cached_in_the_cache_folder_never_below_lib(tmp_path):
    lib = tmp_path / "lib"
    shutil.copytree(PROJECT / "lib", lib, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    _compile(lib, tmp_path / "cache")
    assert _entries(tmp_path / "cache" / "numba"), "nothing cached in LINKWORK_CACHE/numba"
    assert not _entries(lib), _entries(lib)


#: Bytes pickle reads as a request for an exabyte (BINBYTES8 with a huge length): it raises MemoryError.
HUGE = b"\x80\x04\x8e\xff\xff\xff\xff\xff\xff\x00\x00"


@pytest.mark.parametrize("damage", ["truncated", "huge"])
def test_a_damaged_cache_entry_is_compiled_again_and_named(tmp_path, damage):
    cache = tmp_path / "cache"
    first = _compile(PROJECT / "lib", cache).stdout
    damaged = _entries(cache)
    assert damaged
    for path in damaged:  # truncated, as by a full disk or a killed write; or bytes pickle reads as a huge request
        path.write_bytes(path.read_bytes()[:10] if damage == "truncated" else HUGE)
    again = _compile(PROJECT / "lib", cache)
    assert again.stdout == first
    named = [line for line in again.stderr.splitlines() if "was unreadable" in line]
    assert named and all(
        line.startswith("linkwork: compile cache entry ") and "compiling it again" in line for line in named
    ), again.stderr
    assert len(named) == len(set(named))
    third = _compile(PROJECT / "lib", cache)  # repaired: read without complaint
    assert third.stdout == first and "unreadable" not in third.stderr


def test_an_unusable_cache_folder_is_named(tmp_path, monkeypatch):
    a_file = tmp_path / "cache.txt"
    a_file.write_text("not a folder")
    monkeypatch.setenv("LINKWORK_CACHE", str(a_file))
    assert (
        compilecache.problem()
        == f"LINKWORK_CACHE={a_file} is a file, not a folder: point LINKWORK_CACHE to a folder (or unset it for"
        " ~/.cache/linkwork)"
    )
    monkeypatch.setenv("LINKWORK_CACHE", str(tmp_path / "new" / "cache"))
    assert compilecache.problem() is None  # created on first use
    monkeypatch.setattr(os, "access", lambda path, mode: False)  # read-only (root may write anywhere: simulated)
    assert "cannot be written" in compilecache.problem() and str(tmp_path) in compilecache.problem()


@pytest.mark.workflow
def test_snakemake_names_an_unusable_cache_folder_before_any_job(tmp_path, monkeypatch):
    root = copy_project(tmp_path / "project")
    a_file = tmp_path / "cache.txt"
    a_file.write_text("not a folder")
    monkeypatch.setenv("LINKWORK_CACHE", str(a_file))
    proc = snakemake(root, "-n", check=False)
    message = proc.stdout + proc.stderr
    assert proc.returncode != 0 and f"linkwork: LINKWORK_CACHE={a_file} is a file" in message, message[-2000:]
    assert "Traceback" not in message and not (root / "results").exists()
