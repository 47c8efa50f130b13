"""Test-only import tracing (tests/test_workflow.py puts this folder on PYTHONPATH for one real run).

With LINKWORK_TRACE_DIR set, every Python process of the run writes, when it exits, which linkwork
modules (and report helpers) it loaded, with its pid, its parent's pid and, for a Snakemake script
job, the job's outputs.  The test joins a report's kernel to the job that started it by the parent pid.
"""

import atexit
import json
import os
import sys

_DIR = os.environ.get("LINKWORK_TRACE_DIR")
_MAIN = sys.modules.get("__main__")  # the script's module (IPython later puts its own in sys.modules)


def _record() -> None:
    job = getattr(_MAIN, "snakemake", None)
    files = sorted(
        str(getattr(module, "__file__", "") or "")
        for name, module in list(sys.modules.items())
        if name == "linkwork" or name.startswith("linkwork.") or name == "_common"
    )
    record = {
        "pid": os.getpid(),
        "ppid": os.getppid(),
        "outputs": [str(o) for o in job.output] if job is not None else [],
        "files": files,
    }
    with open(os.path.join(_DIR, f"{os.getpid()}.json"), "w", encoding="utf-8") as fh:
        json.dump(record, fh)


if _DIR:
    atexit.register(_record)
