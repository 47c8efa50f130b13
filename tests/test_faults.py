"""Faults of the machine, not of the config: a damaged or unusable compile cache.  Each one is either repaired
(a damaged cache entry is compiled again, with one line naming it) or named in one line before any job, and nothing
is ever compiled into lib/."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
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


#: ``COMPILE``, then numba's own counts of compiles (misses) and cache loads (hits) of the two functions it compiled.
COUNTS = COMPILE + """
stats = [kernels.body_trig.stats, fem._newmark_compiled.stats]
print(sum(sum(s.cache_misses.values()) for s in stats), sum(sum(s.cache_hits.values()) for s in stats))
"""


def _counts(lib: Path, cache: Path) -> tuple[str, int, int]:
    env = {**os.environ, "PYTHONPATH": str(lib), "LINKWORK_CACHE": str(cache)}
    env.pop("NUMBA_CACHE_DIR", None)
    done = subprocess.run(
        [sys.executable, "-c", COUNTS], env=env, capture_output=True, text=True, timeout=600, check=True
    )
    values, counts = done.stdout.splitlines()
    misses, hits = (int(x) for x in counts.split())
    return values, misses, hits


def test_a_copy_of_lib_elsewhere_loads_what_another_copy_compiled(tmp_path):
    """Compiled code is filed by its source's content, not its folder: a second copy of lib in another folder (a
    clone, a test's or a benchmark's copy) loads both functions from the cache instead of compiling them (numba's
    counts) and computes the same; a copy whose source differs compiles its own."""
    copies = [tmp_path / name / "lib" for name in ("first", "second", "edited")]
    for lib in copies:
        shutil.copytree(PROJECT / "lib", lib, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    fem = copies[2] / "linkwork/engines/fem.py"
    fem.write_text(fem.read_text() + "\n# edited\n")
    first, second, edited = (_counts(lib, tmp_path / "cache") for lib in copies)
    assert first[1:] == (2, 0) and second[1:] == (0, 2), (first, second)
    assert edited[1:] == (1, 1), edited  # fem.py differs: its function compiled again; kernels.py loaded
    assert first[0] == second[0] == edited[0]


#: Compiles the right-hand side of a one-body scene (a driven crank under gravity) and prints its module's name and the
#: driver's torque, which reads the kernels' cos and sin of the crank's angle.
CRANK_SCENE = """
import numpy as np
from linkwork.engines.multibody import describe, model
crank = {
    "bodies": {"crank": {"mass_kg": 0.4, "inertia_kg_m2": 1.0e-3, "points": {"O": [-0.05, 0.0], "A": [0.05, 0.0]},
                         "angle_guess_deg": 30}},
    "ground": {"O2": [0.0, 0.0]},
    "joints": {"O2": {"journal": "crank.O", "bearing": "ground.O2"}},
    "driver": {"body": "crank", "speed_rad_s": 20.0, "start_angle_deg": 30},
    "output": "crank",
}
linkage = describe.from_config(crank, "linkages.crank")
scene = model.compile_scene(linkage, True)
diag = np.zeros(scene.N_DIAG)
scene.rhs(0.0, np.full(scene.NY, 0.1), model.pack(linkage)[0], np.zeros(1), np.zeros(8, dtype=np.int64), diag)
print(scene.__name__, repr(float(diag[1])))
"""


def _scene(lib: Path, cache: Path) -> tuple[str, float]:
    env = {**os.environ, "PYTHONPATH": str(lib), "LINKWORK_CACHE": str(cache)}
    env.pop("NUMBA_CACHE_DIR", None)
    done = subprocess.run(
        [sys.executable, "-c", CRANK_SCENE], env=env, capture_output=True, text=True, timeout=600, check=True
    )
    name, torque = done.stdout.split()
    return name, float(torque)


def test_an_edited_kernel_reaches_a_scene_compiled_before_the_edit(tmp_path):
    """numba checks a cached function against its own file only: a generated scene compiled before an edit of
    kernels.py must not keep the old kernels.  After the edit, the scene compiled with the cache of the unedited
    kernels is a new module and computes what a compile from an empty cache computes."""
    lib = tmp_path / "lib"
    shutil.copytree(PROJECT / "lib", lib, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    before = _scene(lib, tmp_path / "cache")
    kernels = lib / "linkwork/engines/multibody/kernels.py"
    line = "        cs[2 * b] = np.cos(q[3 * b + 2])"
    assert line in kernels.read_text()
    kernels.write_text(kernels.read_text().replace(line, "        cs[2 * b] = 2.0 * np.cos(q[3 * b + 2])"))
    after = _scene(lib, tmp_path / "cache")
    assert after[0] != before[0] and after[1] != before[1], (before, after)
    assert after == _scene(lib, tmp_path / "fresh cache")


@pytest.mark.parametrize("damage", ["text", "bytecode"])
def test_a_generated_module_that_does_not_match_its_key_is_rebuilt_never_imported(tmp_path, damage):
    """The compile cache's scene module, once compiled, is given code that writes a file: prepended to its text, or as
    a bytecode file beside it stamped with the module's own time and size (Python's import would take it for the
    module's).  The next run writes the module anew from its source and runs that source: the file is not written,
    the module's text is its source again, and the scene computes what it did."""
    cache = tmp_path / "cache"
    first = _scene(PROJECT / "lib", cache)
    module = cache / "multibody" / f"{first[0]}.py"
    source = module.read_text()
    marker = tmp_path / "pwned.txt"
    code = f"open({str(marker)!r}, 'w').write('pwned')\n"
    if damage == "text":
        module.write_text(code + source)
    else:
        import importlib.util
        from importlib._bootstrap_external import _code_to_timestamp_pyc

        stat = module.stat()
        pyc = Path(importlib.util.cache_from_source(str(module)))
        pyc.parent.mkdir(exist_ok=True)
        bytecode = compile(code + source, str(module), "exec")
        pyc.write_bytes(_code_to_timestamp_pyc(bytecode, stat.st_mtime, stat.st_size))
    assert _scene(PROJECT / "lib", cache) == first
    assert not marker.exists() and module.read_text() == source


