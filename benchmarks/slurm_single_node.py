"""The full reproduction on a real SLURM, against a local run on the same machine.

Needs root on a Debian machine (apt-get). Not part of the test run: `sudo .venv/bin/python
benchmarks/slurm_single_node.py` (or `make slurm-proof`). What it does, in order:

1. installs Debian's slurm-wlm and munge if they are missing, and the project's `slurm` extra
   (snakemake-executor-plugin-slurm) into the running interpreter's environment;
2. stands up a single-node SLURM in a temporary folder: munged with its own key on munge's default socket
   (or the munged already answering there), slurmctld on a free port and a configless slurmd
   (proctrack/linuxproc, task/none, select/cons_tres with cores and memory, no
   accounting storage), one default partition holding this machine's CPUs and 90 % of its memory;
3. makes two fresh clones of this checkout's HEAD, each with an empty compile cache, and runs in one the
   README's local command (`snakemake`) and in the other the README's cluster command (`snakemake --profile
   profiles/slurm --cores 1`, what `make slurm` runs), both timed as whole processes (time.perf_counter);
4. counts the SLURM submissions (sbatch calls, through a counting sbatch first on PATH), compares every netCDF file and
every report of
   the two runs byte for byte (linkwork.pipeline.fingerprint: only the reports that show wall times may
   differ), and stops the daemons it started by their process ids;
5. prints the figures; with --record also writes them to benchmarks/measured/slurm.json (the README's cluster
   figures: `python benchmarks/readme.py`), so that a plain run edits no tracked file.

Exit status 1 if a file differs that must not, or if a run fails.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(PROJECT / "lib"))
from _project import write_figures  # noqa: E402
from linkwork.pipeline.fingerprint import compare, fingerprints  # noqa: E402

DAEMONS = ("munged", "slurmctld", "slurmd")
MUNGE_SOCKET = Path("/run/munge/munge.socket.2")
RATIO_TARGET = 2.0
SUBMISSION_TARGET = 20


def say(message: str) -> None:
    print(f"slurm_single_node: {message}", flush=True)


def run(cmd: list[str], **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, check=True, text=True, **kwargs)


def install() -> None:
    """Debian's slurm-wlm and munge, and the project's slurm extra, where missing."""
    if os.geteuid() != 0:
        sys.exit("slurm_single_node: needs root (it installs and starts slurmctld, slurmd and munged)")
    if not all(shutil.which(d) or Path(f"/usr/sbin/{d}").exists() for d in DAEMONS):
        say("installing slurm-wlm and munge with apt-get ...")
        run(["apt-get", "update", "-qq"])
        run(
            ["apt-get", "install", "-y", "-qq", "slurm-wlm", "munge"],
            env={**os.environ, "DEBIAN_FRONTEND": "noninteractive"}, stdout=subprocess.DEVNULL,
        )
    try:
        import snakemake_executor_plugin_slurm  # noqa: F401
    except ImportError:
        say("installing the slurm extra (snakemake-executor-plugin-slurm) ...")
        run(
            [
                sys.executable, "-m", "pip", "install", "--quiet", "-c", str(PROJECT / "constraints.txt"), "-e",
                f"{PROJECT}[slurm]",
            ]
        )


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def node_line() -> tuple[str, int, int]:
    """(node name, CPUs, memory for jobs in MB) of this machine, as slurmd sees it."""
    fields = dict(
        item.split("=", 1) for item in run(["slurmd", "-C"], capture_output=True).stdout.split() if "=" in item
    )
    return fields["NodeName"], int(fields["CPUs"]), int(int(fields["RealMemory"]) * 0.9)


def slurm_conf(folder: Path) -> tuple[Path, int]:
    """slurm.conf in ``folder`` and slurmctld's port. Configless: slurmd fetches the config from slurmctld and
    caches it where client commands inside a job look (the job step plugin clears SLURM_CONF)."""
    node, cpus, memory = node_line()
    conf, port = folder / "slurm.conf", free_port()
    conf.write_text("\n".join([
        "ClusterName=linkwork-single-node",
        f"SlurmctldHost={node}(127.0.0.1)",
        f"SlurmctldPort={port}",
        "SlurmctldParameters=enable_configless",
        f"SlurmdPort={free_port()}",
        "SlurmUser=root",
        "AuthType=auth/munge",
        "CredType=cred/munge",
        f"StateSaveLocation={folder / 'state'}",
        f"SlurmdSpoolDir={folder / 'spool'}",
        f"SlurmctldPidFile={folder / 'slurmctld.pid'}",
        f"SlurmdPidFile={folder / 'slurmd.pid'}",
        f"SlurmctldLogFile={folder / 'slurmctld.log'}",
        f"SlurmdLogFile={folder / 'slurmd.log'}",
        "ProctrackType=proctrack/linuxproc",
        "TaskPlugin=task/none",
        "SelectType=select/cons_tres",
        "SelectTypeParameters=CR_Core_Memory",
        "SchedulerType=sched/backfill",
        "AccountingStorageType=accounting_storage/none",
        "JobAcctGatherType=jobacct_gather/none",
        "JobCompType=jobcomp/none",
        "MpiDefault=none",
        "ReturnToService=2",
        f"NodeName={node} NodeAddr=127.0.0.1 CPUs={cpus} RealMemory={memory} State=UNKNOWN",
        f"PartitionName=debug Nodes={node} Default=YES MaxTime=INFINITE State=UP",
        "",
    ]))
    for sub in ("state", "spool"):
        (folder / sub).mkdir()
    return conf, port


def pid_of(path: Path, timeout: float = 20.0) -> int:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        with contextlib.suppress(OSError, ValueError, IndexError):
            return int(path.read_text().split()[0])
        time.sleep(0.1)
    raise RuntimeError(f"no pid file {path}")


@contextlib.contextmanager
def single_node() -> Iterator[dict[str, str]]:
    """A running single-node SLURM; yields the environment its clients need (SLURM_CONF). The daemons
    started here are stopped by their process ids on the way out."""
    folder = Path(tempfile.mkdtemp(prefix="linkwork-slurm-"))
    started: dict[str, int] = {}
    try:
        if MUNGE_SOCKET.exists() and subprocess.run(["munge", "-n"], capture_output=True).returncode == 0:
            say(f"using the munged already running at {MUNGE_SOCKET}")
        else:  # its default socket: slurmd fetches its config (configless) before it could read another
            key = folder / "munge.key"
            key.write_bytes(os.urandom(1024))
            key.chmod(0o400)
            MUNGE_SOCKET.parent.mkdir(parents=True, exist_ok=True)
            run(
                [
                    "munged", "--force", f"--key-file={key}", f"--socket={MUNGE_SOCKET}",
                    f"--pid-file={folder / 'munged.pid'}", f"--log-file={folder / 'munged.log'}",
                    f"--seed-file={folder / 'munged.seed'}",
                ]
            )
            started["munged"] = pid_of(folder / "munged.pid")
        conf, port = slurm_conf(folder)
        env = {**os.environ, "SLURM_CONF": str(conf)}
        run(["slurmctld", "-f", str(conf)], env=env)
        started["slurmctld"] = pid_of(folder / "slurmctld.pid")
        run(["slurmd", "--conf-server", f"127.0.0.1:{port}"], env={k: v for k, v in env.items() if k != "SLURM_CONF"})
        started["slurmd"] = pid_of(folder / "slurmd.pid")
        end = time.monotonic() + 60
        while "idle" not in subprocess.run(["sinfo", "-h", "-o", "%T"], env=env, capture_output=True, text=True).stdout:
            if time.monotonic() > end:
                raise RuntimeError(f"the node did not become idle: see {folder}/slurmctld.log and slurmd.log")
            time.sleep(0.5)
        say(f"single-node SLURM up ({', '.join(f'{k} pid {v}' for k, v in started.items())}); config {conf}")
        yield {"SLURM_CONF": str(conf)}
    finally:
        for name in reversed(list(started)):
            with contextlib.suppress(ProcessLookupError):
                os.kill(started[name], signal.SIGTERM)
        for name, pid in started.items():
            end = time.monotonic() + 20
            while time.monotonic() < end and Path(f"/proc/{pid}").exists():
                time.sleep(0.1)
            say(f"stopped {name} (pid {pid})")
        cache_link = Path("/run/slurm/conf")  # slurmd's link to its config cache, inside our folder
        if cache_link.is_symlink() and str(folder) in os.readlink(cache_link):
            cache_link.unlink()
        shutil.rmtree(folder, ignore_errors=True)


def counting_sbatch(folder: Path) -> tuple[Path, Path]:
    """A folder with an ``sbatch`` that appends a line to a tally file, then runs the real one (put it first on
    PATH): the number of submissions, arrays counted once, as the scheduler received them."""
    real, tally = shutil.which("sbatch") or "/usr/bin/sbatch", folder / "submissions.txt"
    (folder / "bin").mkdir()
    wrapper = folder / "bin" / "sbatch"
    wrapper.write_text(f'#!/bin/sh\necho "$*" >> {tally}\nexec {real} "$@"\n')
    wrapper.chmod(0o755)
    tally.write_text("")
    return wrapper.parent, tally


def clone(dest: Path) -> Path:
    run(["git", "clone", "--quiet", "--no-hardlinks", str(PROJECT), str(dest)])
    return dest


def timed(cmd: list[str], cwd: Path, env: dict[str, str], log: Path) -> float:
    """Wall time of a whole process (s); its output goes to ``log``. Raises if it fails."""
    say(f"{' '.join(cmd)} in {cwd} ...")
    start = time.perf_counter()
    with log.open("w") as out:
        proc = subprocess.run(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
    seconds = time.perf_counter() - start
    if proc.returncode:
        sys.exit(f"slurm_single_node: {' '.join(cmd)} failed (exit {proc.returncode}); its output: {log}")
    say(f"  done in {seconds:.0f} s")
    return seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--keep", action="store_true", help="keep the two clones (their paths are printed)")
    parser.add_argument("--record", action="store_true", help="write the figures to benchmarks/measured/slurm.json")
    args = parser.parse_args()
    install()
    if subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=no"], cwd=PROJECT, capture_output=True, text=True
    ).stdout.strip():
        say("note: the checkout has uncommitted changes; the runs use its HEAD commit only")
    work = Path(tempfile.mkdtemp(prefix="linkwork-slurm-runs-"))
    head = run(["git", "rev-parse", "--short", "HEAD"], cwd=PROJECT, capture_output=True).stdout.strip()
    base = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    local, cluster = clone(work / "local"), clone(work / "slurm")
    env_local = {**base, "PYTHONPATH": str(local / "lib"), "LINKWORK_CACHE": str(work / "cache-local")}
    local_s = timed([sys.executable, "-m", "snakemake"], local, env_local, work / "local.log")
    wrapper, tally = counting_sbatch(work)
    with single_node() as slurm_env:
        env_cluster = {
            **base,
            **slurm_env,
            "PATH": f"{wrapper}{os.pathsep}{base['PATH']}",
            "PYTHONPATH": str(cluster / "lib"),
            "LINKWORK_CACHE": str(work / "cache-slurm"),
        }
        cluster_s = timed(
            [sys.executable, "-m", "snakemake", "--profile", "profiles/slurm", "--cores", "1"], cluster, env_cluster,
            work / "slurm.log",
        )
    submissions = len(tally.read_text().splitlines())
    edited = subprocess.run(
        ["git", "status", "--porcelain", "--untracked-files=no"], cwd=cluster, capture_output=True, text=True
    ).stdout.split("\n")
    edited = [line for line in edited if line.strip()]
    split = compare(fingerprints(local), fingerprints(cluster))
    figures = {
        "revision": head,
        "local_s": local_s,
        "slurm_s": cluster_s,
        "ratio": cluster_s / local_s,
        "ratio_target": RATIO_TARGET,
        "submissions": submissions,
        "submission_target": SUBMISSION_TARGET,
        "tracked_files_edited": edited,
        "identical_files": len(split["identical"]),
        "compared_files": sum(len(v) for v in split.values()),
        "measured": split["measured"],
        "differing": split["differing"] + split["missing"],
    }
    say(f"local {local_s:.0f} s, SLURM {cluster_s:.0f} s (ratio {figures['ratio']:.2f}); {submissions} submissions; "
        f"{figures['identical_files']} of {figures['compared_files']} netCDF and HTML files byte-identical")
    for name in split["measured"]:
        say(f"  differs (shows wall times, declared): {name}")
    for name in figures["differing"]:
        say(f"  DIFFERS: {name}")
    if args.record:
        write_figures("slurm", figures, __doc__.split("What it does, in order:", 1)[1].split("Exit status")[0])
    if args.keep:
        say(f"kept {local} and {cluster}")
    else:
        shutil.rmtree(work, ignore_errors=True)
    if edited:
        say(f"  tracked files edited by the run: {edited}")
    if figures["differing"] or edited:
        sys.exit(1)


if __name__ == "__main__":
    main()
