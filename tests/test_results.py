"""netCDF writing: units required, provenance attributes, atomic and byte-identical."""

import hashlib

import numpy as np
import pytest
import xarray as xr

from linkwork.pipeline import results


def _ds():
    return xr.Dataset(
        {"k": ("x", np.arange(3.0), {"units": "N m-1", "long_name": "stiffness"})},
        coords={"x": ("x", np.arange(3.0), {"units": "deg", "long_name": "angle"})},
    )


def test_write_is_byte_identical_and_leaves_no_temporary(tmp_path):
    ds = _ds()
    ds.attrs.update(results.provenance("stiffness", {"b": 2, "a": 1}))
    digests = []
    for _ in range(2):
        path = results.write(ds, tmp_path / "out.nc")
        digests.append(hashlib.sha256(path.read_bytes()).hexdigest())
    assert digests[0] == digests[1]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc", "out.nc.sha256"]
    back = xr.open_dataset(tmp_path / "out.nc")
    assert back.attrs["config_json"] == '{"a":1,"b":2}'
    assert back.attrs["config_sha256"] == results.config_sha256({"a": 1, "b": 2})
    for key in ("paper_id", "linkwork_version", "git_commit"):
        assert key in back.attrs
    back.close()


def test_variables_without_units_are_refused(tmp_path):
    ds = _ds()
    ds["bare"] = ("x", np.ones(3))
    with pytest.raises(ValueError, match="bare"):
        results.write(ds, tmp_path / "out.nc")
    assert not (tmp_path / "out.nc").exists()


def test_a_result_with_unexplained_nan_or_any_inf_is_not_written(tmp_path):
    """NaN is written only where the variable says what it means; inf never; a refused result leaves no file."""
    ds = _ds()
    ds["k"][1] = np.nan
    with pytest.raises(results.NonFiniteResult, match=r"variable k \(stiffness\) is NaN at 1 of 3 points"):
        results.write(ds, tmp_path / "out.nc")
    assert list(tmp_path.iterdir()) == []
    ds["k"].attrs["nan_meaning"] = "no stiffness at a dead centre"
    results.write(ds, tmp_path / "out.nc")
    ds["k"][2] = np.inf
    with pytest.raises(results.NonFiniteResult, match="variable k holds inf at 1 of 3 points"):
        results.write(ds, tmp_path / "other.nc")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc", "out.nc.sha256"]


def test_ctrl_c_during_a_write_is_held_until_the_file_is_complete(tmp_path, monkeypatch):
    """SIGINT arriving inside to_netcdf (where xarray's HDF5 lock can deadlock a KeyboardInterrupt) is delivered
    only after the atomic rename: the file is whole, no temporary is left, and the interrupt still stops the job."""
    import os
    import signal

    ds = _ds()
    original = xr.Dataset.to_netcdf
    before = signal.getsignal(signal.SIGINT)  # the default, or SIG_IGN in a job started in the background

    def interrupted(self, *args, **kwargs):
        os.kill(os.getpid(), signal.SIGINT)
        return original(self, *args, **kwargs)

    monkeypatch.setattr(xr.Dataset, "to_netcdf", interrupted)
    with pytest.raises(KeyboardInterrupt):
        results.write(ds, tmp_path / "out.nc")
    monkeypatch.undo()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc", "out.nc.sha256"]
    with xr.open_dataset(tmp_path / "out.nc") as back:
        assert back.k.values.tolist() == [0.0, 1.0, 2.0]
    assert signal.getsignal(signal.SIGINT) is before  # the handler the write found is back


