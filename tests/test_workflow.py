"""The Snakemake workflow on temporary copies of the project: real runs, dry runs, reruns, bad input."""

import hashlib
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from conftest import PROJECT

pytestmark = pytest.mark.workflow

COPIED = ["Snakefile", "config", "workflow", "lib", "reports", "profiles"]
OUTPUTS = [
    "results/stiffness/stiffness.nc",
    "results/reports/stiffness.html",
    "results/beatup/sixbar.nc",
    "results/beatup/window.nc",
    "results/reports/beatup.html",
    "results/heald/chain.nc",
    "results/reports/heald.html",
    "results/transplanter/ked.nc",
    "results/transplanter/optim.nc",
    "results/reports/transplanter.html",
    "results/clearance/slender/dry_both.nc",
    "results/clearance/claims.nc",
    "results/reports/clearance.html",
    "results/accuracy/summary.nc",
    "results/reports/accuracy.html",
    "results/reports/index.html",
]
ALL_JOBS = {
    "all": 1,
    "stiffness": 1,
    "stiffness_compare": 1,
    "beatup_sixbar": 1,
    "beatup_window": 1,
    "beatup_accuracy": 1,
    "beatup_compare": 1,
    "heald_chain": 1,
    "heald_accuracy": 1,
    "heald_compare": 1,
    "transplanter_optim": 1,
    "transplanter_ked": 1,
    "transplanter_at_published": 1,
    "transplanter_accuracy": 1,
    "transplanter_compare": 1,
    "clearance_scene": 14,
    "clearance_scene_tight": 12,
    "clearance_claims": 1,
    "clearance_work_precision": 1,
    "clearance_compare": 1,
    "accuracy_summary": 1,
    "sweep_point": 15,
    "sweep_gather": 2,
    "report": 7,
    "index": 1,
}
STIFFNESS_JOBS = {"all": 1, "stiffness": 1, "stiffness_compare": 1, "report": 2, "accuracy_summary": 1, "index": 1}
BEATUP_JOBS = {"all": 1, "beatup_sixbar": 1, "beatup_window": 1, "beatup_accuracy": 1, "beatup_compare": 1, "report": 2, "accuracy_summary": 1, "index": 1}
TRANSPLANTER_JOBS = {"all": 1, "transplanter_optim": 1, "transplanter_ked": 1, "transplanter_at_published": 1,
                     "transplanter_accuracy": 1, "transplanter_compare": 1, "report": 2, "accuracy_summary": 1, "index": 1}
CLEARANCE_JOBS = {"all": 1, "clearance_scene": 14, "clearance_scene_tight": 12, "clearance_claims": 1,
                  "clearance_work_precision": 1, "clearance_compare": 1, "report": 3, "accuracy_summary": 1,
                  "sweep_point": 6, "sweep_gather": 1, "index": 1}
HEALD_JOBS = {"all": 1, "heald_chain": 1, "heald_accuracy": 1, "heald_compare": 1, "report": 3, "accuracy_summary": 1,
              "sweep_point": 9, "sweep_gather": 1, "index": 1}


