"""Rule clearance_claims: all scenes (pipeline and tight tolerance) -> the three claims per variant -> claims.nc."""

from pathlib import Path

import xarray as xr

from linkwork import results
from linkwork.clearance_dataset import claims_dataset

section = snakemake.params.section  # noqa: F821


def load(paths):
    runs = {}
    for path in map(Path, paths):
        with xr.open_dataset(path) as ds:
            runs[(ds.attrs["variant"], ds.attrs["scene"])] = ds.load()
    return runs


ds = claims_dataset(section, load(snakemake.input.scenes), load(snakemake.input.tight))  # noqa: F821
ds.attrs.update(results.provenance("clearance", section, title="Claims of the clearance paper, per parameter variant", source=section["source"]))
results.write(ds, snakemake.output[0])  # noqa: F821
