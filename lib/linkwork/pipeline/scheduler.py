"""The Snakemake controller's process (not a job's): settings that keep its scheduler from taking the cores' time.

Snakemake's job-rate limiter (its default: 100 jobs a second) makes the scheduler run again one timespan after every
pass, and each pass stats every input of every waiting job; every finished job starts one more such chain of passes.
Measured on two cores (2026-11-28): the passes took 75 s of CPU in a 554 s full reproduction, time the jobs lost.  Local
jobs start when a core frees (a finished job wakes the scheduler), so the default profile sets a limit no run of this
workflow reaches over a span no run lasts (profiles/default/profile.yaml), and the scheduler sleeps between jobs.  Its
pending re-evaluation timers must then not keep the finished run's process alive until they fire: ``daemon_timers``.
"""

from __future__ import annotations

import threading


class DaemonTimer(threading.Timer):
    """A ``threading.Timer`` that does not keep the interpreter alive at exit (a daemon thread)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.daemon = True


def daemon_timers() -> None:
    """Every ``threading.Timer`` created from now on in this process is a daemon thread: a run ends when its last job
    does, not when the scheduler's last pending re-evaluation would have fired.  Called by the Snakefile (the
    controller's process only; a job's script never reads the Snakefile)."""
    threading.Timer = DaemonTimer