CRANK_RUN = CRANK_SCENE.split("scene = model.compile_scene")[0] + """
import json, sys, time
from pathlib import Path
from linkwork.engines.multibody.simulate import Run
run = Run(linkage, True, {"method": "dop853", "rtol": 1e-8, "atol": 1e-11, "first_step_s": 1e-6, "max_step_s": 1e-3})
while not Path(sys.argv[1]).exists():  # both processes start together
    time.sleep(0.01)
ys, _ = run.advance(np.linspace(0.0, 0.01, 3))
from linkwork.engines.multibody import integrators
compiled = (run.module.rhs_into, integrators.dop853)  # the scene's right-hand side and the integrator
print(json.dumps([sum(sum(f.stats.cache_misses.values()) for f in compiled),
                  sum(sum(f.stats.cache_hits.values()) for f in compiled), [len(f.overloads) for f in compiled],
                  ys[-1].tolist()]))
"""


def test_two_jobs_of_one_scene_type_compile_it_once(tmp_path):
    """Two processes integrate the same scene type at the same moment from an empty cache: one compiles the scene's
    right-hand side and the integrator, the other waits and loads both from the cache (numba's own counts), and both
    compute the same."""
    env = {**os.environ, "PYTHONPATH": str(PROJECT / "lib"), "LINKWORK_CACHE": str(tmp_path / "cache")}
    env.pop("NUMBA_CACHE_DIR", None)
    go = tmp_path / "go"
    procs = [
        subprocess.Popen([sys.executable, "-c", CRANK_RUN, str(go)], env=env, stdout=subprocess.PIPE, text=True)
        for _ in range(2)
    ]
    time.sleep(5.0)  # both past their imports and waiting
    go.touch()
    out = [json.loads(p.communicate(timeout=600)[0]) for p in procs]
    assert all(p.returncode == 0 for p in procs)
    assert sorted((misses, hits) for misses, hits, _, _ in out) == [(0, 2), (2, 0)], out
    assert all(overloads == [1, 1] for _, _, overloads, _ in out)  # the call ran what was compiled for it
    assert out[0][3] == out[1][3]


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


@pytest.mark.parametrize("damage", ["truncated", "folder"])
def test_a_damaged_final_result_that_no_job_reads_is_named_before_planning(tmp_path, damage):
    """A linkage's result is read by no job, so no job would ever verify it: a truncated file (its checksum beside it no
    longer matches) or a folder in its place is named in one line, with its cure, before any job."""
    from linkwork.pipeline.results import write_text

    root = copy_project(tmp_path / "project")
    target = root / "results" / "linkages" / "watt_six_bar_worn_pin.nc"
    target.parent.mkdir(parents=True)
    write_text("a result of 64 characters, standing in for the linkage's netCDF", target)  # with its checksum
    if damage == "truncated":
        target.write_text("a result of 64 char")
        cure = f"rm {target} && snakemake"
    else:
        target.unlink()
        target.mkdir()
        cure = f"rm -r {target}"
    proc = snakemake(root, "-n", check=False)
    message = proc.stdout + proc.stderr
    assert proc.returncode != 0 and cure in message and f"linkwork: {target}" in message, message[-2000:]
    assert "Traceback" not in message


@pytest.mark.parametrize("part", ["multibody", "locks", "numba"])
def test_a_file_in_place_of_a_compile_cache_folder_is_named_before_any_job(tmp_path, monkeypatch, part):
    """A file where the compile cache keeps one of its folders (the generated scene modules, the locks, numba's
    entries) stopped a job with some 70 lines of traceback: now one line before any job names it and its cure."""
    root = copy_project(tmp_path / "project")
    cache = tmp_path / "cache"
    cache.mkdir()
    (cache / part).write_text("not a folder")
    monkeypatch.setenv("LINKWORK_CACHE", str(cache))
    proc = snakemake(root, "-n", check=False)
    message = proc.stdout + proc.stderr
    assert proc.returncode != 0 and f"rm {cache / part}" in message, message[-2000:]
    assert "Traceback" not in message and not (root / "results").exists()
