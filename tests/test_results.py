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
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc"]
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
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc"]


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
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc"]
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
    written: no label is cut to the first file's width (it was: the heald study's second scenario counted no samples)."""
    def labelled(labels):
        return xr.Dataset({"k": ("sample", np.arange(len(labels), dtype=float), {"units": "1", "long_name": "k"})},
                          coords={"sample": ("sample", np.array(labels, dtype=object), {"units": "1", "long_name": "label"})})

    short, long = ["drive at the shaft"] * 2, ["drive at half the shaft frequency"] * 2
    parts = [xr.load_dataset(results.write(labelled(x), tmp_path / f"{k}.nc")) for k, x in enumerate((short, long))]
    results.write(xr.concat(parts, dim="sample"), tmp_path / "gathered.nc")
    assert [str(x) for x in xr.load_dataset(tmp_path / "gathered.nc").sample.values] == short + long
