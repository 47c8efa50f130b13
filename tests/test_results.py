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
