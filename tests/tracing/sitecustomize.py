"""Test-only import tracing (tests/test_workflow.py puts this folder on PYTHONPATH for one real run).

With LINKWORK_TRACE_DIR set, every Python process of the run writes, when it exits, which linkwork
modules (and report helpers) it loaded, with its pid, its parent's pid, for a Snakemake script
job the job's outputs, and the thread count of every OpenBLAS library loaded (numpy and scipy bring
one each).  The test joins a report's kernel to the job that started it by the parent pid.
"""

import atexit
import json
import os
import sys

_DIR = os.environ.get("LINKWORK_TRACE_DIR")
_MAIN = sys.modules.get("__main__")  # the script's module (IPython later puts its own in sys.modules)


#: The thread-count getters of the OpenBLAS builds numpy and scipy ship (symbol names differ by build).
_GETTERS = (
    "scipy_openblas_get_num_threads64_", "scipy_openblas_get_num_threads", "openblas_get_num_threads64_",
    "openblas_get_num_threads",
)


def _blas_threads() -> dict[str, int]:
    """Library file name -> the threads it computes with, for every OpenBLAS mapped into this process."""
    import ctypes

    with open("/proc/self/maps", encoding="utf-8") as fh:
        paths = sorted({ln.split()[-1] for ln in fh if "openblas" in ln.lower() and ln.split()[-1].startswith("/")})
    out = {}
    for path in paths:
        lib = ctypes.CDLL(path)
        for name in _GETTERS:
            getter = getattr(lib, name, None)
            if getter is not None:
                out[os.path.basename(path)] = int(getter())
                break
    return out


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
        "blas_threads": _blas_threads(),
    }
    with open(os.path.join(_DIR, f"{os.getpid()}.json"), "w", encoding="utf-8") as fh:
        json.dump(record, fh)


if _DIR:
    atexit.register(_record)
