"""The Snakemake workflow on fresh copies of the project (no built copy needed): the dry run of a fresh copy and
interrupted runs.  A file of its own, so that these run on the other test worker while tests/test_workflow.py builds
its copy (make test runs the test files on two workers, one file each at a time)."""

import os
import subprocess
import sys

import pytest
import yaml

from test_workflow import ALL_JOBS, _env, copy_project, planned_jobs, snakemake

pytestmark = pytest.mark.workflow


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

    target = "results/reports/stiffness.html"
    # interrupt once the first job's output lands (two jobs still to come), after a short wait so that the signal does
    # not meet Snakemake while it books a finished job; a run the signal did not stop (it ended anyway) proves
    # nothing, so the scenario is tried again later in the run, up to three times, and must be seen interrupted once
    for attempt, delay in enumerate((0.3, 0.0, 1.0)):
        root = copy_project(tmp_path / f"killed{attempt}")
        proc = subprocess.Popen(
            [sys.executable, "-m", "snakemake", target, "--cores", "1"],
            cwd=root,
            env=_env(root),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
            # Ctrl-C as a terminal delivers it: a SIGINT ignored by a parent (make, a CI shell) would be inherited and
            # Python
            # would then install no KeyboardInterrupt handler in Snakemake
            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
        )
        deadline = time.time() + 120
        while not (root / "results/stiffness/stiffness.nc").exists() and time.time() < deadline:
            time.sleep(0.02)
        time.sleep(delay)
        os.killpg(proc.pid, getattr(signal, sig))  # snakemake and the job it runs
        proc.wait(timeout=120)
        if not (root / target).exists():
            break
    assert not (root / target).exists(), "three interrupted runs all ran to the end"
    if sig == "SIGKILL":
        snakemake(root, "--unlock")
    snakemake(root, target)
    with xr.open_dataset(root / "results/stiffness/stiffness.nc") as ds:
        assert ds.K_h.size > 0
    assert "data:image/png;base64" in (root / target).read_text()
    assert not list((root / "results").rglob("*.tmp"))
