"""Rule sweep_gather: all points of a sweep -> results/sweeps/<sweep>.nc."""

import xarray as xr

from linkwork import results
from linkwork.sweeps import gather

sweep = snakemake.wildcards.sweep  # noqa: F821
points = []
for path in snakemake.input.points:  # noqa: F821
    with xr.open_dataset(path) as ds:
        points.append(ds.load())
out = gather(snakemake.params.sweeps, sweep, points)  # noqa: F821
out.attrs.update(results.provenance(sweep, snakemake.params.sweeps[sweep], title=f"{sweep} sweep ({snakemake.params.sweeps['grid']} grid)"))  # noqa: F821
results.write(out, snakemake.output[0])  # noqa: F821
