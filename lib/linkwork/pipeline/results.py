"""Write result Datasets to netCDF with units and provenance, atomically.

Provenance goes into global attributes: the paper id, the paper's config
section as canonical JSON and its sha256, the package version and the git
commit of the working tree.  Nothing time- or host-dependent is written, so a
rerun with the same config and code produces byte-identical files.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import subprocess
from pathlib import Path
from typing import Any

from .. import __version__


def canonical_json(obj: Any) -> str:
    """JSON with sorted keys and no whitespace: the same config gives the same text."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), ensure_ascii=True)


def config_sha256(obj: Any) -> str:
    return hashlib.sha256(canonical_json(obj).encode()).hexdigest()


def git_commit(path: str | os.PathLike[str] = ".") -> str:
    """HEAD commit of the repository holding ``path`` ('-dirty' if tracked files changed).

    Returns 'unknown' outside a git checkout.
    """
    try:
        head = subprocess.run(
            ["git", "rev-parse", "HEAD"], cwd=path, capture_output=True, text=True, check=True
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"], cwd=path, capture_output=True, text=True,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("-dirty" if dirty else "")


def provenance(paper_id: str, config_section: Any, **extra: Any) -> dict[str, Any]:
    """Global attributes that say where a result came from."""
    attrs: dict[str, Any] = {
        "paper_id": paper_id,
        "config_json": canonical_json(config_section),
        "config_sha256": config_sha256(config_section),
        "linkwork_version": __version__,
        "git_commit": git_commit(),
    }
    attrs.update(extra)
    return attrs


def check_units(ds) -> None:
    """Every data variable and coordinate must carry ``units`` and ``long_name``."""
    missing = [
        str(name)
        for name, var in {**ds.data_vars, **ds.coords}.items()
        if "units" not in var.attrs or "long_name" not in var.attrs
    ]
    if missing:
        raise ValueError(f"variables without units/long_name: {', '.join(sorted(missing))}")


class NonFiniteResult(ValueError):
    """A result holds inf, or NaN where no NaN is meaningful."""


def check_finite(ds, name: str = "result") -> None:
    """Every floating variable is finite, except NaN where its attributes say what a NaN means (``nan_meaning``,
    e.g. 'no clearance at this joint in this scene'); inf is never written."""
    import numpy as np

    for key, var in ds.data_vars.items():
        if var.dtype.kind not in "fc":
            continue
        values = np.asarray(var.values)
        if np.isinf(values).any():
            raise NonFiniteResult(
                f"{name}: variable {key} holds inf at {int(np.isinf(values).sum())} of {values.size} points; not"
                " written"
            )
        nans = int(np.isnan(values).sum())
        if nans and not var.attrs.get("nan_meaning"):
            raise NonFiniteResult(
                f"{name}: variable {key} ({var.attrs.get('long_name', '')}) is NaN at {nans} of {values.size} points, "
                "which the study does not expect; not written (check the inputs of this job)"
            )


@contextlib.contextmanager
def _uninterrupted():
    """Hold Ctrl-C (SIGINT) until the block ends, then raise it.

    A KeyboardInterrupt inside ``Dataset.to_netcdf`` can leave xarray's HDF5 lock held and the job hung in its
    own cleanup (seen: Ctrl-C of a run while a job wrote its netCDF).  A write takes well under a second, so
    the interrupt is held that long and then delivered; the write is complete or not begun.
    """
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if caught:
        raise KeyboardInterrupt


def without_string_widths(ds):
    """``ds`` (a shallow copy) without the string widths its text variables were read with: a variable read from a file
    keeps the width of its longest string as its encoding, and xarray writes with it, so strings concatenated from
    files of different widths were cut to the first file's (the heald study's scenario labels were, and its second
    scenario then counted no samples)."""
    out = ds.copy()
    for var in out.variables.values():
        if var.dtype.kind in "OUS" and "dtype" in var.encoding:
            var.encoding = {k: v for k, v in var.encoding.items() if k != "dtype"}
    return out


#: The checksum written beside every result (``<file>.sha256``, sha256sum's format): a read compares it, so a truncated
#: or replaced result is named instead of read.
CHECKSUM_SUFFIX = ".sha256"


class ResultWriteError(RuntimeError):
    """A result could not be written (full disk, read-only folder); the message is one line naming the file."""


def checksum_path(path: str | os.PathLike[str]) -> Path:
    """The checksum file beside a result."""
    target = Path(path)
    return target.with_name(target.name + CHECKSUM_SUFFIX)


def _sha256(path: Path) -> str:
    import hashlib

    return hashlib.sha256(path.read_bytes()).hexdigest()


def _cannot_write(target: Path, exc: BaseException) -> ResultWriteError:
    """One line for a failed write: the file, the system's reason and the cure."""
    reason = getattr(exc, "strerror", None) or (str(exc).splitlines()[0] if str(exc) else type(exc).__name__)
    return ResultWriteError(
        f"cannot write {target} ({reason}): free disk space or make {target.parent} writable, then run snakemake again"
    )


def _named(target: Path) -> str:
    """How a checksum line names its result: the path from the working folder (the project's root under Snakemake),
    so that a result copied over another with its checksum is told apart; an absolute path outside it."""
    relative = os.path.relpath(target)
    return str(target.resolve()) if relative.startswith("..") else relative


def _publish(tmp: Path, target: Path) -> None:
    """The finished temporary file ``tmp`` becomes ``target``, its checksum written first (both renamed atomically)."""
    sidecar = checksum_path(target)
    side_tmp = sidecar.with_name(sidecar.name + ".tmp")
    try:
        side_tmp.write_text(f"{_sha256(tmp)}  {_named(target)}\n", encoding="utf-8")
        os.replace(side_tmp, sidecar)
    finally:
        if side_tmp.exists():
            side_tmp.unlink()
    os.replace(tmp, target)


def write(ds, path: str | os.PathLike[str]) -> Path:
    """Write ``ds`` to netCDF atomically (a temporary file beside it, then rename) with its checksum beside it, after
    checking units and that it is finite where it must be.  A failed write (full disk, read-only folder) leaves no
    temporary file and raises ResultWriteError naming the file."""
    check_units(ds)
    check_finite(ds, str(path))
    ds = without_string_widths(ds)
    target = Path(path)
    tmp = target.with_name(target.name + ".tmp")
    with _uninterrupted():
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4")
            _publish(tmp, target)
        except (OSError, RuntimeError) as exc:  # netCDF4 reports a full disk as RuntimeError('NetCDF: HDF error')
            raise _cannot_write(target, exc) from None
        finally:
            if tmp.exists():
                tmp.unlink()
    return target


def write_text(text: str, path: str | os.PathLike[str]) -> Path:
    """Write a text file atomically, with its checksum beside it (failures as in ``write``)."""
    target = Path(path)
    tmp = target.with_name(target.name + ".tmp")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        tmp.write_text(text, encoding="utf-8")
        _publish(tmp, target)
    except OSError as exc:
        raise _cannot_write(target, exc) from None
    finally:
        if tmp.exists():
            tmp.unlink()
    return target


def unwritable(folder: str | os.PathLike[str]) -> str | None:
    """Why ``folder`` or a folder below it cannot take a new result (a probe file created and removed in each: file
    permissions, a read-only mount, an immutable flag), or None.  Snakemake removes a result before its job rewrites
    it, and fails with a traceback where it cannot: this names the folder first."""
    import tempfile

    top = Path(folder)
    for here, _, _ in os.walk(top) if top.is_dir() else ():
        try:
            handle, probe = tempfile.mkstemp(dir=here, prefix=".linkwork-probe-")
            os.close(handle)
            os.unlink(probe)
        except OSError as exc:
            return (
                f"{here} cannot be written ({exc.strerror}): make {top} writable again (chmod -R u+w {top}), then run"
                " snakemake"
            )
    return None


def verify(path: str | os.PathLike[str]) -> None:
    """A result whose checksum file is beside it must match it: else UnreadableResult naming the file and the command
    that rebuilds it.  A file without one (a config file, a result from before checksums) is read as it is."""
    target = Path(path)
    sidecar = checksum_path(target)
    if not sidecar.is_file() or not target.is_file():
        return
    expected, _, named = sidecar.read_text(encoding="utf-8").strip().partition("  ")
    if _sha256(target) != expected:
        raise UnreadableResult(
            f"cannot read {target} (it does not match its checksum {sidecar.name}: truncated, or replaced by "
            f"another file); rebuild it with: snakemake --force {target}"
        )
    absolute = target.resolve().as_posix()
    if absolute != named and not absolute.endswith(
        "/" + named
    ):  # read from another folder, or the project moved: the same tail
        raise UnreadableResult(
            f"cannot read {target} (its checksum is that of {named}: another result copied over it); "
            f"rebuild it with: snakemake --force {target}"
        )


def final_result_problem(path: str | os.PathLike[str]) -> str:
    """One line on a final result that no job reads (a linkage of your own, a report), checked before planning since
    no job would: a directory where the file belongs, or a file that does not match its checksum, each with its cure;
    '' if it is sound or absent."""
    target = Path(path)
    if target.is_dir():
        return f"{target} is a folder where a result file belongs: remove it (rm -r {target}) and run again"
    sidecar = checksum_path(target)
    if not target.is_file() or not sidecar.is_file():
        return ""
    if _sha256(target) != sidecar.read_text(encoding="utf-8").split()[0]:  # the content alone: a moved project is fine
        return (
            f"{target} does not match its checksum {sidecar.name} (truncated, or replaced by another file): rebuild it"
            f" with: rm {target} && snakemake"
        )
    return ""


class UnreadableResult(RuntimeError):
    """A result file exists but cannot be read (truncated or corrupted)."""


def load(path: str | os.PathLike[str]) -> Any:
    """Read a rule input by its type: netCDF (loaded Dataset), JSON, YAML (dict) or CSV (DataFrame).

    A file that cannot be read, or that does not match the checksum beside it (``verify``), raises UnreadableResult with
    one line naming the file and the command that rebuilds it.
    """
    target = Path(path)
    verify(target)
    try:
        if target.suffix == ".nc":
            import xarray as xr

            with xr.open_dataset(target) as ds:
                return ds.load()
        if target.suffix == ".json":
            return json.loads(target.read_text(encoding="utf-8"))
        if target.suffix in (".yaml", ".yml"):
            import yaml

            return yaml.safe_load(target.read_text(encoding="utf-8"))
        if target.suffix == ".csv":
            import pandas as pd

            return pd.read_csv(target, keep_default_na=True)
    except (OSError, ValueError, RuntimeError, KeyError) as exc:
        raise UnreadableResult(
            f"cannot read {target} ({type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else 'no detail'}); "
            f"rebuild it with: snakemake --force {target}"
        ) from None
    raise ValueError(f"no reader for {target}")


def finish_job() -> None:
    """End a rule's process once its outputs are written (atomically, files closed): flush the streams, run the
    exit handlers, and leave without the interpreter's teardown (freeing every module and the compiled code: 0.1-0.2 s a
    job, measured with and without numba and xarray loaded, about 15 core-seconds over the full reproduction's jobs).
    Only for the rule scripts' last line; a failing job exits through ``sys.exit`` as before."""
    import atexit
    import sys

    sys.stdout.flush()
    sys.stderr.flush()
    atexit._run_exitfuncs()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)