def test_finish_job_runs_the_exit_handlers_flushes_and_leaves_a_written_result_whole(tmp_path):
    """A rule script's last line: its netCDF output reads back whole, buffered output is printed, the exit handlers
    (the resource recorder of benchmarks/job_resources.py is one) run, and the exit status is 0."""
    import subprocess
    import sys
    import textwrap

    script = textwrap.dedent(f"""
        import atexit, sys
        import numpy as np, xarray as xr
        from linkwork.pipeline import results
        atexit.register(lambda: open({str(tmp_path / "handler")!r}, "w").write("ran"))
        ds = xr.Dataset({{"k": ("x", np.arange(1000.0), {{"units": "1", "long_name": "k"}})}},
                        coords={{"x": ("x", np.arange(1000.0), {{"units": "1", "long_name": "x"}})}})
        results.write(ds, {str(tmp_path / "out.nc")!r})
        sys.stdout.write("buffered line")
        results.finish_job()
        print("never reached")
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout == "buffered line"
    assert (tmp_path / "handler").read_text() == "ran"
    assert float(xr.load_dataset(tmp_path / "out.nc").k.sum()) == 499500.0


def test_strings_concatenated_from_files_of_different_widths_are_written_whole(tmp_path):
    """Two results whose labels have different lengths, read back and concatenated (as a gather step does), then
    written: no label is cut to the first file's width (it was: the heald study's second scenario counted no
    samples)."""
    def labelled(labels):
        return xr.Dataset(
            {"k": ("sample", np.arange(len(labels), dtype=float), {"units": "1", "long_name": "k"})},
            coords={"sample": ("sample", np.array(labels, dtype=object), {"units": "1", "long_name": "label"})},
        )

    short, long = ["drive at the shaft"] * 2, ["drive at half the shaft frequency"] * 2
    parts = [xr.load_dataset(results.write(labelled(x), tmp_path / f"{k}.nc")) for k, x in enumerate((short, long))]
    results.write(xr.concat(parts, dim="sample"), tmp_path / "gathered.nc")
    assert [str(x) for x in xr.load_dataset(tmp_path / "gathered.nc").sample.values] == short + long


def test_every_result_has_its_checksum_and_a_truncated_or_replaced_one_is_named(tmp_path):
    """The checksum beside a result is sha256sum's line for it; a read of a truncated CSV, or of a netCDF replaced by
    another valid one, stops with one line naming the file and the command that rebuilds it."""
    table = results.write_text("a,b\n" + "".join(f"{i},{i * i}\n" for i in range(1000)), tmp_path / "comparison.csv")
    line = results.checksum_path(table).read_text()
    assert (
        line == f"{hashlib.sha256(table.read_bytes()).hexdigest()}  {table.resolve()}\n"
    )  # outside the working folder: absolute
    assert len(results.load(table)) == 1000
    table.write_bytes(table.read_bytes()[:3000])  # head -c 3000: still a valid CSV of fewer rows
    with pytest.raises(results.UnreadableResult) as info:
        results.load(table)
    message = str(info.value)
    assert (
        f"cannot read {table}" in message
        and "does not match its checksum" in message
        and f"snakemake --force {table}" in message
    )
    assert "\n" not in message
    first, other = results.write(_ds(), tmp_path / "first.nc"), results.write(_ds() * 2, tmp_path / "other.nc")
    first.write_bytes(other.read_bytes())
    with pytest.raises(results.UnreadableResult, match="first.nc .it does not match its checksum"):
        results.load(first)
    first.write_bytes(other.read_bytes())  # another result copied over it with its own checksum
    results.checksum_path(first).write_bytes(results.checksum_path(other).read_bytes())
    with pytest.raises(
        results.UnreadableResult, match="first.nc .its checksum is that of .*other.nc: another result copied over it"
    ):
        results.load(first)
    results.checksum_path(other).unlink()  # no checksum beside it (a config file): read as it is
    assert float(results.load(other).k[1]) == 2.0


@pytest.mark.parametrize("kind", ["netcdf", "text", "read-only"])
def test_a_full_disk_is_one_line_naming_the_file_and_leaves_no_temporary(tmp_path, monkeypatch, kind):
    """What netCDF4 raises on a full disk (RuntimeError 'NetCDF: HDF error', after a partial file), what a text write
    raises (OSError ENOSPC) and a folder that cannot be written become one line naming the file and the cure; no
    temporary file stays behind."""
    import errno
    from pathlib import Path

    if kind == "netcdf":
        def full(self, path, **kwargs):
            Path(path).write_bytes(b"\x89HDF partial")
            raise RuntimeError("NetCDF: HDF error")

        monkeypatch.setattr(xr.Dataset, "to_netcdf", full)
        write, name, reason = lambda: results.write(_ds(), tmp_path / "out.nc"), "out.nc", "NetCDF: HDF error"
    elif kind == "read-only":  # as results/ made read-only (root writes anyway: simulated)
        def refused(self, *args, **kwargs):
            raise PermissionError(errno.EACCES, "Permission denied")

        monkeypatch.setattr(Path, "mkdir", refused)
        write, name, reason = lambda: results.write(_ds(), tmp_path / "out.nc"), "out.nc", "Permission denied"
    else:
        real = Path.write_text

        def full(self, *args, **kwargs):
            if self.name.endswith(".tmp"):
                real(self, "partial")
                raise OSError(errno.ENOSPC, "No space left on device")
            return real(self, *args, **kwargs)

        monkeypatch.setattr(Path, "write_text", full)
        write, name, reason = (
            lambda: results.write_text("a,b\n1,2\n", tmp_path / "out.csv"), "out.csv", "No space left on device",
        )
    with pytest.raises(results.ResultWriteError) as info:
        write()
    assert (
        str(info.value)
        == f"cannot write {tmp_path / name} ({reason}): free disk space or make {tmp_path} writable, "
        "then run snakemake again"
    )
    assert list(tmp_path.iterdir()) == []


def test_a_checksum_names_its_result_from_the_project_and_holds_from_another_folder(tmp_path, monkeypatch):
    """Under Snakemake a checksum names its result from the project's root (results/...): a report reading it from
    its own folder, or the project moved elsewhere, still matches it."""
    project = tmp_path / "project"
    project.mkdir()
    monkeypatch.chdir(project)
    path = results.write(_ds(), "results/paper/out.nc")
    assert results.checksum_path(path).read_text().endswith("  results/paper/out.nc\n")
    moved = tmp_path / "moved"
    project.rename(moved)
    monkeypatch.chdir(tmp_path)
    assert float(results.load(moved / "results/paper/out.nc").k[2]) == 2.0


def test_a_results_folder_that_cannot_be_written_is_named(tmp_path, monkeypatch):
    """Snakemake deletes a result before its job rewrites it and fails with a traceback in a read-only folder: the probe
    names the folder first (root writes anywhere, so the refusal is simulated at the probe's file creation)."""
    import errno
    import tempfile

    (tmp_path / "results" / "stiffness").mkdir(parents=True)
    assert results.unwritable(tmp_path / "results") is None
    assert not list((tmp_path / "results").rglob(".linkwork-probe-*"))
    real = tempfile.mkstemp

    def refused(*args, dir=None, **kwargs):
        if str(dir).endswith("stiffness"):
            raise PermissionError(errno.EPERM, "Operation not permitted")
        return real(*args, dir=dir, **kwargs)

    monkeypatch.setattr(tempfile, "mkstemp", refused)
    assert (
        results.unwritable(tmp_path / "results")
        == f"{tmp_path / 'results' / 'stiffness'} cannot be written (Operation not permitted): make"
        f" {tmp_path / 'results'} writable again (chmod -R u+w {tmp_path / 'results'}), then run snakemake"
    )