def _env(root: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env["PYTHONPATH"] = str(root / "lib")  # the copy's lib, not the installed one
    return env


def snakemake(root: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    proc = subprocess.run(
        [sys.executable, "-m", "snakemake", *args], cwd=root, env=_env(root), capture_output=True, text=True, timeout=600
    )
    if check and proc.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{proc.stdout}\n{proc.stderr}")
    return proc


def planned_jobs(root: Path) -> dict[str, int]:
    """Rules a dry run would execute, with counts (from Snakemake's job-stats table)."""
    out = snakemake(root, "-n").stdout
    if "Nothing to be done" in out:
        return {}
    stats = out[out.index("Job stats:") :]
    jobs = {}
    for line in stats.splitlines()[3:]:
        m = re.match(r"^(\S+)\s+(\d+)$", line.strip())
        if not m or m.group(1) == "total":
            if jobs:
                break
            continue
        jobs[m.group(1)] = int(m.group(2))
    return jobs


def copy_project(dest: Path) -> Path:
    dest.mkdir(parents=True, exist_ok=True)
    for name in COPIED:
        src = PROJECT / name
        if src.is_dir():
            shutil.copytree(src, dest / name, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
        else:
            shutil.copy2(src, dest / name)
    return dest


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """A copy of the project on which bare `snakemake` (profiles/default) has run once."""
    root = copy_project(tmp_path_factory.mktemp("built"))
    assert planned_jobs(root) == ALL_JOBS
    snakemake(root)
    return root


@pytest.fixture()
def clone(built, tmp_path) -> Path:
    """An independent copy of the built project (results and .snakemake metadata included)."""
    dest = tmp_path / "clone"
    shutil.copytree(built, dest, symlinks=True)
    return dest


def test_real_run_builds_every_output(built):
    for rel in OUTPUTS:
        assert (built / rel).stat().st_size > 0, rel
    for paper in ("stiffness", "beatup", "heald", "transplanter", "clearance", "accuracy", "sweeps"):
        html = (built / f"results/reports/{paper}.html").read_text()
        assert "data:image/png;base64" in html  # figures embedded
        assert "Traceback" not in html
        assert 'vnd.jupyter.stderr" tabindex' not in html  # no warnings or errors printed
    index = (built / "results/reports/index.html").read_text()
    assert all(f"{p}.html" in index for p in ("stiffness", "beatup", "clearance", "heald", "transplanter"))
    assert 'vnd.jupyter.stderr" tabindex' not in index


def test_second_run_has_nothing_to_do(built):
    assert planned_jobs(built) == {}


def test_forced_rerun_writes_identical_bytes(clone):
    path = clone / "results/stiffness/stiffness.nc"
    before = hashlib.sha256(path.read_bytes()).hexdigest()
    proc = snakemake(clone, "results/stiffness/stiffness.nc", "--forcerun", "stiffness")
    assert "1 of 1 steps" in proc.stdout + proc.stderr
    assert hashlib.sha256(path.read_bytes()).hexdigest() == before


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ("fine_step_deg: 1.0", "fine_step_deg: 0.5", STIFFNESS_JOBS),
        ("scaled_crank_m: 0.062", "scaled_crank_m: 0.060", BEATUP_JOBS),
        ("M_P: {value: 8.0", "M_P: {value: 9.0", HEALD_JOBS),
        ("crank_speed_rpm: 300.0", "crank_speed_rpm: 310.0", TRANSPLANTER_JOBS),
        ("restitution: 0.9", "restitution: 0.8", CLEARANCE_JOBS),
    ],
    ids=["stiffness", "beatup", "heald", "transplanter", "clearance"],
)
def test_changing_a_parameter_reruns_only_that_papers_rules(clone, old, new, expected):
    cfg_path = clone / "config/config.yaml"
    text = cfg_path.read_text()
    assert old in text
    cfg_path.write_text(text.replace(old, new, 1))
    assert planned_jobs(clone) == expected


def _touch_module(root: Path, module: str) -> None:
    path = root / "lib/linkwork" / module
    path.write_text(path.read_text() + "\n# edited\n")


def test_editing_stiffness_module_reruns_the_rules_that_use_it(clone):
    _touch_module(clone, "stiffness.py")
    assert planned_jobs(clone) == STIFFNESS_JOBS


def test_editing_beatup_module_reruns_only_beatup_rules(clone):
    _touch_module(clone, "beatup.py")
    assert planned_jobs(clone) == BEATUP_JOBS


def test_editing_the_shared_kinematics_reruns_both_papers(clone):
    _touch_module(clone, "kinematics.py")
    jobs = planned_jobs(clone)
    assert jobs["stiffness"] == 1 and jobs["beatup_sixbar"] == 1 and jobs["transplanter_ked"] == 1
    assert jobs["clearance_scene"] == 14 and jobs["report"] == 6 and jobs["accuracy_summary"] == 1
    assert jobs["sweep_point"] == 6  # the clearance sweep uses the kinematics, the heald sweep does not
    assert "heald_chain" not in jobs  # the chain solver does not use the kinematics


def test_editing_compare_module_does_not_rerun_the_computation(clone):
    _touch_module(clone, "compare.py")
    jobs = planned_jobs(clone)
    assert "stiffness" not in jobs
    assert jobs.get("stiffness_compare") == 1


def _bad_config(tmp_path, edit) -> subprocess.CompletedProcess:
    root = copy_project(tmp_path / "bad")
    cfg_path = root / "config/config.yaml"
    cfg_path.write_text(edit(cfg_path.read_text()))
    proc = snakemake(root, "--cores", "1", check=False)
    assert proc.returncode != 0
    assert not (root / "results").exists(), "a job ran despite the bad config"
    return proc


@pytest.mark.parametrize(
    ("old", "new", "fragments"),
    [
        ("crank_m: 0.015", "crank_m: 0.0", ["stiffness.linkage.crank_m", "0.0"]),
        ("crank_m: 0.015", "crank_m: -0.015", ["stiffness.linkage.crank_m", "-0.015"]),
        ("crank_m: 0.015", "crank_m: 0.2", ["stiffness.linkage", "crank_m=0.2", "cannot be assembled"]),
        ("assembly_tol: 1.0e-9", "assembly_tol: 1e-9", ["stiffness.numerics.assembly_tol", "'1e-9'", "string"]),
        ("    branch: 1 ", "    branch: 1\n    brnach: 1 ", ["stiffness.linkage.brnach", "unknown key"]),
        ("l5_m: 0.500", "l5_m: 0.200", ["beatup.sixbar.l1_m", "cannot be assembled", "crank angle"]),
        ("branch_sley: -1", "branch_sley: 0", ["beatup.sixbar.branch_sley", "0"]),
        ("value: 0.100, status: assumed", "value: 0.200, status: assumed", ["beatup.fourbar.weft_clearance_m", "0.2", "stroke"]),
        ("M_P: {value: 8.0", "M_P: {value: -8.0", ["heald.parameters.M_P.value", "-8.0"]),
        ("eta7: {value: 2.0", "eta7: {value: 0.0", ["heald.parameters.eta7.value", "0.0", "lever ratio"]),
    ],
    ids=["zero-length", "negative-length", "cannot-assemble", "yaml-string-number", "unknown-key",
         "sixbar-cannot-assemble", "branch-not-unit", "sw-above-stroke", "negative-mass", "lever-ratio-zero"],
)
def test_bad_config_stops_before_any_job(tmp_path, old, new, fragments):
    proc = _bad_config(tmp_path, lambda text: text.replace(old, new, 1))
    message = proc.stdout + proc.stderr
    for fragment in fragments:
        assert fragment in message, message


def test_dry_run_of_a_fresh_copy_plans_every_rule(tmp_path):
    root = copy_project(tmp_path / "fresh")
    assert planned_jobs(root) == ALL_JOBS
    assert yaml.safe_load((root / "profiles/default/profile.yaml").read_text())["cores"] == "all"


@pytest.mark.parametrize("sig", ["SIGINT", "SIGKILL"])
def test_a_killed_run_completes_on_the_next_run(tmp_path, sig):
    """Interrupt snakemake while a job runs; the next run finishes with valid outputs and no leftovers.

    SIGINT (Ctrl-C) lets snakemake mark the job incomplete and release its lock; after SIGKILL the
    lock stays and `snakemake --unlock` is needed first (as snakemake itself says).
    """
    import signal
    import time

    import xarray as xr

    root = copy_project(tmp_path / "killed")
    target = "results/reports/stiffness.html"
    proc = subprocess.Popen(
        [sys.executable, "-m", "snakemake", target, "--cores", "1"],
        cwd=root, env=_env(root), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )
    deadline = time.time() + 120
    while not (root / "results/stiffness/comparison.csv").exists() and time.time() < deadline:
        time.sleep(0.05)
    os.killpg(proc.pid, getattr(signal, sig))  # snakemake and the job it runs
    proc.wait(timeout=120)
    assert not (root / target).exists()
    if sig == "SIGKILL":
        snakemake(root, "--unlock")
    snakemake(root, target)
    with xr.open_dataset(root / "results/stiffness/stiffness.nc") as ds:
        assert ds.K_h.size > 0
    assert "data:image/png;base64" in (root / target).read_text()
    assert not list((root / "results").rglob("*.tmp"))
